// 4-lane address stage of the golden sampler's LINEAR batch (speed only, SSE2; sampler_fast.cpp,
// Sampler::FastPaths::batch). Plain twins, which each lane must equal bit for bit:
//   texel_coord4    dp::texel_coord (cmodel/datapath.hpp: float_to_fixed_fast, cmodel/fixed_coord.hpp)
//   texel_coord4_pow2  texel_coord4 on a power-of-two extent, in binary32 (four lanes a register)
//   row_offset4_pow2   row_offset4 (y w) on a power-of-two w: a shift
//   wrap2x4         dp::fast::wrap_taps<kW, 2> (datapath_fast.hpp; wrap_run, texture.hpp); on repeat
//                   over an extent other than a power of two, repeat_remainder4 (wrap_index's floor mod)
// Equality tests: TexelCoord4.EqualsTexelCoordOnEveryExponent, TexelCoord4.Pow2EqualsTexelCoord,
// TexelCoord4.WrapEqualsWrapTaps,
// TexelCoord4.RepeatRemainderEqualsWrapIndex
// (testbench/test_texel_coord4.cpp); through the batch, Properties.BatchQuadsEqualPlainPath and
// BatchEqualsSample. Off with the fast-path switch (TFU_PLAIN=1) with the rest of the batch.
//
// The coordinate unit computes u = floor(x W 2^8) - 2^7 (then i0 = u >> 8, f = u & 255) for four
// coordinates x on one extent W at once, in binary64: x (a 24-bit significand) times W 2^8 (W <=
// 2^15, so at most 15 significant bits) has at most 39 significant bits and is exact; adding 1.5
// 2^52 rounds it to an integer r (|x W 2^8| < 2^51) in whatever rounding mode is set, r > x W 2^8
// moves it down by one (floor), and the integer is read from the sum's low bits (bits(sum) -
// bits(1.5 2^52)). No value is rounded on the way, so the result is float_to_fixed's exact floor.
// The unit takes a lane whose x is zero or normal with |x| < 2^15 (exponent field <= 141): then
// |x W| < 2^30 and i0 fits 32 bits. NaN, infinities, denormals and |x| >= 2^15 are left to the
// plain unit (texel_coord4_lanes gives which lanes the unit takes); denormals so that the result
// does not depend on MXCSR's DAZ (denormal inputs read as zero), which the integer twin ignores.
#pragma once

#if defined(__SSE2__)
#include <emmintrin.h>

#include <bit>
#include <climits>
#include <cstdint>

#include "cmodel/datapath.hpp"
#include "cmodel/texture.hpp"

