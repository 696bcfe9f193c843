#include "cmodel/rom_dump.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cmodel/direction_rom.hpp"

namespace tfu {

void dump_rom_hex(std::span<const uint32_t> words, unsigned width_bits, std::ostream& os) {
  if (width_bits < 1 || width_bits > 32) throw std::invalid_argument("dump_rom_hex: width must be 1..32 bits");
  const int digits = hex_digits(width_bits);
  for (const uint32_t w : words) {
    if (width_bits < 32 && (w >> width_bits) != 0)
      throw std::invalid_argument(fmt::format("dump_rom_hex: word {:#x} does not fit in {} bits", w, width_bits));
    os << fmt::format("{:0{}x}\n", w, digits);
  }
}

void dump_rom_csv(std::span<const uint32_t> words, std::ostream& os) {
  os << "address,value\n";
  for (size_t k = 0; k < words.size(); ++k) os << fmt::format("{},{}\n", k, words[k]);
}

void dump_tile_rom_csv(const TileWeightRom& rom, std::ostream& os) {
  os << "address";
  for (int t = 0; t < rom.taps(); ++t) os << fmt::format(",w[{:+d}]", rom.first_tap() + t);
  for (int t = 0; t < rom.taps(); ++t) os << fmt::format(",s[{0:+d}],mag[{0:+d}]", rom.first_tap() + t);
  os << ",row_sum,position\n";
  for (int k = 0; k < rom.entries(); ++k) {
    os << k;
    int32_t sum = 0;
    for (const RomWord& w : rom.row(k)) {
      os << ',' << w.value();
      sum += w.value();
    }
    for (const RomWord& w : rom.row(k)) os << ',' << (w.neg ? 1 : 0) << ',' << w.mag;
    os << fmt::format(",{},{:.6f}\n", sum, rom.spec().position(k));
  }
}

void dump_tile_rom_hex(const TileWeightRom& rom, std::ostream& os) {
  const unsigned bits = rom.spec().bits;
  std::vector<uint32_t> words;
  words.reserve(static_cast<size_t>(rom.entries()) * static_cast<size_t>(rom.taps()));
  for (int k = 0; k < rom.entries(); ++k)
    for (const RomWord& w : rom.row(k)) words.push_back(tile_word_bits(w, bits));
  dump_rom_hex(words, bits + 1, os);
}

namespace {
template <typename Fn>
void for_directions(int dir, Fn fn) {
  if (dir >= lee_jen::kDirections) throw std::invalid_argument("direction index out of range");
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
    const auto& rom = lee_jen::direction_weight_rom(d);
    const std::vector<uint32_t> words(rom.begin(), rom.end());
    dump_rom_hex(words, 8, os);
  });
}

}  // namespace tfu
