// The timing recurrences' LINEAR quad path: rtl/unit_recurrence_linear_quads.hpp says what it
// forms and why it equals the plain blocks.
#include "rtl/unit_recurrence_linear_quads.hpp"

namespace tfu::rtl::detail {

LinearQuadPath::LinearQuadPath(const Registers& regs, Unit& u, bool enabled)
    : regs_(regs), u_(u), sampler_ok_(regs.samplers.size(), false), texture_ok_(regs.textures.size(), false) {
  if (!enabled) return;
  for (size_t k = 0; k < regs.samplers.size(); ++k) {
    const SamplerDescriptor& s = regs.samplers[k];
    sampler_ok_[k] = s.mode.base == BaseFilter::Linear && !s.anisotropic() && s.wrap_s != WrapMode::ClampToBorder &&
                     s.wrap_t != WrapMode::ClampToBorder;
  }
  for (size_t k = 0; k < regs.textures.size(); ++k) {
    const TextureDescriptor& t = regs.textures[k];
    texture_ok_[k] = (t.format == TexelFormat::RGBA8 || t.format == TexelFormat::L8) &&
                     t.content == TextureContent::Texels && !t.compressed;
  }
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
  }
  u_.address_gen.count_isotropic_pixels(4, stat_slot(q.req));
  return levels;
}

void LinearQuadPath::lerp_level(const std::array<FootprintReq, 4>& f, int level, Rgba8* out) const {
  const LevelReadout& readout = u_.cache_stage.level_readout(texture_, level);
  dp::fast::Quad8 q;
  for (size_t k = 0; k < 4; ++k) {
    Rgba8 taps[4];  // (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1): read_out's order
    read_square_taps<2>(f[k].grid, readout, taps);
    q.a[k] = taps[0];
    q.b[k] = taps[1];
    q.c[k] = taps[2];
    q.d[k] = taps[3];
    q.fu[k] = f[k].tag.fu;
    q.fv[k] = f[k].tag.fv;
  }
  FilterUnit::filter_linear8x4(q, out);
}

void LinearQuadPath::filter(std::array<Rgba8, 4>& out) const {
  lerp_level(footprint_[0], pick_.level0, out.data());
  if (pick_.blend == 0) return;
  std::array<Rgba8, 4> level1;
  lerp_level(footprint_[1], pick_.level1, level1.data());
  for (size_t k = 0; k < 4; ++k) out[k] = FilterUnit::blend_linear8(out[k], level1[k], pick_.blend);
}

}  // namespace tfu::rtl::detail
