// Decoders of the S3TC (BC1, BC2, BC3) and RGTC (BC4, BC5, unsigned and signed) block-compressed
// formats, integer only, against the Khronos Data Format Specification 1.3 ("S3TC Compressed Texture
// Image Formats", "RGTC Compressed Texture Image Formats"; the same text as OpenGL 4.5 Sec. 8.7 and
// EXT_texture_compression_s3tc / ARB_texture_compression_rgtc). docs/compressed-bc.md.
//
// Block layout (all fields little endian, bit 0 the least significant bit of the block's first byte):
//   BC1  8 bytes: color0 (16, R5:G6:B5 with R in bits 15..11), color1 (16), 16 x 2-bit codes
//   BC2 16 bytes: 16 x 4-bit alpha, then a BC1 colour block decoded in 4-colour mode
//   BC3 16 bytes: a BC4 unsigned block as alpha, then a BC1 colour block decoded in 4-colour mode
//   BC4  8 bytes: red0 (8), red1 (8), 16 x 3-bit codes
//   BC5 16 bytes: a BC4 block for red, then one for green
// Texel t of a block, t = 4 y + x (row-major, (x, y) the texel's position in the block), takes the
// code bits [2t+1..2t] (BC1), [4t+3..4t] (BC2 alpha), [3t+2..3t] (BC3 alpha, BC4: bits of bytes 2..7).
//
// Datapath. Endpoints: a 5- or 6-bit colour field v is widened to 8 bits by bit replication,
// e = (v << 3) | (v >> 2) (5 bits), e = (v << 2) | (v >> 4) (6 bits), the widening of D3D10, of
// libsquish, of Mesa and of the hardware decoders below. It is within 1 LSB of the spec's
// RGB0 = v / (2^n - 1) but not always the nearest 8-bit value: it differs from round(255 v / (2^n - 1))
// at v = 3, 7, 24, 28 (5 bits) and 11..15, 48..52 (6 bits) (test_bc_decode, exhaustive). The rules
// below interpolate the widened endpoints. BC2 alpha a (4 bits) is a * 17 = 255 a / 15 exactly.
//
// The spec defines the interpolated colours as real numbers ((2 RGB0 + RGB1) / 3, (RGB0 + RGB1) / 2)
// and D3D10 allows a tolerance on them, so hardware differs. Bc1Interpolation names the rule, per
// 8-bit channel (e0, e1 the widened endpoints, v0, v1 the 5/6-bit fields, / truncating):
//   exact     the spec's value of the widened endpoints rounded to nearest: (2 e0 + e1 + 1) / 3,
//             (e0 + 2 e1 + 1) / 3; 3-colour mode (e0 + e1 + 1) >> 1 (ties, odd sums, round up).
//             Chosen as the golden rule: every interpolant within 1/2 LSB of the spec's formula
//             applied to the 8-bit endpoints, no tie in 4-colour mode (a third is never 1/2), and
//             the D3D10 rule (interpolate the widened UNORM8 endpoints, round to nearest) without
//             the tolerance D3D10 allows.
//   truncate  (2 e0 + e1) / 3, (e0 + 2 e1) / 3, (e0 + e1) / 2: libsquish 1.15 (colourblock.cpp,
//             DecompressColour) and Mesa (util/format/texcompress_s3tc_tmp.h,
//             dxt135_decode_imageblock) both use this rule.
//   nvidia    NVIDIA's hardware as modelled bit-exactly by F. Giesen, "GPU BCn decoding" (2021):
//             red/blue from the 5-bit fields: (2 v0 + v1) 22 / 8 and 3-colour (v0 + v1) 33 / 8;
//             green from the 8-bit widened values, d = e1 - e0 (C division truncating toward 0):
//             (256 e0 + d / 4 + 128 + 80 d) / 256, 3-colour (256 e0 + d / 4 + 128 + 128 d) / 256.
//             Index 3 swaps the endpoints.
//   amd       AMD's hardware (Giesen 2021; R. Geldreich's RX 580 read-back tables, 2020):
//             (43 e0 + 21 e1 + 32) >> 6, index 3 with the endpoints swapped; 3-colour
//             (e0 + e1 + 1) >> 1.
// 3-colour mode (color0 <= color1, as 16-bit integers) exists in BC1 only; BC2 and BC3 always decode
// 4-colour (spec). Code 3 in 3-colour mode is black: alpha 0 in BC1 RGBA, alpha 255 in BC1 RGB.
//
// BC3 alpha and BC4/BC5: the spec's interpolants (6 a0 + a1) / 7 ... and (4 a0 + a1) / 5 ... are
// real numbers. decode_bc4_exact returns them exactly, as integers over a common denominator:
//   unsigned  value = n / (35 * 255), n = 5 (w0 a0 + w1 a1) (7-step, w0 + w1 = 7) or
//             7 (w0 a0 + w1 a1) (5-step, w0 + w1 = 5); codes 6, 7 of the 5-step mode: 0 and 35 * 255
//   signed    value = n / (35 * 127) with a0, a1 the signed bytes, -128 read as -127 (the spec's
//             RED = -1.0 for red = -128); codes 6, 7 of the 5-step mode: -35 * 127, 35 * 127.
//             The mode compares the raw bytes, red0 > red1 (the spec leaves red0 = -127,
//             red1 = -128 undefined; here -127 > -128: the 7-step mode, all -1.0).
// Bc4Interpolation gives the 8-bit result:
//   exact     round(n / 35) (UNORM8 / SNORM8 nearest to the spec's value; n / 35 is k/7 or k/5,
//             never a half, so no tie rule is needed)
//   truncate  (w0 a0 + w1 a1) / 7 or / 5 with C division (toward zero; signed: the raw bytes,
//             -128 not clamped; a result of -128, like the spec's -1.0, is written -127):
//             libsquish 1.15 (alpha.cpp, DecompressAlphaDxt5) and Mesa (texcompress_rgtc_tmp.h,
//             texcompress_s3tc_tmp.h).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "cmodel/enum_names.hpp"
#include "cmodel/texture.hpp"

