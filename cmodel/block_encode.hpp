// Block-compressed encoding: RGBA8 MIP levels to a BlockImage (cmodel/block_formats.hpp), for
// `tfu compress` and the tests (docs/compressed-files.md, "Encoders"). Encoders are offline tools,
// not part of the unit: what matters is that they are deterministic (the same input gives the same
// blocks, on every machine) and that decode(encode(x)) stays within a measured error.
//   * BC1, BC1A, BC2, BC3, BC4, BC5: libsquish 1.15 (Debian libsquish-dev: kDxt1, kDxt3, kDxt5,
//     kBc4, kBc5); `quality` < 34 range fit, < 67 cluster fit, else iterative cluster fit. BC4 and
//     BC5 take red and red + green (libsquish compresses them as BC3's alpha block).
//   * ASTC (every 2D footprint, LDR; LDR sRGB profile when `srgb`): libastcenc 4.2 (Debian
//     libastcenc-dev), one thread, `quality` as astcenc's 0..100 effort (10 fast, 60 medium).
//   * BC7, ETC2 RGB, ETC2 RGBA, EAC R11 and RG11: encoders of this file, because no Debian library
//     encodes them (libnvtt 2.0.8 stops at BC5; etc1tool is a program, ETC1 only). They are simple:
//       - BC7: mode 6 only (one subset, RGBA endpoints of 7 bits + a p-bit each, 4-bit indices). The
//         endpoints are the corners of the block's bounding box, the diagonal chosen among the 8
//         orientations (G, B, A rising or falling with R) by the least squared error; each
//         endpoint's p-bit the one nearer the corner; each texel the index of least squared error.
//       - ETC2 RGB: the ETC1 modes only (individual and differential; valid ETC2 blocks, never T, H
//         or planar). Both flips, both modes (differential where the two 5-bit averages are within
//         the 3-bit delta), each sub-block's table the one of least error with each texel's best
//         modifier; the least total error wins.
//       - EAC (ETC2 RGBA's 8-bit alpha, R11, RG11): per table, the multiplier nearest the block's
//         range over the table's span (and its neighbours), the base centring the range; each texel
//         the modifier of least squared error (R11 in the 11-bit domain, 8-bit input v as
//         round(v * 2047 / 255)).
//       - BC4 and BC5 signed (bc4s, bc5s) and EAC signed R11 / RG11 (eac_r11s, eac_rg11s): the
//         image's red (and green) bytes read as SNORM8 by snorm8_from_image_byte (cmodel/
//         block_formats.hpp: byte v is v - 128, the inverse of what `tfu decompress` writes; EAC
//         then to 11 bits by eac11_signed_from_snorm8). BC4 signed: the block's extremes as the
//         endpoints in both orders (eight-value and six-value mode), each texel the code of least
//         squared error against the decoder's own palette (decode_bc4_snorm8, golden rule); the
//         order of least error wins. EAC signed: the EAC search above with the signed base
//         (-127..127, 8 base nearest the centre).
//       - ETC2 punch-through alpha (etc2a1): alpha >= 128 is opaque. Differential mode only (RGB8A1
//         has no individual mode): per flip, the sub-blocks' means of their opaque texels on the
//         5-bit grid, the second clamped into the 3-bit delta's reach (never T, H or planar). Every
//         texel opaque: opaque bit 1 and the ETC1 table fit; else opaque bit 0, transparent texels
//         index 2, opaque ones the best of base, base + b, base - b per table (KDFS "Format RGB
//         ETC2 with punchthrough alpha"). The flip of least error wins.
// Partial blocks at the right and bottom edges repeat the last column and row (libsquish masks
// them out, libastcenc pads them itself).
// Tested: BlockEncode.* (testbench/test_texture_containers.cpp): PSNR floors per format on a
// procedural texture, determinism, partial blocks, refusals.
#pragma once

#include <span>

#include "cmodel/block_formats.hpp"
#include "cmodel/texture.hpp"

namespace tfu {

struct BlockEncodeOptions {
  int quality = 60;  // 0..100: libastcenc's effort; libsquish's fit (see above); unused by the own encoders
};

// Signed texels in 8-bit images, the one convention of `tfu decompress` (which writes them) and the
// signed encoders (which read them): SNORM8 s (-127..127) is the byte s + 128 (1..255, 0.0 as 128);
// the byte 0 reads as -127 (-1.0, as SNORM8 reads -128).
constexpr uint8_t snorm8_to_image_byte(int s) { return static_cast<uint8_t>(s + 128); }
constexpr int snorm8_from_image_byte(uint8_t v) { return v == 0 ? -127 : v - 128; }
// The inverse of eac11_signed_to_snorm8 (cmodel/etc2_decode.hpp) for the signed EAC encoder:
// SNORM8 s (-127..127) to the nearest 11-bit signed value, round(s * 1023 / 127) (never halfway:
// 1023 and 127 are odd), which eac11_signed_to_snorm8 maps back to s.
constexpr int16_t eac11_signed_from_snorm8(int s) {
  const int m = s < 0 ? -s : s;
  const int e = (m * 1023 + 63) / 127;
  return static_cast<int16_t>(s < 0 ? -e : e);
}

// The encoder of a format, for messages and docs (every format has one).
const char* block_encoder_name(BlockFormat f);

// Encodes each level (any sizes; normally a MIP chain as cmodel/mipmap.hpp makes it). InputError
// when `srgb` is set for a format without an sRGB variant, or there are
// no levels.
BlockImage encode_block_image(std::span<const Image> levels, BlockFormat f, bool srgb,
                              const BlockEncodeOptions& options = {});

// The own encoders, one block each (16 RGBA8 texels row-major, texel (x, y) at [4 y + x]); exposed
// for the tests.
void encode_bc7_mode6_block(const Rgba8 texels[16], uint8_t out[16]);
void encode_etc1_block(const Rgba8 texels[16], uint8_t out[8]);
// EAC of one channel: `values` in 0..255 (alpha8: ETC2 RGBA's alpha) or 0..2047 (R11).
void encode_eac_block(const int values[16], bool r11, uint8_t out[8]);
// Signed EAC R11 of one channel: `values` in -1023..1023.
void encode_eac_r11_signed_block(const int values[16], uint8_t out[8]);
// Signed BC4 of one channel: `values` SNORM8 in -127..127.
void encode_bc4_signed_block(const int values[16], uint8_t out[8]);
// ETC2 RGB8 punch-through alpha (8 bytes).
void encode_etc2_punchthrough_block(const Rgba8 texels[16], uint8_t out[8]);

}  // namespace tfu
