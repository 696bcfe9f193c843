// Text dumps of the ROMs, for people (CSV) and for $readmemh (hex). The SystemVerilog ROMs are
// initialised from these files, so the hex layout is part of the hardware interface:
//
// Tile-weight ROM (interleaved layout), hex: one line per word, address-major then tap:
//   line (k * T + t) = word of tap t (texel offset m = 1 - T/2 + t) at address k,
//   sign-magnitude, (bits + 1) bits: bit [bits] = sign, bits [bits-1:0] = magnitude,
//   written with ceil((bits + 1) / 4) hex digits.
// Direction-weight ROM, hex: 256 lines per direction, address (yf4 << 4) | xf4, 2 hex digits;
//   with all directions, direction i occupies lines [256 i, 256 i + 255].
// CSV: a header line, then one row per address (tile: "address,position,w_m...,"; direction:
//   "direction,address,xf4,yf4,code,weight").
#pragma once

#include <ostream>

#include "cmodel/weight_rom.hpp"

namespace tfu {

void dump_tile_rom_csv(const TileWeightRom& rom, std::ostream& os);
void dump_tile_rom_hex(const TileWeightRom& rom, std::ostream& os);
// dir = -1 dumps all 22 directions.
void dump_direction_rom_csv(int dir, std::ostream& os);
void dump_direction_rom_hex(int dir, std::ostream& os);

}  // namespace tfu
