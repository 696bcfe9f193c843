#include "rtl/address_gen.hpp"

#include "cmodel/datapath.hpp"

namespace tfu::rtl {

AddressGen::AddressGen(sim::Simulator& s, sim::Channel<PixelReq>& i, sim::Channel<FootprintReq>& o, const Sampler& sm)
    : Module(s, "address_gen"), in_(i), out_(o), smp_(sm) {}

namespace {

Tap tap(int x, int y) { return Tap{static_cast<int16_t>(x), static_cast<int16_t>(y), x < 0 || y < 0}; }

// NEAREST: i = floor(s W) (GL).
void nearest_footprint(FootprintReq& f, const SamplerConfig& c, const Image& img, float s, float t) {
  f.ntaps = 1;
  f.taps[0] = tap(wrap_index(c.wrap_s, float_to_fixed(s, static_cast<uint32_t>(img.width), 0), img.width),
                  wrap_index(c.wrap_t, float_to_fixed(t, static_cast<uint32_t>(img.height), 0), img.height));
}

// A T x T block of taps from column i0 + first and row j0 + first, row-major (LINEAR: T = 2,
// first = 0; CUBIC: the ROM's taps).
void square_footprint(FootprintReq& f, const SamplerConfig& c, const Image& img, const dp::LevelCoord& u,
                      const dp::LevelCoord& v, int first, int taps) {
  std::array<int, 4> col{}, row{};
  wrap_run(c.wrap_s, u.i0 + first, taps, img.width, col.data());
  wrap_run(c.wrap_t, v.i0 + first, taps, img.height, row.data());
  f.ntaps = taps * taps;
  for (int j = 0; j < taps; ++j)
    for (int i = 0; i < taps; ++i)
      f.taps[static_cast<size_t>(j * taps + i)] = tap(col[static_cast<size_t>(i)], row[static_cast<size_t>(j)]);
}

// EDGE_PRESERVING: the 12-texel cross, tap k = texel C(k+1) (Lee & Jen Eq. 4), columns and rows
// -1..2 around the centre square.
void cross_footprint(FootprintReq& f, const SamplerConfig& c, const Image& img, const dp::LevelCoord& u,
                     const dp::LevelCoord& v) {
  std::array<int, 4> col{}, row{};
  wrap_run(c.wrap_s, u.i0 - 1, 4, img.width, col.data());
  wrap_run(c.wrap_t, v.i0 - 1, 4, img.height, row.data());
  static const std::array<lee_jen::TexelPos, lee_jen::kTexels> kPos = [] {
    std::array<lee_jen::TexelPos, lee_jen::kTexels> p{};
    for (int n = 1; n <= lee_jen::kTexels; ++n) p[static_cast<size_t>(n - 1)] = lee_jen::texel_pos(n);
    return p;
  }();
  f.ntaps = lee_jen::kTexels;
  for (size_t k = 0; k < lee_jen::kTexels; ++k)
    f.taps[k] = tap(col[static_cast<size_t>(kPos[k].x + 1)], row[static_cast<size_t>(kPos[k].y + 1)]);
}

}  // namespace

void AddressGen::footprint(FootprintReq& f, uint32_t id, int level, float s, float t) const {
  const Image& img = smp_.texture().levels[static_cast<size_t>(level)];
  const SamplerConfig& c = smp_.config();
  f.tag = LevelTag{};
  f.tag.id = id;
  f.level = level;
  f.optional = 0;
  if (c.mode.base == BaseFilter::Nearest) return nearest_footprint(f, c, img, s, t);
  const dp::LevelCoord u = dp::texel_coord(s, img.width), v = dp::texel_coord(t, img.height);
  f.tag.fu = u.f;
  f.tag.fv = v.f;
  switch (c.mode.base) {
    case BaseFilter::Linear: return square_footprint(f, c, img, u, v, 0, 2);
    case BaseFilter::Cubic: return square_footprint(f, c, img, u, v, smp_.cubic_rom()->first_tap(), smp_.cubic_rom()->taps());
    case BaseFilter::EdgePreserving: return cross_footprint(f, c, img, u, v);
    case BaseFilter::Nearest: break;
  }
}

void AddressGen::evaluate() {
  if (!holding_ && in_.can_pop()) {
    const PixelReq& p = in_.front();
    pixel_ = p;
    lod_ = smp_.lod_info(p.lambda);
    count_ = lod_.blend != 0 ? 2 : 1;
    in_.pop();
    holding_ = true;
    sent_ = 0;
    sim_.progress();
  }
  if (holding_ && out_.can_push()) {
    // The footprint is formed straight in the output register (no copy).
    FootprintReq& f = out_.push_slot();
    footprint(f, pixel_.id, sent_ == 0 ? lod_.level0 : lod_.level1, pixel_.s, pixel_.t);
    if (count_ == 2) {
      f.tag.two = true;
      f.tag.second = sent_ == 1;
      f.tag.blend = lod_.blend;
    }
    if (++sent_ == count_) holding_ = false;
    sim_.progress();
  }
}

std::string AddressGen::state() const { return fmt::format("{}, {}, holding {}", in_.state(), out_.state(), holding_); }

}  // namespace tfu::rtl
