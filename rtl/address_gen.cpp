#include "rtl/address_gen.hpp"

#include "cmodel/datapath.hpp"

namespace tfu::rtl {

AddressGen::AddressGen(sim::Simulator& s, sim::Channel<PixelReq>& i, sim::Channel<FootprintReq>& o, const Sampler& sm)
    : Module(s, "address_gen"), in_(i), out_(o), smp_(sm) {}

FootprintReq AddressGen::footprint(uint32_t id, int level, float s, float t) const {
  const Image& img = smp_.texture().levels[static_cast<size_t>(level)];
  const SamplerConfig& c = smp_.config();
  FootprintReq f;
  f.tag.id = id;
  f.level = level;
  const auto tap = [](int x, int y) { return Tap{static_cast<int16_t>(x), static_cast<int16_t>(y), x < 0 || y < 0}; };
  const auto wrapped = [&](int64_t x, int64_t y) {
    return tap(wrap_index(c.wrap_s, x, img.width), wrap_index(c.wrap_t, y, img.height));
  };
  switch (c.mode.base) {
    case BaseFilter::Nearest:  // GL: i = floor(s W)
      f.ntaps = 1;
      f.taps[0] = wrapped(float_to_fixed(s, static_cast<uint32_t>(img.width), 0),
                          float_to_fixed(t, static_cast<uint32_t>(img.height), 0));
      return f;
    case BaseFilter::Linear: {
      const dp::LevelCoord u = dp::texel_coord(s, img.width), v = dp::texel_coord(t, img.height);
      f.ntaps = 4;
      f.taps = {wrapped(u.i0, v.i0), wrapped(u.i0 + 1, v.i0), wrapped(u.i0, v.i0 + 1), wrapped(u.i0 + 1, v.i0 + 1)};
      f.tag.fu = u.f;
      f.tag.fv = v.f;
      return f;
    }
    case BaseFilter::Cubic: {
      const dp::LevelCoord u = dp::texel_coord(s, img.width), v = dp::texel_coord(t, img.height);
      const TileWeightRom& rom = *smp_.cubic_rom();
      const int taps = rom.taps();
      std::array<int, 4> col{}, row{};
      wrap_run(c.wrap_s, u.i0 + rom.first_tap(), taps, img.width, col.data());
      wrap_run(c.wrap_t, v.i0 + rom.first_tap(), taps, img.height, row.data());
      f.ntaps = taps * taps;
      for (int j = 0; j < taps; ++j)
        for (int i = 0; i < taps; ++i) f.taps[static_cast<size_t>(j * taps + i)] = tap(col[static_cast<size_t>(i)], row[static_cast<size_t>(j)]);
      f.tag.fu = u.f;
      f.tag.fv = v.f;
      return f;
    }
    case BaseFilter::EdgePreserving: {
      const dp::LevelCoord u = dp::texel_coord(s, img.width), v = dp::texel_coord(t, img.height);
      std::array<int, 4> col{}, row{};  // columns and rows -1..2 around the centre square
      wrap_run(c.wrap_s, u.i0 - 1, 4, img.width, col.data());
      wrap_run(c.wrap_t, v.i0 - 1, 4, img.height, row.data());
      f.ntaps = lee_jen::kTexels;
      for (int n = 1; n <= lee_jen::kTexels; ++n) {
        const lee_jen::TexelPos p = lee_jen::texel_pos(n);
        f.taps[static_cast<size_t>(n - 1)] = tap(col[static_cast<size_t>(p.x + 1)], row[static_cast<size_t>(p.y + 1)]);
      }
      f.tag.fu = u.f;
      f.tag.fv = v.f;
      return f;
    }
  }
  return f;
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
    f = footprint(pixel_.id, sent_ == 0 ? lod_.level0 : lod_.level1, pixel_.s, pixel_.t);
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
