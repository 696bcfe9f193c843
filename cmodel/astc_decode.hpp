// ASTC LDR 2D decoder (Khronos Data Format Specification 1.4.0, chapter "ASTC Compressed Texture
// Image Formats"; KDFS below, section names quoted), integer only. docs/compressed-astc.md.
//
// What it decodes: the LDR profile ("LDR Profile Support"), every 2D footprint 4x4 .. 12x12, in the
// linear LDR and the sRGB operation mode. Every step, in block order:
//   block mode        11 bits -> weight grid W x H, weight range, dual plane; reserved -> error
//   void extent       bits [8:0] = 1 1111 1100: one UNORM16 colour (LDR, D = 0); HDR (D = 1),
//                     reserved bits 10, 11 not 1, or min >= max coordinates (unless all ones) -> error
//   partitions        1..4; 4 with dual plane -> error; the partition of a texel from the spec's
//                     hash52 / select_partition (small_block: footprints of fewer than 31 texels)
//   endpoint modes    one 4-bit CEM, or per-partition class + 2 bits; LDR modes 0, 1, 4, 5, 6, 8, 9,
//                     10, 12, 13 decoded; HDR modes 2, 3, 7, 11, 14, 15 give the error colour for
//                     the texels of that partition only ("Illegal Encodings", last paragraph)
//   sizes             > 64 weights, weight bits outside 24..96, grid larger than the footprint,
//                     > 18 endpoint values, fewer than ceil(13 C / 5) endpoint bits -> error
//   ISE               trits (5 in 8 bits) and quints (3 in 7 bits) by the spec's bit manipulations,
//                     missing high bits of a final partial block read as 0; weights from bit 127 down
//   unquantization    endpoints to 0..255, weights to 0..64 (cmodel/astc_tables.hpp)
//   weight infill     cs = Ds bs, gs = (cs (W - 1) + 32) >> 6 (Q4.4), bilinear with
//                     w11 = (fs ft + 8) >> 4 and i = (sum p w + 8) >> 4 (4-bit fractions, 0..64 out)
//   interpolation     C = floor((C0 (64 - i) + C1 i + 32) / 64): 16 x 7-bit products, 22-bit sum,
//                     UNORM16 result, per channel; dual plane: the CCS channel takes the plane-1 weight
//   output UNORM8     linear: C0 = e * 257 (bit replication); decode_float16: C = 65535 -> 1.0,
//                     else C / 65536 to FP16 rounding toward zero, i.e. C with all but its 11
//                     leading significant bits cleared (C < 2^11 is exact); then the FP16 value to
//                     UNORM8 as a GPU stores a float to an 8-bit unorm: floor(f x 255 + 1/2) =
//                     (C' x 255 + 2^15) >> 16 (a 16 x 8-bit product, 24 bits)
//                     sRGB: C0 = (e << 8) | 0x80 for R, G, B and A; the top 8 bits C >> 8 of every
//                     channel (R, G, B still sRGB-encoded: the sRGB EOTF is applied after the decoder),
//                     = (e0 (64 - i) + e1 i + 32) >> 6. KDFS 1.3 gave alpha bit replication and
//                     decode_float16 instead (1 LSB apart in 7 % of cases); 1.4.0 and libastcenc
//                     4.2.0 agree on the rule here
//   error colour      opaque magenta (255, 0, 255, 255) in both modes ("ASTC error colors")
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>

#include "cmodel/texture.hpp"

