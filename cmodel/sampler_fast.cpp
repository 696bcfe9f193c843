// Speed-only fast paths of the golden sampler (no effect on results): sample() of LINEAR, CUBIC
// and EDGE_PRESERVING on 8-bit formats, one instantiation per pair of wrap modes, their anisotropic
// probe loops (N > 1), and LINEAR's sample_batch() on the 4-lane lerp unit. The plain datapath they
// must equal bit for bit is sampler.cpp (sample_channels); Properties.FastPathsEqualPlainPath and
// BatchEqualsSample compare them. Off with the fast-path switch (cmodel/fast_paths.hpp: TFU_PLAIN=1,
// the CLI's --plain): a Sampler built then dispatches to the plain datapath only.
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstring>
#include <utility>

#include "cmodel/aniso_fast.hpp"
#include "cmodel/datapath.hpp"
#include "cmodel/datapath_fast.hpp"
#include "cmodel/edge_filter.hpp"
#include "cmodel/fast_paths.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/sampler_internal.hpp"
#include "cmodel/texel_coord4.hpp"

namespace tfu {

using detail::WeightMemo;
using dp::LevelCoord;
using dp::texel_coord;

// ---------------------------------------------------------------- fast paths (software speed only)
// sample() of LINEAR, CUBIC and EDGE_PRESERVING runs one instantiation per pair of wrap modes, so
// that the wrap unit and the border select fold away, and reads texel words straight from the
// level. Same arithmetic, bit for bit, as the plain datapath above (sample_channels), which the
// tests compare them with.
namespace {

template <WrapMode kWs, WrapMode kWt>
inline constexpr bool kMayBorder = kWs == WrapMode::ClampToBorder || kWt == WrapMode::ClampToBorder;

// What the fast paths read of a level: the base address of its texel words and its extent (a
// value, so that a batch keeps it in registers: stores of results cannot change it).
struct LevelView {
  const Rgba8* texels;
  int width, height;
  explicit LevelView(const Image& img) : texels(img.texels.data()), width(img.width), height(img.height) {}
};

// Texel word at wrapped (x, y); a clamp-to-border tap (x or y = -1) reads the border word.
template <bool kBorder>
[[gnu::always_inline]] inline Rgba8 texel_word(LevelView img, int x, int y, Rgba8 border) {
  if (kBorder && (x | y) < 0) return border;
  return img.texels[static_cast<size_t>(y) * static_cast<size_t>(img.width) + static_cast<size_t>(x)];
}

// LINEAR on one level of an 8-bit format: address, wrap and the four texel words of one footprint
// (a LerpLane), as lane k of q, then the same arithmetic as filter_linear (one rounding of the Q.16
// sum) in dp::fast::bilinear_lerp8, or in dp::fast::bilinear_lerp8x4 for four lanes. The result of 8-bit
// inputs is always within 0..255.
// (Words as integers: a struct of Rgba8 members is copied byte by byte by GCC 12.)
struct LerpLane {
  uint32_t a, b, c, d;  // texel words of taps (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1)
  uint32_t fu, fv;
};
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline LerpLane lerp_lane(LevelView img, Rgba8 border, LevelCoord u, LevelCoord v) {
  int xs[2], ys[2];
  dp::fast::wrap_taps<kWs, 2>(u.i0, img.width, xs);
  dp::fast::wrap_taps<kWt, 2>(v.i0, img.height, ys);
  constexpr bool kB = kMayBorder<kWs, kWt>;
  const auto word = [&](int x, int y) { return std::bit_cast<uint32_t>(texel_word<kB>(img, x, y, border)); };
  return {word(xs[0], ys[0]), word(xs[1], ys[0]), word(xs[0], ys[1]), word(xs[1], ys[1]), u.f, v.f};
}
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline void bilinear8_taps_at(LevelView img, Rgba8 border, LevelCoord u, LevelCoord v,
                                                     dp::fast::Quad8& q, size_t k) {
  const LerpLane l = lerp_lane<kWs, kWt>(img, border, u, v);
  q.a[k] = std::bit_cast<Rgba8>(l.a);
  q.b[k] = std::bit_cast<Rgba8>(l.b);
  q.c[k] = std::bit_cast<Rgba8>(l.c);
  q.d[k] = std::bit_cast<Rgba8>(l.d);
  q.fu[k] = l.fu;
  q.fv[k] = l.fv;
}
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline void bilinear8_taps(LevelView img, Rgba8 border, float s, float t, dp::fast::Quad8& q,
                                                  size_t k) {
  bilinear8_taps_at<kWs, kWt>(img, border, texel_coord(s, img.width), texel_coord(t, img.height), q, k);
}
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline Rgba8 bilinear8_at(LevelView img, Rgba8 border, LevelCoord u, LevelCoord v) {
  const LerpLane l = lerp_lane<kWs, kWt>(img, border, u, v);
  return dp::fast::bilinear_lerp8(std::bit_cast<Rgba8>(l.a), std::bit_cast<Rgba8>(l.b), std::bit_cast<Rgba8>(l.c),
                                 std::bit_cast<Rgba8>(l.d), l.fu, l.fv);
}
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline dp::fast::Rgba8q bilinear8q_at(LevelView img, Rgba8 border, LevelCoord u, LevelCoord v) {
  const LerpLane l = lerp_lane<kWs, kWt>(img, border, u, v);
  return dp::fast::bilinear_lerp8q(std::bit_cast<Rgba8>(l.a), std::bit_cast<Rgba8>(l.b), std::bit_cast<Rgba8>(l.c),
                                   std::bit_cast<Rgba8>(l.d), l.fu, l.fv);
}

// CUBIC (4 x 4 taps) on one level of 8-bit texel words with memoized weights: filter_tiled_acc_n
// with the wrap modes fixed, then the normalise stage.
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline Rgba8 cubic8(LevelView img, Rgba8 border, const WeightMemo& memo,
                                            const dp::CubicNormalize& norm, LevelCoord u, LevelCoord v) {
  const int32_t* w = memo.weights(u.f, v.f);
  int col[4], row[4];
  dp::fast::wrap_taps<kWs, 4>(u.i0 - 1, img.width, col);  // taps -1 .. 2
  dp::fast::wrap_taps<kWt, 4>(v.i0 - 1, img.height, row);
  // (R, B) and (G, A) in signed 32-bit lanes, as in filter_tiled_acc_n: modular arithmetic keeps
  // x = low + high 2^32 exactly and each lane's true sum is below 2^31 in magnitude.
  // One row of taps per iteration (kept as a loop: fully unrolled, the compiler spills the 16
  // addresses and weights).
  uint64_t arb = 0, aga = 0;
#pragma GCC unroll 1
  for (int j = 0; j < 4; ++j) {
    const int32_t* wr = w + 4 * j;
    for (int i = 0; i < 4; ++i) {
      const Rgba8 c = texel_word<kMayBorder<kWs, kWt>>(img, col[i], row[j], border);
      const auto wt = static_cast<uint64_t>(static_cast<int64_t>(wr[i]));
      arb += dp::fast::word_lanes_rb(c) * wt;  // (R, B) and (G, A) in 32-bit lanes
      aga += dp::fast::word_lanes_ga(c) * wt;
    }
  }
  const auto lo = [](uint64_t x) { return static_cast<int64_t>(static_cast<int32_t>(static_cast<uint32_t>(x))); };
  const auto hi = [&lo](uint64_t x) {
    return static_cast<int64_t>(static_cast<int32_t>(static_cast<uint32_t>((x - static_cast<uint64_t>(lo(x))) >> 32)));
  };
  const std::array<int64_t, 4> acc{lo(arb), lo(aga), hi(arb), hi(aga)};
  if (norm.M == 255 && !norm.prefiltered) {
    // dp::cubic_normalize of the default 8-bit ROM: clamp(floor((2 acc + 255) / 510)) to 0..255; a
    // negative numerator clamps to 0, so only non-negative ones are divided (truncation = floor).
    const auto n8 = [](int64_t a) {
      const int64_t n = 2 * a + 255;
      return static_cast<uint8_t>(n < 0 ? 0 : std::min<int64_t>(n / 510, 255));
    };
    return {n8(acc[0]), n8(acc[1]), n8(acc[2]), n8(acc[3])};
  }
  const Texel4 c = dp::cubic_normalize(acc, norm);  // within 0..255
  return {static_cast<uint8_t>(c[0]), static_cast<uint8_t>(c[1]), static_cast<uint8_t>(c[2]), static_cast<uint8_t>(c[3])};
}

// EDGE_PRESERVING on one level of an 8-bit format: the cross footprint (edge_footprint with the
// wrap modes fixed and no override; texels outside the shape are read but not used), then the
// Lee & Jen datapath. `block`: the static shapes' tile side, 0 for the cross.
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline Texel4 edge8(LevelView img, Rgba8 border, TexelFormat fmt, int block, LevelCoord u, LevelCoord v) {
  int col[lee_jen::kGridSide], row[lee_jen::kGridSide];  // columns and rows -1 .. 2
  dp::fast::wrap_taps<kWs, lee_jen::kGridSide>(u.i0 + lee_jen::kGridOrigin, img.width, col);
  dp::fast::wrap_taps<kWt, lee_jen::kGridSide>(v.i0 + lee_jen::kGridOrigin, img.height, row);
  const lee_jen::TexelMask mask = block != 0 ? lee_jen::cache_block_mask_of_grid(col, row, block) : lee_jen::kAllTexels;
  std::array<Texel4, lee_jen::kTexels> c;
  for (size_t k = 0; k < c.size(); ++k) {
    const int n = static_cast<int>(k) + 1;
    const Rgba8 w =
        texel_word<kMayBorder<kWs, kWt>>(img, col[lee_jen::grid_col(n)], row[lee_jen::grid_row(n)], border);
    c[k] = ((mask >> k) & 1u) ? Texel4{w.r, w.g, w.b, w.a} : Texel4{0, 0, 0, 0};
  }
  return lee_jen::edge_preserving_interpolate(c, mask, u.f, v.f, fmt);
}

// Trilinear blend unit (dp::level_blend) and output encoding, for the 8-bit paths' texel words
// (channels within 0..255, so encoding is the identity), for LINEAR's Q.8 level results and for
// datapath channels (codes).
inline Rgba8 blend_levels(Rgba8 a, Rgba8 b, int f) { return dp::fast::level_blend8(a, b, f); }
inline Rgba8 blend_levels(dp::fast::Rgba8q a, dp::fast::Rgba8q b, int f) { return dp::fast::level_blend8q(a, b, f); }
inline Texel4 blend_levels(const Texel4& a, const Texel4& b, int f) { return dp::level_blend_codes(a, b, f); }
inline Rgba8 output_word(Rgba8 c, TexelFormat) { return c; }
inline Rgba8 output_word(const Texel4& c, TexelFormat fmt) { return encode_texel(c, fmt); }
// A probe's result as the averaging unit's input channels.
inline Texel4 probe_channels(Rgba8 c) { return {c.r, c.g, c.b, c.a}; }
inline Texel4 probe_channels(const Texel4& c) { return c; }

// Level select of the LOD unit and the blend unit around a filter of one level: f(level) the
// level's code, fq(level) its result for the blend unit (Q.8 for LINEAR).
template <class F, class G>
[[gnu::always_inline]] inline auto filter_levels(int32_t lambda_q8, const LodParams& lod, MipMode mip, int q, F&& f, G&& fq) {
  const LevelPick p = select_levels(lambda_bias_clamp(lambda_q8, lod), mip, q);
  if (p.blend == 0) return f(p.level0);
  return blend_levels(fq(p.level0), fq(p.level1), p.blend);
}

}  // namespace

// The mode's filter on one level at a level coordinate (u, v).
template <Sampler::FastPaths::Variant kV>
[[gnu::always_inline]] inline auto Sampler::FastPaths::filter_at(const Sampler& sm, int l, LevelCoord u, LevelCoord v) {
  const auto level = static_cast<size_t>(l);
  const Impl& im = *sm.impl_;
  if constexpr (kV.path == Path::Linear8) {
    return bilinear8_at<kV.ws, kV.wt>(LevelView(sm.tex_.levels[level]), sm.cfg_.border, u, v);
  } else if constexpr (kV.path == Path::Cubic8) {
    if (im.prefiltered) return cubic8<kV.ws, kV.wt>(LevelView(im.coeffs.codes[level]), Rgba8{}, *im.memo, im.norm, u, v);
    return cubic8<kV.ws, kV.wt>(LevelView(sm.tex_.levels[level]), sm.cfg_.border, *im.memo, im.norm, u, v);
  } else {
    return edge8<kV.ws, kV.wt>(LevelView(sm.tex_.levels[level]), sm.cfg_.border, sm.tex_.format,
                               sm.static_shape_block(), u, v);
  }
}

template <Sampler::FastPaths::Variant kV>
[[gnu::always_inline]] inline auto Sampler::FastPaths::filter_q8_at(const Sampler& sm, int l, LevelCoord u, LevelCoord v) {
  if constexpr (kV.path == Path::Linear8)
    return bilinear8q_at<kV.ws, kV.wt>(LevelView(sm.tex_.levels[static_cast<size_t>(l)]), sm.cfg_.border, u, v);
  else
    return filter_at<kV>(sm, l, u, v);
}

// The mode's filter on one level at (s, t).
template <Sampler::FastPaths::Variant kV>
[[gnu::always_inline]] inline auto Sampler::FastPaths::filter(const Sampler& sm, int l, float s, float t) {
  const Image& img = sm.tex_.levels[static_cast<size_t>(l)];
  return filter_at<kV>(sm, l, texel_coord(s, img.width), texel_coord(t, img.height));
}

// One filtered colour: level select, the filter on one or two levels, blend, encode.
template <Sampler::FastPaths::Variant kV>
Rgba8 Sampler::FastPaths::sample(const Sampler& sm, float s, float t, int32_t lambda_q8) {
  const TexelFormat fmt = sm.tex_.format;
  if constexpr (!kV.mipmapped) {
    return output_word(filter<kV>(sm, 0, s, t), fmt);  // GL: no MIP-mapping -> level 0
  } else {
    const auto at = [&](int l) {
      const Image& img = sm.tex_.levels[static_cast<size_t>(l)];
      return std::pair{texel_coord(s, img.width), texel_coord(t, img.height)};
    };
    return output_word(filter_levels(
                           lambda_q8, sm.cfg_.lod, sm.cfg_.mode.mip, sm.tex_.max_level(),
                           [&](int l) { return filter<kV>(sm, l, s, t); },
                           [&](int l) {
                             const auto [u, v] = at(l);
                             return filter_q8_at<kV>(sm, l, u, v);
                           }),
                       fmt);
  }
}

namespace {

// LINEAR's N > 1 probes on the 4-lane lerp unit, all in registers: with kTwo (the levels blend)
// each call takes two probes, lanes (probe i level0, probe i + 1 level0, probe i level1, probe
// i + 1 level1) as Q.8 results (dp::fast::bilinear_lerp8x4q_lanes), then the blend unit takes the
// two probes side by side (dp::fast::level_blend8q_pairs, 32-bit lanes); without, four probes on
// level0 as codes. The averaging unit sums w_i c_i in 16-bit lanes (sum_i w_i c_i <= 256 * 255 <
// 2^16). A call's missing probes (N not a multiple of its probes) repeat its first with weight 0.
// The same arithmetic as the plain probe datapath (Sampler::sample_channels):
// dp::fast::bilinear_lerp8x4_lanes equals bilinear_lerp8 per lane, the Q.8 lanes bilinear_lerp8q,
// the blend is dp::fast::level_blend8q's, the probe offsets are the offset units' two's-complement forms
// (aniso_fast.hpp: one multiply, then one add-and-shift per rounding, onto the centre's Q.8
// coordinate formed once per pixel), and the result is AnisoAccumulator's (acc + 128) >> 8.
// Returned as the output word: each probe is an output word of the 8-bit LINEAR path (on which
// encoding is the identity, as sample<Linear8> has it) and their weighted mean lies between them,
// channel by channel. (Lanes are not staged in memory: four 32-bit stores read back as one
// 128-bit load cannot be forwarded and stall until the stores retire.) SSE2 (every x86-64);
// elsewhere LINEAR's probes take the per-probe loop of FastPaths::aniso.
#if defined(__SSE2__)
template <WrapMode kWs, WrapMode kWt, bool kTwo>
Rgba8 aniso_linear8(LevelView l0, LevelView l1, Rgba8 border, const LevelPick& p, LevelCoord u0, LevelCoord v0,
                     LevelCoord u1, LevelCoord v1, const AnisoLod& lod) {
  const int n = lod.probes;
  const ProbeRomWord* rom = probe_rom().data() + probe_rom_address(n, 1);  // words (n, 1..n)
  const int64_t major_du = dp::fast::clamped_major(lod.major_du_q16),
                major_dv = dp::fast::clamped_major(lod.major_dv_q16);
  const int64_t cu0 = dp::fast::join_q8(u0), cv0 = dp::fast::join_q8(v0);
  const int64_t cu1 = dp::fast::join_q8(u1), cv1 = dp::fast::join_q8(v1);
  // Probe i's offset (Q.16 level-0 texels), and its footprint on level 0 (level0) or 1 (level1).
  const auto offset = [&](int i) __attribute__((always_inline)) {
    return ProbeOffset{dp::fast::scale_probe_fraction(major_du, rom[i].frac_q16),
                       dp::fast::scale_probe_fraction(major_dv, rom[i].frac_q16)};
  };
  const auto footprint = [&](const ProbeOffset& o, int level) __attribute__((always_inline)) {
    const int l = level == 0 ? p.level0 : p.level1;
    return lerp_lane<kWs, kWt>(
        level == 0 ? l0 : l1, border,
        dp::fast::split_q8((level == 0 ? cu0 : cu1) + dp::fast::probe_offset_on_level(o.du_q16, l)),
        dp::fast::split_q8((level == 0 ? cv0 : cv1) + dp::fast::probe_offset_on_level(o.dv_q16, l)));
  };
  const auto lerp4 = [](const LerpLane& x0, const LerpLane& x1, const LerpLane& x2, const LerpLane& x3) __attribute__((always_inline)) {
    const auto lanes = [&](uint32_t LerpLane::*field) {
      const auto lane = [&](const LerpLane& x) { return static_cast<int32_t>(x.*field); };
      return _mm_setr_epi32(lane(x0), lane(x1), lane(x2), lane(x3));
    };
    return dp::fast::bilinear_lerp8x4_lanes(lanes(&LerpLane::a), lanes(&LerpLane::b), lanes(&LerpLane::c),
                                           lanes(&LerpLane::d), lanes(&LerpLane::fu), lanes(&LerpLane::fv));
  };
  const auto lerp4q = [](const LerpLane& x0, const LerpLane& x1, const LerpLane& x2, const LerpLane& x3) __attribute__((always_inline)) {
    const auto lanes = [&](uint32_t LerpLane::*field) {
      const auto lane = [&](const LerpLane& x) { return static_cast<int32_t>(x.*field); };
      return _mm_setr_epi32(lane(x0), lane(x1), lane(x2), lane(x3));
    };
    return dp::fast::bilinear_lerp8x4q_lanes(lanes(&LerpLane::a), lanes(&LerpLane::b), lanes(&LerpLane::c),
                                            lanes(&LerpLane::d), lanes(&LerpLane::fu), lanes(&LerpLane::fv));
  };
  const auto weight = [&](int i, bool used) { return static_cast<int16_t>(used ? rom[i].weight : 0); };
  const __m128i zero = _mm_setzero_si128();
  __m128i acc = zero;  // 8 x 16-bit: (R, G, B, A) of the even and of the odd probe slots
  if constexpr (kTwo) {
    const __m128i gf = _mm_set1_epi32(static_cast<int32_t>((static_cast<uint32_t>(p.blend) << 16) | static_cast<uint32_t>(256 - p.blend)));
    for (int i = 0; i < n; i += 2) {
      const bool second = i + 1 < n;
      const int j = second ? i + 1 : i;
      const ProbeOffset oi = offset(i), oj = offset(j);
      const dp::fast::Lanes8q c = lerp4q(footprint(oi, 0), footprint(oj, 0), footprint(oi, 1), footprint(oj, 1));
      // lanes (i level0, j level0, i level1, j level1): level0 and level1 side by side, then the
      // 16-bit codes (R, G, B, A) of probe i and of probe j
      const auto blend = [&](__m128i x) {
        return dp::fast::level_blend8q_pairs(_mm_unpacklo_epi16(x, _mm_srli_si128(x, 8)), gf);
      };
      const __m128i rb = _mm_packs_epi32(blend(c.rb), zero), ga = _mm_packs_epi32(blend(c.ga), zero);
      const __m128i blended = _mm_unpacklo_epi16(rb, ga);
      const int16_t wi = weight(i, true), wj = weight(j, second);
      acc = _mm_add_epi16(acc, _mm_mullo_epi16(blended, _mm_setr_epi16(wi, wi, wi, wi, wj, wj, wj, wj)));
    }
  } else {
    for (int i = 0; i < n; i += 4) {
      const int i1 = i + 1 < n ? i + 1 : i, i2 = i + 2 < n ? i + 2 : i, i3 = i + 3 < n ? i + 3 : i;
      const __m128i c = lerp4(footprint(offset(i), 0), footprint(offset(i1), 0), footprint(offset(i2), 0), footprint(offset(i3), 0));
      const int16_t w0 = weight(i, true), w1 = weight(i1, i + 1 < n), w2 = weight(i2, i + 2 < n), w3 = weight(i3, i + 3 < n);
      acc = _mm_add_epi16(acc, _mm_add_epi16(_mm_mullo_epi16(_mm_unpacklo_epi8(c, zero), _mm_setr_epi16(w0, w0, w0, w0, w1, w1, w1, w1)),
                                             _mm_mullo_epi16(_mm_unpackhi_epi8(c, zero), _mm_setr_epi16(w2, w2, w2, w2, w3, w3, w3, w3))));
    }
  }
  constexpr int16_t kHalf = 1 << (kAnisoWeightBits - 1);
  const __m128i sum = _mm_add_epi16(_mm_add_epi16(acc, _mm_srli_si128(acc, 8)), _mm_set1_epi16(kHalf));
  return std::bit_cast<Rgba8>(_mm_cvtsi128_si32(_mm_packus_epi16(_mm_srli_epi16(sum, kAnisoWeightBits), zero)));
}
#endif

}  // namespace

// N > 1 probes (MIP-mapped variants): the levels are selected once (every probe has the same
// lambda) and the centre's coordinate on each level formed once; per probe its offset on each level
// (probe_offset, dp::probe_offset_on_level, dp::probe_texel_coord), the mode's filter, the blend,
// and the averaging unit (dp::AnisoAccumulator); encoded once. The same arithmetic as the plain
// probe datapath (Sampler::sample_channels(s, t, lod)), which the tests compare it with.
template <Sampler::FastPaths::Variant kV>
Rgba8 Sampler::FastPaths::aniso(const Sampler& sm, float s, float t, const AnisoLod& lod) {
  static_assert(kV.mipmapped);
  const LevelPick p = select_levels(lambda_bias_clamp(lod.lambda_q8, sm.cfg_.lod), sm.cfg_.mode.mip, sm.tex_.max_level());
  const Image& i0 = sm.tex_.levels[static_cast<size_t>(p.level0)];
  const Image& i1 = sm.tex_.levels[static_cast<size_t>(p.level1)];
  const LevelCoord u0 = texel_coord(s, i0.width), v0 = texel_coord(t, i0.height);
  const LevelCoord u1 = texel_coord(s, i1.width), v1 = texel_coord(t, i1.height);
#if defined(__SSE2__)  // elsewhere LINEAR's probes take the loop below
  if constexpr (kV.path == Path::Linear8)
    return p.blend != 0
               ? aniso_linear8<kV.ws, kV.wt, true>(LevelView(i0), LevelView(i1), sm.cfg_.border, p, u0, v0, u1, v1, lod)
               : aniso_linear8<kV.ws, kV.wt, false>(LevelView(i0), LevelView(i1), sm.cfg_.border, p, u0, v0, u1, v1, lod);
#endif
  const int n = lod.probes;
  dp::AnisoAccumulator acc;
  for (int i = 1; i <= n; ++i) {
    const ProbeOffset o = probe_offset(lod, i);
    const auto at = [&](int level, LevelCoord u, LevelCoord v) {
      return filter_at<kV>(sm, level, dp::probe_texel_coord(u, dp::probe_offset_on_level(o.du_q16, level)),
                           dp::probe_texel_coord(v, dp::probe_offset_on_level(o.dv_q16, level)));
    };
    const auto at_q8 = [&](int level, LevelCoord u, LevelCoord v) {
      return filter_q8_at<kV>(sm, level, dp::probe_texel_coord(u, dp::probe_offset_on_level(o.du_q16, level)),
                              dp::probe_texel_coord(v, dp::probe_offset_on_level(o.dv_q16, level)));
    };
    if (p.blend == 0)
      acc.add(probe_channels(at(p.level0, u0, v0)), n, i);
    else
      acc.add(probe_channels(blend_levels(at_q8(p.level0, u0, v0), at_q8(p.level1, u1, v1), p.blend)), n, i);
  }
  return encode_texel(acc.result(), sm.tex_.format);
}

// sample<kV> over a batch, LINEAR on 8-bit formats (plain twin: batch_plain, sample() per
// request; tests: Properties.BatchEqualsSample, BatchPartialQuads, FastPathsEqualPlainPath): the
// sampler's registers are read once, and four requests at a time share the 4-lane lerp unit (their
// address, wrap and texel fetch are independent, so the core overlaps them). A last group of 1..3
// requests takes the same unit with its missing lanes masked: their taps are zero words with zero
// fractions (never fetched), their results not stored. MIP-mapped: when the group's requests share
// one lambda (a quad's pixels: the LOD unit gives one lambda per quad), the levels are selected
// once and every lane blends with the same weight or none does; else each lane selects its own
// levels, the second level's lerp runs when some lane blends, and a lane that does not blend takes
// its level0 again with weight 0 (the blend unit then gives bilinear_lerp8's value, as
// filter_levels). The lanes are 32-bit texel words and 8-bit fractions (dp::fast::Quad8); with
// SSE2 a group whose requests share their levels builds them in registers (GroupLanes), through
// the 4-lane address stage (cmodel/texel_coord4.hpp: coordinates, wrap, texel indices for the four
// lanes at once; its tests TexelCoord4.*) when every coordinate is one its coordinate unit takes and
// the wrap modes are repeat (any extent) or the clamps, else lane by lane.
namespace {
// A group of m = 1..4 requests: lane k < m filled by tap(k); the other lanes zero.
template <class F>
[[gnu::always_inline]] inline void fill_lanes(size_t m, dp::fast::Quad8& q, F&& tap) {
  if (m == 4) {
    for (size_t k = 0; k < 4; ++k) tap(k);
    return;
  }
  q = {};
  for (size_t k = 0; k < m; ++k) tap(k);
}
// The same, each lane k < m the footprint of request r[k] on one level.
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline void group_taps(size_t m, LevelView img, Rgba8 border, const SampleRequest* r, dp::fast::Quad8& q) {
  if (m == 4) {
    for (size_t k = 0; k < 4; ++k) bilinear8_taps<kWs, kWt>(img, border, r[k].s, r[k].t, q, k);
    return;
  }
  q = {};
  for (size_t k = 0; k < m; ++k) bilinear8_taps<kWs, kWt>(img, border, r[k].s, r[k].t, q, k);
}
#if defined(__SSE2__)
// A group's four footprints on one level as the 4-lane unit's inputs, built in registers (as
// aniso_linear8's lanes: four 32-bit stores read back as one 128-bit load of a dp::fast::Quad8
// cannot be forwarded and stall until the stores retire).
struct GroupLanes {
  __m128i a, b, c, d, fu, fv;
};
// Per lane: address, wrap and the four texel words of lerp_lane (lane k >= m masked: zero). Out of
// line and cold: the renderer's groups take group_lanes4 (coordinates the coordinate unit takes,
// repeat or the clamps), and inlined this path's spills and frame were paid by
// every call of the batch.
template <WrapMode kWs, WrapMode kWt>
[[gnu::noinline, gnu::cold]] GroupLanes group_lanes_per_lane(size_t m, LevelView img, Rgba8 border, const SampleRequest* r) {
  const auto at = [&](size_t k) __attribute__((always_inline)) {
    return k < m ? lerp_lane<kWs, kWt>(img, border, texel_coord(r[k].s, img.width), texel_coord(r[k].t, img.height))
                 : LerpLane{0, 0, 0, 0, 0, 0};
  };
  const LerpLane x0 = at(0), x1 = at(1), x2 = at(2), x3 = at(3);
  const auto lanes = [&](uint32_t LerpLane::*field) {
    const auto lane = [&](const LerpLane& x) { return static_cast<int32_t>(x.*field); };
    return _mm_setr_epi32(lane(x0), lane(x1), lane(x2), lane(x3));
  };
  return {lanes(&LerpLane::a), lanes(&LerpLane::b), lanes(&LerpLane::c), lanes(&LerpLane::d), lanes(&LerpLane::fu), lanes(&LerpLane::fv)};
}

// The group's coordinates for the 4-lane address stage (cmodel/texel_coord4.hpp), formed once per
// group: s and t of lanes 0..3 (binary32; widened to binary64 on a level whose extent is not a power
// of two); a lane k >= m repeats request 0 (its footprint is fetched, in range, and its result not
// stored). `unit`: every s and t is one the coordinate unit takes (else the group takes
// group_lanes_per_lane).
struct GroupCoords {
  __m128 s, t;
  bool unit;
};
// The coordinate unit on one axis of a level: on a power-of-two extent the binary32 form
// (dp::fast::texel_coord4_pow2, four lanes a register) where it takes the group, else the binary64
// form (dp::fast::texel_coord4); both equal dp::texel_coord per lane (TexelCoord4.*).
[[gnu::always_inline]] inline dp::fast::TexelCoords4 axis_coords(__m128 x, int size) {
  dp::fast::TexelCoords4 c;
  if ((size & (size - 1)) == 0 && dp::fast::texel_coord4_pow2(x, size, c)) return c;
  return dp::fast::texel_coord4(dp::fast::widen4(x), size);
}
[[gnu::always_inline]] inline GroupCoords group_coords(size_t m, const SampleRequest* r) {
  static_assert(offsetof(SampleRequest, s) == 0 && offsetof(SampleRequest, t) == 4);
  const auto st = [&](size_t k) __attribute__((always_inline)) {  // (s, t) of lane k in the low half
    return _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&r[k < m ? k : 0])));
  };
  const __m128 x01 = _mm_unpacklo_ps(st(0), st(1)), x23 = _mm_unpacklo_ps(st(2), st(3));  // s0 s1 t0 t1, s2 s3 t2 t3
  const __m128 s = _mm_movelh_ps(x01, x23), t = _mm_movehl_ps(x23, x01);
  return {s, t, (dp::fast::texel_coord4_lanes(s) & dp::fast::texel_coord4_lanes(t)) == 15};
}

