// Speed-only forms of datapath.hpp's units, for the fast paths of the golden sampler
// (sampler_fast.cpp) and of the cycle model (rtl/filter_unit's 8-bit word LINEAR, the recurrences'
// LINEAR quad path, rtl/address_gen_fixed_grids.cpp). Each equals its plain twin bit for bit; the
// plain twins are the reference and what the SystemVerilog implements:
//   bilinear_lerp8, bilinear_lerp8_words  dp::bilinear_lerp + encode_texel
//   bilinear_lerp8x4                      bilinear_lerp8 per lane (four requests at once)
//   level_blend8                          dp::level_blend_codes + encode_texel (codes: CUBIC, EDGE)
//   bilinear_lerp8q                       dp::bilinear_lerp_q8 (four 16-bit Q.8 channels)
//   level_blend8q                         dp::level_blend + encode_texel (Q.8 inputs: LINEAR)
//   bilinear_blend8x4                     bilinear_lerp8q of two levels + level_blend8q per lane
//   wrap_taps                             wrap_run (texture.hpp), the mode fixed at compile time
// Tests: Properties.WordLerpAndBlendEqualChannelDatapath, Properties.QuadLerpEqualsScalarLerp and
// Properties.QuadLerpBlendEqualsScalarUnits (the units), Properties.FastPathsEqualPlainPath and TfuUnit.FixedWrapGridsEqualThePlainAddressUnit
// (their users). The fast-path switch (cmodel/fast_paths.hpp: TFU_PLAIN=1, the CLI's --plain) turns
// every user over to the plain twins.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "cmodel/texture.hpp"