namespace tfu {

inline constexpr int kAstcBlockBytes = 16;
inline constexpr int kAstcMaxTexels = 144;  // 12 x 12

// The 14 2D footprints (KDFS "Block Determination and Bit Rates", Table "ASTC 2D footprint and bit
// rates").
struct AstcFootprint {
  int w = 0, h = 0;
  friend constexpr bool operator==(const AstcFootprint&, const AstcFootprint&) = default;
};
// clang-format off
inline constexpr std::array<AstcFootprint, 14> kAstcFootprints{{
    {4, 4}, {5, 4}, {5, 5}, {6, 5}, {6, 6}, {8, 5}, {8, 6}, {8, 8}, {10, 5}, {10, 6}, {10, 8}, {10, 10}, {12, 10},
    {12, 12}}};
// clang-format on
constexpr bool is_astc_footprint(int w, int h) {
  for (const AstcFootprint& f : kAstcFootprints)
    if (f.w == w && f.h == h) return true;
  return false;
}

// Opaque magenta, the error colour of both LDR operation modes (KDFS "ASTC error colors").
inline constexpr Rgba8 kAstcErrorColor{255, 0, 255, 255};

// Linear LDR output of one channel: decode_float16 of the UNORM16 interpolation result c, then the
// FP16 value f to UNORM8 by floor(f x 255 + 1/2) (KDFS "Weight Application"). c = 65535 is 1.0;
// otherwise c / 65536 rounded toward zero to FP16 keeps the 11 leading significant bits of c (values
// below 2^-14, c < 4, are FP16 subnormals with step 2^-24: exact), so f = c' / 65536 with the lower
// bits of c cleared, and the result is (c' x 255 + 2^15) >> 16 (a 16 x 8-bit product).
constexpr uint8_t astc_unorm16_to_unorm8(uint32_t c) {
  if (c == 0xFFFFu) return 255;
  const int msb = std::bit_width(c) - 1;
  if (msb > 10) c &= ~((1u << (msb - 10)) - 1u);
  return static_cast<uint8_t>((c * 255u + 0x8000u) >> 16);
}
static_assert(astc_unorm16_to_unorm8(0x8000) == 128 && astc_unorm16_to_unorm8(0x7FFF) == 127 &&
              astc_unorm16_to_unorm8(129) == 1 && astc_unorm16_to_unorm8(0xFF00) == 254);

// Why a block decodes to the error colour (KDFS "Illegal Encodings"), or None.
enum class AstcIllegal : uint8_t {
  None,
  ReservedBlockMode,        // a block mode the 2D layout table lists as reserved
  VoidExtentReservedBits,   // void extent with bits 10, 11 not both 1
  VoidExtentHdr,            // void extent with D = 1 (FP16 colour) in an LDR operation mode
  VoidExtentCoordinates,    // void extent with min >= max on an axis, coordinates not all ones
  TooManyWeights,           // more than 64 weights (both planes)
  WeightBitsOutOfRange,     // weight ISE of fewer than 24 or more than 96 bits
  GridExceedsFootprint,     // W > block width or H > block height
  DualPlaneFourPartitions,  // dual plane with 4 partitions
  TooManyEndpointValues,    // more than 18 endpoint integers
  TooFewEndpointBits,       // fewer than ceil(13 C / 5) bits left for C endpoint integers
};
const char* astc_illegal_name(AstcIllegal why);

// The configuration fields of one block, as the decoder reads them before any texel.
struct AstcBlockConfig {
  AstcIllegal illegal = AstcIllegal::None;
  bool void_extent = false;
  std::array<uint16_t, 4> void_color{};  // void extent: UNORM16 R, G, B, A
  int grid_w = 0, grid_h = 0;            // weight grid
  int weight_range = 0;                  // index into astc::kIseRanges (0..11)
  bool dual_plane = false;
  int ccs = 0;  // dual plane: the channel (0 R .. 3 A) on plane 1
  int partitions = 1;
  int partition_seed = 0;    // the 10-bit partition pattern index
  std::array<int, 4> cem{};  // colour endpoint mode of each partition
  int endpoint_values = 0;   // C, 2 per endpoint pair
  int endpoint_range = 0;    // index into astc::kIseRanges (4..20)
  int weight_bits = 0;       // bits of the weight ISE
};

// Reads the block's configuration for a block_w x block_h footprint (any w, h in 4..12; only the
// 14 footprints are formats). Void extents with D = 1 (HDR) are illegal: this is an LDR decoder.
AstcBlockConfig astc_block_config(const uint8_t block[kAstcBlockBytes], int block_w, int block_h);

// Decodes one block to block_w * block_h texels, row-major (texel (x, y) at out[y * block_w + x]).
// srgb selects the sRGB operation mode (R, G, B, A of the result are the sRGB-encoded bytes), else
// linear LDR with decode_float16. block_w, block_h must be a footprint of kAstcFootprints.
void decode_astc_block(const uint8_t block[kAstcBlockBytes], int block_w, int block_h, bool srgb, Rgba8* out);

// A whole image of ceil(width / block_w) x ceil(height / block_h) blocks in raster order (KDFS
// "Block Layout"); the texels of edge blocks beyond the image are dropped. Throws InputError when
// the footprint is not one of the 14, a size is not in 1..65536, or `size` is not the block count
// times 16.
Image decode_astc_image(const uint8_t* data, size_t size, int width, int height, int block_w, int block_h, bool srgb);

}  // namespace tfu
