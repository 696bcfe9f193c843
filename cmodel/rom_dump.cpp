#include "cmodel/rom_dump.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "cmodel/direction_rom.hpp"

namespace tfu {

void dump_tile_rom_csv(const TileWeightRom& rom, std::ostream& os) {
  os << "address,position";
  for (int t = 0; t < rom.taps(); ++t) os << fmt::format(",w[{:+d}]", rom.first_tap() + t);
  os << ",row_sum\n";
  for (int k = 0; k < rom.entries(); ++k) {
    os << fmt::format("{},{:.6f}", k, rom.spec().position(k));
    int32_t sum = 0;
    for (const RomWord& w : rom.row(k)) {
      os << ',' << w.value();
      sum += w.value();
    }
    os << ',' << sum << '\n';
  }
}

void dump_tile_rom_hex(const TileWeightRom& rom, std::ostream& os) {
  const unsigned bits = rom.spec().bits;
  const int digits = static_cast<int>((bits + 1 + 3) / 4);
  for (int k = 0; k < rom.entries(); ++k)
    for (const RomWord& w : rom.row(k)) {
      const uint32_t word = (static_cast<uint32_t>(w.neg) << bits) | w.mag;
      os << fmt::format("{:0{}x}\n", word, digits);
    }
}

namespace {
template <typename Fn>
void for_directions(int dir, Fn fn) {
  if (dir >= 0) {
    fn(dir);
    return;
  }
  for (int i = 0; i < lee_jen::kDirections; ++i) fn(i);
}
}  // namespace

void dump_direction_rom_csv(int dir, std::ostream& os) {
  os << "direction,address,xf4,yf4,code,weight\n";
  for_directions(dir, [&](int d) {
    const auto& rom = lee_jen::direction_weight_rom(d);
    for (int a = 0; a < 256; ++a) {
      const uint8_t c = rom[static_cast<size_t>(a)];
      os << fmt::format("{},{},{},{},{},{}\n", d, a, a & 15, a >> 4, c,
                        c == lee_jen::kNeverChoose ? std::string("never") : fmt::format("{:.4f}", lee_jen::decode_weight(c)));
    }
  });
}

void dump_direction_rom_hex(int dir, std::ostream& os) {
  for_directions(dir, [&](int d) {
    for (uint8_t c : lee_jen::direction_weight_rom(d)) os << fmt::format("{:02x}\n", c);
  });
}

}  // namespace tfu
