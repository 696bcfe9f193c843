// The block-compressed texel formats, one table (kBlockFormats): every name, block size, channel
// count and GL internal format of the formats the model decodes, for the descriptors, texture
// memory, containers, the CLI and the tests. The decoders are per family (cmodel/bc_decode.hpp,
// bc7_decode.hpp, etc2_decode.hpp, astc_decode.hpp; each writes its rounding against the Khronos
// Data Format Specification); decode_block() is the one dispatch over them, and what every model
// (golden, cycle, SystemVerilog) calls the decoder.
//
// What the unit filters. The texel datapath is RGBA8 UNORM (cmodel/texture.hpp), so a block
// decodes to RGBA8 words:
//   * colour formats (BC1-BC3, BC7, ETC2, ASTC LDR): the decoder's UNORM8 result; RGB-only formats
//     give alpha 255;
//   * one- and two-channel formats (BC4, BC5, EAC R11/RG11) as GL returns a RED / RG texture:
//     (r, 0, 0, 255) and (r, g, 0, 255); BC4/BC5 by the UNORM8 rule of BcRules, EAC R11 by
//     eac11_to_unorm8 (round to nearest of v * 255 / 2047);
//   * signed formats (BC4/BC5 SNORM, signed EAC) are decoded by `tfu decompress` and the decoder
//     tests, but the unit has no signed 8-bit texel (a descriptor refuses them: unit_filterable);
//   * sRGB is a flag of the texture beside the format, not a format of its own: the decoders give
//     the stored (sRGB-encoded) bytes; ASTC alone decodes sRGB differently (the top 8 bits of its
//     UNORM16 result instead of the FP16 rounding: astc_decode.hpp), so the flag is passed to it.
// Tested: BlockFormats.* (testbench/test_block_formats.cpp): the GL codes against <GL/glext.h>,
// the table's sizes against each family's, and decode_block against each family's decoder.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "cmodel/bc_decode.hpp"
#include "cmodel/enum_names.hpp"
#include "cmodel/texture.hpp"

