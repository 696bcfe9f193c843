// The timing recurrences' probe quad path: rtl/unit_recurrence_probes.hpp says what it forms, its
// plain twin and its equality test.
#include "rtl/unit_recurrence_probes.hpp"

#include <bit>

#include "cmodel/aniso_fast.hpp"

namespace tfu::rtl::detail {

ProbeQuadPath::ProbeQuadPath(const Registers& regs, Unit& u, bool enabled)
    : u_(u), regs_(regs), sampler_ok_(regs.samplers.size(), false), texture_ok_(regs.textures.size(), false) {
  for (auto& pixel : grid_)
    for (TapGrid& g : pixel) g = TapGrid{{0, 0, 0, 0}, {0, 0, 0, 0}, 2, 2, square_cells(2, 2)};
  if (!enabled) return;
  for (size_t k = 0; k < regs.samplers.size(); ++k) sampler_ok_[k] = takes_sampler(regs.samplers[k]);
  for (size_t k = 0; k < regs.textures.size(); ++k) texture_ok_[k] = takes_texture(regs.textures[k]);
}

template <WrapMode kWs, WrapMode kWt>
int ProbeQuadPath::probe_footprints(const QuadReq& q, const AnisoLod& lod) {
  const LevelPick pick = u_.address_gen.pick_levels(q.req, lod.lambda_q8);
  const size_t levels = pick.blend != 0 ? 2 : 1, probes = static_cast<size_t>(lod.probes);
  const TextureDescriptor& tex = regs_.textures[q.req.texture];
  // Per level: its size, read-out registers (a local copy: the texel words are char-typed) and the
  // four pixels' centre coordinates, Q.8 (dp::texel_coord, once per pixel and level).
  std::array<int, 2> w{}, h{};
  std::array<LevelReadout, 2> readout;
  std::array<std::array<int64_t, 4>, 2> cu{}, cv{};
  for (size_t n = 0; n < levels; ++n) {
    const int level = n == 0 ? pick.level0 : pick.level1;
    w[n] = tex.level_width(level);
    h[n] = tex.level_height(level);
    readout[n] = u_.cache_stage.level_readout(texture_, level);
    for (size_t k = 0; k < 4; ++k) {
      cu[n][k] = dp::fast::join_q8(dp::texel_coord(q.s[k], w[n]));
      cv[n][k] = dp::fast::join_q8(dp::texel_coord(q.t[k], h[n]));
    }
    for (size_t i = 0; i < probes; ++i) levels_of_[i * levels + n] = level;
  }
  // Probe i's offset (Q.16 level-0 texels, probe ROM word (N, i + 1); N = 1: q(1, 1) = 0, the
  // centre, as the plain unit's probe without offset).
  const ProbeRomWord* rom = probe_rom().data() + probe_rom_address(lod.probes, 1);
  const int64_t major_du = dp::fast::clamped_major(lod.major_du_q16), major_dv = dp::fast::clamped_major(lod.major_dv_q16);
  // The four pixels' footprints of probe i on level n (its offset on the level `du`, `dv`): the
  // grids (AddressGen::grid_fixed's LINEAR grid) and the lerp unit's lanes (lane k pixel k; the taps
  // in read_square_taps<2>'s order (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1)).
  struct Lanes {
    std::array<uint32_t, 4> a, b, c, d, fu, fv;
  };
  const auto level_lanes = [&](size_t i, size_t n, int64_t du, int64_t dv, Lanes& l) __attribute__((always_inline)) {
    const LevelReadout& r = readout[n];
    const auto word = [&](size_t offset) { return std::bit_cast<uint32_t>(r.at(offset)); };
#pragma GCC unroll 4
    for (size_t k = 0; k < 4; ++k) {
      const dp::LevelCoord u = dp::fast::split_q8(cu[n][k] + du), v = dp::fast::split_q8(cv[n][k] + dv);
      int col[2], row[2];
      dp::fast::wrap_taps<kWs, 2>(u.i0, w[n], col);
      dp::fast::wrap_taps<kWt, 2>(v.i0, h[n], row);
      TapGrid& g = grid_[k][i * levels + n];
      g.x[0] = static_cast<int16_t>(col[0]);
      g.x[1] = static_cast<int16_t>(col[1]);
      g.y[0] = static_cast<int16_t>(row[0]);
      g.y[1] = static_cast<int16_t>(row[1]);
      const size_t c0 = r.column(col[0]), c1 = r.column(col[1]), r0 = r.row(row[0]), r1 = r.row(row[1]);
      l.a[k] = word(c0 + r0);
      l.b[k] = word(c1 + r0);
      l.c[k] = word(c0 + r1);
      l.d[k] = word(c1 + r1);
      l.fu[k] = u.f;
      l.fv[k] = v.f;
    }
  };
  std::array<Rgba8, 4> c;  // probe i's four colours
#if defined(__SSE2__)
  const auto reg = [](const std::array<uint32_t, 4>& x) __attribute__((always_inline)) {
    return _mm_setr_epi32(static_cast<int32_t>(x[0]), static_cast<int32_t>(x[1]), static_cast<int32_t>(x[2]),
                          static_cast<int32_t>(x[3]));
  };
  const auto pair = static_cast<int32_t>((static_cast<uint32_t>(pick.blend) << 16) | static_cast<uint32_t>(256 - pick.blend));
  const __m128i blend_w = _mm_set1_epi32(pair), zero = _mm_setzero_si128();
  __m128i acc01 = zero, acc23 = zero;  // the probe accumulators, 16-bit (R, G, B, A) of pixels 0, 1 and 2, 3
#else
  std::array<std::array<int32_t, 4>, 4> acc{};
#endif
  for (size_t i = 0; i < probes; ++i) {
    const int64_t du = dp::fast::scale_probe_fraction(major_du, rom[i].frac_q16),
                  dv = dp::fast::scale_probe_fraction(major_dv, rom[i].frac_q16);
    Lanes l0, l1;
    level_lanes(i, 0, dp::fast::probe_offset_on_level(du, pick.level0), dp::fast::probe_offset_on_level(dv, pick.level0), l0);
    if (levels == 2)
      level_lanes(i, 1, dp::fast::probe_offset_on_level(du, pick.level1), dp::fast::probe_offset_on_level(dv, pick.level1), l1);
#if defined(__SSE2__)
    __m128i words;
    if (levels == 2) {
      const dp::fast::Lanes8q x = dp::fast::bilinear_lerp8x4q_lanes(reg(l0.a), reg(l0.b), reg(l0.c), reg(l0.d), reg(l0.fu), reg(l0.fv));
      const dp::fast::Lanes8q y = dp::fast::bilinear_lerp8x4q_lanes(reg(l1.a), reg(l1.b), reg(l1.c), reg(l1.d), reg(l1.fu), reg(l1.fv));
      words = dp::fast::level_blend8x4_lanes(x, y, blend_w, blend_w);
    } else {
      words = dp::fast::bilinear_lerp8x4_lanes(reg(l0.a), reg(l0.b), reg(l0.c), reg(l0.d), reg(l0.fu), reg(l0.fv));
    }
    const __m128i wi = _mm_set1_epi16(static_cast<int16_t>(rom[i].weight));
    acc01 = _mm_add_epi16(acc01, _mm_mullo_epi16(_mm_unpacklo_epi8(words, zero), wi));
    acc23 = _mm_add_epi16(acc23, _mm_mullo_epi16(_mm_unpackhi_epi8(words, zero), wi));
#else
    const auto quad = [](const Lanes& l) {
      dp::fast::Quad8 q8;
      for (size_t k = 0; k < 4; ++k) {
        q8.a[k] = std::bit_cast<Rgba8>(l.a[k]), q8.b[k] = std::bit_cast<Rgba8>(l.b[k]);
        q8.c[k] = std::bit_cast<Rgba8>(l.c[k]), q8.d[k] = std::bit_cast<Rgba8>(l.d[k]);
        q8.fu[k] = l.fu[k], q8.fv[k] = l.fv[k];
      }
      return q8;
    };
    if (levels == 2)
      FilterUnit::filter_blend_linear8x4(quad(l0), quad(l1), pick.blend, c.data());
    else
      FilterUnit::filter_linear8x4(quad(l0), c.data());
    const int32_t wi = rom[i].weight;
    for (size_t k = 0; k < 4; ++k) {
      acc[k][0] += wi * c[k].r;
      acc[k][1] += wi * c[k].g;
      acc[k][2] += wi * c[k].b;
      acc[k][3] += wi * c[k].a;
    }
#endif
  }
  // (sum + 128) >> 8 per channel, in 0..255: encode_texel of RGBA8 and L8 packs it unchanged.
  constexpr int kHalf = 1 << (kAnisoWeightBits - 1);
#if defined(__SSE2__)
  const auto result = [&](__m128i sum) { return _mm_srli_epi16(_mm_add_epi16(sum, _mm_set1_epi16(kHalf)), kAnisoWeightBits); };
  _mm_storeu_si128(reinterpret_cast<__m128i*>(c.data()), _mm_packus_epi16(result(acc01), result(acc23)));
#else
  for (size_t k = 0; k < 4; ++k) {
    Texel4 p;
    for (size_t ch = 0; ch < 4; ++ch) p[ch] = (acc[k][ch] + kHalf) >> kAnisoWeightBits;
    c[k] = encode_texel(p, tex.format);
  }
#endif
  colour_ = c;
  u_.address_gen.count_pixels(4, lod.probes, stat_slot(q.req));
  return static_cast<int>(probes * levels);
}

template <size_t... k>
ProbeQuadPath::ProbeFootprintsFn ProbeQuadPath::probe_footprints_fn(size_t wrap_pair, std::index_sequence<k...>) {
  static constexpr ProbeFootprintsFn kTable[] = {
      &ProbeQuadPath::probe_footprints<static_cast<WrapMode>(k / 4), static_cast<WrapMode>(k % 4)>...};
  return kTable[wrap_pair];
}

void ProbeQuadPath::look_up(int footprints, int levels) {
  TexelCache& tags = u_.cache_stage.tags();
  const std::array<int, 2> level{levels_of_[0], levels_of_[static_cast<size_t>(levels) - 1]};
  std::array<LineCounts, 2> sum{};  // per level
  uint16_t missed = 0;
  for (size_t k = 0; k < 4; ++k)
    tags.access_squares(texture_, level, levels, grid_[k].data(), static_cast<size_t>(footprints), lookup_[k].data(),
                        missed_.data(), missed, sum);
  const size_t slot = stat_slot(texture_, stage_);
  for (size_t n = 0; n < static_cast<size_t>(levels); ++n) u_.cache_stage.count_lines(slot, level[n], sum[n]);
}

int ProbeQuadPath::address(const QuadReq& q, const AnisoLod& lod) {
  texture_ = q.req.texture;
  stage_ = q.req.stage;
  const SamplerDescriptor& c = regs_.samplers[q.req.sampler];
  const auto pair = static_cast<size_t>(4 * static_cast<int>(c.wrap_s) + static_cast<int>(c.wrap_t));
  const int footprints = (this->*probe_footprints_fn(pair, std::make_index_sequence<16>()))(q, lod);
  look_up(footprints, footprints / lod.probes);
  return footprints;
}

}  // namespace tfu::rtl::detail
