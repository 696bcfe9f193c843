// LOD unit (Pharr, GPU Gems ch. 25; GL 4.6 Sec. 8.14): level of detail lambda per 2x2 pixel quad,
// per explicit-gradient request or per explicit-LOD request, in fixed point.
//
// Datapath (all integer; see docs/sampler.md, "LOD unit"):
//   u_i = floor(s_i W 2^16), v_i = floor(t_i H 2^16)       texel coordinates, Q.16 (fixed_coord.hpp)
//   coarse quad derivatives (one lambda per quad, pixel (0,0) is the reference):
//     du/dx = u(1,0) - u(0,0)   dv/dx = v(1,0) - v(0,0)   du/dy = u(0,1) - u(0,0)   dv/dy = v(0,1) - v(0,0)
//   each magnitude clamped to 2^31 - 1 (>= 2^15 texels: beyond any level)
//   rho^2 = max(du/dx^2 + dv/dx^2, du/dy^2 + dv/dy^2)   GL vector lengths, squared; Q.32, uint64
//   log2(rho) = log2(rho^2) / 2   -> no square root: the log2 unit works on the squared length
//   lambda = round_half_up(log2_q8(rho^2) / 2) - 16 * 256 + bias, clamped to [min_lod, max_lod]
// lambda is a signed Q.8 number (1/256 of a level).
//
// log2 unit: leading-one detector gives the integer part e; the 9 bits below the leading one address
// a 512 x 9-bit ROM holding round(256 log2(1 + (k + 1/2) / 512)) (nearest-centred entries); bits
// below those are dropped. |error| <= 256 (log2(1 + 1/1024)) + 1/2 LSB < 0.9 LSB = 0.9/256 of a level
// (tested exhaustively over 2^24 inputs and at every power of two).
#pragma once

#include <array>
#include <cstdint>

namespace tfu {

inline constexpr int kLodFracBits = 8;                       // lambda in Q.8
inline constexpr int32_t kLodMinusInfinity = -(64 << 8);     // log2(0)
inline constexpr int kLog2RomIndexBits = 9;

// 512 entries of 9 bits (0..256: the last entries round up to 1.0).
const std::array<uint16_t, 1u << kLog2RomIndexBits>& log2_rom();
// log2(x) in Q.8 for x >= 1; kLodMinusInfinity for x == 0.
int32_t log2_q8(uint64_t x);

struct LodParams {
  int32_t bias_q8 = 0;
  int32_t min_lod_q8 = -1000 * 256;
  int32_t max_lod_q8 = 1000 * 256;
  friend constexpr bool operator==(const LodParams&, const LodParams&) = default;
};

// Texel-space derivatives of a quad or a gradient request: Q.16 level-0 texels, as the input
// stage computes them (float_to_fixed_fast of s W, t H; differences for a quad). The anisotropic
// LOD unit (aniso.hpp) starts from the same values.
struct TexelDerivatives {
  int64_t dudx = 0, dvdx = 0, dudy = 0, dvdy = 0;
};
// derivatives_from_quad is the input stage of every model (the renderer, the cycle model's LOD unit,
// rtl::golden_outputs): its speed-only form (lod_fast.hpp) unless the fast paths are off
// (fast_paths.hpp), else its plain twin derivatives_from_quad_plain; equal for every input (LodFast.*).
TexelDerivatives derivatives_from_quad(const float s[4], const float t[4], int width, int height);
TexelDerivatives derivatives_from_quad_plain(const float s[4], const float t[4], int width, int height);
TexelDerivatives derivatives_from_gradients(float dsdx, float dtdx, float dsdy, float dtdy, int width, int height);

// |d| clamped to 2^31 - 1 (>= 2^15 texels in Q.16: beyond any level); 31 bits.
inline constexpr uint32_t kDerivativeClamp = (uint32_t{1} << 31) - 1;
inline uint32_t derivative_magnitude(int64_t d) {
  const uint64_t m = d < 0 ? uint64_t{0} - static_cast<uint64_t>(d) : static_cast<uint64_t>(d);
  return m > kDerivativeClamp ? kDerivativeClamp : static_cast<uint32_t>(m);
}
// Squared length of a derivative vector: |du|^2 + |dv|^2 of the clamped magnitudes, Q.32, < 2^63.
inline uint64_t derivative_length_sq(int64_t du, int64_t dv) {
  const uint64_t a = derivative_magnitude(du), b = derivative_magnitude(dv);
  return a * a + b * b;
}
// lambda = log2(rho / D) from rho^2 (Q.32) and log2(D^2) in Q.8 (0 for the isotropic D = 1):
// (log2_q8(rho^2) - 32 * 256 - log2_div_sq_q8 + 1) >> 1; kLodMinusInfinity for rho^2 = 0.
int32_t lambda_from_length_sq(uint64_t rho2_q32, int32_t log2_div_sq_q8 = 0);

// Texel-space derivative lengths -> lambda (before bias/clamp). Derivatives in Q.16 texels.
int32_t lambda_from_derivatives(int64_t dudx, int64_t dvdx, int64_t dudy, int64_t dvdy);
inline int32_t lambda_from_derivatives(const TexelDerivatives& d) {
  return lambda_from_derivatives(d.dudx, d.dvdx, d.dudy, d.dvdy);
}
// A 2x2 quad: s[k], t[k] for pixels (0,0), (1,0), (0,1), (1,1). width/height of level 0.
int32_t lambda_from_quad(const float s[4], const float t[4], int width, int height);
// textureGrad: explicit derivatives of s and t.
int32_t lambda_from_gradients(float dsdx, float dtdx, float dsdy, float dtdy, int width, int height);
// textureLod: explicit lambda (nearest Q.8 value).
int32_t lambda_explicit(float lod);
// lambda' = clamp(lambda + bias, min_lod, max_lod) (GL Eq. 8.6 order: bias, then clamp).
// Names: `lambda_q8` is lambda before bias and clamp (Q.8) everywhere; the result of this function
// is `lambda_clamped_q8` (LodInfo, select_levels).
constexpr int32_t lambda_bias_clamp(int32_t lambda_q8, const LodParams& p) {
  const int64_t l = int64_t{lambda_q8} + p.bias_q8;
  return static_cast<int32_t>(l < p.min_lod_q8 ? p.min_lod_q8 : (l > p.max_lod_q8 ? p.max_lod_q8 : l));
}

}  // namespace tfu
