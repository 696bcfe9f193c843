// The timing recurrences' CUBIC quad path: rtl/unit_recurrence_cubic_quads.hpp says what it forms
// and why it equals the plain blocks.
#include "rtl/unit_recurrence_cubic_quads.hpp"

namespace tfu::rtl::detail {

CubicQuadPath::CubicQuadPath(const Registers& regs, Unit& u, bool enabled)
    : regs_(regs),
      u_(u),
      sampler_ok_(regs.samplers.size(), false),
      texture_ok_(regs.textures.size(), false),
      weights_(regs.samplers.size()) {
  if (!enabled) return;
  for (size_t k = 0; k < regs.samplers.size(); ++k) {
    const SamplerDescriptor& s = regs.samplers[k];
    const TileWeightRom* rom = u.roms.rom(static_cast<int>(k));
    sampler_ok_[k] = takes_sampler(s, rom);
    if (sampler_ok_[k]) weights_[k] = std::make_unique<dp::fast::TileWeightMemo>(*rom, s.cubic_recon);
  }
  for (size_t k = 0; k < regs.textures.size(); ++k) texture_ok_[k] = takes_texture(regs.textures[k]);
}

int CubicQuadPath::address(const QuadReq& q, const AnisoLod& lod) {
  texture_ = q.req.texture;
  stage_ = q.req.stage;
  sampler_ = q.req.sampler;
  pick_ = u_.address_gen.pick_levels(q.req, lod.lambda_q8);
  const int levels = pick_.blend != 0 ? 2 : 1;
  const SamplerDescriptor& c = regs_.samplers[q.req.sampler];
  const TextureDescriptor& tex = regs_.textures[q.req.texture];
  const TileWeightRom& rom = *u_.roms.rom(q.req.sampler);
  norm_ = cubic_normalize_registers(rom.spec().bits, tex);
  const AddressGen::GridFn grid = u_.address_gen.grid_function(q.req.sampler);
  for (int n = 0; n < levels; ++n) {
    const int level = n == 0 ? pick_.level0 : pick_.level1;
    const int w = tex.level_width(level), h = tex.level_height(level);
    std::array<FootprintReq, 4>& f = footprint_[static_cast<size_t>(n)];
    for (size_t k = 0; k < 4; ++k) grid(c, rom.taps(), rom.first_tap(), f[k], w, h, q.s[k], q.t[k], nullptr);
  }
  u_.address_gen.count_isotropic_pixels(4, stat_slot(q.req));
  return levels;
}

// read_out's taps of a full 4 x 4 grid (read_square_taps<4>, row-major: FilterReq order), then
// FilterUnit::filter_level's CUBIC datapath on the words, rounded to the level's code.
void CubicQuadPath::level_codes(int n, int level, std::array<Rgba8, 4>& out) {
  const std::array<FootprintReq, 4>& f = footprint_[static_cast<size_t>(n)];
  const LevelReadout& readout = u_.cache_stage.level_readout(texture_, level);
  dp::fast::TileWeightMemo& weights = *weights_[static_cast<size_t>(sampler_)];
  for (size_t k = 0; k < 4; ++k) {
    Rgba8 taps[16];
    read_square_taps<4>(f[k].grid, readout, taps);
    bool narrow = false;
    const int32_t* w = weights.weights(f[k].tag.fu, f[k].tag.fv, narrow);
    const std::array<int64_t, 4> acc =
        narrow ? dp::fast::cubic_accumulate8_narrow(taps, w) : dp::fast::cubic_accumulate8(taps, w);
    out[k] = dp::fast::cubic_normalize8(acc, norm_);
  }
}

void CubicQuadPath::filter(std::array<Rgba8, 4>& out) {
  level_codes(0, pick_.level0, out);
  if (pick_.blend == 0) return;
  std::array<Rgba8, 4> level1;
  level_codes(1, pick_.level1, level1);
  for (size_t k = 0; k < 4; ++k) out[k] = dp::fast::level_blend8(out[k], level1[k], pick_.blend);
}

}  // namespace tfu::rtl::detail
