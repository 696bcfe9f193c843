// The timing recurrences' LINEAR quad path: rtl/unit_recurrence_linear_quads.hpp says what it
// forms and why it equals the plain blocks.
#include "rtl/unit_recurrence_linear_quads.hpp"

namespace tfu::rtl::detail {

LinearQuadPath::LinearQuadPath(const Registers& regs, Unit& u, bool enabled)
    : regs_(regs), u_(u), sampler_ok_(regs.samplers.size(), false), texture_ok_(regs.textures.size(), false) {
  for (TapGrid& g : grids_) g = TapGrid{{0, 0, 0, 0}, {0, 0, 0, 0}, 2, 2, square_cells(2, 2)};
  if (!enabled) return;
  for (size_t k = 0; k < regs.samplers.size(); ++k) sampler_ok_[k] = takes_sampler(regs.samplers[k]);
  for (size_t k = 0; k < regs.textures.size(); ++k) texture_ok_[k] = takes_texture(regs.textures[k]);
}

int LinearQuadPath::address(const QuadReq& q, const AnisoLod& lod) {
  texture_ = q.req.texture;
  stage_ = q.req.stage;
  pick_ = u_.address_gen.pick_levels(q.req, lod.lambda_q8);
  const int levels = pick_.blend != 0 ? 2 : 1;
  const SamplerDescriptor& c = regs_.samplers[q.req.sampler];
  const TextureDescriptor& tex = regs_.textures[q.req.texture];
  const AddressGen::GridFn grid = u_.address_gen.grid_function(q.req.sampler);
  const AddressGen::QuadGridFn quad_grid = u_.address_gen.quad_grid_function(q.req.sampler);
  for (int n = 0; n < levels; ++n) {
    const int level = n == 0 ? pick_.level0 : pick_.level1;
    const int w = tex.level_width(level), h = tex.level_height(level);
    std::array<FootprintReq, 4>& f = footprint_[static_cast<size_t>(n)];
    if (quad_grid != nullptr) {  // the four at once (AddressGen::quad_grid_function; its twin: the loop below)
      quad_grid(f.data(), w, h, q.s.data(), q.t.data());
    } else {
      for (size_t k = 0; k < 4; ++k) grid(c, 2, 0, f[k], w, h, q.s[k], q.t[k], nullptr);  // grid, fu, fv
    }
    if (tex.compressed)
      for (size_t k = 0; k < 4; ++k) block_grid(tex.block(), f[k].grid, squares_[static_cast<size_t>(n)][k]);
  }
  compressed_ = tex.compressed;
  srgb_ = tex.format == TexelFormat::SRGBA8;  // takes_texture: compressed
  if (!compressed_) look_up(levels);
  u_.address_gen.count_isotropic_pixels(4, stat_slot(q.req));
  return levels;
}

void LinearQuadPath::look_up(int levels) {
  const auto n = static_cast<size_t>(levels);
  levels_ = levels;
  for (size_t k = 0; k < 4; ++k)
    for (size_t m = 0; m < n; ++m) {  // the columns and rows (2 x 2, every cell used: the rest as set up)
      grids_[k * n + m].x = footprint_[m][k].grid.x;
      grids_[k * n + m].y = footprint_[m][k].grid.y;
    }
  std::array<LineCounts, 2> sum{};  // per level
  uint16_t missed = 0;
  const std::array<int, 2> level{pick_.level0, levels == 2 ? pick_.level1 : pick_.level0};
  u_.cache_stage.tags().access_squares(texture_, level, levels, grids_.data(), 4 * n, lookup_.data(), missed_.data(),
                                       missed, sum);
  const size_t slot = stat_slot(texture_, stage_);
  for (size_t m = 0; m < n; ++m) u_.cache_stage.count_lines(slot, level[m], sum[m]);
}

uint64_t LinearQuadPath::admit_compressed(int k, int n, uint64_t now, int& bank_cycles) {
  return u_.cache_stage.admit_block_square(texture_, stage_, n == 0 ? pick_.level0 : pick_.level1,
                                           footprint_[static_cast<size_t>(n)][static_cast<size_t>(k)].grid,
                                           squares_[static_cast<size_t>(n)][static_cast<size_t>(k)], now, bank_cycles);
}

void LinearQuadPath::level_taps(int n, int level, dp::fast::Quad8& q) const {
  const std::array<FootprintReq, 4>& f = footprint_[static_cast<size_t>(n)];
  const auto lanes = [&](size_t k, const Rgba8* taps) {
    q.a[k] = taps[0];
    q.b[k] = taps[1];
    q.c[k] = taps[2];
    q.d[k] = taps[3];
    q.fu[k] = f[k].tag.fu;
    q.fv[k] = f[k].tag.fv;
  };
  if (compressed_) {
    std::array<std::array<Rgba8, 4>, 4> taps;
    u_.cache_stage.read_block_squares(texture_, level, squares_[static_cast<size_t>(n)], taps);
    for (size_t k = 0; k < 4; ++k) lanes(k, taps[k].data());
  } else {
    const LevelReadout& readout = u_.cache_stage.level_readout(texture_, level);
    for (size_t k = 0; k < 4; ++k) {
      Rgba8 taps[4];  // (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1): read_out's order
      read_square_taps<2>(f[k].grid, readout, taps);
      lanes(k, taps);
    }
  }
}

// The four footprints of one level on a compressed SRGBA8 texture: their taps as on any compressed
// texture, each decoded to linear unorm12 (decode_texel) and lerped as FilterUnit::filter_level
// does: the lerp unit's Q.8 result for the blend unit (dp::bilinear_lerp_q8).
std::array<Texel4, 4> LinearQuadPath::srgb_level(int n, int level) const {
  const std::array<FootprintReq, 4>& f = footprint_[static_cast<size_t>(n)];
  std::array<std::array<Rgba8, 4>, 4> taps;
  u_.cache_stage.read_block_squares(texture_, level, squares_[static_cast<size_t>(n)], taps);
  std::array<Texel4, 4> c;
  for (size_t k = 0; k < 4; ++k) {
    const auto linear = [&](size_t t) { return decode_texel(taps[k][t], TexelFormat::SRGBA8); };
    c[k] = dp::bilinear_lerp_q8({linear(0), linear(1), linear(2), linear(3)}, f[k].tag.fu, f[k].tag.fv);
  }
  return c;
}

// FilterUnit::filter's plain branch for an isotropic pixel: level0's Q.8 result, blended with
// level1's (dp::level_blend, one rounding) when the pixel blends, else rounded (dp::round_level),
// encoded back to the stored format.
void LinearQuadPath::filter_srgb(std::array<Rgba8, 4>& out) const {
  const std::array<Texel4, 4> q0 = srgb_level(0, pick_.level0);
  std::array<Texel4, 4> c;
  if (pick_.blend != 0) {
    const std::array<Texel4, 4> q1 = srgb_level(1, pick_.level1);
    for (size_t k = 0; k < 4; ++k) c[k] = dp::level_blend(q0[k], q1[k], pick_.blend);
  } else {
    for (size_t k = 0; k < 4; ++k) c[k] = dp::round_level(q0[k]);
  }
  for (size_t k = 0; k < 4; ++k) out[k] = encode_texel(c[k], TexelFormat::SRGBA8);
}

void LinearQuadPath::filter(std::array<Rgba8, 4>& out) const {
  if (srgb_) [[unlikely]] {
    filter_srgb(out);
    return;
  }
  dp::fast::Quad8 q0, q1;
  level_taps(0, pick_.level0, q0);
  if (pick_.blend == 0) {
    FilterUnit::filter_linear8x4(q0, out.data());
    return;
  }
  level_taps(1, pick_.level1, q1);
  FilterUnit::filter_blend_linear8x4(q0, q1, pick_.blend, out.data());
}

}  // namespace tfu::rtl::detail
