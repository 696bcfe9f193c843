// Text dumps of the ROMs, for people (CSV) and for $readmemh (hex). The SystemVerilog ROMs are
// initialised from these files, so the hex layout is part of the hardware interface.
//
// Generic (any ROM of unsigned words):
//   hex: one word per line, lowercase, zero-padded to ceil(width / 4) digits, line k = address k,
//        no address markers and no comments, so `$readmemh(file, mem)` with
//        `logic [width-1:0] mem [0:depth-1]` loads it as is.
//   CSV: header "address,value", then one row per address with the unsigned value in decimal.
//
// Tile-weight ROM (weight_rom.hpp, interleaved layout, T taps per address):
//   hex: one line per tap word, address-major then tap:
//          line (k * T + t) = word of tap t (texel offset m = 1 - T/2 + t) at address k,
//        sign-magnitude, (bits + 1) bits: bit [bits] = sign (1 = negative), bits [bits-1:0] =
//        magnitude (scale 2^bits - 1), written with ceil((bits + 1) / 4) hex digits.
//        In SystemVerilog: `logic [bits:0] mem [0:entries*T-1]`, tap t of address k at k*T + t.
//   CSV: header, then one row per address:
//          address, w[m] for each tap (signed value, m = texel offset, e.g. w[-1],w[+0],w[+1],w[+2]),
//          then for each tap s[m] (sign bit 0/1) and mag[m] (magnitude code),
//          then row_sum (sum of the signed values) and position (local position sampled, in [0, 1]).
// Direction-weight ROM (direction_rom.hpp, Lee & Jen):
//   hex: 256 lines per direction, address (fv4 << 4) | fu4, 2 hex digits (the 8-bit 4.4 code,
//        ff = never choose); with all directions, direction i occupies lines [256 i, 256 i + 255]
//        (`logic [7:0] mem [0:22*256-1]`, i.e. address (i << 8) | (fv4 << 4) | fu4).
//   CSV: header "direction,address,xf4,yf4,code,weight", one row per (direction, address);
//        weight is code / 16 with 4 decimals, or "never" for code 255. (The columns xf4, yf4 keep
//        the paper's names: they are fu4, fv4.)
#pragma once

#include <cstdint>
#include <ostream>
#include <span>

#include "cmodel/weight_rom.hpp"

namespace tfu {

// Generic ROM of unsigned words, each < 2^width_bits (1..32 bits).
void dump_rom_hex(std::span<const uint32_t> words, unsigned width_bits, std::ostream& os);
void dump_rom_csv(std::span<const uint32_t> words, std::ostream& os);

// Number of hex digits of a `width_bits`-bit word in the hex dumps.
constexpr int hex_digits(unsigned width_bits) { return static_cast<int>((width_bits + 3) / 4); }
// Sign-magnitude word of the tile ROM hex dump: bit [bits] = sign, [bits-1:0] = magnitude.
constexpr uint32_t tile_word_bits(const RomWord& w, unsigned bits) {
  return (static_cast<uint32_t>(w.neg) << bits) | w.mag;
}

void dump_tile_rom_csv(const TileWeightRom& rom, std::ostream& os);
void dump_tile_rom_hex(const TileWeightRom& rom, std::ostream& os);
// dir = -1 dumps all 22 directions.
void dump_direction_rom_csv(int dir, std::ostream& os);
void dump_direction_rom_hex(int dir, std::ostream& os);

}  // namespace tfu
