// The timing recurrences' LINEAR quad path: rtl/unit_recurrence_linear_quads.hpp says what it
// forms and why it equals the plain blocks.
#include "rtl/unit_recurrence_linear_quads.hpp"

namespace tfu::rtl::detail {

LinearQuadPath::LinearQuadPath(const Registers& regs, Unit& u, bool enabled)
    : regs_(regs), u_(u), sampler_ok_(regs.samplers.size(), false), texture_ok_(regs.textures.size(), false) {
  if (!enabled) return;
  for (size_t k = 0; k < regs.samplers.size(); ++k) {
    const SamplerDescriptor& s = regs.samplers[k];
    sampler_ok_[k] = s.mode.base == BaseFilter::Linear && s.mode.mip == MipMode::None &&
                     s.wrap_s != WrapMode::ClampToBorder && s.wrap_t != WrapMode::ClampToBorder;
  }
  for (size_t k = 0; k < regs.textures.size(); ++k) {
    const TextureDescriptor& t = regs.textures[k];
    texture_ok_[k] = (t.format == TexelFormat::RGBA8 || t.format == TexelFormat::L8) && t.content == TextureContent::Texels;
  }
}

void LinearQuadPath::address(const QuadReq& q) {
  texture_ = q.req.texture;
  stage_ = q.req.stage;
  const SamplerDescriptor& c = regs_.samplers[q.req.sampler];
  const TextureDescriptor& tex = regs_.textures[q.req.texture];
  const AddressGen::GridFn grid = u_.addr.grid_function(q.req.sampler);
  const int w = tex.level_width(0), h = tex.level_height(0);
  for (size_t k = 0; k < 4; ++k) grid(c, 2, 0, footprint_[k], w, h, q.s[k], q.t[k], nullptr);  // grid, fu, fv
  u_.addr.count_single_footprint_pixels(4);
}

void LinearQuadPath::filter(std::array<Rgba8, 4>& out) const {
  const LevelReadout& level = u_.cst.level_readout(texture_, 0);
  dp::Quad8 q;
  for (size_t k = 0; k < 4; ++k) {
    Rgba8 taps[4];  // (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1): read_out's order
    read_square_taps<2>(footprint_[k].grid, level, taps);
    q.a[k] = taps[0];
    q.b[k] = taps[1];
    q.c[k] = taps[2];
    q.d[k] = taps[3];
    q.fu[k] = footprint_[k].tag.fu;
    q.fv[k] = footprint_[k].tag.fv;
  }
  FilterUnit::filter_linear8x4(q, out.data());
}

}  // namespace tfu::rtl::detail
