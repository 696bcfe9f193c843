// Speed-only form of the LOD unit's input stage on a quad (derivatives_from_quad, lod.cpp): the
// texel-space derivatives du/dx, dv/dx, du/dy, dv/dy of a 2x2 quad in Q.16 level-0 texels. Plain
// twin: derivatives_from_quad_plain (lod.cpp: float_to_fixed_fast of s W and t H per pixel, then
// differences). Equality tests: LodFast.* in testbench/test_lod_fast.cpp (the conversion of one
// value against float_to_fixed for every exponent and sign, boundary and random mantissas and every
// kind of scale; random and special quads through both forms). derivatives_from_quad (the one
// function the renderer, the cycle model's LOD unit and rtl::golden_outputs call) takes this form
// unless the fast-path switch is off (cmodel/fast_paths.hpp: TFU_PLAIN=1, the CLI's --plain).
//
// Why it is the same: float_to_fixed(x, scale, 16) is floor(x scale 2^16) saturated to
// +-kFixedLimit = +-2^46, and 0 for a NaN (fixed_coord.hpp). In double precision every step of that
// is exact for every FP32 x and scale in 1..2^15:
//   - x widens to double exactly (denormals included); scale 2^16 <= 2^31 is a double exactly;
//   - x (scale 2^16) is exact: a 24-bit significand times an integer of at most 16 significant bits
//     (times a power of two) has at most 40 significant bits < 53, and its exponent stays within
//     [-149, 128 + 31] (no overflow, no underflow); +-Inf stays +-Inf;
//   - a NaN lane is masked to +0 (cmpord), then clamped to [-2^46, 2^46] (min/max, exact): the
//     clamp commutes with floor because the bounds are integers;
//   - floor of a clamped v (|v| <= 2^46 < 2^51): r = (v + M) - M with M = 1.5 * 2^52 is v rounded
//     to the nearest integer (v + M lies in [2^52, 2^53), where the spacing of doubles is 1), and
//     floor(v) = r - (r > v);
//   - the differences of two such integers (|.| <= 2^47) are exact, and an integer d with
//     |d| < 2^51 is the int64 bits(d + M) - bits(M) (d + M's significand holds d + 2^51).
// Two lanes per SSE2 register (SSE2 is part of x86-64; packed double operations round each lane as
// the scalar ones do); elsewhere the plain twin stands in.
#pragma once

#include <bit>
#include <cstdint>

#include "cmodel/lod.hpp"

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define TFU_LOD_FAST_SSE2 1
#endif

namespace tfu::lod_fast {

#if TFU_LOD_FAST_SSE2
namespace detail {

inline constexpr double kMagic = 6755399441055744.0;  // 1.5 * 2^52
inline constexpr double kLimit = 70368744177664.0;    // 2^46 = kFixedLimit

// floor(v) of each lane of v = x scale 2^16 (exact), NaN -> 0, saturated to +-2^46; as doubles.
[[gnu::always_inline]] inline __m128d fixed_q16(__m128d v) {
  v = _mm_and_pd(v, _mm_cmpord_pd(v, v));
  v = _mm_max_pd(_mm_min_pd(v, _mm_set1_pd(kLimit)), _mm_set1_pd(-kLimit));
  const __m128d m = _mm_set1_pd(kMagic);
  const __m128d r = _mm_sub_pd(_mm_add_pd(v, m), m);
  return _mm_sub_pd(r, _mm_and_pd(_mm_cmpgt_pd(r, v), _mm_set1_pd(1.0)));
}

// Integer-valued lanes, |d| < 2^51, as int64 lanes.
[[gnu::always_inline]] inline __m128i to_int64(__m128d d) {
  const __m128d m = _mm_set1_pd(kMagic);
  return _mm_sub_epi64(_mm_castpd_si128(_mm_add_pd(d, m)), _mm_castpd_si128(m));
}

// Pixels 0, 1, 2 of the quad in Q.16 level-0 texels, (u, v) a register: fixed_q16 of s W and t H.
[[gnu::always_inline]] inline void quad_positions(const float s[4], const float t[4], int width, int height, __m128d& p0,
                                                  __m128d& p1, __m128d& p2) {
  const __m128 sv = _mm_loadu_ps(s), tv = _mm_loadu_ps(t);
  const __m128 st01 = _mm_unpacklo_ps(sv, tv), st23 = _mm_unpackhi_ps(sv, tv);  // s0 t0 s1 t1, s2 t2 s3 t3
  const __m128d scale = _mm_set_pd(static_cast<double>(height) * 65536.0, static_cast<double>(width) * 65536.0);
  p0 = fixed_q16(_mm_mul_pd(_mm_cvtps_pd(st01), scale));                      // u0 v0
  p1 = fixed_q16(_mm_mul_pd(_mm_cvtps_pd(_mm_movehl_ps(st01, st01)), scale));  // u1 v1
  p2 = fixed_q16(_mm_mul_pd(_mm_cvtps_pd(st23), scale));                      // u2 v2
}

}  // namespace detail

// = float_to_fixed(x, scale, 16) (the lane form above on one value; what the tests sweep).
inline int64_t to_fixed_q16(float x, uint32_t scale) {
  using namespace detail;
  const __m128d v = _mm_mul_sd(_mm_cvtss_sd(_mm_setzero_pd(), _mm_set_ss(x)), _mm_set_sd(static_cast<double>(scale) * 65536.0));
  return _mm_cvtsi128_si64(to_int64(fixed_q16(v)));
}

// = derivatives_from_quad_plain(s, t, width, height) for width, height in 1..2^15.
inline TexelDerivatives derivatives_from_quad(const float s[4], const float t[4], int width, int height) {
  using namespace detail;
  __m128d p0, p1, p2;
  quad_positions(s, t, width, height, p0, p1, p2);
  TexelDerivatives d;
  static_assert(sizeof(TexelDerivatives) == 4 * sizeof(int64_t), "dudx, dvdx, dudy, dvdy in order");
  _mm_storeu_si128(reinterpret_cast<__m128i*>(&d.dudx), to_int64(_mm_sub_pd(p1, p0)));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(&d.dudy), to_int64(_mm_sub_pd(p2, p0)));
  return d;
}
#endif