namespace tfu::dp::fast {

// Four coordinates as binary64 (exact), lanes 0-1 and 2-3: formed once per group, used per level.
struct Coords4d {
  __m128d lo, hi;
};
[[gnu::always_inline]] inline Coords4d widen4(__m128 x) { return {_mm_cvtps_pd(x), _mm_cvtps_pd(_mm_movehl_ps(x, x))}; }

// Bit k set where lane k of x is one the unit takes (zero, or normal with exponent field <= 141).
[[gnu::always_inline]] inline int texel_coord4_lanes(__m128 x) {
  const __m128i a = _mm_and_si128(_mm_castps_si128(x), _mm_set1_epi32(0x7FFFFFFF));
  const __m128i normal = _mm_and_si128(_mm_cmpgt_epi32(a, _mm_set1_epi32(0x007FFFFF)),
                                       _mm_cmplt_epi32(a, _mm_set1_epi32(142 << 23)));
  return _mm_movemask_ps(_mm_castsi128_ps(_mm_or_si128(normal, _mm_cmpeq_epi32(a, _mm_setzero_si128()))));
}

// i0 and f of dp::texel_coord in 32-bit lanes.
struct TexelCoords4 {
  __m128i i0, f;
};
// dp::texel_coord(x_k, size) for the four lanes (defined on the lanes texel_coord4_lanes takes).
[[gnu::always_inline]] inline TexelCoords4 texel_coord4(const Coords4d& x, int size) {
  static_assert(kSubTexelBits == 8);
  const __m128d scale = _mm_set1_pd(static_cast<double>(size) * (1 << kSubTexelBits));
  constexpr double kRound = 0x1.8p52;  // 1.5 2^52: the sum's low bits hold the integer
  const __m128d c = _mm_set1_pd(kRound);
  // bits(sum) - bits(1.5 2^52) - 2^7 = r - 2^7
  const __m128i bias = _mm_set1_epi64x(std::bit_cast<int64_t>(kRound) + (int64_t{1} << (kSubTexelBits - 1)));
  const auto u2 = [&](__m128d v) __attribute__((always_inline)) {  // floor(v W 2^8) - 2^7, 64-bit lanes
    const __m128d t = _mm_mul_pd(v, scale);                           // exact
    const __m128d y = _mm_add_pd(t, c);                               // r + 1.5 2^52, r an integer next to t
    const __m128i above = _mm_castpd_si128(_mm_cmpgt_pd(_mm_sub_pd(y, c), t));  // r > t: -1
    return _mm_add_epi64(_mm_sub_epi64(_mm_castpd_si128(y), bias), above);
  };
  const __m128i u01 = u2(x.lo), u23 = u2(x.hi);  // |u| < 2^39
  const auto low32 = [](__m128i a, __m128i b) {  // the low 32 bits of the four 64-bit lanes
    return _mm_castps_si128(_mm_shuffle_ps(_mm_castsi128_ps(a), _mm_castsi128_ps(b), _MM_SHUFFLE(2, 0, 2, 0)));
  };
  // u >> 8 fits 32 bits, so its low 32 bits are the same for a logical and an arithmetic shift
  return {low32(_mm_srli_epi64(u01, kSubTexelBits), _mm_srli_epi64(u23, kSubTexelBits)),
          _mm_and_si128(low32(u01, u23), _mm_set1_epi32((1 << kSubTexelBits) - 1))};
}

// texel_coord4 on a power-of-two extent W = 2^k in binary32 (fast path of texel_coord4; plain twins
// texel_coord4 and dp::texel_coord; equality test TexelCoord4.Pow2EqualsTexelCoord): for a lane the
// unit takes (texel_coord4_lanes: zero, or normal with |x| < 2^15), y = x 2^(k + 8) is exact in
// binary32 (a multiply by a power of two whose result stays normal, below 2^38); when every lane's
// |y| < 2^30 (else it returns false and the caller takes texel_coord4), floor(y) is the truncation
// cvttps2dq (no rounding mode involved) less one where y is below the truncation read back as a
// float (exact: an integer of at most 24 significant bits, or y itself), and u = floor(y) - 2^7,
// i0 = u >> 8, f = u & 255 in 32-bit lanes (|u| < 2^30 + 2^7). No step rounds and none meets a
// denormal, so FTZ, DAZ and the rounding mode do not matter. Four lanes a register instead of two.
[[gnu::always_inline]] inline bool texel_coord4_pow2(__m128 x, int size, TexelCoords4& out) {
  static_assert(kSubTexelBits == 8);
  const __m128 y = _mm_mul_ps(x, _mm_set1_ps(static_cast<float>(size) * 256.0f));  // exact
  const __m128 ay = _mm_and_ps(y, _mm_castsi128_ps(_mm_set1_epi32(0x7FFFFFFF)));
  if (_mm_movemask_ps(_mm_cmplt_ps(ay, _mm_set1_ps(0x1p30f))) != 15) return false;
  const __m128i t = _mm_cvttps_epi32(y);
  const __m128i below = _mm_castps_si128(_mm_cmplt_ps(y, _mm_cvtepi32_ps(t)));  // y < trunc(y): -1
  const __m128i u = _mm_sub_epi32(_mm_add_epi32(t, below), _mm_set1_epi32(1 << (kSubTexelBits - 1)));
  out = {_mm_srai_epi32(u, kSubTexelBits), _mm_and_si128(u, _mm_set1_epi32((1 << kSubTexelBits) - 1))};
  return true;
}

// Whether wrap2x4 takes the mode (kWrap2x4) and, on this extent, the mode: repeat (on any extent
// from 1 to 2^15), the clamps (not mirrored repeat).
template <WrapMode kW>
inline constexpr bool kWrap2x4 = kW != WrapMode::MirroredRepeat;
template <WrapMode kW>
[[gnu::always_inline]] inline bool wrap2x4_takes(int) {
  return kWrap2x4<kW>;
}
// i mod size (the floor remainder, 0 <= r < size) for four lanes of any 32-bit i, 1 <= size <= 2^15:
// the remainder unit of repeat on an extent other than a power of two (wrap_index). In binary64:
// q, an integer within one of i / size (i times the rounded 1 / size, |error| < 2^-20, made an
// integer by adding and subtracting 1.5 2^52 in whatever rounding mode is set), then r = i - q size,
// exact (integers below 2^33 in magnitude), so -size <= r <= size; one add of size where r < 0 and
// one subtract where r = size bring it into 0..size - 1. No value depends on the rounding mode's
// choice of q, FTZ or DAZ (no denormal arises).
[[gnu::always_inline]] inline __m128i repeat_remainder4(__m128i i, int size) {
  const __m128d inv = _mm_set1_pd(1.0 / static_cast<double>(size)), w = _mm_set1_pd(static_cast<double>(size));
  const __m128d c = _mm_set1_pd(0x1.8p52);
  const auto half = [&](__m128d d) __attribute__((always_inline)) {
    const __m128d q = _mm_sub_pd(_mm_add_pd(_mm_mul_pd(d, inv), c), c);
    return _mm_cvttpd_epi32(_mm_sub_pd(d, _mm_mul_pd(q, w)));  // exact integers, |r| <= size
  };
  const __m128i r01 = half(_mm_cvtepi32_pd(i)), r23 = half(_mm_cvtepi32_pd(_mm_shuffle_epi32(i, _MM_SHUFFLE(1, 0, 3, 2))));
  const __m128i n = _mm_set1_epi32(size);
  __m128i r = _mm_unpacklo_epi64(r01, r23);
  r = _mm_add_epi32(r, _mm_and_si128(_mm_srai_epi32(r, 31), n));   // -size..-1: + size
  return _mm_andnot_si128(_mm_cmpeq_epi32(r, n), r);              // size: 0
}
// The wrap unit for taps i0 and i0 + 1 of four lanes (|i0| < 2^31 - 1): t0, t1 the wrapped taps as
// wrap_taps<kW, 2> gives them (clamp to border: -1 outside).
template <WrapMode kW>
[[gnu::always_inline]] inline void wrap2x4(__m128i i0, int size, __m128i& t0, __m128i& t1) {
  const __m128i i1 = _mm_add_epi32(i0, _mm_set1_epi32(1));
  if constexpr (kW == WrapMode::Repeat) {
    if ((size & (size - 1)) == 0) {  // a power of two: the low bits
      const __m128i m = _mm_set1_epi32(size - 1);
      t0 = _mm_and_si128(i0, m);
      t1 = _mm_and_si128(i1, m);
    } else {  // the remainder of i0, then the next tap as wrap_run steps it: t0 + 1, or 0 at the extent
      t0 = repeat_remainder4(i0, size);
      const __m128i next = _mm_add_epi32(t0, _mm_set1_epi32(1));
      t1 = _mm_andnot_si128(_mm_cmpeq_epi32(next, _mm_set1_epi32(size)), next);
    }
  } else if constexpr (kW == WrapMode::ClampToEdge) {
    const __m128i hi = _mm_set1_epi32(size - 1);
    const auto clamp = [&](__m128i i) {  // max(0, min(i, size - 1)); |i - (size - 1)| < 2^31
      const __m128i d = _mm_sub_epi32(i, hi);
      const __m128i lo = _mm_add_epi32(hi, _mm_and_si128(d, _mm_srai_epi32(d, 31)));
      return _mm_andnot_si128(_mm_srai_epi32(lo, 31), lo);
    };
    // The second tap from the first: clamp(i0 + 1) = clamp(i0) + 1 where 0 <= i0 < size - 1 (an
    // unsigned compare: signed after flipping the sign bits), else clamp(i0) (both 0 below the
    // extent, both size - 1 at and above its last texel).
    const __m128i sign = _mm_set1_epi32(INT32_MIN);
    const __m128i inside = _mm_cmpgt_epi32(_mm_xor_si128(hi, sign), _mm_xor_si128(i0, sign));  // -1 where 0 <= i0 < size - 1
    t0 = clamp(i0);
    t1 = _mm_sub_epi32(t0, inside);
    (void)i1;
  } else {
    static_assert(kW == WrapMode::ClampToBorder);
    const __m128i n = _mm_set1_epi32(size);
    const auto inside = [&](__m128i i) {  // 0 <= i < size ? i : -1
      const __m128i in = _mm_and_si128(_mm_cmpgt_epi32(i, _mm_set1_epi32(-1)), _mm_cmpgt_epi32(n, i));
      return _mm_or_si128(i, _mm_xor_si128(in, _mm_set1_epi32(-1)));
    };
    t0 = inside(i0);
    t1 = inside(i1);
  }
}

// y w for four lanes 0 <= y < 2^15, 0 < w <= 2^15 (pmuludq on lanes 0, 2 and 1, 3).
[[gnu::always_inline]] inline __m128i row_offset4(__m128i y, __m128i w) {
  const __m128i even = _mm_mul_epu32(y, w), odd = _mm_mul_epu32(_mm_srli_epi64(y, 32), w);
  return _mm_unpacklo_epi32(_mm_shuffle_epi32(even, _MM_SHUFFLE(3, 1, 2, 0)), _mm_shuffle_epi32(odd, _MM_SHUFFLE(3, 1, 2, 0)));
}

// row_offset4 on a power-of-two w = 2^log2w: y << log2w (fast path of row_offset4, its plain twin;
// equality test TexelCoord4.RowOffsetEqualsProduct): one shift instead of two pmuludq and shuffles.
[[gnu::always_inline]] inline __m128i row_offset4_pow2(__m128i y, int log2w) { return _mm_sll_epi32(y, _mm_cvtsi32_si128(log2w)); }

}  // namespace tfu::dp::fast

#endif
