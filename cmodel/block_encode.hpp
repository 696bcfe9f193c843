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
// Not encoded: the signed formats (BC4S, BC5S, EAC signed; an RGBA8 image has no signed source)
// and ETC2 punch-through alpha (etc2a1): InputError.
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

// True when encode_block_image encodes the format; the encoder's name for messages and docs.
bool has_block_encoder(BlockFormat f);
const char* block_encoder_name(BlockFormat f);

// Encodes each level (any sizes; normally a MIP chain as cmodel/mipmap.hpp makes it). InputError
// when the format has no encoder, `srgb` is set for a format without an sRGB variant, or there are
// no levels.
BlockImage encode_block_image(std::span<const Image> levels, BlockFormat f, bool srgb,
                              const BlockEncodeOptions& options = {});

// The own encoders, one block each (16 RGBA8 texels row-major, texel (x, y) at [4 y + x]); exposed
// for the tests.
void encode_bc7_mode6_block(const Rgba8 texels[16], uint8_t out[16]);
void encode_etc1_block(const Rgba8 texels[16], uint8_t out[8]);
// EAC of one channel: `values` in 0..255 (alpha8: ETC2 RGBA's alpha) or 0..2047 (R11).
void encode_eac_block(const int values[16], bool r11, uint8_t out[8]);

}  // namespace tfu
