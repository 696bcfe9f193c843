// Speed-only form of the texture environment and the display ramp on the four pixels of a quad at
// once, for the golden renderer (raster.cpp, shade_triangle). Plain twin: combine_stage
// (texenv.hpp) and display_ramp (scene.hpp), one pixel at a time. Equality test: TexEnvQuad.* in
// testbench/test_texenv_quad.cpp (every (previous, texel) byte pair through every environment and
// RGB scale, every byte through every display shift, and random quads against the per-pixel
// forms). Off with the fast-path switch (cmodel/fast_paths.hpp: TFU_PLAIN=1, the CLI's --plain),
// which makes shade_triangle call the plain twins.
//
// The quad's four words (16 bytes, pixel k's R, G, B, A at bytes 4k..4k+3) are widened to 16-bit
// lanes, two pixels per SSE2 register (SSE2 is part of x86-64); elsewhere a portable loop over the
// plain twins stands in. Widths, per 16-bit lane (all values unsigned and below 2^15 unless said):
//   modulate  p s <= 255 * 255 = 65,025; div255_round: i = p s + 128 <= 65,153 and
//             i + (i >> 8) <= 65,407 < 2^16, so the unsigned 16-bit lane holds texenv.hpp's
//             division-free rounding exactly (logical shifts).
//   add       p + s <= 510, clamped to 255.
//   decal     p (255 - As) + s As <= 255 * 255, rounded as modulate; As is the texel's alpha,
//             broadcast to its pixel's four lanes.
//   scale     v * rgb_scale <= 1,020 (a left shift by 0, 1 or 2), clamped to 255 on R, G, B only.
//   ramp      v << shift <= 1,020 (shift 0..kMaxDisplayShift = 2), clamped to 255 on R, G, B only.
// The clamps are signed 16-bit minima of non-negative values below 2^15, so they equal the plain
// unsigned std::min; the final pack to bytes sees values <= 255 only.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>

#include "cmodel/scene.hpp"
#include "cmodel/texenv.hpp"

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define TFU_TEXENV_QUAD_SSE2 1
#endif

namespace tfu::texenv_quad {

static_assert(kMaxDisplayShift <= 6, "the ramp's 16-bit lanes hold 255 << shift below 2^15");

using Quad = std::array<Rgba8, 4>;
static_assert(sizeof(Quad) == 16, "a quad's colours are four 4-byte words");

#if TFU_TEXENV_QUAD_SSE2
namespace detail {

// round(x / 255) per unsigned 16-bit lane, x <= 255 * 255 (texenv.hpp div255_round).
[[gnu::always_inline]] inline __m128i div255_round16(__m128i x) {
  const __m128i i = _mm_add_epi16(x, _mm_set1_epi16(128));
  return _mm_srli_epi16(_mm_add_epi16(i, _mm_srli_epi16(i, 8)), 8);
}

// Lanes 3 and 7 (each pixel's alpha) all ones, the others zero.
[[gnu::always_inline]] inline __m128i alpha_lanes() { return _mm_set_epi16(-1, 0, 0, 0, -1, 0, 0, 0); }

// One register of two pixels (8 lanes): the environment, then the RGB scale (shift by log2 of it).
[[gnu::always_inline]] inline __m128i combine_pair(__m128i p, __m128i s, TexEnv env, int scale_shift) {
  const __m128i a_lanes = alpha_lanes();
  __m128i rgb, alpha;
  switch (env) {
    case TexEnv::Replace: rgb = s, alpha = s; break;
    case TexEnv::Modulate: rgb = alpha = div255_round16(_mm_mullo_epi16(p, s)); break;
    case TexEnv::Add:
      rgb = _mm_min_epi16(_mm_add_epi16(p, s), _mm_set1_epi16(255));
      alpha = div255_round16(_mm_mullo_epi16(p, s));
      break;
    case TexEnv::Decal:
    default: {
      // As broadcast to its pixel's lanes: lanes 3 and 7 copied to 0..3 and 4..7.
      const __m128i as = _mm_shufflehi_epi16(_mm_shufflelo_epi16(s, 0xFF), 0xFF);
      const __m128i blend = _mm_add_epi16(_mm_mullo_epi16(p, _mm_sub_epi16(_mm_set1_epi16(255), as)), _mm_mullo_epi16(s, as));
      rgb = div255_round16(blend);
      alpha = p;
      break;
    }
  }
  if (scale_shift != 0) rgb = _mm_min_epi16(_mm_sll_epi16(rgb, _mm_cvtsi32_si128(scale_shift)), _mm_set1_epi16(255));
  return _mm_or_si128(_mm_andnot_si128(a_lanes, rgb), _mm_and_si128(a_lanes, alpha));
}

// R, G, B min(255, v << shift), alpha kept.
[[gnu::always_inline]] inline __m128i ramp_pair(__m128i c, int shift) {
  const __m128i a_lanes = alpha_lanes();
  const __m128i rgb = _mm_min_epi16(_mm_sll_epi16(c, _mm_cvtsi32_si128(shift)), _mm_set1_epi16(255));
  return _mm_or_si128(_mm_andnot_si128(a_lanes, rgb), _mm_and_si128(a_lanes, c));
}

[[gnu::always_inline]] inline __m128i load(const Quad& q) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(q.data())); }
[[gnu::always_inline]] inline void store(Quad& q, __m128i v) { _mm_storeu_si128(reinterpret_cast<__m128i*>(q.data()), v); }

}  // namespace detail
#endif

// log2 of an RGB scale of 1, 2 or 4.
constexpr int scale_shift(int rgb_scale) { return rgb_scale == 4 ? 2 : rgb_scale == 2 ? 1 : 0; }

// colour[k] = combine_stage(colour[k], texel[k], c) for k = 0..3.
inline void combine(Quad& colour, const Quad& texel, StageCombine c) {
#if TFU_TEXENV_QUAD_SSE2
  using namespace detail;
  const __m128i zero = _mm_setzero_si128(), p = load(colour), s = load(texel);
  const int shift = scale_shift(c.rgb_scale);
  const __m128i lo = combine_pair(_mm_unpacklo_epi8(p, zero), _mm_unpacklo_epi8(s, zero), c.env, shift);
  const __m128i hi = combine_pair(_mm_unpackhi_epi8(p, zero), _mm_unpackhi_epi8(s, zero), c.env, shift);
  store(colour, _mm_packus_epi16(lo, hi));
#else
  for (size_t k = 0; k < 4; ++k) colour[k] = combine_stage(colour[k], texel[k], c);
#endif
}

// colour[k] = display_ramp(colour[k], shift) for k = 0..3, 0 <= shift <= kMaxDisplayShift.
inline void display_ramp(Quad& colour, int shift) {
#if TFU_TEXENV_QUAD_SSE2
  using namespace detail;
  if (shift == 0) return;
  const __m128i zero = _mm_setzero_si128(), c = load(colour);
  store(colour, _mm_packus_epi16(ramp_pair(_mm_unpacklo_epi8(c, zero), shift), ramp_pair(_mm_unpackhi_epi8(c, zero), shift)));
#else
  for (auto& c : colour) c = tfu::display_ramp(c, shift);
#endif
}

}  // namespace tfu::texenv_quad
