// Per-stage arithmetic of the filter datapath, shared by the golden sampler (sampler.cpp) and the
// cycle model's pipeline stages (rtl/): one definition of every width and rounding
// (docs/sampler.md). Nothing here knows about cycles. The fast paths' speed-only forms of these
// units (on 8-bit texel words, wrap modes fixed at compile time) are in datapath_fast.hpp.
#pragma once

#include <array>
#include <cstdint>

#include "cmodel/fixed_coord.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/weight_rom.hpp"

namespace tfu::dp {

// Address generator: u = floor(s W 2^8) - 128 (Q.8, texel centres at integers); i0 = u >> 8 is
// the tap left of / above the sample point, f = u & 255 the 8-bit subtexel fraction.
// kSubTexelBits is the fraction's width (Vulkan's subTexelPrecisionBits, cmodel/api_limits.hpp).
inline constexpr int kSubTexelBits = 8;
struct LevelCoord {
  int64_t i0;
  uint32_t f;
};
[[gnu::always_inline]] inline LevelCoord texel_coord(float s, int size) {
  const int64_t u =
      float_to_fixed_fast(s, static_cast<uint32_t>(size), kSubTexelBits) - (int64_t{1} << (kSubTexelBits - 1));
  return {u >> kSubTexelBits, static_cast<uint32_t>(u & ((int64_t{1} << kSubTexelBits) - 1))};
}

// Bilinear lerp unit: c = (sum c w + 2^15) >> 16 with w = (256 - fu | fu)(256 - fv | fv) in Q.16;
// taps ordered (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1).
inline Texel4 bilinear_lerp(const std::array<Texel4, 4>& c, uint32_t fu_, uint32_t fv_, TexelFormat fmt) {
  const auto fu = static_cast<int32_t>(fu_), fv = static_cast<int32_t>(fv_);
  const std::array<int32_t, 4> w{(256 - fu) * (256 - fv), fu * (256 - fv), (256 - fu) * fv, fu * fv};
  Texel4 out{};
  if (fmt != TexelFormat::VS16X2) {  // 8-bit (SRGBA8: 12-bit) channels: 12 + 16 bits fit 32
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

// Level results in Q.8 for the trilinear blend unit: a level's filtered channels with
// kLevelFracBits fraction bits (code x 2^8 + fraction), so that *_MIPMAP_LINEAR rounds once, in the
// blend, and not once per level and again in the blend (which left Vulkan's bounds by one code,
// docs/sampler.md "Within the spec's bounds"). The bilinear lerp unit gives its Q.16 sum's top bits
// (the lower 8 dropped: round_level of it is bilinear_lerp, so a level that is not blended keeps its
// code); NEAREST, CUBIC and EDGE_PRESERVING give their codes with a zero fraction (level_q8).
inline constexpr int kLevelFracBits = 8;
inline Texel4 bilinear_lerp_q8(const std::array<Texel4, 4>& c, uint32_t fu_, uint32_t fv_) {
  const auto fu = static_cast<int64_t>(fu_), fv = static_cast<int64_t>(fv_);
  const std::array<int64_t, 4> w{(256 - fu) * (256 - fv), fu * (256 - fv), (256 - fu) * fv, fu * fv};
  Texel4 out{};
  for (size_t ch = 0; ch < 4; ++ch)  // floor: an arithmetic shift (VS16X2 channels are signed)
    out[ch] = static_cast<int32_t>((c[0][ch] * w[0] + c[1][ch] * w[1] + c[2][ch] * w[2] + c[3][ch] * w[3]) >>
                                   (16 - kLevelFracBits));
  return out;
}
inline Texel4 level_q8(const Texel4& c) {
  Texel4 out{};
  for (size_t ch = 0; ch < 4; ++ch) out[ch] = c[ch] * (1 << kLevelFracBits);
  return out;
}
// A Q.8 level result rounded to a code, half up: (q + 2^7) >> 8 (round_level(bilinear_lerp_q8) ==
// bilinear_lerp: floor(floor(S / 2^8) + 2^7) / 2^8) = floor((S + 2^15) / 2^16)).
inline Texel4 round_level(const Texel4& q) {
  Texel4 out{};
  for (size_t ch = 0; ch < 4; ++ch) out[ch] = (q[ch] + (1 << (kLevelFracBits - 1))) >> kLevelFracBits;
  return out;
}

// Trilinear blend unit on Q.8 level results: c = (c0 (256 - f) + c1 f + 2^15) >> 16, f = the weight
// of level1 (Q.8), one rounding half up. 8-bit channels: c0, c1 < 2^16, the sum < 2^24; VS16X2's
// signed 16-bit channels take 64 bits.
inline Texel4 level_blend(const Texel4& c0_q8, const Texel4& c1_q8, int f) {
  Texel4 out{};
  for (size_t ch = 0; ch < 4; ++ch)
    out[ch] = static_cast<int32_t>(
        (int64_t{c0_q8[ch]} * (256 - f) + int64_t{c1_q8[ch]} * f + (int64_t{1} << (7 + kLevelFracBits))) >>
        (8 + kLevelFracBits));
  return out;
}
// The blend unit fed two codes (fraction zero): level_blend(level_q8(c0), level_q8(c1), f), which is
// (c0 (256 - f) + c1 f + 128) >> 8 (what the SystemVerilog tfu_level_blend computes).
inline Texel4 level_blend_codes(const Texel4& c0, const Texel4& c1, int f) {
  return level_blend(level_q8(c0), level_q8(c1), f);
}

// Cubic weight stage: the 2D weights of the separable tiled-ROM filter (T x T taps, T <= 4):
// tile-weight multipliers for all taps but the centre one (offset (0, 0)), which takes the
// complement so that the weights sum to exactly M = 2^b - 1.
void tile_weights_2d(const TileWeightRom& rom, RomRecon recon, uint32_t fu, uint32_t fv, std::array<int32_t, 16>& w2);

// Cubic adder tree: acc = sum over the n = T x T taps of c w, per channel (exact: 8-bit channels
// and b <= 16 bit weights stay below 2^31; VS16X2 below 2^40).
inline std::array<int64_t, 4> cubic_accumulate(const Texel4* c, const int32_t* w, int n) {
  std::array<int64_t, 4> acc{};
  for (int k = 0; k < n; ++k)
    for (size_t ch = 0; ch < 4; ++ch) acc[ch] += int64_t{c[k][ch]} * w[k];
  return acc;
}

inline int64_t floor_div(int64_t a, int64_t b) {  // b > 0
  const int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

// Cubic normalise-and-clamp stage (docs/sampler.md): weights at scale M = 2^b - 1.
//   plain kernels   : out = clamp(floor((2 acc + M) / (2 M)))
//   bspline-interp  : out = clamp(floor((acc S + B M + M 2^11) / (M 2^12))), S and B the texture's
//                     scale/bias registers (Q.12) of the stored coefficient codes
struct CubicNormalize {
  int64_t M = 255;
  bool prefiltered = false;
  int64_t scale_q = 0, bias_q = 0;
  int32_t lo = 0, hi = 255;  // channel range of the format
};
inline constexpr int kBsplineScaleBits = 12;
inline Texel4 cubic_normalize(const std::array<int64_t, 4>& acc, const CubicNormalize& n) {
  const auto clamp_ch = [lo = n.lo, hi = n.hi](int64_t v) { return static_cast<int32_t>(v < lo ? lo : (v > hi ? hi : v)); };
  if (n.prefiltered) {
    const int64_t den = n.M << kBsplineScaleBits;
    const auto dec = [&](int64_t a) { return clamp_ch(floor_div(a * n.scale_q + n.bias_q * n.M + den / 2, den)); };
    return {dec(acc[0]), dec(acc[1]), dec(acc[2]), dec(acc[3])};
  }
  if (n.M == 255) {  // the default 8-bit ROM: a constant divisor (the compiler multiplies)
    const auto n8 = [&](int64_t a) { return clamp_ch(floor_div(2 * a + 255, 510)); };
    return {n8(acc[0]), n8(acc[1]), n8(acc[2]), n8(acc[3])};
  }
  const auto nb = [&](int64_t a) { return clamp_ch(floor_div(2 * a + n.M, 2 * n.M)); };
  return {nb(acc[0]), nb(acc[1]), nb(acc[2]), nb(acc[3])};
}

}  // namespace tfu::dp