// The four footprints on one level through the 4-lane address stage: coordinates
// (axis_coords: dp::fast::texel_coord4_pow2 or texel_coord4), wrap (dp::fast::wrap2x4; the caller checks wrap2x4_takes), texel
// indices y w + x, then the texel words: when every lane's taps i0 and i0 + 1 are next to each
// other in a row (and no tap is a border tap), each row's two words of a lane in one 64-bit load;
// else one load per tap, and the border word where x or y is -1. Lanes equal lerp_lane's.
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline GroupLanes group_lanes4(LevelView img, Rgba8 border, const GroupCoords& g) {
  const dp::fast::TexelCoords4 u = axis_coords(g.s, img.width), v = axis_coords(g.t, img.height);
  __m128i x0, x1, y0, y1;
  dp::fast::wrap2x4<kWs>(u.i0, img.width, x0, x1);
  dp::fast::wrap2x4<kWt>(v.i0, img.height, y0, y1);
  constexpr bool kB = kMayBorder<kWs, kWt>;
  __m128i next = _mm_cmpeq_epi32(x1, _mm_add_epi32(x0, _mm_set1_epi32(1)));  // taps i0, i0 + 1 side by side
  __m128i bx0{}, bx1{}, by0{}, by1{};  // border taps (-1): all ones
  if constexpr (kB) {
    bx0 = _mm_srai_epi32(x0, 31), bx1 = _mm_srai_epi32(x1, 31), by0 = _mm_srai_epi32(y0, 31), by1 = _mm_srai_epi32(y1, 31);
    next = _mm_andnot_si128(_mm_or_si128(_mm_or_si128(bx0, bx1), _mm_or_si128(by0, by1)), next);
    x0 = _mm_andnot_si128(bx0, x0), x1 = _mm_andnot_si128(bx1, x1);  // read texel 0 there, then the border word
    y0 = _mm_andnot_si128(by0, y0), y1 = _mm_andnot_si128(by1, y1);
  }
  __m128i r0, r1;  // y w: a shift on a power-of-two width
  if ((img.width & (img.width - 1)) == 0) {
    const int log2w = std::countr_zero(static_cast<unsigned>(img.width));
    r0 = dp::fast::row_offset4_pow2(y0, log2w), r1 = dp::fast::row_offset4_pow2(y1, log2w);
  } else {
    const __m128i w = _mm_set1_epi32(img.width);
    r0 = dp::fast::row_offset4(y0, w), r1 = dp::fast::row_offset4(y1, w);
  }
  const __m128i ia = _mm_add_epi32(r0, x0), ic = _mm_add_epi32(r1, x0);
  const auto word = [&](int32_t i) __attribute__((always_inline)) {
    return std::bit_cast<int32_t>(img.texels[static_cast<uint32_t>(i)]);
  };
  if (_mm_movemask_ps(_mm_castsi128_ps(next)) == 15) {
    alignas(16) int32_t ix[8];
    _mm_store_si128(reinterpret_cast<__m128i*>(ix), ia);
    _mm_store_si128(reinterpret_cast<__m128i*>(ix + 4), ic);
    const auto pair = [&](int32_t i) __attribute__((always_inline)) {  // words i, i + 1
      return _mm_loadl_epi64(reinterpret_cast<const __m128i*>(img.texels + static_cast<uint32_t>(i)));
    };
    const __m128i ab01 = _mm_unpacklo_epi32(pair(ix[0]), pair(ix[1])), ab23 = _mm_unpacklo_epi32(pair(ix[2]), pair(ix[3]));
    const __m128i cd01 = _mm_unpacklo_epi32(pair(ix[4]), pair(ix[5])), cd23 = _mm_unpacklo_epi32(pair(ix[6]), pair(ix[7]));
    return {_mm_unpacklo_epi64(ab01, ab23), _mm_unpackhi_epi64(ab01, ab23), _mm_unpacklo_epi64(cd01, cd23),
            _mm_unpackhi_epi64(cd01, cd23), u.f, v.f};
  }
  alignas(16) int32_t ix[16];
  _mm_store_si128(reinterpret_cast<__m128i*>(ix), ia);
  _mm_store_si128(reinterpret_cast<__m128i*>(ix + 4), _mm_add_epi32(r0, x1));
  _mm_store_si128(reinterpret_cast<__m128i*>(ix + 8), ic);
  _mm_store_si128(reinterpret_cast<__m128i*>(ix + 12), _mm_add_epi32(r1, x1));
  const auto gather = [&](const int32_t* i) __attribute__((always_inline)) {
    return _mm_setr_epi32(word(i[0]), word(i[1]), word(i[2]), word(i[3]));
  };
  GroupLanes l{gather(ix), gather(ix + 4), gather(ix + 8), gather(ix + 12), u.f, v.f};
  if constexpr (kB) {
    const __m128i bw = _mm_set1_epi32(std::bit_cast<int32_t>(border));
    const auto sel = [&](__m128i x, __m128i m) { return _mm_or_si128(_mm_andnot_si128(m, x), _mm_and_si128(m, bw)); };
    l.a = sel(l.a, _mm_or_si128(bx0, by0)), l.b = sel(l.b, _mm_or_si128(bx1, by0));
    l.c = sel(l.c, _mm_or_si128(bx0, by1)), l.d = sel(l.d, _mm_or_si128(bx1, by1));
  }
  return l;
}
// A group's footprints on one level: the 4-lane address stage where it takes the group, else per lane.
template <WrapMode kWs, WrapMode kWt>
[[gnu::always_inline]] inline GroupLanes group_lanes(size_t m, LevelView img, Rgba8 border, const SampleRequest* r,
                                                     const GroupCoords& g) {
  if constexpr (dp::fast::kWrap2x4<kWs> && dp::fast::kWrap2x4<kWt>)
    if (g.unit && dp::fast::wrap2x4_takes<kWs>(img.width) && dp::fast::wrap2x4_takes<kWt>(img.height))
      return group_lanes4<kWs, kWt>(img, border, g);
  return group_lanes_per_lane<kWs, kWt>(m, img, border, r);
}
inline __m128i lerp_group(const GroupLanes& g) { return dp::fast::bilinear_lerp8x4_lanes(g.a, g.b, g.c, g.d, g.fu, g.fv); }
inline dp::fast::Lanes8q lerp_group_q8(const GroupLanes& g) {
  return dp::fast::bilinear_lerp8x4q_lanes(g.a, g.b, g.c, g.d, g.fu, g.fv);
}
// Stores the group's m result words of v (out has room for m words only): lanes 0-1 as one 64-bit
// store, lane 0 or 2 as one 32-bit store (no staging array and no copy loop for a partial group).
[[gnu::always_inline]] inline void store_group(size_t m, Rgba8* out, __m128i v) {
  if (m == 4) return _mm_storeu_si128(reinterpret_cast<__m128i*>(out), v);
  const auto word = [](Rgba8* o, __m128i x) __attribute__((always_inline)) {  // lane 0 of x
    const int32_t w = _mm_cvtsi128_si32(x);
    std::memcpy(static_cast<void*>(o), &w, sizeof w);
  };
  if (m == 1) return word(out, v);
  _mm_storel_epi64(reinterpret_cast<__m128i*>(out), v);
  if (m == 3) word(out + 2, _mm_unpackhi_epi64(v, v));
}
#endif
// Stores the group's m results (out has room for m words only).
template <class F>
[[gnu::always_inline]] inline void store_lanes(size_t m, Rgba8* out, F&& unit) {
  if (m == 4) return unit(out);
  std::array<Rgba8, 4> r;
  unit(r.data());
  std::copy_n(r.begin(), m, out);
}
}  // namespace

