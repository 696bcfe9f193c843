// The one table of block-compressed formats (cmodel/block_formats.hpp) against its sources: the GL
// enums of <GL/glext.h>, each family's block sizes and format tables, and decode_block against each
// family's own decoder.
#include <gtest/gtest.h>

#include <GL/gl.h>
#include <GL/glext.h>

#include <random>
#include <vector>

#include "cmodel/astc_decode.hpp"
#include "cmodel/bc_decode.hpp"
#include "cmodel/block_formats.hpp"
#include "cmodel/etc2_decode.hpp"
#include "testbench/iterations.hpp"

namespace tfu {
namespace {

TEST(BlockFormats, GlEnumsAreTheHeadersValues) {
  const std::vector<std::pair<BlockFormat, std::pair<uint32_t, uint32_t>>> want{
      {BlockFormat::BC1, {GL_COMPRESSED_RGB_S3TC_DXT1_EXT, GL_COMPRESSED_SRGB_S3TC_DXT1_EXT}},
      {BlockFormat::BC1A, {GL_COMPRESSED_RGBA_S3TC_DXT1_EXT, GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT}},
      {BlockFormat::BC2, {GL_COMPRESSED_RGBA_S3TC_DXT3_EXT, GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT3_EXT}},
      {BlockFormat::BC3, {GL_COMPRESSED_RGBA_S3TC_DXT5_EXT, GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT5_EXT}},
      {BlockFormat::BC4, {GL_COMPRESSED_RED_RGTC1, 0}},
      {BlockFormat::BC4S, {GL_COMPRESSED_SIGNED_RED_RGTC1, 0}},
      {BlockFormat::BC5, {GL_COMPRESSED_RG_RGTC2, 0}},
      {BlockFormat::BC5S, {GL_COMPRESSED_SIGNED_RG_RGTC2, 0}},
      {BlockFormat::BC7, {GL_COMPRESSED_RGBA_BPTC_UNORM, GL_COMPRESSED_SRGB_ALPHA_BPTC_UNORM}},
      {BlockFormat::ETC2, {GL_COMPRESSED_RGB8_ETC2, GL_COMPRESSED_SRGB8_ETC2}},
      {BlockFormat::ETC2A1, {GL_COMPRESSED_RGB8_PUNCHTHROUGH_ALPHA1_ETC2, GL_COMPRESSED_SRGB8_PUNCHTHROUGH_ALPHA1_ETC2}},
      {BlockFormat::ETC2A, {GL_COMPRESSED_RGBA8_ETC2_EAC, GL_COMPRESSED_SRGB8_ALPHA8_ETC2_EAC}},
      {BlockFormat::EAC_R11, {GL_COMPRESSED_R11_EAC, 0}},
      {BlockFormat::EAC_R11S, {GL_COMPRESSED_SIGNED_R11_EAC, 0}},
      {BlockFormat::EAC_RG11, {GL_COMPRESSED_RG11_EAC, 0}},
      {BlockFormat::EAC_RG11S, {GL_COMPRESSED_SIGNED_RG11_EAC, 0}},
      {BlockFormat::ASTC_4x4, {GL_COMPRESSED_RGBA_ASTC_4x4_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_4x4_KHR}},
      {BlockFormat::ASTC_5x4, {GL_COMPRESSED_RGBA_ASTC_5x4_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_5x4_KHR}},
      {BlockFormat::ASTC_5x5, {GL_COMPRESSED_RGBA_ASTC_5x5_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_5x5_KHR}},
      {BlockFormat::ASTC_6x5, {GL_COMPRESSED_RGBA_ASTC_6x5_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_6x5_KHR}},
      {BlockFormat::ASTC_6x6, {GL_COMPRESSED_RGBA_ASTC_6x6_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_6x6_KHR}},
      {BlockFormat::ASTC_8x5, {GL_COMPRESSED_RGBA_ASTC_8x5_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_8x5_KHR}},
      {BlockFormat::ASTC_8x6, {GL_COMPRESSED_RGBA_ASTC_8x6_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_8x6_KHR}},
      {BlockFormat::ASTC_8x8, {GL_COMPRESSED_RGBA_ASTC_8x8_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_8x8_KHR}},
      {BlockFormat::ASTC_10x5, {GL_COMPRESSED_RGBA_ASTC_10x5_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_10x5_KHR}},
      {BlockFormat::ASTC_10x6, {GL_COMPRESSED_RGBA_ASTC_10x6_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_10x6_KHR}},
      {BlockFormat::ASTC_10x8, {GL_COMPRESSED_RGBA_ASTC_10x8_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_10x8_KHR}},
      {BlockFormat::ASTC_10x10, {GL_COMPRESSED_RGBA_ASTC_10x10_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_10x10_KHR}},
      {BlockFormat::ASTC_12x10, {GL_COMPRESSED_RGBA_ASTC_12x10_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_12x10_KHR}},
      {BlockFormat::ASTC_12x12, {GL_COMPRESSED_RGBA_ASTC_12x12_KHR, GL_COMPRESSED_SRGB8_ALPHA8_ASTC_12x12_KHR}},
  };
  ASSERT_EQ(want.size(), kBlockFormats.size());
  for (const auto& [f, gl] : want) {
    EXPECT_EQ(block_format_info(f).gl_internal_format, gl.first) << block_format_name(f);
    EXPECT_EQ(block_format_info(f).gl_srgb_internal_format, gl.second) << block_format_name(f);
  }
}

TEST(BlockFormats, SizesAgreeWithEachFamilysTables) {
  int astc = 0;
  for (const BlockFormatInfo& i : kBlockFormats) {
    EXPECT_EQ(block_format_from_name(i.name), i.format);
    if (i.family == BlockFamily::ASTC) {
      EXPECT_EQ(kAstcFootprints[static_cast<size_t>(astc)], (AstcFootprint{i.block_w, i.block_h})) << i.name;
      EXPECT_EQ(i.block_bytes, kAstcBlockBytes);
      ++astc;
    } else {
      EXPECT_EQ(i.block_w, 4);
      EXPECT_EQ(i.block_h, 4);
    }
  }
  EXPECT_EQ(astc, static_cast<int>(kAstcFootprints.size()));
  for (const EtcFormatInfo& e : kEtcFormats) {  // every ETC format (sRGB ones as the flag) is in the table
    bool found = false;
    for (const BlockFormatInfo& i : kBlockFormats) {
      if (i.family == BlockFamily::ETC && i.block_bytes == e.block_bytes && i.channels == e.channels && i.is_signed == e.is_signed)
        found = true;
    }
    EXPECT_TRUE(found) << e.name;
  }
  EXPECT_EQ(block_format_info(BlockFormat::BC1).block_bytes, bc_block_bytes(BcFormat::BC1_RGB));
  EXPECT_EQ(block_format_info(BlockFormat::BC5).block_bytes, bc_block_bytes(BcFormat::BC5_UNORM));
  EXPECT_EQ(block_level_bytes(BlockFormat::ASTC_6x6, 13, 7), 3u * 2u * 16u);  // partial blocks count whole
  EXPECT_EQ(block_level_bytes(BlockFormat::BC1, 1, 1), 8u);
  EXPECT_FALSE(unit_filterable(BlockFormat::BC4S));
  EXPECT_TRUE(unit_filterable(BlockFormat::EAC_RG11));
}

// decode_block is a dispatch: each format gives what its family's image decoder gives.
TEST(BlockFormats, DecodeBlockIsEachFamilysDecoder) {
  std::mt19937 rng(7);
  const int n = test::iterations(200);
  for (const BlockFormatInfo& i : kBlockFormats) {
    if (i.is_signed) continue;
    for (int k = 0; k < n; ++k) {
      const int w = 1 + static_cast<int>(rng() % 23), h = 1 + static_cast<int>(rng() % 17);
      std::vector<uint8_t> blocks(block_level_bytes(i.format, w, h));
      for (uint8_t& b : blocks) b = static_cast<uint8_t>(rng());
      const bool srgb = i.family == BlockFamily::ASTC && (k & 1);
      const Image got = decode_block_level(i.format, w, h, blocks, {kBcRulesSpec, srgb});
      std::vector<Rgba8> want;
      if (i.family == BlockFamily::BC) {
        want = decode_bc_image(kBcFormatNames.from_name(i.name), w, h, blocks);
      } else if (i.family == BlockFamily::ETC) {
        const EtcFormat e = i.format == BlockFormat::ETC2     ? EtcFormat::Rgb8
                            : i.format == BlockFormat::ETC2A1 ? EtcFormat::Rgb8A1
                            : i.format == BlockFormat::ETC2A  ? EtcFormat::Rgba8
                            : i.format == BlockFormat::EAC_R11 ? EtcFormat::R11
                                                               : EtcFormat::Rg11;
        want = decode_etc_image(e, w, h, blocks);
      } else {
        want = decode_astc_image(blocks.data(), blocks.size(), w, h, i.block_w, i.block_h, srgb).texels;
      }
      ASSERT_EQ(got.texels, want) << i.name << " " << w << "x" << h;
    }
  }
  EXPECT_THROW(decode_block_level(BlockFormat::BC1, 4, 4, std::vector<uint8_t>(7), {}), InputError);
  EXPECT_THROW(decode_block_level(BlockFormat::BC1, 0, 4, std::vector<uint8_t>(8), {}), InputError);
}

}  // namespace
}  // namespace tfu
