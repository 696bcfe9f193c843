#include "rtl/filter_unit.hpp"

#include "cmodel/datapath.hpp"
#include "cmodel/datapath_fast.hpp"
#include "cmodel/fast_paths.hpp"

namespace tfu::rtl {

FilterUnit::FilterUnit(sim::Simulator& s, sim::Channel<FilterReq>& i, sim::Channel<Response>& o, const Registers& regs,
                       const WeightRomBank& roms, int lanes)
    : Module(s, "filter"), in_(i), out_(o), regs_(regs), roms_(roms), lanes_(lanes), word_lerps_(fast_paths_enabled()) {
  for (size_t n = 0; n < extra_clocks_.size(); ++n) extra_clocks_[n] = (static_cast<int>(n) + 4 * lanes_ - 1) / (4 * lanes_) - 1;
  busy_cycles_.assign(stat_slots(regs.textures.size()), 0);
}

// The level's result for the blend unit, Q.8: the bilinear lerp unit's dp::bilinear_lerp_q8, the
// other filters' codes with a zero fraction (dp::level_q8).
Texel4 FilterUnit::filter_level(const FilterReq& r, TexelFormat unpack) const {
  const auto texel = [&](int k) { return decode_texel(r.texels[static_cast<size_t>(k)], unpack); };
  switch (r.tag.base) {
    case BaseFilter::Nearest: return dp::level_q8(texel(0));
    case BaseFilter::Linear: return dp::bilinear_lerp_q8({texel(0), texel(1), texel(2), texel(3)}, r.tag.fu, r.tag.fv);
    case BaseFilter::Cubic: {
      const TileWeightRom& rom = *roms_.rom(r.tag.req.sampler);
      std::array<int32_t, 16> w{};
      dp::tile_weights_2d(rom, regs_.samplers[r.tag.req.sampler].cubic_recon, r.tag.fu, r.tag.fv, w);
      std::array<Texel4, 16> c{};
      for (int k = 0; k < r.ntaps; ++k) c[static_cast<size_t>(k)] = texel(k);
      return dp::level_q8(dp::cubic_normalize(dp::cubic_accumulate(c.data(), w.data(), r.ntaps),
                                              cubic_normalize_registers(rom.spec().bits, regs_.textures[r.tag.req.texture])));
    }
    case BaseFilter::EdgePreserving: break;  // its own pipeline (edge_datapath.hpp)
  }
  return {};
}

void FilterUnit::evaluate() {
  if (!in_.can_pop()) return;
  const FilterReq& r = in_.front();
  if (remaining_ < 0) remaining_ = extra_clocks(r.ntaps);
  if (remaining_ > 0) {  // the lanes are still working on this footprint
    --remaining_;
    ++busy_cycles_[stat_slot(r.tag.req)];
    sim_.progress();
    return;
  }
  if (r.tag.emits() && !out_.can_push()) return;
  Response out;
  if (filter(r, out)) out_.push(out);
  in_.pop();
  remaining_ = -1;
  sim_.progress();
}

bool FilterUnit::filter(const FilterReq& r, Response& out) {
  if (r.tag.base == BaseFilter::Linear && byte_channels(r.tag.format) && word_lerps_) {
    // LINEAR on 8-bit words: the same lerp and blend units, on the words (dp::fast::*8); speed only, the plain
    // form is filter_level below (off with TFU_PLAIN=1 or --plain, cmodel/fast_paths.hpp)
    const auto& w = r.texels;
    if (r.tag.holds()) {  // level0 of a blending pixel: its Q.8 result waits in the register
      first8q_ = dp::fast::bilinear_lerp8q(w[0], w[1], w[2], w[3], r.tag.fu, r.tag.fv);
      return false;
    }
    const Rgba8 p = r.tag.blends ? blend_linear8(first8q_, dp::fast::bilinear_lerp8q(w[0], w[1], w[2], w[3], r.tag.fu, r.tag.fv),
                                                 r.tag.blend)
                                 : dp::fast::bilinear_lerp8(w[0], w[1], w[2], w[3], r.tag.fu, r.tag.fv);
    if (r.tag.probes == 1) {
      out = {r.tag.id, p};
      return true;
    }
    // an anisotropic probe: the probe accumulator
    Texel4 c{p.r, p.g, p.b, p.a};
    if (!probes_.add(r.tag, c)) return false;
    out = {r.tag.id, encode_texel(c, r.tag.format)};
    return true;
  }
  // bspline-interp reads the stored coefficient codes (RGBA8 words) instead of the texels.
  const bool coeffs = regs_.textures[r.tag.req.texture].content == TextureContent::BsplineCoefficients;
  const Texel4 q = filter_level(r, coeffs ? TexelFormat::RGBA8 : r.tag.format);
  if (r.tag.holds()) {
    first_ = q;
    return false;
  }
  Texel4 c = r.tag.blends ? dp::level_blend(first_, q, r.tag.blend) : dp::round_level(q);
  if (!probes_.add(r.tag, c)) return false;
  out = {r.tag.id, encode_texel(c, r.tag.format)};
  return true;
}

std::string FilterUnit::state() const { return fmt::format("{}, {}, lanes busy {}", in_.state(), out_.state(), remaining_); }

}  // namespace tfu::rtl
