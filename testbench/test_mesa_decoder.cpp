// The outside reference itself (testbench/mesa_decoder.hpp): a hand-derived S3TC block decodes as
// derived, and every refusal comes back as std::nullopt with its reason. The ETC2/EAC checks are
// in test_etc2_decode.cpp.
#include <gtest/gtest.h>

#include <GL/gl.h>
#include <GL/glext.h>

#include <cstdint>
#include <string>
#include <vector>

#include "testbench/mesa_decoder.hpp"

namespace tfu::test {
namespace {

// BC1 (DXT1 RGB): color0 = 0xF800 (565 red 31, 0, 0 -> 255, 0, 0), color1 = 0x001F (blue ->
// 0, 0, 255); color0 > color1 selects the four-colour mode: c2 = (2 c0 + c1) / 3 = (170, 0, 85),
// c3 = (c0 + 2 c1) / 3 = (85, 0, 170) (exact thirds of 255: every BC1 rounding variant agrees).
// Row 0 indices 0, 1, 2, 3 (byte 4 = 11 10 01 00b = 0xE4, texel 0 in the low bits), rows 1-3
// index 0 (red).
TEST(MesaDecoder, Bc1HandBlock) {
  if (!mesa_available()) GTEST_SKIP() << "no OSMesa context";
  const std::vector<uint8_t> block{0x00, 0xF8, 0x1F, 0x00, 0xE4, 0x00, 0x00, 0x00};
  std::string why;
  const auto t = mesa_decode(GL_COMPRESSED_RGB_S3TC_DXT1_EXT, 4, 4, block, GL_RGBA, GL_UNSIGNED_BYTE, &why);
  ASSERT_TRUE(t) << why;
  ASSERT_EQ(t->size(), 64u);
  const std::vector<uint8_t> row0{255, 0, 0, 255, 0, 0, 255, 255, 170, 0, 85, 255, 85, 0, 170, 255};
  EXPECT_EQ(std::vector<uint8_t>(t->begin(), t->begin() + 16), row0);
  for (size_t i = 4; i < 16; ++i) EXPECT_EQ((*t)[4 * i], 255) << i;
  // Three components are read as four and the fourth dropped (mesa_decoder.hpp): same texels.
  const auto rgb = mesa_decode(GL_COMPRESSED_RGB_S3TC_DXT1_EXT, 4, 4, block, GL_RGB, GL_UNSIGNED_BYTE);
  ASSERT_TRUE(rgb);
  EXPECT_EQ(std::vector<uint8_t>(rgb->begin(), rgb->begin() + 6), (std::vector<uint8_t>{255, 0, 0, 0, 0, 255}));
}

TEST(MesaDecoder, RefusalsSayWhy) {
  if (!mesa_available()) GTEST_SKIP() << "no OSMesa context";
  const std::vector<uint8_t> block(8);
  std::string why;
  EXPECT_FALSE(mesa_decode(0x1234, 4, 4, block, GL_RGBA, GL_UNSIGNED_BYTE, &why));
  EXPECT_EQ(why, "glCompressedTexImage2D: GL_INVALID_ENUM");
  EXPECT_FALSE(mesa_decode(GL_COMPRESSED_RGB8_ETC2, 8, 4, block, GL_RGBA, GL_UNSIGNED_BYTE, &why));  // 2 blocks
  EXPECT_EQ(why, "glCompressedTexImage2D: GL_INVALID_VALUE");
  EXPECT_FALSE(mesa_decode(GL_COMPRESSED_RGB8_ETC2, 0, 4, block, GL_RGBA, GL_UNSIGNED_BYTE, &why));
  EXPECT_EQ(why, "mesa_decode: empty image");
  EXPECT_FALSE(mesa_decode(GL_COMPRESSED_RGB8_ETC2, 4, 4, block, GL_RGBA, GL_UNSIGNED_INT_8_8_8_8, &why));
  EXPECT_EQ(why, "mesa_decode: unsupported read-back format/type");
  // The context is still usable after refusals.
  EXPECT_TRUE(mesa_decode(GL_COMPRESSED_RGB8_ETC2, 4, 4, block, GL_RGBA, GL_UNSIGNED_BYTE));
}

}  // namespace
}  // namespace tfu::test