namespace {
// A group of m = 1..4 requests whose lambdas differ (never from the renderer, whose quads share the
// LOD unit's one lambda): each lane selects its own levels, the second level's lerp runs when some
// lane blends, and a lane that does not blend (or is masked) takes its level0 again with weight 0.
// Out of line and cold, so that its two dp::fast::Quad8 and their zeroing are not part of every
// call's frame.
template <WrapMode kWs, WrapMode kWt>
[[gnu::noinline, gnu::cold]] void group_own_lambdas(size_t m, const Image* levels, Rgba8 border, const LodParams& lod,
                                                    MipMode mip, int top, const SampleRequest* r, Rgba8* out) {
  dp::fast::Quad8 q0, q1;  // level0 and level1 taps; q1's lanes are used only where the lane blends
  std::array<int, 4> blend{};
  int any = 0;
  fill_lanes(m, q0, [&](size_t k) {
    const LevelPick p = select_levels(lambda_bias_clamp(r[k].lambda_q8, lod), mip, top);
    bilinear8_taps<kWs, kWt>(LevelView(levels[p.level0]), border, r[k].s, r[k].t, q0, k);
    if (p.blend != 0) bilinear8_taps<kWs, kWt>(LevelView(levels[p.level1]), border, r[k].s, r[k].t, q1, k);
    blend[k] = p.blend;
    any |= p.blend;
  });
  if (any == 0) return store_lanes(m, out, [&](Rgba8* o) { dp::fast::bilinear_lerp8x4(q0, o); });
  for (size_t k = 0; k < 4; ++k)  // a lane that does not blend (or is masked): its level0 again, weight 0
    if (blend[k] == 0) {
      q1.a[k] = q0.a[k], q1.b[k] = q0.b[k], q1.c[k] = q0.c[k], q1.d[k] = q0.d[k];
      q1.fu[k] = q0.fu[k], q1.fv[k] = q0.fv[k];
    }
  store_lanes(m, out, [&](Rgba8* o) { dp::fast::bilinear_blend8x4(q0, q1, blend, o); });
}
}  // namespace

