// Per-stage arithmetic of the filter datapath, shared by the golden sampler (sampler.cpp) and the
// cycle model's pipeline stages (rtl/): one definition of every width and rounding
// (docs/sampler.md). Nothing here knows about cycles.
#pragma once

#include <array>
#include <cstdint>

#include "cmodel/fixed_coord.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/weight_rom.hpp"

namespace tfu::dp {

// Address generator: u = floor(s W 2^8) - 128 (Q.8, texel centres at integers); i0 = u >> 8 is
// the tap left of / above the sample point, f = u & 255 the 8-bit subtexel fraction.
struct LevelCoord {
  int64_t i0;
  uint32_t f;
};
inline LevelCoord texel_coord(float s, int size) {
  const int64_t u = float_to_fixed(s, static_cast<uint32_t>(size), 8) - 128;
  return {u >> 8, static_cast<uint32_t>(u & 255)};
}

// Bilinear lerp unit: c = (sum c w + 2^15) >> 16 with w = (256 - fu | fu)(256 - fv | fv) in Q.16;
// taps ordered (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1).
inline Texel4 bilinear_lerp(const std::array<Texel4, 4>& c, uint32_t fu_, uint32_t fv_, TexelFormat fmt) {
  const auto fu = static_cast<int32_t>(fu_), fv = static_cast<int32_t>(fv_);
  const std::array<int32_t, 4> w{(256 - fu) * (256 - fv), fu * (256 - fv), (256 - fu) * fv, fu * fv};
  Texel4 out{};
  if (fmt != TexelFormat::VS16X2) {  // 8-bit channels: 8 + 16 + 2 bits fit 32
    for (size_t ch = 0; ch < 4; ++ch)
      out[ch] = (c[0][ch] * w[0] + c[1][ch] * w[1] + c[2][ch] * w[2] + c[3][ch] * w[3] + (1 << 15)) >> 16;
    return out;
  }
  for (size_t ch = 0; ch < 4; ++ch) {
    const int64_t acc = int64_t{c[0][ch]} * w[0] + int64_t{c[1][ch]} * w[1] + int64_t{c[2][ch]} * w[2] +
                        int64_t{c[3][ch]} * w[3];
    out[ch] = static_cast<int32_t>((acc + (1 << 15)) >> 16);
  }
  return out;
}

// Trilinear blend unit: c = (c0 (256 - f) + c1 f + 128) >> 8, f = the weight of level1 (Q.8).
inline Texel4 level_blend(const Texel4& c0, const Texel4& c1, int f) {
  Texel4 out{};
  for (size_t ch = 0; ch < 4; ++ch) out[ch] = (c0[ch] * (256 - f) + c1[ch] * f + 128) >> 8;
  return out;
}

// Cubic weight stage: the 2D weights of the separable tiled-ROM filter (T x T taps, T <= 4):
// tile-weight multipliers for all taps but the centre one (offset (0, 0)), which takes the
// complement so that the weights sum to exactly M = 2^b - 1.
void tile_weights_2d(const TileWeightRom& rom, RomRecon recon, uint32_t fu, uint32_t fv, std::array<int32_t, 16>& w2);

}  // namespace tfu::dp