namespace tfu::dp::fast {

// Wrap unit for the n taps start, start + 1, ... of one row or column with the mode fixed at
// compile time (wrap_run with the mode's branches folded away): repeat on a power-of-two extent
// keeps the low bits, the clamps select per tap; anything else takes wrap_run (texture.hpp).
template <WrapMode kW, int n>
[[gnu::always_inline]] inline void wrap_taps(int64_t start, int size, int* out) {
  if constexpr (kW == WrapMode::Repeat) {
    if ((size & (size - 1)) == 0) {
      for (int k = 0; k < n; ++k) out[k] = static_cast<int>((start + k) & (size - 1));
      return;
    }
  } else if constexpr (kW == WrapMode::ClampToEdge) {
    for (int k = 0; k < n; ++k) out[k] = static_cast<int>(start + k < 0 ? 0 : start + k >= size ? size - 1 : start + k);
    return;
  } else if constexpr (kW == WrapMode::ClampToBorder) {
    for (int k = 0; k < n; ++k) out[k] = start + k >= 0 && start + k < size ? static_cast<int>(start + k) : -1;
    return;
  }
  wrap_run(kW, start, n, size, out);
}

// The bilinear lerp and trilinear blend units on 8-bit texel words (RGBA8, L8: channels 0..255, so
// the result needs no clamp and encode_texel is the identity). Bit-identical to dp::bilinear_lerp /
// dp::level_blend followed by encode_texel (tested, both forms of the lerp).
//   bilinear: sum c w with w = (256 - fu | fu)(256 - fv | fv) = gv (a gu + b fu) + fv (c gu + d fu),
//   a horizontal lerp at most 255 * 256 < 2^16, the vertical one < 2^24, then (+ 2^15) >> 16.
// Portable form: two channels per 64-bit word, exact in 32-bit lanes.
inline uint64_t word_lanes_rb(Rgba8 x) { return uint64_t{x.r} | (uint64_t{x.b} << 32); }  // (R, B)
inline uint64_t word_lanes_ga(Rgba8 x) { return uint64_t{x.g} | (uint64_t{x.a} << 32); }  // (G, A)
inline Rgba8 bilinear_lerp8_words(Rgba8 a, Rgba8 b, Rgba8 c, Rgba8 d, uint32_t fu_, uint32_t fv_) {
  const uint64_t fu = fu_, fv = fv_, gu = 256 - fu, gv = 256 - fv;
  constexpr uint64_t kHalf = (uint64_t{1} << 15) | (uint64_t{1} << 47);
  const uint64_t rb = gv * (word_lanes_rb(a) * gu + word_lanes_rb(b) * fu) +
                      fv * (word_lanes_rb(c) * gu + word_lanes_rb(d) * fu) + kHalf;
  const uint64_t ga = gv * (word_lanes_ga(a) * gu + word_lanes_ga(b) * fu) +
                      fv * (word_lanes_ga(c) * gu + word_lanes_ga(d) * fu) + kHalf;
  return {static_cast<uint8_t>(rb >> 16), static_cast<uint8_t>(ga >> 16), static_cast<uint8_t>(rb >> 48),
          static_cast<uint8_t>(ga >> 48)};
}
// With SSE2 (every x86-64) the four channels of one sample go side by side in 16-bit lanes, the
// horizontal lerps (h0, h1) = (a, c) gu + (b, d) fu exact, the vertical one the biased pmaddwd of
// bilinear_lerp8x4 below; elsewhere the portable form.
[[gnu::always_inline]] inline Rgba8 bilinear_lerp8(Rgba8 a, Rgba8 b, Rgba8 c, Rgba8 d, uint32_t fu_, uint32_t fv_) {
#if defined(__SSE2__)
  const auto pair = [](Rgba8 x, Rgba8 y) {  // 16-bit lanes: x.r x.g x.b x.a y.r y.g y.b y.a
    const __m128i w = _mm_unpacklo_epi32(_mm_cvtsi32_si128(std::bit_cast<int32_t>(x)), _mm_cvtsi32_si128(std::bit_cast<int32_t>(y)));
    return _mm_unpacklo_epi8(w, _mm_setzero_si128());
  };
  const auto fu = static_cast<int16_t>(fu_);
  const __m128i h = _mm_add_epi16(_mm_mullo_epi16(pair(a, c), _mm_set1_epi16(static_cast<int16_t>(256 - fu))),
                                  _mm_mullo_epi16(pair(b, d), _mm_set1_epi16(fu)));  // (h0, h1) per channel
  const __m128i hb = _mm_xor_si128(h, _mm_set1_epi16(static_cast<int16_t>(0x8000)));  // h - 2^15
  const __m128i h01 = _mm_unpacklo_epi16(hb, _mm_srli_si128(hb, 8));                  // (h0, h1) pairs per channel
  const __m128i v = _mm_madd_epi16(h01, _mm_set1_epi32(static_cast<int32_t>((uint32_t{fv_} << 16) | (256 - fv_))));
  const __m128i ch = _mm_srli_epi32(_mm_add_epi32(v, _mm_set1_epi32((1 << 23) + (1 << 15))), 16);  // 4 x 0..255
  const __m128i bytes = _mm_packus_epi16(_mm_packs_epi32(ch, ch), _mm_setzero_si128());
  return std::bit_cast<Rgba8>(_mm_cvtsi128_si32(bytes));
#else
  return bilinear_lerp8_words(a, b, c, d, fu_, fv_);
#endif
}

// Four bilinear lerp units side by side (lane k = request k, as the unit filters a 2x2 quad's
// samples together): out[k] = bilinear_lerp8(a[k], b[k], c[k], d[k], fu[k], fv[k]), bit for bit
// (tested over every fraction pair). With SSE2 (every x86-64) the lanes are 32-bit texel words:
//   horizontal: h = a gu + b fu <= 255 * 256 < 2^16, exact in 16-bit lanes, (R, B) and (G, A);
//   vertical:   h0 gv + h1 fv = pmaddwd([h0 - 2^15, h1 - 2^15], [gv, fv]) + 2^15 * 256 (gv + fv
//               = 256), the biased h fitting signed 16 bits; then (+ 2^15) >> 16 as in the scalar unit.
// Elsewhere, the scalar unit per lane.
struct Quad8 {
  std::array<Rgba8, 4> a, b, c, d;  // taps (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1) per lane
  std::array<uint32_t, 4> fu, fv;   // 8-bit fractions per lane
};
#if defined(__SSE2__)
// The four lanes in registers: a, b, c, d hold the lanes' texel words, fu and fv their fractions
// in 32-bit lanes; returns the four result words.
[[gnu::always_inline]] inline __m128i bilinear_lerp8x4_lanes(__m128i a, __m128i b, __m128i c, __m128i d, __m128i fu,
                                                             __m128i fv) {
  const __m128i lo8 = _mm_set1_epi32(0x00FF00FF);
  const __m128i fu2 = _mm_or_si128(fu, _mm_slli_epi32(fu, 16));       // (fu, fu) per word
  const __m128i gu2 = _mm_sub_epi16(_mm_set1_epi16(256), fu2);         // (256 - fu, 256 - fu)
  const auto hlerp = [&](__m128i x, __m128i y, bool ga) {              // x gu + y fu - 2^15, 16-bit lanes
    const __m128i xs = ga ? _mm_srli_epi16(x, 8) : _mm_and_si128(x, lo8);
    const __m128i ys = ga ? _mm_srli_epi16(y, 8) : _mm_and_si128(y, lo8);
    const __m128i h = _mm_add_epi16(_mm_mullo_epi16(xs, gu2), _mm_mullo_epi16(ys, fu2));
    return _mm_xor_si128(h, _mm_set1_epi16(static_cast<int16_t>(0x8000)));
  };
  const __m128i gvfv = _mm_or_si128(_mm_sub_epi32(_mm_set1_epi32(256), fv), _mm_slli_epi32(fv, 16));
  const __m128i wlo = _mm_unpacklo_epi32(gvfv, gvfv), whi = _mm_unpackhi_epi32(gvfv, gvfv);  // lanes 0-1, 2-3
  const __m128i round = _mm_set1_epi32((1 << 23) + (1 << 15));
  const auto vlerp = [&](__m128i h0, __m128i h1) {  // 16-bit channel results, lanes 0..3
    const __m128i l = _mm_madd_epi16(_mm_unpacklo_epi16(h0, h1), wlo);
    const __m128i h = _mm_madd_epi16(_mm_unpackhi_epi16(h0, h1), whi);
    return _mm_packs_epi32(_mm_srli_epi32(_mm_add_epi32(l, round), 16), _mm_srli_epi32(_mm_add_epi32(h, round), 16));
  };
  const __m128i rb = vlerp(hlerp(a, b, false), hlerp(c, d, false));
  const __m128i ga = vlerp(hlerp(a, b, true), hlerp(c, d, true));
  return _mm_or_si128(rb, _mm_slli_epi16(ga, 8));
}
#endif
inline void bilinear_lerp8x4(const Quad8& q, Rgba8* out) {
#if defined(__SSE2__)
  const auto lanes = [](const auto& w) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(w.data())); };
  _mm_storeu_si128(reinterpret_cast<__m128i*>(out),
                   bilinear_lerp8x4_lanes(lanes(q.a), lanes(q.b), lanes(q.c), lanes(q.d), lanes(q.fu), lanes(q.fv)));