template <Sampler::FastPaths::Variant kV>
void Sampler::FastPaths::batch(const Sampler& sm, const SampleRequest* req, size_t n, Rgba8* out) {
  static_assert(kV.path == Path::Linear8);
  const Rgba8 border = sm.cfg_.border;
  if constexpr (!kV.mipmapped) {
    const LevelView img(sm.tex_.levels[0]);
    for (size_t i = 0; i < n; i += 4) {
      const size_t m = std::min<size_t>(4, n - i);
      const SampleRequest* r = req + i;
#if defined(__SSE2__)
      store_group(m, out + i, lerp_group(group_lanes<kV.ws, kV.wt>(m, img, border, r, group_coords(m, r))));
#else
      dp::fast::Quad8 q;  // every used lane is written before its use, the others zeroed
      group_taps<kV.ws, kV.wt>(m, img, border, r, q);
      store_lanes(m, out + i, [&](Rgba8* o) { dp::fast::bilinear_lerp8x4(q, o); });
#endif
    }
  } else {
    const Image* levels = sm.tex_.levels.data();
    const LodParams lod = sm.cfg_.lod;
    const MipMode mip = sm.cfg_.mode.mip;
    const int top = sm.tex_.max_level();
#if !defined(__SSE2__)
    dp::fast::Quad8 q0, q1;  // level0 and level1 taps; q1's lanes are used only where the lane blends
#endif
    for (size_t i = 0; i < n; i += 4) {
      const size_t m = std::min<size_t>(4, n - i);
      const SampleRequest* r = req + i;
      bool shared = true;
      for (size_t k = 1; k < m; ++k) shared &= r[k].lambda_q8 == r[0].lambda_q8;
      if (shared) {  // one level pick for the group
        const LevelPick p = select_levels(lambda_bias_clamp(r[0].lambda_q8, lod), mip, top);
#if defined(__SSE2__)
        const GroupCoords g = group_coords(m, r);
        const GroupLanes g0 = group_lanes<kV.ws, kV.wt>(m, LevelView(levels[p.level0]), border, r, g);
        if (p.blend == 0) {
          store_group(m, out + i, lerp_group(g0));
          continue;
        }
        const dp::fast::Lanes8q x = lerp_group_q8(g0);
        const dp::fast::Lanes8q y = lerp_group_q8(group_lanes<kV.ws, kV.wt>(m, LevelView(levels[p.level1]), border, r, g));
        const __m128i w = _mm_set1_epi32(static_cast<int32_t>((static_cast<uint32_t>(p.blend) << 16) | static_cast<uint32_t>(256 - p.blend)));
        store_group(m, out + i, dp::fast::level_blend8x4_lanes(x, y, w, w));
        continue;
#else
        group_taps<kV.ws, kV.wt>(m, LevelView(levels[p.level0]), border, r, q0);
        if (p.blend == 0) {
          store_lanes(m, out + i, [&](Rgba8* o) { dp::fast::bilinear_lerp8x4(q0, o); });
          continue;
        }
        group_taps<kV.ws, kV.wt>(m, LevelView(levels[p.level1]), border, r, q1);
        const std::array<int, 4> f{p.blend, p.blend, p.blend, p.blend};
        store_lanes(m, out + i, [&](Rgba8* o) { dp::fast::bilinear_blend8x4(q0, q1, f, o); });
        continue;
#endif
      }
      group_own_lambdas<kV.ws, kV.wt>(m, levels, border, lod, mip, top, r, out + i);
    }
  }
}