#if !TFU_LOD_FAST_SSE2
inline int64_t to_fixed_q16(float x, uint32_t scale) { return float_to_fixed(x, scale, 16); }
inline TexelDerivatives derivatives_from_quad(const float s[4], const float t[4], int width, int height) {
  return derivatives_from_quad_plain(s, t, width, height);
}
#endif

// The renderer's lambda of a quad, inline (fast path; plain twin lambda_from_quad of lod.cpp with
// the fast paths off: lambda_from_derivatives(derivatives_from_quad_plain(...)); equality tests
// LodFast.LambdaFromLengthEqualsThePlainUnit, LodFast.LambdaFromQuadEqualsThePlainTwin). The same
// operations as lambda_from_length_sq and log2_q8 (lod.cpp) on the largest squared length, written
// here so that a caller holding the fast-path switch (cmodel/raster.cpp) pays no call, no read of
// the switch and no call of log2_rom() per quad; the ROM's address is read once (a local static).
inline int32_t lambda_from_length_sq(uint64_t rho2_q32) {
  if (rho2_q32 == 0) return kLodMinusInfinity;
  static const uint16_t* const rom = log2_rom().data();
  const int e = 63 - std::countl_zero(rho2_q32);  // leading-one detector
  const auto index = static_cast<uint32_t>(
      (e >= kLog2RomIndexBits ? rho2_q32 >> (e - kLog2RomIndexBits) : rho2_q32 << (kLog2RomIndexBits - e)) &
      ((1u << kLog2RomIndexBits) - 1));
  const int32_t l2 = (e << kLodFracBits) + rom[index] - (32 << kLodFracBits);  // log2(rho^2), Q.8
  return (l2 + 1) >> 1;                                                          // halve, round half up
}
// The squared lengths in SSE2 as well: the derivatives are the integer-valued doubles of
// derivatives_from_quad (|d| <= 2^47, exact), |d| clamped to 2^31 - 1 (andpd, minpd: exact) and
// converted to 32-bit integers (cvttpd2dq: exact), squared and summed in 64-bit lanes (pmuludq,
// paddq: |du|^2 + |dv|^2 < 2^63), as derivative_magnitude and derivative_length_sq.
inline int32_t lambda_from_quad(const float s[4], const float t[4], int width, int height) {
#if TFU_LOD_FAST_SSE2
  using namespace detail;
  __m128d p0, p1, p2;
  quad_positions(s, t, width, height, p0, p1, p2);
  const __m128d abs = _mm_castsi128_pd(_mm_set1_epi64x(INT64_MAX)), clamp = _mm_set1_pd(kDerivativeClamp);
  const auto magnitude = [&](__m128d d) __attribute__((always_inline)) {  // two 32-bit lanes, low half
    return _mm_cvttpd_epi32(_mm_min_pd(_mm_and_pd(d, abs), clamp));
  };
  const __m128i m = _mm_unpacklo_epi64(magnitude(_mm_sub_pd(p1, p0)), magnitude(_mm_sub_pd(p2, p0)));  // |dudx| |dvdx| |dudy| |dvdy|
  const __m128i sq = _mm_add_epi64(_mm_mul_epu32(m, m), _mm_mul_epu32(_mm_srli_epi64(m, 32), _mm_srli_epi64(m, 32)));
  const auto lx = static_cast<uint64_t>(_mm_cvtsi128_si64(sq)), ly = static_cast<uint64_t>(_mm_cvtsi128_si64(_mm_unpackhi_epi64(sq, sq)));
#else
  const TexelDerivatives d = derivatives_from_quad(s, t, width, height);
  const uint64_t lx = derivative_length_sq(d.dudx, d.dvdx), ly = derivative_length_sq(d.dudy, d.dvdy);
#endif
  return lambda_from_length_sq(lx > ly ? lx : ly);
}

}  // namespace tfu::lod_fast