#else
  for (size_t k = 0; k < 4; ++k) out[k] = bilinear_lerp8(q.a[k], q.b[k], q.c[k], q.d[k], q.fu[k], q.fv[k]);
#endif
}

inline Rgba8 level_blend8(Rgba8 c0, Rgba8 c1, int f) {
  const auto mix = [f](uint8_t p, uint8_t q) { return static_cast<uint8_t>((p * (256 - f) + q * f + 128) >> 8); };
  return {mix(c0.r, c1.r), mix(c0.g, c1.g), mix(c0.b, c1.b), mix(c0.a, c1.a)};
}

// A level's Q.8 result on an 8-bit format (dp::bilinear_lerp_q8): four channels of code x 2^8 +
// fraction, each < 2^16.
struct Rgba8q {
  uint16_t r, g, b, a;
  friend bool operator==(const Rgba8q&, const Rgba8q&) = default;
};
// dp::bilinear_lerp_q8 on words: the sum of bilinear_lerp8_words without the rounding constant, its
// bits 8..23 per channel.
inline Rgba8q bilinear_lerp8q(Rgba8 a, Rgba8 b, Rgba8 c, Rgba8 d, uint32_t fu_, uint32_t fv_) {
  const uint64_t fu = fu_, fv = fv_, gu = 256 - fu, gv = 256 - fv;
  const uint64_t rb = gv * (word_lanes_rb(a) * gu + word_lanes_rb(b) * fu) + fv * (word_lanes_rb(c) * gu + word_lanes_rb(d) * fu);
  const uint64_t ga = gv * (word_lanes_ga(a) * gu + word_lanes_ga(b) * fu) + fv * (word_lanes_ga(c) * gu + word_lanes_ga(d) * fu);
  return {static_cast<uint16_t>(rb >> 8), static_cast<uint16_t>(ga >> 8), static_cast<uint16_t>(rb >> 40),
          static_cast<uint16_t>(ga >> 40)};
}
// dp::level_blend on Q.8 words: (p (256 - f) + q f + 2^15) >> 16 <= 255 (p, q < 2^16: < 2^25).
inline Rgba8 level_blend8q(Rgba8q c0, Rgba8q c1, int f) {
  const auto g = static_cast<uint32_t>(256 - f), h = static_cast<uint32_t>(f);
  const auto mix = [g, h](uint32_t p, uint32_t q) { return static_cast<uint8_t>((p * g + q * h + (1u << 15)) >> 16); };
  return {mix(c0.r, c1.r), mix(c0.g, c1.g), mix(c0.b, c1.b), mix(c0.a, c1.a)};
}

