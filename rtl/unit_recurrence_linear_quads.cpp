// The timing recurrences' LINEAR quad path: rtl/unit_recurrence_linear_quads.hpp says what it
// forms and why it equals the plain blocks.
#include "rtl/unit_recurrence_linear_quads.hpp"

namespace tfu::rtl::detail {

LinearQuadPath::LinearQuadPath(const Registers& regs, Unit& u, bool enabled)
    : regs_(regs), u_(u), sampler_ok_(regs.samplers.size(), false), texture_ok_(regs.textures.size(), false) {
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
  for (int n = 0; n < levels; ++n) {
    const int level = n == 0 ? pick_.level0 : pick_.level1;
    const int w = tex.level_width(level), h = tex.level_height(level);
    std::array<FootprintReq, 4>& f = footprint_[static_cast<size_t>(n)];
    for (size_t k = 0; k < 4; ++k) grid(c, 2, 0, f[k], w, h, q.s[k], q.t[k], nullptr);  // grid, fu, fv
    if (tex.compressed) form_block_squares(tex, f, squares_[static_cast<size_t>(n)]);
  }
  compressed_ = tex.compressed;
  u_.address_gen.count_isotropic_pixels(4, stat_slot(q.req));
  return levels;
}

// The block column and row of each tap column and row (x / block_w, y / block_h by block_quotient:
// every tap is inside the level) and each tap's texel inside its block.
void LinearQuadPath::form_block_squares(const TextureDescriptor& tex, const std::array<FootprintReq, 4>& f,
                                        std::array<CacheStage::BlockSquare, 4>& sq) const {
  const BlockFormatInfo& b = tex.block();
  const uint32_t mw = block_reciprocal(b.block_w), mh = block_reciprocal(b.block_h);
  for (size_t k = 0; k < 4; ++k) {
    const TapGrid& g = f[k].grid;
    CacheStage::BlockSquare& s = sq[k];
    s.blocks = g;
    int in_x[2], in_y[2];
    for (size_t i = 0; i < 2; ++i) {
      const int bx = block_quotient(g.x[i], mw), by = block_quotient(g.y[i], mh);
      s.blocks.x[i] = static_cast<int16_t>(bx);
      s.blocks.y[i] = static_cast<int16_t>(by);
      in_x[i] = g.x[i] - bx * b.block_w;
      in_y[i] = g.y[i] - by * b.block_h;
    }
    for (size_t t = 0; t < 4; ++t)  // read_out's order: tap t = (column t & 1, row t >> 1)
      s.texel[t] = static_cast<uint8_t>(in_y[t >> 1] * b.block_w + in_x[t & 1u]);
  }
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

void LinearQuadPath::filter(std::array<Rgba8, 4>& out) const {
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
