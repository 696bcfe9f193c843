// Speed-only forms of the probe offset units of aniso.hpp (dp::scale_probe_fraction,
// dp::probe_offset_on_level, dp::probe_texel_coord), for the golden model's anisotropic fast path
// (sampler_fast.cpp, aniso_linear8). Equal to the plain units for every input
// (AnisoProbes.FastOffsetUnitsEqualThePlainUnits); the plain units are the reference and what the
// cycle model and the SystemVerilog use. Off with the fast-path switch (cmodel/fast_paths.hpp:
// TFU_PLAIN=1, the CLI's --plain), which turns the whole anisotropic fast path off.
//
// The plain units round half away from zero in sign-magnitude form, sgn(x) ((|x| + 2^(k-1)) >> k).
// In two's complement the same value is (x + 2^(k-1) - [x < 0]) >> k with an arithmetic shift
// (C++20 defines >> of a negative value as floor division by 2^k): for x < 0,
// -floor((-x + 2^(k-1)) / 2^k) = ceil((x - 2^(k-1)) / 2^k) = floor((x + 2^(k-1) - 1) / 2^k).
// So a probe's offset is one multiply by the signed fraction and one add-and-shift per rounding,
// and its coordinate on a level one add to the centre's Q.8 coordinate, formed once per pixel.
#pragma once

#include <cstdint>

#include "cmodel/aniso.hpp"
#include "cmodel/datapath.hpp"
#include "cmodel/lod.hpp"

namespace tfu::dp::fast {

// sgn(x) ((|x| + 2^(k-1)) >> k), for 1 <= k <= 62 and |x| < 2^62.
[[gnu::always_inline]] inline int64_t round_half_away_shift(int64_t x, int k) {
  return (x + (int64_t{1} << (k - 1)) + (x >> 63)) >> k;  // x >> 63: -1 for x < 0, else 0
}

// The offset unit's input: the major derivative component with its magnitude clamped
// (derivative_magnitude), sign kept; |result| < 2^31.
[[gnu::always_inline]] inline int64_t clamped_major(int64_t major_q16) {
  const auto m = static_cast<int64_t>(derivative_magnitude(major_q16));
  return major_q16 < 0 ? -m : m;
}

// = dp::scale_probe_fraction(major_q16, frac_q16) for major = clamped_major(major_q16): the signed
// product (|x| < 2^46) rounded at bit 16.
[[gnu::always_inline]] inline int64_t scale_probe_fraction(int64_t clamped_major_q16, int32_t frac_q16) {
  return round_half_away_shift(clamped_major_q16 * frac_q16, kProbeFracBits);
}

// = dp::probe_offset_on_level(offset_q16, level), level 0..15.
[[gnu::always_inline]] inline int64_t probe_offset_on_level(int64_t offset_q16, int level) {
  return round_half_away_shift(offset_q16, 8 + level);
}

// A level coordinate as one Q.8 number, (i0 << 8) + f, and back: dp::probe_texel_coord(c, o) =
// split_q8(join_q8(c) + o).
[[gnu::always_inline]] inline int64_t join_q8(dp::LevelCoord c) { return c.i0 * 256 + static_cast<int64_t>(c.f); }
[[gnu::always_inline]] inline dp::LevelCoord split_q8(int64_t u) { return {u >> 8, static_cast<uint32_t>(u & 255)}; }

}  // namespace tfu::dp::fast
