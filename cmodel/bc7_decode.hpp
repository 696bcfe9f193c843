// BC7 (BPTC, RGBA UNORM) decoder, integer only, against the Khronos Data Format Specification 1.3
// "BPTC Compressed Texture Image Formats" (= OpenGL 4.5 Sec. 8.7, ARB_texture_compression_bptc; D3D11's
// BC7 is the same format). Bit exact by the spec: unlike BC1-BC5, BC7 leaves no rounding to the
// implementation. docs/compressed-bc.md.
//
// A block is 128 bits, bit 0 = bit 0 of byte 0. Fields from bit 0 up, widths per mode (kBc7Modes,
// the spec's table "Mode-dependent BPTC parameters"):
//   mode        m zero bits then a one (mode m); byte 0 == 0 is reserved: all texels (0, 0, 0, 0), as
//               D3D11 specifies for the reserved mode
//   partition   PB bits (NS = 2 or 3 subsets); rotation RB bits; index selection ISB bit
//   colour      CB bits per value, ordered channel (R, G, B) > subset > endpoint (innermost)
//   alpha       AB bits, same order (AB = 0: alpha 255)
//   p-bits      EPB: one per endpoint, subset-major; SPB: one per subset, both endpoints
//   indices     primary IB bits per texel t = 0..15 (t = 4 y + x), IB - 1 bits at each anchor texel;
//               then secondary IB2 bits the same way (one subset: anchor texel 0 only)
// Endpoint: the p-bit, if any, is appended below the field (CB + 1 bits), then the value is widened to
// 8 bits by replicating its top bits: e = (v << (8 - w)) | (v >> (2 w - 8)), w the width.
// Interpolation (the only arithmetic): c = ((64 - w) e0 + w e1 + 32) >> 6 per channel, w from
// kBc7Weights2/3/4 by the index (6-bit weights 0..64; the product sum < 2^14 + 32, 15 bits).
// Index use: colour from the secondary index if ISB = 1, alpha from the primary then; otherwise colour
// from the primary and alpha from the secondary if IB2 > 0, else the primary. Rotation 1/2/3 swaps
// alpha with R/G/B after interpolation.
#pragma once

#include <array>
#include <cstdint>

#include "cmodel/bc_decode.hpp"

namespace tfu {

struct Bc7Mode {
  int subsets;         // NS
  int partition_bits;  // PB
  int rotation_bits;   // RB
  int index_sel_bits;  // ISB
  int colour_bits;     // CB
  int alpha_bits;      // AB
  int endpoint_pbits;  // EPB (0/1: one p-bit per endpoint)
  int shared_pbits;    // SPB (0/1: one p-bit per subset)
  int index_bits;      // IB
  int index2_bits;     // IB2
};
// The spec's table "Mode-dependent BPTC parameters", row by row.
inline constexpr std::array<Bc7Mode, 8> kBc7Modes{{
    {3, 4, 0, 0, 4, 0, 1, 0, 3, 0},
    {2, 6, 0, 0, 6, 0, 0, 1, 3, 0},
    {3, 6, 0, 0, 5, 0, 0, 0, 2, 0},
    {2, 6, 0, 0, 7, 0, 1, 0, 2, 0},
    {1, 0, 2, 1, 5, 6, 0, 0, 2, 3},
    {1, 0, 2, 0, 7, 8, 0, 0, 2, 2},
    {1, 0, 0, 0, 7, 7, 1, 0, 4, 0},
    {2, 6, 0, 0, 5, 5, 1, 0, 2, 0},
}};

// The spec's table "BPTC interpolation factors" (6-bit weights of 2-, 3- and 4-bit indices).
inline constexpr std::array<uint8_t, 4> kBc7Weights2{0, 21, 43, 64};
inline constexpr std::array<uint8_t, 8> kBc7Weights3{0, 9, 18, 27, 37, 46, 55, 64};
inline constexpr std::array<uint8_t, 16> kBc7Weights4{0, 4, 9, 13, 17, 21, 26, 30, 34, 38, 43, 47, 51, 55, 60, 64};

// The mode of a block (0..7), or -1 for the reserved encoding (byte 0 == 0).
int bc7_mode(const uint8_t* block);

// Partitions (bc7_decode.cpp holds the one table: the spec's 2- and 3-subset partition tables with
// each subset's anchor texel marked, from the spec's anchor index tables). subsets = 1, 2 or 3,
// partition 0..63 (ignored for one subset), texel t = 4 y + x.
int bc7_subset(int subsets, int partition, int texel);
int bc7_anchor(int subsets, int partition, int subset);  // subset 0: texel 0

BcBlockTexels decode_bc7_block(const uint8_t* block);

}  // namespace tfu
