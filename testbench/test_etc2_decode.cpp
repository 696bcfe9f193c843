// ETC2 / EAC decoders (cmodel/etc2_decode.hpp): hand-derived blocks for every mode, each derived
// from the KDFS 1.3 text in the comment above it, and bit-exact agreement with Mesa's decoders
// (testbench/mesa_decoder.hpp) on seeded random blocks of every format, in images whose sizes are
// not multiples of 4. docs/compressed-etc2.md.
// Runtime: about 1 s in a Release build (10 formats x 20,000 random blocks through both decoders).
#include <gtest/gtest.h>

#include <GL/gl.h>
#include <GL/glext.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "cmodel/error.hpp"
#include "cmodel/etc2_decode.hpp"
#include "testbench/docs_text.hpp"
#include "testbench/iterations.hpp"
#include "testbench/mesa_decoder.hpp"

namespace tfu::test {
namespace {

using Block8 = std::array<uint8_t, 8>;

std::array<Rgba8, 16> rgb_block(const Block8& b) {
  std::array<Rgba8, 16> out;
  decode_etc2_rgb_block(b.data(), out.data());
  return out;
}
std::array<Rgba8, 16> a1_block(const Block8& b) {
  std::array<Rgba8, 16> out;
  decode_etc2_rgb8a1_block(b.data(), out.data());
  return out;
}
Rgba8 at(const std::array<Rgba8, 16>& t, int x, int y) { return t[static_cast<size_t>(4 * y + x)]; }
constexpr Rgba8 rgb(int r, int g, int b) {
  return {static_cast<uint8_t>(r), static_cast<uint8_t>(g), static_cast<uint8_t>(b), 255};
}
std::string hex(std::span<const uint8_t> b) {
  std::string s;
  char buf[4];
  for (uint8_t v : b) {
    std::snprintf(buf, sizeof buf, "%02x", v);
    s += buf;
  }
  return s;
}

// ------------------------------------------------------------------------- hand-derived: ETC2 RGB

// Individual mode (D = bit 33 = 0), flip 0. Bytes A5 3C 0F 1C | 00 01 80 01:
//   R1 = 0xA, R2 = 0x5 (byte 0), G1 = 0x3, G2 = 0xC, B1 = 0x0, B2 = 0xF; byte 3 = 000 111 0 0:
//   table1 = 0 (a, b = 2, 8), table2 = 7 (47, 183), D = 0, flip = 0 (subblock 2 = columns 2-3).
//   base 1 = (0xAA, 0x33, 0x00) = (170, 51, 0), base 2 = (0x55, 0xCC, 0xFF) = (85, 204, 255).
//   Low word 0x00018001: MSB plane (bits 31-16) = 0x0001 -> texel a (j = 0); LSB plane (15-0) =
//   0x8001 -> a and p (j = 15). a = (0,0): index 11 -> -8: (162, 43, -8 -> 0);
//   p = (3,3): index 01 -> +183: (268, 387, 438) -> (255, 255, 255); others index 00 -> +a:
//   subblock 1 (172, 53, 2), subblock 2 (132, 251, 302 -> 255).
TEST(Etc2Decode, IndividualMode) {
  const Block8 b{0xA5, 0x3C, 0x0F, 0x1C, 0x00, 0x01, 0x80, 0x01};
  EXPECT_EQ(etc2_block_mode(b.data(), false), Etc2Mode::Individual);
  const auto t = rgb_block(b);
  EXPECT_EQ(at(t, 0, 0), rgb(162, 43, 0));
  EXPECT_EQ(at(t, 3, 3), rgb(255, 255, 255));
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      if ((x == 0 && y == 0) || (x == 3 && y == 3)) continue;
      EXPECT_EQ(at(t, x, y), x < 2 ? rgb(172, 53, 2) : rgb(132, 251, 255)) << x << "," << y;
    }
}

// Differential mode, flip 1 (the spec's own example colours). Bytes E4 22 18 57 | 80 24 80 21:
//   R = 11100 = 28, dR = 100 = -4; G = 00100 = 4, dG = 010 = +2; B = 00011 = 3, dB = 000;
//   byte 3 = 010 101 1 1: table1 = 2 (9, 29), table2 = 5 (24, 80), D = 1, flip = 1 (subblock 2 =
//   rows 2-3). Sums 24, 6, 3 in [0, 31]: differential. base 1 = extend5(28, 4, 3) =
//   (231, 33, 24), base 2 = extend5(24, 6, 3) = (198, 49, 24) (KDFS's worked numbers).
//   MSB plane 0x8024 (j = 2, 5, 15), LSB plane 0x8021 (j = 0, 5, 15):
//   (0,0) j 0 index 01 -> +29: (260, 62, 53) -> (255, 62, 53)
//   (1,1) j 5 index 11 -> -29: (202, 4, -5) -> (202, 4, 0)
//   (0,2) j 2 index 10 -> -24: (174, 25, 0)
//   (3,3) j 15 index 11 -> -80: (118, -31, -56) -> (118, 0, 0)
//   others index 00: rows 0-1 +9 -> (240, 42, 33); rows 2-3 +24 -> (222, 73, 48).
TEST(Etc2Decode, DifferentialModeFlipped) {
  const Block8 b{0xE4, 0x22, 0x18, 0x57, 0x80, 0x24, 0x80, 0x21};
  EXPECT_EQ(etc2_block_mode(b.data(), false), Etc2Mode::Differential);
  const auto t = rgb_block(b);
  EXPECT_EQ(at(t, 0, 0), rgb(255, 62, 53));
  EXPECT_EQ(at(t, 1, 1), rgb(202, 4, 0));
  EXPECT_EQ(at(t, 0, 2), rgb(174, 25, 0));
  EXPECT_EQ(at(t, 3, 3), rgb(118, 0, 0));
  EXPECT_EQ(at(t, 3, 0), rgb(240, 42, 33));
  EXPECT_EQ(at(t, 0, 1), rgb(240, 42, 33));
  EXPECT_EQ(at(t, 1, 3), rgb(222, 73, 48));
  EXPECT_EQ(at(t, 3, 2), rgb(222, 73, 48));
}

// T mode. Bytes F3 2D 84 FB | 11 00 10 10:
//   bits 63-59 = 11110 = 30, 58-56 = 011 = +3: R + dR = 33 > 31 -> T.
//   R1a = bits 60-59 = 10, R1b = 57-56 = 11 -> R1 = 1011 = 11; G1 = 0x2, B1 = 0xD (byte 1);
//   R2 = 0x8, G2 = 0x4 (byte 2); byte 3 = 1111 10 1 1: B2 = 0xF, da = 10, db = 1 -> index 101
//   = 5 -> d = 32. base 1 = (187, 34, 221), base 2 = (136, 68, 255).
//   paint 0 = (187, 34, 221), 1 = base 2 + 32 = (168, 100, 287 -> 255), 2 = (136, 68, 255),
//   3 = base 2 - 32 = (104, 36, 223).
//   Row 0 indices 0, 1, 2, 3 (j = 0, 4, 8, 12): MSB plane 0x1100, LSB plane 0x1010; others 0.
TEST(Etc2Decode, TMode) {
  const Block8 b{0xF3, 0x2D, 0x84, 0xFB, 0x11, 0x00, 0x10, 0x10};
  EXPECT_EQ(etc2_block_mode(b.data(), false), Etc2Mode::T);
  const auto t = rgb_block(b);
  EXPECT_EQ(at(t, 0, 0), rgb(187, 34, 221));
  EXPECT_EQ(at(t, 1, 0), rgb(168, 100, 255));
  EXPECT_EQ(at(t, 2, 0), rgb(136, 68, 255));
  EXPECT_EQ(at(t, 3, 0), rgb(104, 36, 223));
  for (int y = 1; y < 4; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(at(t, x, y), rgb(187, 34, 221)) << x << "," << y;
}

// H mode. Bytes 1A F2 D0 37 | 00 0C 00 0A:
//   bit 63 = 0, R1 = bits 62-59 = 0011, G1a = 58-56 = 010; R = 00011 = 3, dR = 010: 5, not T.
//   bits 55-53 = 111, G1b = bit 52 = 1, B1a = bit 51 = 0: G = 11110 = 30; bit 50 = 0, bits 49-48
//   = 10: dG = +2, G + dG = 32 > 31 -> H.
//   G1 = 010:1 = 5, B1 = 0:101 (B1b = bits 49-47 = 101) = 5: base 1 = (0x33, 0x55, 0x55) =
//   (51, 85, 85). R2 = bits 46-43 = 1010, G2 = 42-39 = 0000, B2 = 38-35 = 0110: base 2 =
//   (170, 0, 102). value(base 1) = 0x335555 < value(base 2) = 0xAA0066 -> LSB 0; da = bit 34 =
//   1, db = bit 32 = 1: index 110 = 6 -> d = 41.
//   paint 0 = (92, 126, 126), 1 = (10, 44, 44), 2 = (211, 41, 143), 3 = (129, -41 -> 0, 61).
//   Column 0 indices 0, 1, 2, 3 (j = 0..3): MSB plane 0x000C, LSB plane 0x000A; others 0.
TEST(Etc2Decode, HMode) {
  const Block8 b{0x1A, 0xF2, 0xD0, 0x37, 0x00, 0x0C, 0x00, 0x0A};
  EXPECT_EQ(etc2_block_mode(b.data(), false), Etc2Mode::H);
  const auto t = rgb_block(b);
  EXPECT_EQ(at(t, 0, 0), rgb(92, 126, 126));
  EXPECT_EQ(at(t, 0, 1), rgb(10, 44, 44));
  EXPECT_EQ(at(t, 0, 2), rgb(211, 41, 143));
  EXPECT_EQ(at(t, 0, 3), rgb(129, 0, 61));
  for (int y = 0; y < 4; ++y)
    for (int x = 1; x < 4; ++x) EXPECT_EQ(at(t, x, y), rgb(92, 126, 126)) << x << "," << y;
}

// H mode's third distance bit when base 1 >= base 2: the H block above with R1 and R2 swapped
// in value order: R1 = 1011 (bits 62-59), so byte 0 = 0 1011 010 = 0x5A; R = 01011 = 11, dR = +2:
// 13, not T. base 1 = (187, 85, 85) > base 2 = (170, 0, 102) -> LSB 1: index 111 = 7 -> d = 64.
//   paint 0 = (251, 149, 149), 1 = (123, 21, 21), 2 = (234, 64, 166), 3 = (106, -64 -> 0, 38).
// Equal bases give LSB 1 too (>=): the first H block with base 2 = base 1 = (51, 85, 85): R2 =
// 0011, G2 = 0101, B2 = 0101 -> byte 2 = 1 0011 010 = 0x9A, byte 3 = 1 0101 1 1 1 = 0xAF; index
// 111 -> d = 64: paint 0 = paint 2 = (115, 149, 149), paint 1 = paint 3 = (-13 -> 0, 21, 21).
TEST(Etc2Decode, HModeDistanceBitFromColourOrder) {
  const Block8 b{0x5A, 0xF2, 0xD0, 0x37, 0x00, 0x0C, 0x00, 0x0A};
  EXPECT_EQ(etc2_block_mode(b.data(), false), Etc2Mode::H);
  const auto t = rgb_block(b);
  EXPECT_EQ(at(t, 0, 0), rgb(251, 149, 149));
  EXPECT_EQ(at(t, 0, 1), rgb(123, 21, 21));
  EXPECT_EQ(at(t, 0, 2), rgb(234, 64, 166));
  EXPECT_EQ(at(t, 0, 3), rgb(106, 0, 38));
  const auto tie = rgb_block({0x1A, 0xF2, 0x9A, 0xAF, 0x00, 0x0C, 0x00, 0x0A});
  EXPECT_EQ(at(tie, 0, 0), rgb(115, 149, 149));
  EXPECT_EQ(at(tie, 0, 1), rgb(0, 21, 21));
  EXPECT_EQ(at(tie, 0, 2), rgb(115, 149, 149));
  EXPECT_EQ(at(tie, 0, 3), rgb(0, 21, 21));
}

// Planar mode. Bytes 41 00 F9 62 | 01 F8 1F D5:
//   bit 63 = 0, RO = bits 62-57 = 100000 = 32, GO1 = bit 56 = 1; bit 55 = 0, GO2 = 54-49 =
//   000000, BO1 = bit 48 = 0; bits 47-45 = 111, BO2 = 44-43 = 11, bit 42 = 0, BO3 = 41-39 = 010;
//   RH1 = 38-34 = 11000, bit 33 = 1, RH2 = bit 32 = 0; GH = 31-25 = 0, BH = 24-19 = 111111,
//   RV = 18-13 = 0, GV = 12-6 = 1111111, BV = 5-0 = 010101.
//   Mode: R = 01000 = 8, dR = 001 -> 9; G = 00000, dG = 000 -> 0; B = 11111 = 31, dB = 001 ->
//   32 > 31 -> planar.
//   O = (extend6(32), extend7(64), extend6(011010 = 26)) = (130, 129, 105);
//   H = (extend6(48), 0, extend6(63)) = (195, 0, 255); V = (0, 255, extend6(21)) = (0, 255, 85).
//   Texel = O + x (H - O) / 4 + y (V - O) / 4 rounded half up:
//   (1,0): R 130 + 16.25 = 146, G 129 - 32.25 = 97, B 105 + 37.5 = 142.5 -> 143 (tie, up)
//   (3,0): R 130 + 48.75 = 179, G 129 - 96.75 = 32, B 105 + 112.5 = 217.5 -> 218
//   (0,3): R 130 - 97.5 = 32.5 -> 33, G 129 + 94.5 = 223.5 -> 224, B 105 - 15 = 90
//   (3,3): R 81.25 -> 81, G 126.75 -> 127, B 202.5 -> 203
TEST(Etc2Decode, PlanarModeRoundsHalfUp) {
  const Block8 b{0x41, 0x00, 0xF9, 0x62, 0x01, 0xF8, 0x1F, 0xD5};
  EXPECT_EQ(etc2_block_mode(b.data(), false), Etc2Mode::Planar);
  const auto t = rgb_block(b);
  EXPECT_EQ(at(t, 0, 0), rgb(130, 129, 105));
  EXPECT_EQ(at(t, 1, 0), rgb(146, 97, 143));
  EXPECT_EQ(at(t, 3, 0), rgb(179, 32, 218));
  EXPECT_EQ(at(t, 0, 3), rgb(33, 224, 90));
  EXPECT_EQ(at(t, 3, 3), rgb(81, 127, 203));
}

// ------------------------------------------------------------------ hand-derived: punch-through

// The differential block above with the opaque bit (33) cleared: byte 3 = 0x55. Opaque = 0:
// modifiers of indices 00 and 10 are 0 and index 10 is (0, 0, 0, 0):
//   (0,0) index 01 +29 -> (255, 62, 53, 255); (1,1) index 11 -29 -> (202, 4, 0, 255);
//   (0,2) index 10 -> (0, 0, 0, 0); (3,3) index 11 -80 -> (118, 0, 0, 255);
//   index 00 -> the base colours: rows 0-1 (231, 33, 24), rows 2-3 (198, 49, 24).
// With the opaque bit set (0x57) the block decodes as RGB8 with alpha 255.
TEST(Etc2Decode, PunchThroughDifferential) {
  const Block8 clear{0xE4, 0x22, 0x18, 0x55, 0x80, 0x24, 0x80, 0x21};
  EXPECT_EQ(etc2_block_mode(clear.data(), true), Etc2Mode::Differential);
  const auto t = a1_block(clear);
  EXPECT_EQ(at(t, 0, 0), rgb(255, 62, 53));
  EXPECT_EQ(at(t, 1, 1), rgb(202, 4, 0));
  EXPECT_EQ(at(t, 0, 2), (Rgba8{0, 0, 0, 0}));
  EXPECT_EQ(at(t, 3, 3), rgb(118, 0, 0));
  EXPECT_EQ(at(t, 3, 0), rgb(231, 33, 24));
  EXPECT_EQ(at(t, 1, 3), rgb(198, 49, 24));
  const Block8 opaque{0xE4, 0x22, 0x18, 0x57, 0x80, 0x24, 0x80, 0x21};
  EXPECT_EQ(a1_block(opaque), rgb_block(opaque));
}

// The T block with the opaque bit cleared (byte 3 = 0xF9): paint colour 2 (texel (2,0)) becomes
// (0, 0, 0, 0), the others keep their colour and alpha 255. The H block likewise (0x35): texel
// (0,2), index 2, transparent. The planar block with the opaque bit cleared (0x60) ignores it.
TEST(Etc2Decode, PunchThroughTHPlanar) {
  const auto t = a1_block({0xF3, 0x2D, 0x84, 0xF9, 0x11, 0x00, 0x10, 0x10});
  EXPECT_EQ(at(t, 0, 0), rgb(187, 34, 221));
  EXPECT_EQ(at(t, 1, 0), rgb(168, 100, 255));
  EXPECT_EQ(at(t, 2, 0), (Rgba8{0, 0, 0, 0}));
  EXPECT_EQ(at(t, 3, 0), rgb(104, 36, 223));
  const auto h = a1_block({0x1A, 0xF2, 0xD0, 0x35, 0x00, 0x0C, 0x00, 0x0A});
  EXPECT_EQ(at(h, 0, 1), rgb(10, 44, 44));
  EXPECT_EQ(at(h, 0, 2), (Rgba8{0, 0, 0, 0}));
  EXPECT_EQ(at(h, 0, 3), rgb(129, 0, 61));
  const Block8 planar_clear{0x41, 0x00, 0xF9, 0x60, 0x01, 0xF8, 0x1F, 0xD5};
  EXPECT_EQ(etc2_block_mode(planar_clear.data(), true), Etc2Mode::Planar);
  EXPECT_EQ(a1_block(planar_clear), rgb_block({0x41, 0x00, 0xF9, 0x62, 0x01, 0xF8, 0x1F, 0xD5}));
}

// ---------------------------------------------------------------------------- hand-derived: EAC

// KDFS's worked example: base 103, table 13 ([-1, -2, -3, -10, 0, 1, 2, 9]), multiplier 2,
// texel b = (0,1) index 3 (bits 44-42 = 011), every other index 0. Bytes 67 2D 0C 00 00 00 00 00.
//   RGBA8 alpha: texel b 103 - 20 = 83; others 103 - 2 = 101.
//   R11: texel b 828 - 160 = 668 (16 bits: 21386, the spec's numbers); others 828 - 16 = 812.
//   Multiplier 0 (byte 1 = 0x0D): alpha = 103 everywhere; R11 texel b 828 - 10 = 818, others 827.
TEST(EacDecode, SpecExampleUnsigned) {
  const Block8 b{0x67, 0x2D, 0x0C, 0, 0, 0, 0, 0};
  uint8_t a[16];
  uint16_t r[16];
  decode_eac_alpha8_block(b.data(), a);
  decode_eac_r11_block(b.data(), r);
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(a[i], i == 4 ? 83 : 101) << i;  // texel (0,1) is out[4]
    EXPECT_EQ(r[i], i == 4 ? 668 : 812) << i;
  }
  EXPECT_EQ(eac11_to_unorm16(668), 21386);
  const Block8 m0{0x67, 0x0D, 0x0C, 0, 0, 0, 0, 0};
  decode_eac_alpha8_block(m0.data(), a);
  decode_eac_r11_block(m0.data(), r);
  for (int i = 0; i < 16; ++i) {
    EXPECT_EQ(a[i], 103) << i;
    EXPECT_EQ(r[i], i == 4 ? 818 : 827) << i;
  }
}

// Signed: base 60, same table, multiplier and indices: texel b 480 - 160 = 320, others 480 - 16
// = 464; multiplier 0: 480 - 10 = 470 (16 bits: 15054, the spec's numbers; the spec's text says
// "base_codeword of 65" but computes with 60), others 479.
TEST(EacDecode, SpecExampleSigned) {
  int16_t s[16];
  decode_eac_r11_signed_block(Block8{60, 0x2D, 0x0C, 0, 0, 0, 0, 0}.data(), s);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(s[i], i == 4 ? 320 : 464) << i;
  decode_eac_r11_signed_block(Block8{60, 0x0D, 0x0C, 0, 0, 0, 0, 0}.data(), s);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(s[i], i == 4 ? 470 : 479) << i;
  EXPECT_EQ(eac11_signed_to_snorm16(470), 15054);
  EXPECT_EQ(eac11_signed_to_snorm16(-470), -15054);
  EXPECT_EQ(eac11_signed_to_snorm16(1023), 32767);
  EXPECT_EQ(eac11_signed_to_snorm16(-1023), -32767);
}

// Clamps and the base -128 rule. Table 0 = [-3, -6, -9, -15, 2, 5, 8, 14]; index field all 7
// (+14) except texel a (index 3, -15) and texel b (index 4, +2): bits 47-45 = 011, 44-42 = 100,
// then 14 x 111: 0x71FFFFFFFFFF -> bytes 71 FF FF FF FF FF.
//   unsigned, base 255, m 15: 2044 + 1680 -> 2047; a 2044 - 1800 = 244; b 2044 + 240 = 2284 -> 2047
//   unsigned, base 0, m 15: a 4 - 1800 -> 0; others 4 + 1680 = 1684, b 4 + 240 = 244
//   alpha, base 250, m 15: 250 + 210 -> 255; a 250 - 225 = 25; b 250 + 30 -> 255
//   signed, base 0x80 (-128 -> -127), m 1: a -1016 - 120 = -1136 -> -1023; b -1016 + 16 = -1000
//   (-1008 if -128 were kept); others -1016 + 112 = -904. Base 0x81 (-127) gives the same.
//   signed, base 127, m 15: others 1016 + 1680 -> 1023; a 1016 - 1800 = -784; b 1016 + 240 -> 1023
TEST(EacDecode, ClampsAndMinus128) {
  const auto with_base = [](int base, int m) {
    return Block8{static_cast<uint8_t>(base), static_cast<uint8_t>(m << 4), 0x71, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
  };
  uint16_t r[16];
  decode_eac_r11_block(with_base(255, 15).data(), r);
  EXPECT_EQ(r[0], 244);
  EXPECT_EQ(r[4], 2047);
  EXPECT_EQ(r[15], 2047);
  decode_eac_r11_block(with_base(0, 15).data(), r);
  EXPECT_EQ(r[0], 0);
  EXPECT_EQ(r[4], 244);
  EXPECT_EQ(r[15], 1684);
  uint8_t a[16];
  decode_eac_alpha8_block(with_base(250, 15).data(), a);
  EXPECT_EQ(a[0], 25);
  EXPECT_EQ(a[4], 255);
  EXPECT_EQ(a[15], 255);
  int16_t s[16], s127[16];
  decode_eac_r11_signed_block(with_base(0x80, 1).data(), s);
  decode_eac_r11_signed_block(with_base(0x81, 1).data(), s127);
  EXPECT_EQ(s[0], -1023);
  EXPECT_EQ(s[4], -1000);
  EXPECT_EQ(s[15], -904);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(s[i], s127[i]) << i;
  decode_eac_r11_signed_block(with_base(127, 15).data(), s);
  EXPECT_EQ(s[0], -784);
  EXPECT_EQ(s[4], 1023);
  EXPECT_EQ(s[15], 1023);
}

// RGBA8 = EAC alpha (bytes 0-7) + ETC2 colour (bytes 8-15): the individual-mode block's colours
// with the spec example's alphas.
TEST(Etc2Decode, Rgba8IsAlphaThenColour) {
  const std::array<uint8_t, 16> b{0x67, 0x2D, 0x0C, 0, 0, 0, 0, 0, 0xA5, 0x3C, 0x0F, 0x1C, 0x00, 0x01, 0x80, 0x01};
  Rgba8 t[16];
  decode_etc2_rgba8_block(b.data(), t);
  EXPECT_EQ(t[0], (Rgba8{162, 43, 0, 101}));
  EXPECT_EQ(t[4], (Rgba8{172, 53, 2, 83}));
  EXPECT_EQ(t[15], (Rgba8{255, 255, 255, 101}));
}

// The 8-bit forms are the nearest 8-bit value, checked against exact rationals for every code.
TEST(EacDecode, EightBitFormsRoundToNearest) {
  for (int v = 0; v <= 2047; ++v) {
    const int e = eac11_to_unorm8(static_cast<uint16_t>(v));
    // |e / 255 - v / 2047| < 1 / 510  <=>  |2047 e - 255 v| * 510 < 255 * 2047
    ASSERT_LT(std::abs(2047 * e - 255 * v) * 2, 2047) << v;
  }
  for (int v = -1023; v <= 1023; ++v) {
    const int e = eac11_signed_to_snorm8(static_cast<int16_t>(v));
    ASSERT_LT(std::abs(1023 * e - 127 * v) * 2, 1023) << v;
  }
  EXPECT_EQ(eac11_to_unorm8(2047), 255);
  EXPECT_EQ(eac11_signed_to_snorm8(-1023), -127);
}

// ------------------------------------------------------------------------------ images, errors

TEST(Etc2Decode, ImageWithPartialEdgeBlocks) {
  // 5 x 6 texels: 2 x 2 blocks; block (1,0) gives only its column 0, block (0,1) its rows 0-1.
  std::vector<uint8_t> blocks;
  const Block8 ind{0xA5, 0x3C, 0x0F, 0x1C, 0x00, 0x01, 0x80, 0x01};
  const Block8 t{0xF3, 0x2D, 0x84, 0xFB, 0x11, 0x00, 0x10, 0x10};
  for (const Block8* b : {&ind, &t, &t, &ind}) blocks.insert(blocks.end(), b->begin(), b->end());
  const auto img = decode_etc_image(EtcFormat::Rgb8, 5, 6, blocks);
  ASSERT_EQ(img.size(), 30u);
  EXPECT_EQ(img[0], rgb(162, 43, 0));             // (0,0): block 0 texel (0,0)
  EXPECT_EQ(img[4], rgb(187, 34, 221));           // (4,0): block 1 texel (0,0), paint 0
  EXPECT_EQ(img[5 * 4 + 1], rgb(168, 100, 255));  // (1,4): block 2 texel (1,0), paint 1
  EXPECT_EQ(img[5 * 5 + 4], rgb(172, 53, 2));     // (4,5): block 3 texel (0,1)
  EXPECT_EQ(img[5 * 3 + 3], rgb(255, 255, 255));  // (3,3): block 0 texel (3,3)
}

TEST(Etc2Decode, BadImagesAreInputErrors) {
  const std::vector<uint8_t> eight(8), sixteen(16);
  EXPECT_THROW(decode_etc_image(EtcFormat::Rgb8, 5, 4, eight), InputError);   // needs 2 blocks
  EXPECT_THROW(decode_etc_image(EtcFormat::Rgba8, 4, 4, eight), InputError);  // needs 16 bytes
  EXPECT_THROW(decode_etc_image(EtcFormat::Rgb8, 0, 4, eight), InputError);
  EXPECT_THROW(decode_etc_image(EtcFormat::R11Signed, 4, 4, eight), InputError);
  EXPECT_THROW(decode_eac11_image(EtcFormat::Rgb8, 4, 4, eight), InputError);
  EXPECT_NO_THROW(decode_eac11_image(EtcFormat::Rg11Signed, 4, 4, sixteen));
  try {
    decode_etc_image(EtcFormat::Rgb8, 5, 4, eight);
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "etc2_rgb8 image 5x4 needs 16 bytes of blocks, got 8");
  }
}

TEST(Etc2Decode, DocsShowTheFormatTable) {
  EXPECT_NE(docs_text("compressed-etc2.md").find(etc_formats_markdown()), std::string::npos)
      << "docs/compressed-etc2.md is stale: paste etc_formats_markdown() under \"Formats\"";
}

// ------------------------------------------------------------------------------ against Mesa

struct MesaCase {
  EtcFormat format;
  GLenum internal_format;
  GLenum read_format;
  GLenum read_type;
};
// Colour formats read back as RGBA bytes; 11-bit formats as 16-bit words, where Mesa keeps the
// spec's bit-replicated 16-bit form (mesa_decoder.hpp).
constexpr MesaCase kMesaCases[] = {
    {EtcFormat::Rgb8, GL_COMPRESSED_RGB8_ETC2, GL_RGBA, GL_UNSIGNED_BYTE},
    {EtcFormat::Srgb8, GL_COMPRESSED_SRGB8_ETC2, GL_RGBA, GL_UNSIGNED_BYTE},
    {EtcFormat::Rgb8A1, GL_COMPRESSED_RGB8_PUNCHTHROUGH_ALPHA1_ETC2, GL_RGBA, GL_UNSIGNED_BYTE},
    {EtcFormat::Srgb8A1, GL_COMPRESSED_SRGB8_PUNCHTHROUGH_ALPHA1_ETC2, GL_RGBA, GL_UNSIGNED_BYTE},
    {EtcFormat::Rgba8, GL_COMPRESSED_RGBA8_ETC2_EAC, GL_RGBA, GL_UNSIGNED_BYTE},
    {EtcFormat::Srgb8Alpha8, GL_COMPRESSED_SRGB8_ALPHA8_ETC2_EAC, GL_RGBA, GL_UNSIGNED_BYTE},
    {EtcFormat::R11, GL_COMPRESSED_R11_EAC, GL_RED, GL_UNSIGNED_SHORT},
    {EtcFormat::R11Signed, GL_COMPRESSED_SIGNED_R11_EAC, GL_RED, GL_SHORT},
    {EtcFormat::Rg11, GL_COMPRESSED_RG11_EAC, GL_RG, GL_UNSIGNED_SHORT},
    {EtcFormat::Rg11Signed, GL_COMPRESSED_SIGNED_RG11_EAC, GL_RG, GL_SHORT},
};

static_assert(kMesaCases[0].format == EtcFormat::Rgb8 && kMesaCases[4].format == EtcFormat::Rgba8);  // used below

void PrintTo(const MesaCase& c, std::ostream* os) { *os << etc_format_info(c.format).name; }

// Our decode of an image in Mesa's read-back layout (bytes as glGetTexImage writes them).
std::vector<uint8_t> model_readback(const MesaCase& c, int w, int h, std::span<const uint8_t> blocks) {
  std::vector<uint8_t> out;
  const EtcFormatInfo& info = etc_format_info(c.format);
  if (!info.eac11) {
    for (const Rgba8& t : decode_etc_image(c.format, w, h, blocks)) out.insert(out.end(), {t.r, t.g, t.b, t.a});
    return out;
  }
  for (int16_t v : decode_eac11_image(c.format, w, h, blocks)) {
    const auto word =
        info.is_signed ? static_cast<uint16_t>(eac11_signed_to_snorm16(v)) : eac11_to_unorm16(static_cast<uint16_t>(v));
    out.push_back(static_cast<uint8_t>(word & 0xFF));  // host order (little-endian x86/ARM)
    out.push_back(static_cast<uint8_t>(word >> 8));
  }
  return out;
}

// What a random-block run hit: ETC2 colour modes (and the punch-through opaque bit), EAC
// multiplier 0 and the signed base -128.
struct Coverage {
  std::array<long, kEtc2ModeCount> modes{};
  long transparent_blocks = 0, flip_blocks = 0, eac_m0 = 0, eac_m_nonzero = 0, eac_minus128 = 0;
};

void count(const EtcFormatInfo& info, const uint8_t* b, Coverage& cov) {
  if (info.eac11 || info.block_bytes == 16) {
    for (int c = 0; c < (info.block_bytes == 16 && !info.eac11 ? 1 : info.channels); ++c) {
      const uint8_t* e = b + 8 * c;
      ((e[1] >> 4) == 0 ? cov.eac_m0 : cov.eac_m_nonzero)++;
      if (e[0] == 0x80) cov.eac_minus128++;
    }
  }
  if (info.eac11) return;
  const uint8_t* colour = info.block_bytes == 16 ? b + 8 : b;
  const bool punch = info.channels == 4 && info.block_bytes == 8;
  const Etc2Mode m = etc2_block_mode(colour, punch);
  cov.modes[static_cast<size_t>(m)]++;
  if (punch && (colour[3] & 2) == 0) cov.transparent_blocks++;
  if ((m == Etc2Mode::Individual || m == Etc2Mode::Differential) && (colour[3] & 1)) cov.flip_blocks++;
}

// One image of random blocks through both decoders; every texel compared. Returns mismatching
// texels (and prints the first few blocks).
long compare_with_mesa(const MesaCase& c, int w, int h, std::mt19937_64& rng, Coverage& cov) {
  const EtcFormatInfo& info = etc_format_info(c.format);
  std::vector<uint8_t> blocks(etc_block_count(w, h) * static_cast<size_t>(info.block_bytes));
  for (auto& v : blocks) v = static_cast<uint8_t>(rng());
  for (size_t i = 0; i < blocks.size(); i += static_cast<size_t>(info.block_bytes)) count(info, &blocks[i], cov);
  std::string why;
  const auto mesa = mesa_decode(c.internal_format, w, h, blocks, c.read_format, c.read_type, &why);
  if (!mesa) {
    ADD_FAILURE() << info.name << ": " << why;
    return 1;
  }
  const auto ours = model_readback(c, w, h, blocks);
  EXPECT_EQ(mesa->size(), ours.size());
  const size_t texel_bytes = ours.size() / (static_cast<size_t>(w) * static_cast<size_t>(h));
  long bad = 0;
  for (size_t t = 0; t < ours.size() / texel_bytes; ++t) {
    bool same = true;
    for (size_t k = 0; k < texel_bytes; ++k) same = same && (*mesa)[t * texel_bytes + k] == ours[t * texel_bytes + k];
    if (same) continue;
    if (bad++ < 5) {
      const int x = static_cast<int>(t % static_cast<size_t>(w)), y = static_cast<int>(t / static_cast<size_t>(w));
      const size_t bi = static_cast<size_t>((y / 4) * ((w + 3) / 4) + x / 4) * static_cast<size_t>(info.block_bytes);
      ADD_FAILURE() << info.name << " " << w << "x" << h << " texel (" << x << "," << y << ") block "
                    << hex(std::span(blocks).subspan(bi, static_cast<size_t>(info.block_bytes))) << ": Mesa "
                    << hex(std::span(*mesa).subspan(t * texel_bytes, texel_bytes)) << ", model "
                    << hex(std::span(ours).subspan(t * texel_bytes, texel_bytes));
    }
  }
  return bad;
}

class Etc2Mesa : public ::testing::TestWithParam<MesaCase> {};

// At least 20,000 random blocks per format in one image of 4 bw - 1 x 4 bh - 2 texels (partial
// blocks on the right and bottom edges), plus small images of every partial shape.
TEST_P(Etc2Mesa, RandomBlocksBitExact) {
  if (!mesa_available()) GTEST_SKIP() << "no OSMesa context";
  const MesaCase& c = GetParam();
  const EtcFormatInfo& info = etc_format_info(c.format);
  std::mt19937_64 rng(0xe7c2'0000u + static_cast<unsigned>(c.format));
  Coverage cov;
  const int n = iterations(20000);
  int bw = 1;
  while (bw * bw < n) ++bw;
  const int bh = (n + bw - 1) / bw;
  long bad = compare_with_mesa(c, 4 * bw - 1, 4 * bh - 2, rng, cov);
  for (int h = 1; h <= 9; ++h)
    for (int w = 1; w <= 9; ++w) bad += compare_with_mesa(c, w, h, rng, cov);
  EXPECT_EQ(bad, 0) << info.name;

  if (info.eac11) {
    EXPECT_GT(cov.eac_m0, 0);
    EXPECT_GT(cov.eac_m_nonzero, 0);
    if (info.is_signed) {
      EXPECT_GT(cov.eac_minus128, 0);
    }
    return;
  }
  const bool punch = info.channels == 4 && info.block_bytes == 8;
  for (int m = 0; m < kEtc2ModeCount; ++m) {
    if (punch && m == static_cast<int>(Etc2Mode::Individual)) {
      EXPECT_EQ(cov.modes[static_cast<size_t>(m)], 0);  // RGB8A1 has no individual mode
      continue;
    }
    EXPECT_GT(cov.modes[static_cast<size_t>(m)], 0) << info.name << " mode " << m;
  }
  EXPECT_GT(cov.flip_blocks, 0);
  if (punch) {
    EXPECT_GT(cov.transparent_blocks, 0);
  }
  if (info.block_bytes == 16) {
    EXPECT_GT(cov.eac_m0, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(AllFormats, Etc2Mesa, ::testing::ValuesIn(kMesaCases),
                         [](const ::testing::TestParamInfo<MesaCase>& p) {
                           return std::string(etc_format_info(p.param.format).name);
                         });

// The hand-derived blocks decode the same in Mesa (the oracle agrees with the spec's worked values).
TEST(Etc2Mesa, HandBlocks) {
  if (!mesa_available()) GTEST_SKIP() << "no OSMesa context";
  const Block8 blocks[] = {
      {0xA5, 0x3C, 0x0F, 0x1C, 0x00, 0x01, 0x80, 0x01}, {0xE4, 0x22, 0x18, 0x57, 0x80, 0x24, 0x80, 0x21},
      {0xF3, 0x2D, 0x84, 0xFB, 0x11, 0x00, 0x10, 0x10}, {0x1A, 0xF2, 0xD0, 0x37, 0x00, 0x0C, 0x00, 0x0A},
      {0x5A, 0xF2, 0xD0, 0x37, 0x00, 0x0C, 0x00, 0x0A}, {0x1A, 0xF2, 0x9A, 0xAF, 0x00, 0x0C, 0x00, 0x0A},
      {0x41, 0x00, 0xF9, 0x62, 0x01, 0xF8, 0x1F, 0xD5}};
  for (const Block8& b : blocks) {
    const auto mesa = mesa_decode(GL_COMPRESSED_RGB8_ETC2, 4, 4, b, GL_RGBA, GL_UNSIGNED_BYTE);
    ASSERT_TRUE(mesa);
    EXPECT_EQ(*mesa, model_readback(kMesaCases[0], 4, 4, b)) << hex(b);
  }
}

// The 8-bit forms against Mesa's 8-bit read-back (GL_UNSIGNED_BYTE / GL_BYTE of R11 and signed
// R11) for every 11-bit value: one block per value v, multiplier 0 and one index everywhere, so
// that every texel decodes to 8 base + 4 + modifier (unsigned) or 8 base + modifier (signed) = v;
// each v in range has such a (base, table, index) (modifiers cover -15..14 around every 8 base).
TEST(Etc2Mesa, EightBitFormsMatchMesaForEvery11BitValue) {
  if (!mesa_available()) GTEST_SKIP() << "no OSMesa context";
  for (const bool is_signed : {false, true}) {
    const int lo = is_signed ? -1023 : 0, hi = is_signed ? 1023 : 2047;
    std::vector<uint8_t> blocks;
    std::vector<int> expected;
    for (int v = lo; v <= hi; ++v) {
      bool found = false;
      for (int base = is_signed ? -127 : 0; base <= (is_signed ? 127 : 255) && !found; ++base)
        for (int table = 0; table < 16 && !found; ++table)
          for (int index = 0; index < 8 && !found; ++index) {
            if (8 * base + (is_signed ? 0 : 4) +
                    kEacModifiers[static_cast<size_t>(table)][static_cast<size_t>(index)] !=
                v)
              continue;
            uint64_t w = (uint64_t{static_cast<uint8_t>(base)} << 56) | (uint64_t(table) << 48);  // multiplier 0
            for (int j = 0; j < 16; ++j) w |= uint64_t(index) << (45 - 3 * j);
            for (int k = 7; k >= 0; --k) blocks.push_back(static_cast<uint8_t>(w >> (8 * k)));
            found = true;
          }
      ASSERT_TRUE(found) << v;
      expected.push_back(v);
    }
    const int n = static_cast<int>(expected.size());
    const auto ours = decode_eac11_image(is_signed ? EtcFormat::R11Signed : EtcFormat::R11, 4 * n, 4, blocks);
    const auto mesa = mesa_decode(is_signed ? GL_COMPRESSED_SIGNED_R11_EAC : GL_COMPRESSED_R11_EAC, 4 * n, 4, blocks,
                                  GL_RED, is_signed ? GL_BYTE : GL_UNSIGNED_BYTE);
    ASSERT_TRUE(mesa);
    for (int i = 0; i < n; ++i) {
      const size_t t = static_cast<size_t>(4 * i + 1 + 4 * n * 2);  // texel (1, 2) of block i
      ASSERT_EQ(ours[t], expected[static_cast<size_t>(i)]);
      const int want = is_signed ? eac11_signed_to_snorm8(static_cast<int16_t>(expected[static_cast<size_t>(i)]))
                                 : eac11_to_unorm8(static_cast<uint16_t>(expected[static_cast<size_t>(i)]));
      const int got = is_signed ? static_cast<int8_t>((*mesa)[t]) : (*mesa)[t];
      EXPECT_EQ(got, want) << (is_signed ? "signed " : "unsigned ") << expected[static_cast<size_t>(i)];
    }
  }
}

// Mesa 22.3.6 read back as GL_RGB returns wrong ETC2 texels (mesa_decoder.hpp); mesa_decode reads
// four components and drops the fourth, so a GL_RGB read-back equals the model's RGB.
TEST(Etc2Mesa, ThreeComponentReadBack) {
  if (!mesa_available()) GTEST_SKIP() << "no OSMesa context";
  std::mt19937_64 rng(0x3c0);
  std::vector<uint8_t> blocks(etc_block_count(13, 7) * 8);
  for (auto& v : blocks) v = static_cast<uint8_t>(rng());
  const auto mesa = mesa_decode(GL_COMPRESSED_RGB8_ETC2, 13, 7, blocks, GL_RGB, GL_UNSIGNED_BYTE);
  ASSERT_TRUE(mesa);
  std::vector<uint8_t> ours;
  for (const Rgba8& t : decode_etc_image(EtcFormat::Rgb8, 13, 7, blocks)) ours.insert(ours.end(), {t.r, t.g, t.b});
  EXPECT_EQ(*mesa, ours);
}

// mesa_decode from several threads at once (one context, serialized by its mutex): every call
// still returns its own image.
TEST(Etc2Mesa, ConcurrentCalls) {
  if (!mesa_available()) GTEST_SKIP() << "no OSMesa context";
  std::atomic<int> bad{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([t, &bad] {
      std::mt19937_64 rng(0xc0c0 + static_cast<unsigned>(t));
      for (int i = 0; i < 10; ++i) {
        std::vector<uint8_t> blocks(etc_block_count(9, 6) * 16);
        for (auto& v : blocks) v = static_cast<uint8_t>(rng());
        const auto mesa = mesa_decode(GL_COMPRESSED_RGBA8_ETC2_EAC, 9, 6, blocks, GL_RGBA, GL_UNSIGNED_BYTE);
        if (!mesa || *mesa != model_readback(kMesaCases[4], 9, 6, blocks)) ++bad;
      }
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(bad.load(), 0);
}

}  // namespace
}  // namespace tfu::test
