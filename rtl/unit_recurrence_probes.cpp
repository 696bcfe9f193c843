// The timing recurrences' probe quad path: rtl/unit_recurrence_probes.hpp says what it forms, its
// plain twin and its equality test.
#include "rtl/unit_recurrence_probes.hpp"

#include "cmodel/aniso_fast.hpp"

namespace tfu::rtl::detail {

ProbeQuadPath::ProbeQuadPath(const Registers& regs, Unit& u, bool enabled)
    : u_(u), regs_(regs), sampler_ok_(regs.samplers.size(), false), texture_ok_(regs.textures.size(), false) {
  if (!enabled) return;
  for (size_t k = 0; k < regs.samplers.size(); ++k) sampler_ok_[k] = takes_sampler(regs.samplers[k]);
  for (size_t k = 0; k < regs.textures.size(); ++k) texture_ok_[k] = takes_texture(regs.textures[k]);
}

// AddressGen::grid_fixed's LINEAR grid at the probe's coordinate (centre + offset, Q.8), then
// read_square_taps<2> of the grid into lane k of the probe's lerp lanes.
template <WrapMode kWs, WrapMode kWt>
void ProbeQuadPath::level_footprints(size_t k, size_t n, float s, float t, int w, int h, const LevelReadout& readout) {
  const int64_t cu = dp::fast::join_q8(dp::texel_coord(s, w)), cv = dp::fast::join_q8(dp::texel_coord(t, h));
  const auto levels = static_cast<size_t>(levels_);
  for (size_t i = 0; i < static_cast<size_t>(probes_); ++i) {
    const dp::LevelCoord u = dp::fast::split_q8(cu + du_q8_[n][i]), v = dp::fast::split_q8(cv + dv_q8_[n][i]);
    int col[2], row[2];
    dp::fast::wrap_taps<kWs, 2>(u.i0, w, col);
    dp::fast::wrap_taps<kWt, 2>(v.i0, h, row);
    TapGrid& g = grid_[k][i * levels + n];
    g.x = {static_cast<int16_t>(col[0]), static_cast<int16_t>(col[1]), 0, 0};
    g.y = {static_cast<int16_t>(row[0]), static_cast<int16_t>(row[1]), 0, 0};
    g.cols = g.rows = 2;
    g.used = square_cells(2, 2);
    Rgba8 taps[4];  // (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1): read_out's order
    read_square_taps<2>(g, readout, taps);
    dp::fast::Quad8& q = taps_[n][i];
    q.a[k] = taps[0];
    q.b[k] = taps[1];
    q.c[k] = taps[2];
    q.d[k] = taps[3];
    q.fu[k] = u.f;
    q.fv[k] = v.f;
  }
}

template <size_t... k>
ProbeQuadPath::LevelFootprintsFn ProbeQuadPath::level_footprints_fn(size_t wrap_pair, std::index_sequence<k...>) {
  static constexpr LevelFootprintsFn kTable[] = {
      &ProbeQuadPath::level_footprints<static_cast<WrapMode>(k / 4), static_cast<WrapMode>(k % 4)>...};
  return kTable[wrap_pair];
}

int ProbeQuadPath::address(const QuadReq& q, const AnisoLod& lod) {
  texture_ = q.req.texture;
  stage_ = q.req.stage;
  probes_ = lod.probes;
  pick_ = u_.address_gen.pick_levels(q.req, lod.lambda_q8);
  levels_ = pick_.blend != 0 ? 2 : 1;
  const SamplerDescriptor& c = regs_.samplers[q.req.sampler];
  const TextureDescriptor& tex = regs_.textures[q.req.texture];
  format_ = tex.format;
  // Probe i's offset (Q.16 level-0 texels, probe ROM word (N, i + 1)), then on each level.
  const ProbeRomWord* rom = probe_rom().data() + probe_rom_address(probes_, 1);
  const int64_t major_du = dp::fast::clamped_major(lod.major_du_q16), major_dv = dp::fast::clamped_major(lod.major_dv_q16);
  for (size_t i = 0; i < static_cast<size_t>(probes_); ++i) {
    // N = 1: the plain unit adds no offset (the centre's coordinate), the same as an offset of 0
    // (q(1, 1) = 0).
    const int64_t du = dp::fast::scale_probe_fraction(major_du, rom[i].frac_q16),
                  dv = dp::fast::scale_probe_fraction(major_dv, rom[i].frac_q16);
    for (size_t n = 0; n < static_cast<size_t>(levels_); ++n) {
      const int level = n == 0 ? pick_.level0 : pick_.level1;
      du_q8_[n][i] = dp::fast::probe_offset_on_level(du, level);
      dv_q8_[n][i] = dp::fast::probe_offset_on_level(dv, level);
      levels_of_[i * static_cast<size_t>(levels_) + n] = level;
    }
  }
  const auto pair = static_cast<size_t>(4 * static_cast<int>(c.wrap_s) + static_cast<int>(c.wrap_t));
  const LevelFootprintsFn footprints = level_footprints_fn(pair, std::make_index_sequence<16>());
  for (size_t n = 0; n < static_cast<size_t>(levels_); ++n) {
    const int level = n == 0 ? pick_.level0 : pick_.level1;
    const int w = tex.level_width(level), h = tex.level_height(level);
    const LevelReadout& readout = u_.cache_stage.level_readout(texture_, level);
    for (size_t k = 0; k < 4; ++k) (this->*footprints)(k, n, q.s[k], q.t[k], w, h, readout);
  }
  u_.address_gen.count_pixels(4, probes_, stat_slot(q.req));
  return probes_ * levels_;
}

void ProbeQuadPath::filter(std::array<Rgba8, 4>& out) const {
  const ProbeRomWord* rom = probe_rom().data() + probe_rom_address(probes_, 1);
  // The probe accumulator of each pixel: sum of w(N, i) c_i per channel, at most 256 * 255.
  std::array<std::array<int32_t, 4>, 4> acc{};
  for (size_t i = 0; i < static_cast<size_t>(probes_); ++i) {
    std::array<Rgba8, 4> c;
    if (levels_ == 2)
      FilterUnit::filter_blend_linear8x4(taps_[0][i], taps_[1][i], pick_.blend, c.data());
    else
      FilterUnit::filter_linear8x4(taps_[0][i], c.data());
    const int32_t w = rom[i].weight;
    for (size_t k = 0; k < 4; ++k) {
      acc[k][0] += w * c[k].r;
      acc[k][1] += w * c[k].g;
      acc[k][2] += w * c[k].b;
      acc[k][3] += w * c[k].a;
    }
  }
  constexpr int32_t kHalf = 1 << (kAnisoWeightBits - 1);
  for (size_t k = 0; k < 4; ++k) {
    Texel4 p;
    for (size_t ch = 0; ch < 4; ++ch) p[ch] = (acc[k][ch] + kHalf) >> kAnisoWeightBits;
    out[k] = encode_texel(p, format_);
  }
}

}  // namespace tfu::rtl::detail