namespace tfu {

inline constexpr int kBcBlockDim = 4;      // texels per block edge
inline constexpr int kBcBlockTexels = 16;  // texel t = 4 y + x
using BcBlockTexels = std::array<Rgba8, kBcBlockTexels>;

enum class BcFormat { BC1_RGB, BC1_RGBA, BC2, BC3, BC4_UNORM, BC4_SNORM, BC5_UNORM, BC5_SNORM, BC7 };
inline constexpr EnumNames<BcFormat, 9> kBcFormatNames{"block-compressed format",
                                                       {{{BcFormat::BC1_RGB, "bc1"},
                                                         {BcFormat::BC1_RGBA, "bc1a"},
                                                         {BcFormat::BC2, "bc2"},
                                                         {BcFormat::BC3, "bc3"},
                                                         {BcFormat::BC4_UNORM, "bc4"},
                                                         {BcFormat::BC4_SNORM, "bc4s"},
                                                         {BcFormat::BC5_UNORM, "bc5"},
                                                         {BcFormat::BC5_SNORM, "bc5s"},
                                                         {BcFormat::BC7, "bc7"}}}};
constexpr int bc_block_bytes(BcFormat f) {
  return f == BcFormat::BC1_RGB || f == BcFormat::BC1_RGBA || f == BcFormat::BC4_UNORM || f == BcFormat::BC4_SNORM ? 8
                                                                                                                   : 16;
}

enum class Bc1Interpolation { EXACT, TRUNCATE, NVIDIA, AMD };
inline constexpr EnumNames<Bc1Interpolation, 4> kBc1InterpolationNames{"BC1 interpolation",
                                                                       {{{Bc1Interpolation::EXACT, "exact"},
                                                                         {Bc1Interpolation::TRUNCATE, "truncate"},
                                                                         {Bc1Interpolation::NVIDIA, "nvidia"},
                                                                         {Bc1Interpolation::AMD, "amd"}}}};
enum class Bc4Interpolation { EXACT, TRUNCATE };
inline constexpr EnumNames<Bc4Interpolation, 2> kBc4InterpolationNames{
    "BC4 interpolation", {{{Bc4Interpolation::EXACT, "exact"}, {Bc4Interpolation::TRUNCATE, "truncate"}}}};

// The rules of one decoder: colour (BC1, BC2, BC3) and alpha / red / green (BC3, BC4, BC5).
struct BcRules {
  Bc1Interpolation colour = Bc1Interpolation::EXACT;
  Bc4Interpolation alpha = Bc4Interpolation::EXACT;
  friend constexpr bool operator==(const BcRules&, const BcRules&) = default;
};
inline constexpr BcRules kBcRulesSpec{};                                                             // golden
inline constexpr BcRules kBcRulesLibsquish{Bc1Interpolation::TRUNCATE, Bc4Interpolation::TRUNCATE};  // 1.15
inline constexpr BcRules kBcRulesMesa{Bc1Interpolation::TRUNCATE, Bc4Interpolation::TRUNCATE};       // 22.3

// The 8-bit widening of a 5- or 6-bit colour field by bit replication.
constexpr int bc_widen5(int v) { return (v << 3) | (v >> 2); }
constexpr int bc_widen6(int v) { return (v << 2) | (v >> 4); }

// The four colours of a BC1 colour block (bytes 0..3: color0, color1), index = code. alpha 0 on
// code 3 in 3-colour mode when `three_colour_alpha0`. `four_colour_only`: BC2/BC3 (no 3-colour mode).
std::array<Rgba8, 4> bc1_palette(const uint8_t* block, Bc1Interpolation rule, bool four_colour_only,
                                 bool three_colour_alpha0);

// Blocks: `block` points at bc_block_bytes(format) bytes. Texel t = 4 y + x.
BcBlockTexels decode_bc1_block(const uint8_t* block, bool rgba, Bc1Interpolation rule);  // rgba: BC1_RGBA
BcBlockTexels decode_bc2_block(const uint8_t* block, Bc1Interpolation rule);
BcBlockTexels decode_bc3_block(const uint8_t* block, BcRules rules);

// One BC4 channel (8 bytes): the spec's value of each texel as n / (35 * 255) (unsigned) or
// n / (35 * 127) (signed), exactly.
inline constexpr int kBc4ExactScale = 35;
std::array<int32_t, kBcBlockTexels> decode_bc4_exact(const uint8_t* block, bool is_signed);
// The 8-bit results: UNORM8 (0..255) or SNORM8 (-127..127).
std::array<uint8_t, kBcBlockTexels> decode_bc4_unorm8(const uint8_t* block, Bc4Interpolation rule);
std::array<int8_t, kBcBlockTexels> decode_bc4_snorm8(const uint8_t* block, Bc4Interpolation rule);

// BC4 / BC5 as texels: unsigned (R, 0, 0, 255) / (R, G, 0, 255); signed as the two's complement
// bytes of SNORM8 (R, 0, 0, 127) / (R, G, 0, 127) (127 = 1.0), the layout GL returns for
// glReadPixels(GL_RGBA, GL_BYTE).
BcBlockTexels decode_bc4_block(const uint8_t* block, bool is_signed, Bc4Interpolation rule);
BcBlockTexels decode_bc5_block(const uint8_t* block, bool is_signed, Bc4Interpolation rule);

// Any block of any BC format (BC7 through bc7_decode.hpp; `rules` unused there).
BcBlockTexels decode_bc_block(BcFormat format, const uint8_t* block, BcRules rules);

// Bytes of a width x height image: ceil(w / 4) * ceil(h / 4) blocks, row-major (the spec's block
// offset blocksize * (ceil(w / 4) * floor(y / 4) + floor(x / 4))).
size_t bc_image_bytes(BcFormat format, int width, int height);

// A whole image, row-major width x height texels; edge blocks of sizes not a multiple of 4 keep
// their top-left texels. InputError (one line) when a size is not in 1..65536 or `blocks` holds
// fewer or more bytes than bc_image_bytes.
std::vector<Rgba8> decode_bc_image(BcFormat format, int width, int height, std::span<const uint8_t> blocks,
                                   BcRules rules = kBcRulesSpec);

}  // namespace tfu