// sample<kV> for the 16 pairs of wrap modes, indexed by 4 wrap_s + wrap_t.
template <Sampler::FastPaths::Path kP, bool kMip, size_t... k>
constexpr std::array<Sampler::SampleFn, 16> Sampler::FastPaths::wrap_table(std::index_sequence<k...>) {
  return {&sample<Variant{kP, kMip, static_cast<WrapMode>(k / 4), static_cast<WrapMode>(k % 4)}>...};
}

// batch<kV> of LINEAR for the 16 pairs of wrap modes, indexed by 4 wrap_s + wrap_t.
template <bool kMip, size_t... k>
constexpr std::array<Sampler::BatchFn, 16> Sampler::FastPaths::batch_table(std::index_sequence<k...>) {
  return {&batch<Variant{Path::Linear8, kMip, static_cast<WrapMode>(k / 4), static_cast<WrapMode>(k % 4)}>...};
}

// aniso<kV> for the 16 pairs of wrap modes (MIP-mapped), indexed by 4 wrap_s + wrap_t.
template <Sampler::FastPaths::Path kP, size_t... k>
constexpr std::array<Sampler::AnisoFn, 16> Sampler::FastPaths::aniso_table(std::index_sequence<k...>) {
  return {&aniso<Variant{kP, true, static_cast<WrapMode>(k / 4), static_cast<WrapMode>(k % 4)}>...};
}