namespace tfu {

enum class BlockFamily : uint8_t { BC, ETC, ASTC };

enum class BlockFormat : uint8_t {
  BC1, BC1A, BC2, BC3, BC4, BC4S, BC5, BC5S, BC7,
  ETC2, ETC2A1, ETC2A, EAC_R11, EAC_R11S, EAC_RG11, EAC_RG11S,
  ASTC_4x4, ASTC_5x4, ASTC_5x5, ASTC_6x5, ASTC_6x6, ASTC_8x5, ASTC_8x6, ASTC_8x8,
  ASTC_10x5, ASTC_10x6, ASTC_10x8, ASTC_10x10, ASTC_12x10, ASTC_12x12,
};

struct BlockFormatInfo {
  BlockFormat format;
  const char* name;  // CLI, scene and trace name ("bc1", "astc6x6"): kBlockFormatNames
  BlockFamily family;
  int block_w, block_h;  // texels per block
  int block_bytes;       // 8 or 16
  int channels;          // 1 (R), 2 (RG), 3 (RGB), 4 (RGBA)
  bool is_signed;        // SNORM: decoded, not filtered by the unit
  uint32_t gl_internal_format;       // the GL enum of the linear variant (KTX files, Mesa)
  uint32_t gl_srgb_internal_format;  // the sRGB variant's, 0 when the format has none
  uint32_t dxgi_format;       // DXGI_FORMAT of the linear variant (DDS files' DX10 header), 0: none
  uint32_t dxgi_srgb_format;  // DXGI_FORMAT of the sRGB variant, 0: none
};

// clang-format off
inline constexpr std::array<BlockFormatInfo, 30> kBlockFormats{{
    // GL_EXT_texture_compression_s3tc, GL_EXT_texture_sRGB; DXGI_FORMAT_BC1..BC5_*, BC7_* (dxgiformat.h)
    {BlockFormat::BC1,   "bc1",  BlockFamily::BC, 4, 4,  8, 3, false, 0x83F0, 0x8C4C, 71, 72},
    {BlockFormat::BC1A,  "bc1a", BlockFamily::BC, 4, 4,  8, 4, false, 0x83F1, 0x8C4D, 71, 72},
    {BlockFormat::BC2,   "bc2",  BlockFamily::BC, 4, 4, 16, 4, false, 0x83F2, 0x8C4E, 74, 75},
    {BlockFormat::BC3,   "bc3",  BlockFamily::BC, 4, 4, 16, 4, false, 0x83F3, 0x8C4F, 77, 78},
    // GL_ARB_texture_compression_rgtc
    {BlockFormat::BC4,   "bc4",  BlockFamily::BC, 4, 4,  8, 1, false, 0x8DBB, 0, 80,  0},
    {BlockFormat::BC4S,  "bc4s", BlockFamily::BC, 4, 4,  8, 1, true,  0x8DBC, 0, 81,  0},
    {BlockFormat::BC5,   "bc5",  BlockFamily::BC, 4, 4, 16, 2, false, 0x8DBD, 0, 83,  0},
    {BlockFormat::BC5S,  "bc5s", BlockFamily::BC, 4, 4, 16, 2, true,  0x8DBE, 0, 84,  0},
    // GL_ARB_texture_compression_bptc
    {BlockFormat::BC7,   "bc7",  BlockFamily::BC, 4, 4, 16, 4, false, 0x8E8C, 0x8E8D, 98, 99},
    // GL_ARB_ES3_compatibility (ETC2 / EAC)
    {BlockFormat::ETC2,      "etc2",      BlockFamily::ETC, 4, 4,  8, 3, false, 0x9274, 0x9275,  0,  0},
    {BlockFormat::ETC2A1,    "etc2a1",    BlockFamily::ETC, 4, 4,  8, 4, false, 0x9276, 0x9277,  0,  0},
    {BlockFormat::ETC2A,     "etc2a",     BlockFamily::ETC, 4, 4, 16, 4, false, 0x9278, 0x9279,  0,  0},
    {BlockFormat::EAC_R11,   "eac_r11",   BlockFamily::ETC, 4, 4,  8, 1, false, 0x9270, 0,  0,  0},
    {BlockFormat::EAC_R11S,  "eac_r11s",  BlockFamily::ETC, 4, 4,  8, 1, true,  0x9271, 0,  0,  0},
    {BlockFormat::EAC_RG11,  "eac_rg11",  BlockFamily::ETC, 4, 4, 16, 2, false, 0x9272, 0,  0,  0},
    {BlockFormat::EAC_RG11S, "eac_rg11s", BlockFamily::ETC, 4, 4, 16, 2, true,  0x9273, 0,  0,  0},
    // GL_KHR_texture_compression_astc_ldr: RGBA 0x93B0 + i, SRGB8_ALPHA8 0x93D0 + i
    {BlockFormat::ASTC_4x4,   "astc4x4",   BlockFamily::ASTC,  4,  4, 16, 4, false, 0x93B0, 0x93D0,  0,  0},
    {BlockFormat::ASTC_5x4,   "astc5x4",   BlockFamily::ASTC,  5,  4, 16, 4, false, 0x93B1, 0x93D1,  0,  0},
    {BlockFormat::ASTC_5x5,   "astc5x5",   BlockFamily::ASTC,  5,  5, 16, 4, false, 0x93B2, 0x93D2,  0,  0},
    {BlockFormat::ASTC_6x5,   "astc6x5",   BlockFamily::ASTC,  6,  5, 16, 4, false, 0x93B3, 0x93D3,  0,  0},
    {BlockFormat::ASTC_6x6,   "astc6x6",   BlockFamily::ASTC,  6,  6, 16, 4, false, 0x93B4, 0x93D4,  0,  0},
    {BlockFormat::ASTC_8x5,   "astc8x5",   BlockFamily::ASTC,  8,  5, 16, 4, false, 0x93B5, 0x93D5,  0,  0},
    {BlockFormat::ASTC_8x6,   "astc8x6",   BlockFamily::ASTC,  8,  6, 16, 4, false, 0x93B6, 0x93D6,  0,  0},
    {BlockFormat::ASTC_8x8,   "astc8x8",   BlockFamily::ASTC,  8,  8, 16, 4, false, 0x93B7, 0x93D7,  0,  0},
    {BlockFormat::ASTC_10x5,  "astc10x5",  BlockFamily::ASTC, 10,  5, 16, 4, false, 0x93B8, 0x93D8,  0,  0},
    {BlockFormat::ASTC_10x6,  "astc10x6",  BlockFamily::ASTC, 10,  6, 16, 4, false, 0x93B9, 0x93D9,  0,  0},
    {BlockFormat::ASTC_10x8,  "astc10x8",  BlockFamily::ASTC, 10,  8, 16, 4, false, 0x93BA, 0x93DA,  0,  0},
    {BlockFormat::ASTC_10x10, "astc10x10", BlockFamily::ASTC, 10, 10, 16, 4, false, 0x93BB, 0x93DB,  0,  0},
    {BlockFormat::ASTC_12x10, "astc12x10", BlockFamily::ASTC, 12, 10, 16, 4, false, 0x93BC, 0x93DC,  0,  0},
    {BlockFormat::ASTC_12x12, "astc12x12", BlockFamily::ASTC, 12, 12, 16, 4, false, 0x93BD, 0x93DD,  0,  0},
}};
// clang-format on

constexpr bool block_formats_in_enum_order() {
  for (size_t i = 0; i < kBlockFormats.size(); ++i)
    if (static_cast<size_t>(kBlockFormats[i].format) != i) return false;
  return true;
}
static_assert(block_formats_in_enum_order(), "block_format_info indexes kBlockFormats by the enum value");
constexpr const BlockFormatInfo& block_format_info(BlockFormat f) { return kBlockFormats[static_cast<size_t>(f)]; }

// The names, derived from the table (EnumNames: from_name with its one-line error and "did you mean").
inline constexpr EnumNames<BlockFormat, kBlockFormats.size()> kBlockFormatNames = [] {
  EnumNames<BlockFormat, kBlockFormats.size()> n{"block-compressed format", {}};
  for (size_t i = 0; i < kBlockFormats.size(); ++i) n.entries[i] = {kBlockFormats[i].format, kBlockFormats[i].name};
  return n;
}();
BlockFormat block_format_from_name(const std::string& name);  // kBlockFormatNames
const char* block_format_name(BlockFormat f);

// True when the unit filters the format (not signed: see the header).
constexpr bool unit_filterable(BlockFormat f) { return !block_format_info(f).is_signed; }

// Blocks per row and column, and the bytes, of a w x h level (partial blocks at the right and
// bottom edges count whole).
constexpr int blocks_across(BlockFormat f, int width) { return (width + block_format_info(f).block_w - 1) / block_format_info(f).block_w; }
constexpr int blocks_down(BlockFormat f, int height) { return (height + block_format_info(f).block_h - 1) / block_format_info(f).block_h; }
size_t block_level_bytes(BlockFormat f, int width, int height);

// A compressed texture as files hold it and texture memory stores it: one format, the sRGB flag,
// and per MIP level its size in texels and its blocks, row-major, block_level_bytes(format, w, h)
// bytes (level n + 1 is max(1, w >> 1) x max(1, h >> 1), as for every texture: cmodel/texture.hpp).
struct BlockLevel {
  int width = 0, height = 0;
  std::vector<uint8_t> blocks;
};
struct BlockImage {
  BlockFormat format = BlockFormat::BC1;
  bool srgb = false;
  std::vector<BlockLevel> levels;
};

// How a block becomes texels: the BC1-BC5 interpolation rules (a descriptor field; the spec's by
// default) and the sRGB flag (ASTC only).
struct BlockDecodeRules {
  BcRules bc = kBcRulesSpec;
  bool srgb = false;
  friend constexpr bool operator==(const BlockDecodeRules&, const BlockDecodeRules&) = default;
};

// A compressed texture's blocks as texture memory stores them, with the rules the unit decodes
// them by (Texture::compressed).
struct CompressedLevels {
  BlockImage image;
  BlockDecodeRules rules;
};

// Decodes one block (block_format_info(f).block_bytes bytes) to block_w x block_h RGBA8 words,
// row-major (texel (x, y) at out[y * block_w + x]), as the unit sees them (the header's rules).
// Signed formats: the SNORM8 bytes as two's complement in the same channels.
void decode_block(BlockFormat f, const uint8_t* block, const BlockDecodeRules& rules, Rgba8* out);

// A whole w x h level (blocks row-major, partial edge blocks cropped): Image of RGBA8 words.
// InputError (naming `what`) when the bytes do not match the size.
Image decode_block_level(BlockFormat f, int width, int height, std::span<const uint8_t> blocks, const BlockDecodeRules& rules,
                         const std::string& what = "compressed level");

// The texture the models sample from a compressed image: its levels (the BlockImage's, as many as
// it stores: no MIP generation on compressed data; a shorter chain behaves as any texture with
// stored levels, its last level the last one LOD selects) decoded by decode_block_level, the same
// decoder the cycle model applies to the blocks it fetches; the blocks kept in `compressed` for
// texture memory. The sRGB flag of the rules is the image's. RGBA8 texels, layout and tile size
// as given (texture memory stores blocks row-major whatever the layout: cmodel/texture_memory.hpp).
// InputError (naming `what`) for a signed format (the unit filters no SNORM texels), no levels,
// or levels whose sizes or bytes break the floor rule.
Texture texture_from_block_image(const BlockImage& image, const BlockDecodeRules& rules,
                                 const std::string& what = "compressed texture",
                                 MemoryLayout layout = MemoryLayout::Tiled, int tile_bytes = 64);

}  // namespace tfu
