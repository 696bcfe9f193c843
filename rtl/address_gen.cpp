#include "rtl/address_gen.hpp"

#include "cmodel/aniso.hpp"
#include "cmodel/datapath.hpp"
#include "cmodel/fast_paths.hpp"
#include "cmodel/fixed_coord.hpp"
#include "rtl/address_gen_blocks.hpp"
#include "rtl/address_gen_detail.hpp"
#include "rtl/unit_stats.hpp"

namespace tfu::rtl {

using detail::cells_inside;
using detail::probe_coord;

AddressGen::AddressGen(sim::Simulator& s, sim::Channel<PixelReq>& i, sim::Channel<FootprintReq>& o,
                       const Registers& regs, const WeightRomBank& roms)
    : Module(s, "address_gen"), in_(i), out_(o), regs_(regs), probe_hist_(stat_slots(regs.textures.size())) {
  for (size_t k = 0; k < regs.samplers.size(); ++k) {
    const SamplerDescriptor& c = regs.samplers[k];
    const TileWeightRom* rom = roms.rom(static_cast<int>(k));
    GridFn grid = &grid_any;
    QuadGridFn quad_grid = nullptr;
    const bool fast = fast_paths_enabled();  // off (TFU_PLAIN=1, --plain): grid_any, the plain twin
    if (fast && (c.mode.base == BaseFilter::Linear || c.mode.base == BaseFilter::EdgePreserving))
      grid = fixed_wrap_grid(c.mode.base == BaseFilter::EdgePreserving ? FixedGrid::Cross : FixedGrid::Linear, c.wrap_s,
                             c.wrap_t);
    if (fast && c.mode.base == BaseFilter::Linear) quad_grid = linear_quad_grid(c.wrap_s, c.wrap_t);
    if (fast && c.mode.base == BaseFilter::Cubic && rom->taps() == 4)
      grid = fixed_wrap_grid(FixedGrid::Cubic4, c.wrap_s, c.wrap_t);
    decoded_.push_back({grid, rom ? rom->taps() : 0, rom ? rom->first_tap() : 0, quad_grid});
  }
}

namespace {

// NEAREST: i = floor(s W) (GL); an anisotropic probe: the probe offset's carry into it
// (dp::probe_nearest_tap).
int64_t nearest_tap(float s, int size, const ProbeLevelOffset* o, int64_t offset_q8) {
  const int64_t centre = float_to_fixed(s, static_cast<uint32_t>(size), 0);
  return o ? dp::probe_nearest_tap(centre, dp::texel_coord(s, size), offset_q8) : centre;
}
void nearest_footprint(FootprintReq& f, const SamplerDescriptor& c, int w, int h, float s, float t, const ProbeLevelOffset* o) {
  TapGrid& g = f.grid;
  g.cols = g.rows = 1;
  g.x[0] = static_cast<int16_t>(wrap_index(c.wrap_s, nearest_tap(s, w, o, o ? o->du_q8 : 0), w));
  g.y[0] = static_cast<int16_t>(wrap_index(c.wrap_t, nearest_tap(t, h, o, o ? o->dv_q8 : 0), h));
}

// T x T taps from column i0 + first and row j0 + first (CUBIC: the ROM's taps; the edge cross:
// T = 4, first = -1).
void square_footprint(FootprintReq& f, const SamplerDescriptor& c, int w, int h, const dp::LevelCoord& u,
                      const dp::LevelCoord& v, int first, int taps) {
  std::array<int, 4> col{}, row{};
  wrap_run(c.wrap_s, u.i0 + first, taps, w, col.data());
  wrap_run(c.wrap_t, v.i0 + first, taps, h, row.data());
  TapGrid& g = f.grid;
  g.cols = g.rows = taps;
  for (size_t i = 0; i < static_cast<size_t>(taps); ++i) {
    g.x[i] = static_cast<int16_t>(col[i]);
    g.y[i] = static_cast<int16_t>(row[i]);
  }
}

}  // namespace

void AddressGen::grid_any(const SamplerDescriptor& c, int taps, int first_tap, FootprintReq& f, int w, int h, float s,
                          float t, const ProbeLevelOffset* o) {
  if (c.mode.base == BaseFilter::Nearest) {
    nearest_footprint(f, c, w, h, s, t, o);
  } else {
    const dp::LevelCoord u = probe_coord(s, w, o, o ? o->du_q8 : 0), v = probe_coord(t, h, o, o ? o->dv_q8 : 0);
    f.tag.fu = u.f;
    f.tag.fv = v.f;
    switch (c.mode.base) {
      case BaseFilter::Cubic: square_footprint(f, c, w, h, u, v, first_tap, taps); break;
      case BaseFilter::EdgePreserving:  // the cross: columns and rows -1..2 around the centre square
        square_footprint(f, c, w, h, u, v, -1, 4);
        f.cross = true;
        break;
      case BaseFilter::Linear: square_footprint(f, c, w, h, u, v, 0, 2); break;
      case BaseFilter::Nearest: break;
    }
  }
  TapGrid& g = f.grid;
  g.used = f.cross ? cross_cells(lee_jen::kAllTexels) : square_cells(g.cols, g.rows);
  if (c.wrap_s == WrapMode::ClampToBorder || c.wrap_t == WrapMode::ClampToBorder)
    g.used = static_cast<uint16_t>(g.used & cells_inside(g));
}

void AddressGen::footprint(FootprintReq& f, const PixelReq& p, int level, const ProbeLevelOffset* o) const {
  const SamplerDescriptor& c = regs_.samplers[p.req.sampler];
  const TextureDescriptor& tex = regs_.textures[p.req.texture];
  // Every field written (the output register is reused): fu, fv by the grid, the rest here.
  f.tag = LevelTag{.id = p.id, .req = p.req, .base = c.mode.base, .format = tex.format};
  f.level = level;
  f.optional = 0;
  f.cross = false;
  const SamplerDecode& d = decoded_[p.req.sampler];
  d.grid(c, d.taps, d.first_tap, f, tex.level_width(level), tex.level_height(level), p.s, p.t, o);
  // A compressed texture: the grid in blocks and each tap's texel in its block, for the cache stage.
  if (tex.compressed) block_grid(tex.block(), f.grid, f.blocks);
}

void AddressGen::next_probe() {
  ++probe_;
  offset_ = {probe_offset_q16(pixel_.major_du_q16, pixel_.probes, probe_ + 1),
             probe_offset_q16(pixel_.major_dv_q16, pixel_.probes, probe_ + 1)};
}

void AddressGen::evaluate() {
  if (!holding_ && in_.can_pop()) {
    begin(in_.front());
    in_.pop();
    holding_ = true;
    sim_.progress();
  }
  if (holding_ && out_.can_push()) {
    // The footprint is formed straight in the output register (no copy).
    if (issue(out_.push_slot())) holding_ = false;
    sim_.progress();
  }
}

void AddressGen::begin(const PixelReq& p) {
  pixel_ = p;
  pick_ = pick_levels(p.req, p.lambda_q8);
  count_ = pick_.blend != 0 ? 2 : 1;
  sent_ = 0;
  probe_ = -1;
  ++probe_hist_[stat_slot(p.req)][static_cast<size_t>(pixel_.probes)];
  if (pixel_.probes > 1) next_probe();
}

bool AddressGen::issue(FootprintReq& f) {
  const int level = sent_ == 0 ? pick_.level0 : pick_.level1;
  if (pixel_.probes == 1) {
    footprint(f, pixel_, level, nullptr);
  } else {  // probe probe_ + 1 of N: its offset on this level
    const ProbeLevelOffset o{dp::probe_offset_on_level(offset_.du_q16, level), dp::probe_offset_on_level(offset_.dv_q16, level)};
    footprint(f, pixel_, level, &o);
    f.tag.probes = static_cast<uint8_t>(pixel_.probes);
    f.tag.probe = static_cast<uint8_t>(probe_);
  }
  if (count_ == 2) {
    f.tag.blends = true;
    f.tag.is_level1 = sent_ == 1;
    f.tag.blend = pick_.blend;
  }
  if (++sent_ == count_) {
    if (pixel_.probes > 1 && probe_ + 1 < pixel_.probes) {
      sent_ = 0;
      next_probe();
    } else {
      return true;
    }
  }
  return false;
}

void AddressGen::publish_histogram(sim::Stats& st, const std::array<uint64_t, kMaxAniso + 1>& hist,
                                   bool with_histogram) {
  uint64_t probes = 0;
  for (size_t n = 1; n < hist.size(); ++n) probes += n * hist[n];
  add(st, UnitStat::Probes, probes);
  if (with_histogram)
    st.set_histogram(stat_key(UnitStat::AnisoProbes), std::vector<uint64_t>(hist.begin(), hist.end()));
}

// Decided by the registers, not by the pixels this unit saw: every unit of a run then publishes the
// histogram, and the run's total (the units' histograms added) keeps the one-probe pixels of a unit
// that met no anisotropic pixel.
bool AddressGen::any_anisotropic() const {
  for (const SamplerDescriptor& d : regs_.samplers)
    if (d.anisotropic()) return true;
  return false;
}

void AddressGen::publish(sim::Stats& st) const {
  std::array<uint64_t, kMaxAniso + 1> sum{};
  for (const auto& h : probe_hist_)
    for (size_t n = 0; n < h.size(); ++n) sum[n] += h[n];
  publish_histogram(st, sum, any_anisotropic());
}

void AddressGen::publish_slot(sim::Stats& st, size_t slot) const {
  publish_histogram(st, probe_hist_[slot], any_anisotropic());
}

std::string AddressGen::state() const { return fmt::format("{}, {}, holding {}", in_.state(), out_.state(), holding_); }

}  // namespace tfu::rtl