template <Sampler::FastPaths::Path kP>
Sampler::AnisoFn Sampler::FastPaths::pick_aniso(bool mipmapped, WrapMode ws, WrapMode wt) {
  if (!mipmapped) return &aniso_plain;  // never issued with N > 1 (SamplerDescriptor::aniso())
  return aniso_table<kP>(std::make_index_sequence<16>())[static_cast<size_t>(4 * static_cast<int>(ws) + static_cast<int>(wt))];
}

template <Sampler::FastPaths::Path kP>
Sampler::SampleFn Sampler::FastPaths::pick(bool mipmapped, WrapMode ws, WrapMode wt) {
  const auto k = static_cast<size_t>(4 * static_cast<int>(ws) + static_cast<int>(wt));
  return mipmapped ? wrap_table<kP, true>(std::make_index_sequence<16>())[k]
                   : wrap_table<kP, false>(std::make_index_sequence<16>())[k];
}

void Sampler::FastPaths::setup(Sampler& sm) {
  const Impl& im = *sm.impl_;
  const WrapMode ws = sm.cfg_.wrap_s, wt = sm.cfg_.wrap_t;
  const bool mip = sm.cfg_.mode.mip != MipMode::None;
  const bool bytes = byte_channels(sm.tex_.format);
  sm.sample_fn_ = &sample_plain;
  sm.batch_fn_ = &batch_plain;
  sm.aniso_fn_ = &aniso_plain;
  if (!fast_paths_enabled()) return;  // TFU_PLAIN=1 or --plain: the plain datapath only
  switch (sm.cfg_.mode.base) {
    case BaseFilter::Nearest: break;
    case BaseFilter::Linear:
      if (bytes) {
        sm.sample_fn_ = pick<Path::Linear8>(mip, ws, wt);
        sm.aniso_fn_ = pick_aniso<Path::Linear8>(mip, ws, wt);
        const auto k = static_cast<size_t>(4 * static_cast<int>(ws) + static_cast<int>(wt));
        sm.batch_fn_ = mip ? batch_table<true>(std::make_index_sequence<16>())[k]
                           : batch_table<false>(std::make_index_sequence<16>())[k];
      }
      break;
    case BaseFilter::Cubic:
      if (bytes && im.memo && im.rom->taps() == 4) {
        sm.sample_fn_ = pick<Path::Cubic8>(mip, ws, wt);
        sm.aniso_fn_ = pick_aniso<Path::Cubic8>(mip, ws, wt);
      }
      break;
    case BaseFilter::EdgePreserving:
      if (bytes) {
        sm.sample_fn_ = pick<Path::Edge8>(mip, ws, wt);
        sm.aniso_fn_ = pick_aniso<Path::Edge8>(mip, ws, wt);
      }
      break;
  }
}

}  // namespace tfu
