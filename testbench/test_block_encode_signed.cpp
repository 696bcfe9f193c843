// The own encoders of the signed formats (BC4 / BC5 signed, EAC signed R11 / RG11) and of ETC2
// punch-through alpha (cmodel/block_encode.hpp, docs/compressed-files.md "Encoders"): exact round
// trips where the format can hold the input exactly, hand-derived blocks, PSNR floors through our
// decoders, and the encoded blocks decoded by an outside decoder, Mesa 22.3 (OSMesa softpipe,
// testbench/mesa_decoder.hpp), which must give the texels our decoders give in its rules.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>

#include "cmodel/bc_decode.hpp"
#include "cmodel/block_encode.hpp"
#include "cmodel/etc2_decode.hpp"
#include "cmodel/metrics.hpp"
#include "cmodel/procedural.hpp"
#include "testbench/mesa_decoder.hpp"

namespace tfu::test {
namespace {

constexpr uint32_t kGlRed = 0x1903, kGlRg = 0x8227, kGlRgba = 0x1908;
constexpr uint32_t kGlByte = 0x1400, kGlUnsignedByte = 0x1401, kGlShort = 0x1402;

// A 61x45 crop of a 64x64 procedural texture: partial blocks at the right and bottom edges.
Image crop_61x45(const std::string& name) {
  const Image s = make_procedural(name, 64).texture.levels[0];
  Image c(61, 45);
  for (int y = 0; y < 45; ++y)
    for (int x = 0; x < 61; ++x) c.at(x, y) = s.at(x, y);
  return c;
}

BlockLevel encode_one(const Image& src, BlockFormat f) {
  return encode_block_image(std::span(&src, 1), f, false).levels.at(0);
}

TEST(BlockEncodeSigned, ImageBytesAndElevenBitsRoundTrip) {
  for (int s = -127; s <= 127; ++s) {
    EXPECT_EQ(snorm8_from_image_byte(snorm8_to_image_byte(s)), s);
    EXPECT_EQ(eac11_signed_to_snorm8(eac11_signed_from_snorm8(s)), s);
  }
  EXPECT_EQ(snorm8_to_image_byte(0), 128);
  EXPECT_EQ(snorm8_from_image_byte(0), -127);  // no -128: SNORM8 -128 is -1.0, as -127
  EXPECT_EQ(snorm8_from_image_byte(255), 127);
  EXPECT_EQ(eac11_signed_from_snorm8(127), 1023);
  EXPECT_EQ(eac11_signed_from_snorm8(-1), -8);  // 1023 / 127 = 8.055
}

// A constant block holds its value exactly: BC4 signed with both endpoints the value (code 0), EAC
// signed within one 11-bit step (base 8 b, multiplier 0, modifiers -3..2), which is the same SNORM8.
TEST(BlockEncodeSigned, ConstantBlocksDecodeToTheirValue) {
  for (int s = -127; s <= 127; ++s) {
    int v[16];
    std::fill(std::begin(v), std::end(v), s);
    uint8_t block[8];
    encode_bc4_signed_block(v, block);
    for (const int8_t d : decode_bc4_snorm8(block, Bc4Interpolation::EXACT)) ASSERT_EQ(d, s);
    std::fill(std::begin(v), std::end(v), eac11_signed_from_snorm8(s));
    encode_eac_r11_signed_block(v, block);
    int16_t d11[16];
    decode_eac_r11_signed_block(block, d11);
    for (const int16_t d : d11) {
      ASSERT_LE(std::abs(d - eac11_signed_from_snorm8(s)), 1) << s;
      ASSERT_EQ(eac11_signed_to_snorm8(d), s);
    }
  }
}

// Two values, eight texels each: the eight-value mode with the extremes as endpoints, red0 = 100,
// red1 = -100; texels 0..7 code 0 (red0), texels 8..15 code 1 (red1): the 3-bit codes at bits 3t
// of bytes 2..7 (little-endian), 1 << 24 | 1 << 27 | ... | 1 << 45.
TEST(BlockEncodeSigned, HandDerivedBc4Block) {
  int v[16];
  for (int t = 0; t < 16; ++t) v[t] = t < 8 ? 100 : -100;
  std::array<uint8_t, 8> block{};
  encode_bc4_signed_block(v, block.data());
  EXPECT_EQ(block, (std::array<uint8_t, 8>{0x64, 0x9c, 0x00, 0x00, 0x00, 0x49, 0x92, 0x24}));
}

// Measured (PSNR in dB of the channels held, image bytes v against decode(encode(v)) as image bytes,
// 61x45 crops): noise / zoneplate bc4s 51.86 / 33.87, bc5s 50.03 / 30.86, eac_r11s 51.66 / 35.55,
// eac_rg11s 49.69 / 32.54. Floors: these less 0.5 dB (the encoders are deterministic). Then Mesa
// decodes the same blocks to the texels of our decoders in its rules (BC4: truncating, kBcRulesMesa;
// EAC: the spec's 16-bit form of the 11-bit value).
TEST(BlockEncodeSigned, PsnrFloorsAndMesaDecodesTheBlocksAlike) {
  struct Floor {
    BlockFormat format;
    double noise, zoneplate;
  };
  for (const Floor& fl : {Floor{BlockFormat::BC4S, 51.3, 33.3}, Floor{BlockFormat::BC5S, 49.5, 30.3},
                          Floor{BlockFormat::EAC_R11S, 51.1, 35.0}, Floor{BlockFormat::EAC_RG11S, 49.1, 32.0}}) {
    const BlockFormatInfo& info = block_format_info(fl.format);
    SCOPED_TRACE(info.name);
    for (const bool zone : {false, true}) {
      const Image src = crop_61x45(zone ? "zoneplate" : "noise");
      const BlockLevel level = encode_one(src, fl.format);
      const Image back = decode_block_level(fl.format, src.width, src.height, level.blocks, {});
      Image got = back, want = src;
      for (size_t i = 0; i < src.texels.size(); ++i) {
        const Rgba8 b = back.texels[i], s = src.texels[i];
        got.texels[i] = Rgba8{snorm8_to_image_byte(static_cast<int8_t>(b.r)),
                              info.channels == 2 ? snorm8_to_image_byte(static_cast<int8_t>(b.g)) : uint8_t{0}, 0, 255};
        want.texels[i] =
            Rgba8{snorm8_to_image_byte(snorm8_from_image_byte(s.r)),
                  info.channels == 2 ? snorm8_to_image_byte(snorm8_from_image_byte(s.g)) : uint8_t{0}, 0, 255};
      }
      EXPECT_GE(psnr_db(got, want), zone ? fl.zoneplate : fl.noise);

      if (!mesa_available()) continue;
      const bool eac = info.family == BlockFamily::ETC;
      std::string why;
      const auto mesa =
          mesa_decode(info.gl_internal_format, src.width, src.height, level.blocks,
                      eac ? (info.channels == 1 ? kGlRed : kGlRg) : kGlRgba, eac ? kGlShort : kGlByte, &why);
      ASSERT_TRUE(mesa) << why;
      int mismatches = 0;
      if (eac) {
        const std::vector<int16_t> v = decode_eac11_image(
            info.channels == 1 ? EtcFormat::R11Signed : EtcFormat::Rg11Signed, src.width, src.height, level.blocks);
        ASSERT_EQ(mesa->size(), 2 * v.size());
        for (size_t i = 0; i < v.size(); ++i)
          mismatches += static_cast<uint16_t>(eac11_signed_to_snorm16(v[i])) !=
                        static_cast<uint16_t>((*mesa)[2 * i] | (*mesa)[2 * i + 1] << 8);
      } else {
        const Image ours = decode_block_level(fl.format, src.width, src.height, level.blocks, {kBcRulesMesa, false});
        ASSERT_EQ(mesa->size(), 4 * ours.texels.size());
        for (size_t i = 0; i < ours.texels.size(); ++i) {
          const Rgba8 m{(*mesa)[4 * i], (*mesa)[4 * i + 1], (*mesa)[4 * i + 2], (*mesa)[4 * i + 3]};
          mismatches += ours.texels[i] != m;
        }
      }
      EXPECT_EQ(mismatches, 0);
    }
  }
}

// Punch-through alpha: alpha >= 128 is opaque. A 61x45 zoneplate with alpha a ramp across it (left
// half transparent): every decoded alpha is exactly 0 or 255 as the source's side of 128, the
// transparent texels are (0, 0, 0, 0), and the opaque texels' RGB PSNR (measured 23.86 dB) stays
// above it less 0.5 dB. The same image opaque: every block has the opaque bit and decodes as an
// ETC2 RGB8 block (measured 23.87 dB; the ETC1-mode encoder of etc2, which may also use the
// individual mode, 24.51). Mesa decodes both to our texels.
TEST(BlockEncodePunchThrough, AlphaExactColourFloorsAndMesa) {
  Image ramp = crop_61x45("zoneplate");
  for (int y = 0; y < ramp.height; ++y)
    for (int x = 0; x < ramp.width; ++x) ramp.at(x, y).a = static_cast<uint8_t>((x * 255) / (ramp.width - 1));
  Image opaque = crop_61x45("zoneplate");
  for (const bool all_opaque : {false, true}) {
    const Image& src = all_opaque ? opaque : ramp;
    const BlockLevel level = encode_one(src, BlockFormat::ETC2A1);
    const Image back = decode_block_level(BlockFormat::ETC2A1, src.width, src.height, level.blocks, {});
    Image got(src.width, src.height), want(src.width, src.height);
    int kept = 0;
    for (size_t i = 0; i < src.texels.size(); ++i) {
      const bool o = src.texels[i].a >= 128;
      ASSERT_EQ(back.texels[i].a, o ? 255 : 0) << i;
      if (!o) {
        ASSERT_EQ(back.texels[i], (Rgba8{0, 0, 0, 0})) << i;
        continue;
      }
      got.texels[static_cast<size_t>(kept)] = Rgba8{back.texels[i].r, back.texels[i].g, back.texels[i].b, 255};
      want.texels[static_cast<size_t>(kept++)] = Rgba8{src.texels[i].r, src.texels[i].g, src.texels[i].b, 255};
    }
    EXPECT_EQ(kept, all_opaque ? 61 * 45 : 30 * 45);  // x * 255 / 60 >= 128 from x = 31
    got.texels.resize(static_cast<size_t>(kept)), want.texels.resize(static_cast<size_t>(kept));
    got.width = want.width = kept, got.height = want.height = 1;
    EXPECT_GE(psnr_db(got, want), all_opaque ? 23.37 : 23.36);
    if (all_opaque)
      for (size_t b = 0; b < level.blocks.size(); b += 8) {
        ASSERT_NE(level.blocks[b + 3] & 2, 0) << "opaque bit of block " << b / 8;
        Rgba8 a[16], c[16];
        decode_etc2_rgb8a1_block(&level.blocks[b], a);
        decode_etc2_rgb_block(&level.blocks[b], c);
        ASSERT_TRUE(std::equal(std::begin(a), std::end(a), std::begin(c))) << "block " << b / 8;
      }
    if (!mesa_available()) continue;
    const auto mesa = mesa_decode(block_format_info(BlockFormat::ETC2A1).gl_internal_format, src.width, src.height,
                                  level.blocks, kGlRgba, kGlUnsignedByte);
    ASSERT_TRUE(mesa);
    int mismatches = 0;
    for (size_t i = 0; i < back.texels.size(); ++i)
      mismatches += back.texels[i] != Rgba8{(*mesa)[4 * i], (*mesa)[4 * i + 1], (*mesa)[4 * i + 2], (*mesa)[4 * i + 3]};
    EXPECT_EQ(mismatches, 0);
  }
}

// One block by hand: colour (200, 100, 50), texel (0, 0) transparent. Opaque bit 0: index 2 is
// transparent black, index 0 the base colour with modifier 0. The base is the colour on the 5-bit
// grid, round(v * 31 / 255) = (24, 12, 6), widened (x << 3 | x >> 2) to (198, 99, 49); base +/- b
// is at least 8 away (b >= 8), so every opaque texel takes index 0 and decodes to the base.
TEST(BlockEncodePunchThrough, HandDerivedBlock) {
  Rgba8 t[16];
  std::fill(std::begin(t), std::end(t), Rgba8{200, 100, 50, 255});
  t[0].a = 0;
  uint8_t block[8];
  encode_etc2_punchthrough_block(t, block);
  EXPECT_EQ(block[3] & 2, 0);  // opaque bit
  EXPECT_EQ(etc2_block_mode(block, true), Etc2Mode::Differential);
  Rgba8 out[16];
  decode_etc2_rgb8a1_block(block, out);
  EXPECT_EQ(out[0], (Rgba8{0, 0, 0, 0}));
  for (int i = 1; i < 16; ++i) EXPECT_EQ(out[i], (Rgba8{198, 99, 49, 255})) << i;
}

}  // namespace
}  // namespace tfu::test