// Four lanes of two levels, lerped and blended: out[k] = level_blend8q(bilinear_lerp8q(level0 lane
// k), bilinear_lerp8q(level1 lane k), f[k]) (f[k] = 0: bilinear_lerp8 of level0's lane, the same
// value: (q 256 + 2^15) >> 16 = (q + 2^7) >> 8). With SSE2 (every x86-64), the lanes as in
// bilinear_lerp8x4; the Q.8 sums are kept biased by -2^15 in 16-bit lanes (floor(S / 2^8) - 2^15)
// and the blend is a biased pmaddwd again, (q0 - 2^15)(256 - f) + (q1 - 2^15) f + 2^23 + 2^15,
// then >> 16. Elsewhere the scalar units per lane.
#if defined(__SSE2__)
// The 4-lane bilinear lerp unit's Q.8 results: rb = R0 B0 R1 B1 R2 B2 R3 B3, ga = G0 A0 .. G3 A3,
// 16-bit lanes, each floor(S / 2^8) - 2^15.
struct Lanes8q {
  __m128i rb, ga;
};
[[gnu::always_inline]] inline Lanes8q bilinear_lerp8x4q_lanes(__m128i a, __m128i b, __m128i c, __m128i d, __m128i fu,
                                                              __m128i fv) {
  const __m128i lo8 = _mm_set1_epi32(0x00FF00FF);
  const __m128i fu2 = _mm_or_si128(fu, _mm_slli_epi32(fu, 16));
  const __m128i gu2 = _mm_sub_epi16(_mm_set1_epi16(256), fu2);
  const auto hlerp = [&](__m128i x, __m128i y, bool ga) {  // x gu + y fu - 2^15, 16-bit lanes
    const __m128i xs = ga ? _mm_srli_epi16(x, 8) : _mm_and_si128(x, lo8);
    const __m128i ys = ga ? _mm_srli_epi16(y, 8) : _mm_and_si128(y, lo8);
    const __m128i h = _mm_add_epi16(_mm_mullo_epi16(xs, gu2), _mm_mullo_epi16(ys, fu2));
    return _mm_xor_si128(h, _mm_set1_epi16(static_cast<int16_t>(0x8000)));
  };
  const __m128i gvfv = _mm_or_si128(_mm_sub_epi32(_mm_set1_epi32(256), fv), _mm_slli_epi32(fv, 16));
  const __m128i wlo = _mm_unpacklo_epi32(gvfv, gvfv), whi = _mm_unpackhi_epi32(gvfv, gvfv);
  const auto vlerp = [&](__m128i h0, __m128i h1) {  // S - 2^23 per channel, >> 8 (arithmetic): floor(S / 2^8) - 2^15
    const __m128i l = _mm_madd_epi16(_mm_unpacklo_epi16(h0, h1), wlo);
    const __m128i h = _mm_madd_epi16(_mm_unpackhi_epi16(h0, h1), whi);
    return _mm_packs_epi32(_mm_srai_epi32(l, 8), _mm_srai_epi32(h, 8));
  };
  return {vlerp(hlerp(a, b, false), hlerp(c, d, false)), vlerp(hlerp(a, b, true), hlerp(c, d, true))};
}
// The blend unit on biased Q.8 16-bit lanes: x, y hold (channel p, channel q) pairs side by side
// after an unpack; w the (256 - f, f) pairs. Returns the 32-bit codes.
[[gnu::always_inline]] inline __m128i level_blend8q_pairs(__m128i xy, __m128i w) {
  return _mm_srli_epi32(_mm_add_epi32(_mm_madd_epi16(xy, w), _mm_set1_epi32((1 << 23) + (1 << 15))), 16);
}
// The blend unit of bilinear_blend8x4 on the four lanes of both levels (x level0, y level1), w01
// and w23 the (256 - f, f) pairs of lanes 0, 1 and 2, 3 (each twice); returns the four words.
[[gnu::always_inline]] inline __m128i level_blend8x4_lanes(const Lanes8q& x, const Lanes8q& y, __m128i w01, __m128i w23) {
  const auto blend = [&](__m128i p, __m128i q) {  // 16-bit codes (ch0, ch1) of lanes 0..3
    return _mm_packs_epi32(level_blend8q_pairs(_mm_unpacklo_epi16(p, q), w01), level_blend8q_pairs(_mm_unpackhi_epi16(p, q), w23));
  };
  return _mm_or_si128(blend(x.rb, y.rb), _mm_slli_epi16(blend(x.ga, y.ga), 8));
}
#endif
inline void bilinear_blend8x4(const Quad8& q0, const Quad8& q1, const std::array<int, 4>& f, Rgba8* out) {
#if defined(__SSE2__)
  const auto lanes = [](const auto& w) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(w.data())); };
  const Lanes8q x = bilinear_lerp8x4q_lanes(lanes(q0.a), lanes(q0.b), lanes(q0.c), lanes(q0.d), lanes(q0.fu), lanes(q0.fv));
  const Lanes8q y = bilinear_lerp8x4q_lanes(lanes(q1.a), lanes(q1.b), lanes(q1.c), lanes(q1.d), lanes(q1.fu), lanes(q1.fv));
  const auto pair = [&](size_t k) { return static_cast<int32_t>((static_cast<uint32_t>(f[k]) << 16) | static_cast<uint32_t>(256 - f[k])); };
  const __m128i w01 = _mm_setr_epi32(pair(0), pair(0), pair(1), pair(1)), w23 = _mm_setr_epi32(pair(2), pair(2), pair(3), pair(3));
  _mm_storeu_si128(reinterpret_cast<__m128i*>(out), level_blend8x4_lanes(x, y, w01, w23));
#else
  for (size_t k = 0; k < 4; ++k)
    out[k] = level_blend8q(bilinear_lerp8q(q0.a[k], q0.b[k], q0.c[k], q0.d[k], q0.fu[k], q0.fv[k]),
                           bilinear_lerp8q(q1.a[k], q1.b[k], q1.c[k], q1.d[k], q1.fu[k], q1.fv[k]), f[k]);
#endif
}

}  // namespace tfu::dp::fast
