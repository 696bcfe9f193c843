// BC1-BC5 and BC7 decoders (cmodel/bc_decode.hpp, cmodel/bc7_decode.hpp): hand-derived blocks per
// format and mode, the BC1/BC4 interpolation variants, the BC7 partition table against the spec's
// anchor tables, and bit-exact comparisons with libsquish 1.15 and Mesa 22.3 (OSMesa) on random blocks
// and images whose sizes are not multiples of 4. docs/compressed-bc.md.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <span>
#include <vector>

#include <gtest/gtest.h>
#include <squish.h>

#include "cmodel/bc7_decode.hpp"
#include "cmodel/bc_decode.hpp"
#include "cmodel/error.hpp"
#include "testbench/iterations.hpp"
#include "testbench/mesa_decoder.hpp"

namespace tfu {
namespace {

using Block8 = std::array<uint8_t, 8>;
using Block16 = std::array<uint8_t, 16>;

// A BC1 colour block: color0, color1 (R5:G6:B5), then the 16 2-bit codes, texel t at bits 2t.
Block8 bc1_block(uint16_t color0, uint16_t color1, const std::array<int, 16>& codes) {
  uint32_t bits = 0;
  for (int t = 0; t < 16; ++t) bits |= static_cast<uint32_t>(codes[t]) << (2 * t);
  return {static_cast<uint8_t>(color0),      static_cast<uint8_t>(color0 >> 8), static_cast<uint8_t>(color1),
          static_cast<uint8_t>(color1 >> 8), static_cast<uint8_t>(bits),        static_cast<uint8_t>(bits >> 8),
          static_cast<uint8_t>(bits >> 16),  static_cast<uint8_t>(bits >> 24)};
}

// A BC4 block: red0, red1, then 16 3-bit codes, texel t at bits 3t of bytes 2..7.
Block8 bc4_block(uint8_t red0, uint8_t red1, const std::array<int, 16>& codes) {
  uint64_t bits = 0;
  for (int t = 0; t < 16; ++t) bits |= static_cast<uint64_t>(codes[t]) << (3 * t);
  Block8 b{red0, red1};
  for (int i = 0; i < 6; ++i) b[2 + i] = static_cast<uint8_t>(bits >> (8 * i));
  return b;
}

TEST(BcDecode, WideningByBitReplication) {
  // Bit replication against round(255 v / (2^n - 1)) (exhaustive): at most 1 LSB apart, and different
  // exactly at v = 3, 7, 24, 28 (5 bits; e.g. v = 3: 24 against 24.68 -> 25) and v = 11..15, 48..52
  // (6 bits; e.g. v = 11: 44 against 44.52 -> 45).
  std::vector<int> differ5, differ6;
  for (int v = 0; v < 32; ++v) {
    const int nearest = (2 * 255 * v + 31) / 62;
    EXPECT_LE(std::abs(bc_widen5(v) - nearest), 1);
    if (bc_widen5(v) != nearest) differ5.push_back(v);
  }
  for (int v = 0; v < 64; ++v) {
    const int nearest = (2 * 255 * v + 63) / 126;
    EXPECT_LE(std::abs(bc_widen6(v) - nearest), 1);
    if (bc_widen6(v) != nearest) differ6.push_back(v);
  }
  EXPECT_EQ(differ5, (std::vector<int>{3, 7, 24, 28}));
  EXPECT_EQ(differ6, (std::vector<int>{11, 12, 13, 14, 15, 48, 49, 50, 51, 52}));
  EXPECT_EQ(bc_widen5(3), 24);
  EXPECT_EQ(bc_widen6(11), 44);
}

// color0 = (31, 63, 31) = 0xffff, color1 = (1, 1, 1) = 0x0821: widened e0 = (255, 255, 255),
// e1 = (8, 4, 8). color0 > color1: 4-colour mode. Texels 0..3 take codes 0..3.
// code 2 = 2/3 e0 + 1/3 e1, code 3 = 1/3 e0 + 2/3 e1 (R, G; B = R):
//   exact     (510 + 8 + 1) / 3 = 173, (510 + 4 + 1) / 3 = 171; (255 + 16 + 1) / 3 = 90, (255 + 8 + 1) / 3 = 88
//   truncate  518 / 3 = 172, 514 / 3 = 171; 271 / 3 = 90, 263 / 3 = 87
//   nvidia    R (2*31 + 1) 22 / 8 = 1386 / 8 = 173; G d = 4 - 255 = -251, d / 4 = -62,
//             (65280 - 62 + 128 - 20080) / 256 = 45266 / 256 = 176;
//             code 3: R (2*1 + 31) 22 / 8 = 726 / 8 = 90; G d = 251, (1024 + 62 + 128 + 20080) / 256 = 83
//   amd       (43*255 + 21*8 + 32) >> 6 = 11165 >> 6 = 174, (10965 + 84 + 32) >> 6 = 173;
//             (43*8 + 21*255 + 32) >> 6 = 5731 >> 6 = 89, (172 + 5355 + 32) >> 6 = 86
TEST(BcDecode, Bc1FourColourModeByRule) {
  const Block8 b = bc1_block(0xffff, 0x0821, {0, 1, 2, 3});
  struct Case {
    Bc1Interpolation rule;
    Rgba8 c2, c3;
  };
  for (const Case& c : {Case{Bc1Interpolation::EXACT, {173, 171, 173, 255}, {90, 88, 90, 255}},
                        Case{Bc1Interpolation::TRUNCATE, {172, 171, 172, 255}, {90, 87, 90, 255}},
                        Case{Bc1Interpolation::NVIDIA, {173, 176, 173, 255}, {90, 83, 90, 255}},
                        Case{Bc1Interpolation::AMD, {174, 173, 174, 255}, {89, 86, 89, 255}}}) {
    SCOPED_TRACE(kBc1InterpolationNames.name(c.rule));
    const BcBlockTexels t = decode_bc1_block(b.data(), true, c.rule);
    EXPECT_EQ(t[0], (Rgba8{255, 255, 255, 255}));
    EXPECT_EQ(t[1], (Rgba8{8, 4, 8, 255}));
    EXPECT_EQ(t[2], c.c2);
    EXPECT_EQ(t[3], c.c3);
    EXPECT_EQ(t[4], t[0]);  // codes 0 beyond texel 3
  }
}

// color0 = 0x0821 < color1 = 0xffff: 3-colour mode in BC1, e0 = (8, 4, 8), e1 = (255, 255, 255).
// code 2 = (e0 + e1) / 2: exact and amd (8 + 255 + 1) >> 1 = 132, (4 + 255 + 1) >> 1 = 130;
// truncate 263 >> 1 = 131, 259 >> 1 = 129; nvidia R (1 + 31) 33 / 8 = 132, G d = 251,
// (1024 + 62 + 128 + 32128) / 256 = 130. code 3: black, alpha 0 (RGBA) or 255 (RGB).
// BC2 and BC3 decode the same colour block in 4-colour mode: code 2 = exact (16 + 255 + 1) / 3 = 90,
// (8 + 255 + 1) / 3 = 88, i.e. the swapped endpoints' code 3 above.
TEST(BcDecode, Bc1ThreeColourModeAndBc2Bc3FourColourOnly) {
  const Block8 b = bc1_block(0x0821, 0xffff, {0, 1, 2, 3});
  EXPECT_EQ(decode_bc1_block(b.data(), true, Bc1Interpolation::EXACT)[2], (Rgba8{132, 130, 132, 255}));
  EXPECT_EQ(decode_bc1_block(b.data(), true, Bc1Interpolation::AMD)[2], (Rgba8{132, 130, 132, 255}));
  EXPECT_EQ(decode_bc1_block(b.data(), true, Bc1Interpolation::TRUNCATE)[2], (Rgba8{131, 129, 131, 255}));
  EXPECT_EQ(decode_bc1_block(b.data(), true, Bc1Interpolation::NVIDIA)[2], (Rgba8{132, 130, 132, 255}));
  EXPECT_EQ(decode_bc1_block(b.data(), true, Bc1Interpolation::EXACT)[3], (Rgba8{0, 0, 0, 0}));
  EXPECT_EQ(decode_bc1_block(b.data(), false, Bc1Interpolation::EXACT)[3], (Rgba8{0, 0, 0, 255}));

  // BC2: alpha nibbles 0, 1, 15 for texels 0..2 (a * 17: 0, 17, 255), then the colour block.
  Block16 bc2{0x10, 0x0f};
  std::copy(b.begin(), b.end(), bc2.begin() + 8);
  const BcBlockTexels t2 = decode_bc2_block(bc2.data(), Bc1Interpolation::EXACT);
  EXPECT_EQ(t2[0], (Rgba8{8, 4, 8, 0}));
  EXPECT_EQ(t2[1], (Rgba8{255, 255, 255, 17}));
  EXPECT_EQ(t2[2], (Rgba8{90, 88, 90, 255}));
  EXPECT_EQ(t2[3], (Rgba8{173, 171, 173, 0}));

  // BC3: alpha block 255, 0 (7-step), codes 0, 1, 2 -> 255, 0, (6*255 + 0 + 3) / 7 = 219 (exact),
  // 1530 / 7 = 218 (truncate).
  const Block8 alpha = bc4_block(255, 0, {0, 1, 2});
  Block16 bc3{};
  std::copy(alpha.begin(), alpha.end(), bc3.begin());
  std::copy(b.begin(), b.end(), bc3.begin() + 8);
  const BcBlockTexels t3 = decode_bc3_block(bc3.data(), kBcRulesSpec);
  EXPECT_EQ(t3[0], (Rgba8{8, 4, 8, 255}));
  EXPECT_EQ(t3[1], (Rgba8{255, 255, 255, 0}));
  EXPECT_EQ(t3[2], (Rgba8{90, 88, 90, 219}));
  EXPECT_EQ(decode_bc3_block(bc3.data(), kBcRulesLibsquish)[2], (Rgba8{90, 87, 90, 218}));
}

// Unsigned, red0 = 200 > red1 = 10 (7-step): code 2 = (6*200 + 10) / 7 = 1210 / 7 = 172.86: exact
// 173 (n = 5 * 1210 = 6050), truncate 172; code 7 = (200 + 6*10) / 7 = 37.14: 37 both.
// red0 = 10 <= red1 = 201 (5-step): code 3 = (3*10 + 2*201) / 5 = 86.4: 86; code 4 = (20 + 603) / 5 =
// 124.6: exact 125, truncate 124; code 5 = (10 + 804) / 5 = 162.8: 163 / 162; code 6 = 0, code 7 = 255.
TEST(BcDecode, Bc4UnsignedByRule) {
  const Block8 a = bc4_block(200, 10, {0, 1, 2, 7});
  EXPECT_EQ(decode_bc4_exact(a.data(), false)[2], 6050);
  EXPECT_EQ(decode_bc4_exact(a.data(), false)[0], 35 * 200);
  const auto ea = decode_bc4_unorm8(a.data(), Bc4Interpolation::EXACT);
  const auto ta = decode_bc4_unorm8(a.data(), Bc4Interpolation::TRUNCATE);
  EXPECT_EQ((std::array<int, 4>{ea[0], ea[1], ea[2], ea[3]}), (std::array<int, 4>{200, 10, 173, 37}));
  EXPECT_EQ((std::array<int, 4>{ta[0], ta[1], ta[2], ta[3]}), (std::array<int, 4>{200, 10, 172, 37}));

  const Block8 b = bc4_block(10, 201, {3, 4, 5, 6, 7});
  EXPECT_EQ(decode_bc4_exact(b.data(), false)[1], 7 * 623);
  EXPECT_EQ(decode_bc4_exact(b.data(), false)[4], 35 * 255);
  const auto eb = decode_bc4_unorm8(b.data(), Bc4Interpolation::EXACT);
  const auto tb = decode_bc4_unorm8(b.data(), Bc4Interpolation::TRUNCATE);
  EXPECT_EQ((std::array<int, 5>{eb[0], eb[1], eb[2], eb[3], eb[4]}), (std::array<int, 5>{86, 125, 163, 0, 255}));
  EXPECT_EQ((std::array<int, 5>{tb[0], tb[1], tb[2], tb[3], tb[4]}), (std::array<int, 5>{86, 124, 162, 0, 255}));
  EXPECT_EQ(decode_bc4_block(b.data(), false, Bc4Interpolation::EXACT)[1], (Rgba8{125, 0, 0, 255}));
}

// Signed, red0 = -128 (0x80), red1 = 100: -128 <= 100, 5-step mode. The spec reads -128 as -127:
//   code 2: (4*-127 + 100) / 5 = -81.6 -> -82 (n = 7 * -408); truncate on the raw byte (4*-128 + 100) / 5
//           = -82.4 -> -82
//   code 3: (3*-127 + 200) / 5 = -36.2 -> -36; truncate (-384 + 200) / 5 = -36.8 -> -36
//   code 4: (2*-127 + 300) / 5 = 9.2 -> 9;     truncate (-256 + 300) / 5 = 8.8 -> 8
//   code 5: (-127 + 400) / 5 = 54.6 -> 55;     truncate (-128 + 400) / 5 = 54.4 -> 54
//   code 0: -127 (truncate: -128, written -127); code 6: -127; code 7: 127.
TEST(BcDecode, Bc4SignedByRule) {
  const Block8 b = bc4_block(0x80, 100, {2, 3, 4, 5, 0, 6, 7, 1});
  EXPECT_EQ(decode_bc4_exact(b.data(), true)[0], -7 * 408);
  EXPECT_EQ(decode_bc4_exact(b.data(), true)[5], -35 * 127);
  const auto e = decode_bc4_snorm8(b.data(), Bc4Interpolation::EXACT);
  const auto t = decode_bc4_snorm8(b.data(), Bc4Interpolation::TRUNCATE);
  EXPECT_EQ((std::vector<int>(e.begin(), e.begin() + 8)), (std::vector<int>{-82, -36, 9, 55, -127, -127, 127, 100}));
  EXPECT_EQ((std::vector<int>(t.begin(), t.begin() + 8)), (std::vector<int>{-82, -36, 8, 54, -127, -127, 127, 100}));
  Block16 bc5{};
  std::copy(b.begin(), b.end(), bc5.begin());
  const Block8 g = bc4_block(10, 20, {});  // green: code 0 everywhere = 10
  std::copy(g.begin(), g.end(), bc5.begin() + 8);
  EXPECT_EQ(decode_bc5_block(bc5.data(), true, Bc4Interpolation::EXACT)[2], (Rgba8{9, 10, 0, 127}));
  EXPECT_EQ(decode_bc5_block(bc5.data(), true, Bc4Interpolation::EXACT)[0],
            (Rgba8{static_cast<uint8_t>(-82), 10, 0, 127}));
}

// ---- BC7 ----

// The fields of a BC7 block, written in the spec's order by a writer of the test's own.
struct Bc7Fields {
  int mode = 0, partition = 0, rotation = 0, index_sel = 0;
  std::array<std::array<std::array<int, 2>, 3>, 4> endpoint{};  // [R, G, B, A][subset][endpoint]
  std::array<std::array<int, 2>, 3> pbit{};                     // [subset][endpoint]; shared: [s][0]
  std::array<int, 16> index1{}, index2{};
};

Block16 encode_bc7(const Bc7Fields& f) {
  Block16 b{};
  int pos = 0;
  const auto put = [&](int v, int bits) {
    for (int i = 0; i < bits; ++i, ++pos)
      if ((v >> i) & 1) b[pos / 8] = static_cast<uint8_t>(b[pos / 8] | (1 << (pos % 8)));
  };
  const Bc7Mode& m = kBc7Modes[f.mode];
  put(1 << f.mode, f.mode + 1);
  put(f.partition, m.partition_bits);
  put(f.rotation, m.rotation_bits);
  put(f.index_sel, m.index_sel_bits);
  for (int c = 0; c < 4; ++c)
    for (int s = 0; s < m.subsets; ++s)
      for (int e = 0; e < 2; ++e) put(f.endpoint[c][s][e], c < 3 ? m.colour_bits : m.alpha_bits);
  for (int s = 0; s < m.subsets; ++s)
    for (int e = 0; e < 2; ++e) put(f.pbit[s][e], m.endpoint_pbits);
  for (int s = 0; s < m.subsets; ++s) put(f.pbit[s][0], m.shared_pbits);
  for (int t = 0; t < 16; ++t) {
    const bool anchor = bc7_anchor(m.subsets, f.partition, bc7_subset(m.subsets, f.partition, t)) == t;
    put(f.index1[t], m.index_bits - (anchor ? 1 : 0));
  }
  for (int t = 0; t < 16 && m.index2_bits; ++t) put(f.index2[t], m.index2_bits - (t == 0 ? 1 : 0));
  EXPECT_EQ(pos, 128) << "mode " << f.mode;
  return b;
}

TEST(Bc7Decode, PartitionTableAgainstTheSpec) {
  // Anchors from the spec's anchor index tables (KDFS "BPTC anchor index values ..."): second subset
  // of 2-subset partitions 0, 16, 17, 18, 34, 35, 63 = 15, 15, 2, 8, 6, 8, 15; 3-subset partitions
  // 0, 1, 2 second/third = 3/15, 3/8, 15/8.
  const std::array<std::pair<int, int>, 7> a2{{{0, 15}, {16, 15}, {17, 2}, {18, 8}, {34, 6}, {35, 8}, {63, 15}}};
  for (const auto& [p, anchor] : a2) EXPECT_EQ(bc7_anchor(2, p, 1), anchor) << p;
  EXPECT_EQ(bc7_anchor(3, 0, 1), 3);
  EXPECT_EQ(bc7_anchor(3, 0, 2), 15);
  EXPECT_EQ(bc7_anchor(3, 1, 1), 3);
  EXPECT_EQ(bc7_anchor(3, 1, 2), 8);
  EXPECT_EQ(bc7_anchor(3, 2, 1), 15);
  EXPECT_EQ(bc7_anchor(3, 2, 2), 8);
  // The spec's 2-subset anchor table (counted by hand, row by row) holds 15 at 32 partitions, 2 at 18,
  // 8 at 10, 6 at 4.
  std::array<int, 16> count{};
  for (int p = 0; p < 64; ++p) ++count[bc7_anchor(2, p, 1)];
  EXPECT_EQ(count[15], 32);
  EXPECT_EQ(count[2], 18);
  EXPECT_EQ(count[8], 10);
  EXPECT_EQ(count[6], 4);
  // Subset sizes read off the spec's partition tables: 2-subset 0 (columns 0-1 | 2-3) 8/8, 2-subset 15
  // (rows 0-2 | row 3) 12/4; 3-subset 0 (rows 0011 0011 0221 2222) 5/5/6,
  // 3-subset 8 (rows 0-1 | row 2 | row 3) 8/4/4.
  const auto sizes = [](int subsets, int p) {
    std::array<int, 3> n{};
    for (int t = 0; t < 16; ++t) ++n[bc7_subset(subsets, p, t)];
    return n;
  };
  EXPECT_EQ(sizes(2, 0), (std::array<int, 3>{8, 8, 0}));
  EXPECT_EQ(sizes(2, 15), (std::array<int, 3>{12, 4, 0}));
  EXPECT_EQ(sizes(3, 0), (std::array<int, 3>{5, 5, 6}));
  EXPECT_EQ(sizes(3, 8), (std::array<int, 3>{8, 4, 4}));
  // Every subset's anchor lies in its subset.
  for (int ns = 2; ns <= 3; ++ns)
    for (int p = 0; p < 64; ++p)
      for (int s = 0; s < ns; ++s) EXPECT_EQ(bc7_subset(ns, p, bc7_anchor(ns, p, s)), s) << ns << " " << p;
}

// One or two texels per mode, the fields chosen by hand and the values derived from the spec:
// endpoint = (field << 1 | p) widened by replicating its top bits, c = ((64 - w) e0 + w e1 + 32) >> 6.
TEST(Bc7Decode, HandDerivedTexelPerMode) {
  {  // mode 0, partition 0 (3 subsets; texel 0 subset 0, texel 2 subset 1, anchors 0, 3, 15).
    Bc7Fields f;
    f.mode = 0;
    f.endpoint[0][0] = {15, 0};  // R of subset 0: 1111p, p = 1 -> 11111 -> 255; 0000p, p = 0 -> 0
    f.pbit[0] = {1, 0};
    f.endpoint[1][1] = {8, 8};  // G of subset 1: 10000 (p 0) = 16 -> 132; 10001 (p 1) = 17 -> 140
    f.pbit[1] = {0, 1};
    f.index1[0] = 3;  // anchor, 2 bits: w = 27: (37*255 + 32) >> 6 = 9467 >> 6 = 147; G, B: e0 = 00001
                      // (the p-bit) = 8, e1 = 0: (37*8 + 32) >> 6 = 5
    f.index1[1] = 7;  // w = 64: 0
    f.index1[2] = 4;  // w = 37: (27*132 + 37*140 + 32) >> 6 = 8776 >> 6 = 137; R, B: 0, 8: 5
    const BcBlockTexels t = decode_bc7_block(encode_bc7(f).data());
    EXPECT_EQ(t[0], (Rgba8{147, 5, 5, 255}));
    EXPECT_EQ(t[1], (Rgba8{0, 0, 0, 255}));
    EXPECT_EQ(t[2], (Rgba8{5, 137, 5, 255}));
  }
  {  // mode 1, partition 0, shared p-bits: subset 0 p = 1, subset 1 p = 0.
    Bc7Fields f;
    f.mode = 1;
    f.endpoint[0][0] = {63, 0};  // 1111111 -> 255; 0000001 -> (1 << 1) | 0 = 2
    f.endpoint[2][1] = {0, 63};  // 0000000 -> 0; 1111110 = 126 -> 252 | 1 = 253
    f.pbit[0] = {1, 1};
    f.index1[1] = 2;   // subset 0, w = 18: (46*255 + 18*2 + 32) >> 6 = 11798 >> 6 = 184; G, B 2, 2: 2
    f.index1[15] = 3;  // subset 1's anchor, 2 bits, w = 27: (27*253 + 32) >> 6 = 6863 >> 6 = 107
    const BcBlockTexels t = decode_bc7_block(encode_bc7(f).data());
    EXPECT_EQ(t[1], (Rgba8{184, 2, 2, 255}));
    EXPECT_EQ(t[15], (Rgba8{0, 0, 107, 255}));
  }
  {  // mode 2, partition 0, subset 2 (texels 9, 15): R 31 -> 255, 16 -> 132, no p-bits.
    Bc7Fields f;
    f.mode = 2;
    f.endpoint[0][2] = {31, 16};
    f.index1[15] = 1;  // anchor, 1 bit, w = 21: (43*255 + 21*132 + 32) >> 6 = 13769 >> 6 = 215
    f.index1[9] = 2;   // w = 43: (21*255 + 43*132 + 32) >> 6 = 11063 >> 6 = 172
    const BcBlockTexels t = decode_bc7_block(encode_bc7(f).data());
    EXPECT_EQ(t[15], (Rgba8{215, 0, 0, 255}));
    EXPECT_EQ(t[9], (Rgba8{172, 0, 0, 255}));
  }
  {  // mode 3, partition 1, subset 0: G 127 (p 1) -> 255, 64 (p 0) -> 10000000 = 128.
    Bc7Fields f;
    f.mode = 3;
    f.partition = 1;
    f.endpoint[1][0] = {127, 64};
    f.pbit[0] = {1, 0};
    f.index1[0] = 1;  // anchor, 1 bit, w = 21: (43*255 + 21*128 + 32) >> 6 = 13685 >> 6 = 213;
                      // R, B: 00000001 = 1, 0: (43 + 32) >> 6 = 1
    const BcBlockTexels t = decode_bc7_block(encode_bc7(f).data());
    EXPECT_EQ(t[0], (Rgba8{1, 213, 1, 255}));
  }
  {  // mode 4, rotation 1 (swap A, R), index selection 1 (colour from the 3-bit index).
    Bc7Fields f;
    f.mode = 4;
    f.rotation = 1;
    f.index_sel = 1;
    f.endpoint[0][0] = {31, 0};  // R 255, 0
    f.endpoint[3][0] = {0, 63};  // A (6 bits) 0, 111111 -> 255
    f.index1[5] = 1;             // alpha w = 21: (21*255 + 32) >> 6 = 84
    f.index2[5] = 5;             // colour w = 46: (18*255 + 32) >> 6 = 72
    const BcBlockTexels t = decode_bc7_block(encode_bc7(f).data());
    EXPECT_EQ(t[5], (Rgba8{84, 0, 0, 72}));  // (R, A) = (72, 84) swapped
  }
  {  // mode 5, rotation 2 (swap A, G), 8-bit alpha.
    Bc7Fields f;
    f.mode = 5;
    f.rotation = 2;
    f.endpoint[1][0] = {127, 0};    // G 255, 0
    f.endpoint[3][0] = {200, 100};  // A 200, 100
    f.index1[3] = 2;                // colour w = 43: (21*255 + 32) >> 6 = 84
    f.index2[3] = 1;                // alpha w = 21: (43*200 + 21*100 + 32) >> 6 = 10732 >> 6 = 167
    const BcBlockTexels t = decode_bc7_block(encode_bc7(f).data());
    EXPECT_EQ(t[3], (Rgba8{0, 167, 0, 84}));
  }
  {  // mode 6, 4-bit indices, p-bits 1 / 0 on every channel.
    Bc7Fields f;
    f.mode = 6;
    f.endpoint[0][0] = {127, 0};  // R 11111111 = 255, 0
    f.endpoint[3][0] = {127, 0};  // A 255, 0
    f.pbit[0] = {1, 0};           // G 0000000p = 1, 0
    f.index1[6] = 8;              // w = 34: (30*255 + 32) >> 6 = 7682 >> 6 = 120; G (30 + 32) >> 6 = 0
    f.index1[0] = 7;              // anchor, 3 bits, w = 30: (34*255 + 32) >> 6 = 8702 >> 6 = 135; G 1
    const BcBlockTexels t = decode_bc7_block(encode_bc7(f).data());
    EXPECT_EQ(t[6], (Rgba8{120, 0, 0, 120}));
    EXPECT_EQ(t[0], (Rgba8{135, 1, 1, 135}));
  }
  {  // mode 7, partition 0, subset 1 (texel 2): 5-bit fields + p-bit = 6 bits.
    Bc7Fields f;
    f.mode = 7;
    f.endpoint[3][1] = {31, 0};   // A 111111 = 63 -> 255; 0
    f.endpoint[0][1] = {16, 16};  // R 100001 = 33 -> 132 | 2 = 134; 100000 = 32 -> 130
    f.pbit[1] = {1, 0};
    f.index1[2] = 2;  // w = 43: R (21*134 + 43*130 + 32) >> 6 = 8436 >> 6 = 131; A (21*255 + 32) >> 6 = 84;
                      // G, B: 000001 = 1 -> 4, 0: (21*4 + 32) >> 6 = 1
    const BcBlockTexels t = decode_bc7_block(encode_bc7(f).data());
    EXPECT_EQ(t[2], (Rgba8{131, 1, 1, 84}));
  }
  // Reserved mode (byte 0 == 0): transparent black.
  Block16 reserved{};
  reserved[5] = 0xff;
  EXPECT_EQ(bc7_mode(reserved.data()), -1);
  for (const Rgba8& t : decode_bc7_block(reserved.data())) EXPECT_EQ(t, (Rgba8{0, 0, 0, 0}));
}

// ---- Images and bad input ----

TEST(BcDecode, ImageWithPartialEdgeBlocks) {
  // 5 x 6 texels: 2 x 2 BC4 blocks; block (bx, by) all code 0 with red0 = 10 bx + 100 by.
  std::vector<uint8_t> blocks;
  blocks.reserve(4 * sizeof(Block8));  // (GCC 12 -O2 warns of a false stringop-overflow in insert otherwise)
  for (int by = 0; by < 2; ++by)
    for (int bx = 0; bx < 2; ++bx) {
      const Block8 b = bc4_block(static_cast<uint8_t>(10 * bx + 100 * by), 0, {});
      blocks.insert(blocks.end(), b.begin(), b.end());
    }
  const std::vector<Rgba8> img = decode_bc_image(BcFormat::BC4_UNORM, 5, 6, blocks);
  ASSERT_EQ(img.size(), 30u);
  EXPECT_EQ(img[0].r, 0);
  EXPECT_EQ(img[4].r, 10);           // (4, 0): block (1, 0)
  EXPECT_EQ(img[5 * 4].r, 100);      // (0, 4): block (0, 1)
  EXPECT_EQ(img[5 * 5 + 4].r, 110);  // (4, 5): block (1, 1)
  EXPECT_EQ(bc_image_bytes(BcFormat::BC7, 5, 6), 64u);
  EXPECT_THROW(decode_bc_image(BcFormat::BC4_UNORM, 5, 6, std::span(blocks).first(24)), InputError);
  EXPECT_THROW(decode_bc_image(BcFormat::BC4_UNORM, 0, 6, blocks), InputError);
  try {
    decode_bc_image(BcFormat::BC3, 5, 6, blocks);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "bc3 image of 5 x 6 texels needs 64 bytes of blocks, got 32");
  }
}

// ---- libsquish 1.15 ----

std::vector<uint8_t> random_bytes(std::mt19937_64& rng, size_t n) {
  std::vector<uint8_t> v(n);
  for (uint8_t& b : v) b = static_cast<uint8_t>(rng());
  return v;
}

// Random blocks with a bias toward the interesting cases: half the BC1 colour blocks have
// color0 <= color1 (3-colour mode), half the unsigned BC4 blocks red0 <= red1 (5-step mode); every
// 16th block has equal endpoints (3-colour / 5-step with a zero-length segment), and every 16th signed
// block has red0 = -127, red1 = -128 (the case the spec leaves undefined; both Mesa and the truncate
// rule compare the raw bytes).
void shape_block(std::vector<uint8_t>& b, size_t offset, BcFormat f, size_t i) {
  const auto swap_if = [&](size_t a, size_t n, bool want_le) {
    uint32_t x = 0, y = 0;
    for (size_t k = 0; k < n; ++k) {
      x |= static_cast<uint32_t>(b[offset + a + k]) << (8 * k);
      y |= static_cast<uint32_t>(b[offset + a + n + k]) << (8 * k);
    }
    if ((x <= y) != want_le)
      for (size_t k = 0; k < n; ++k) std::swap(b[offset + a + k], b[offset + a + n + k]);
  };
  const auto equal = [&](size_t a, size_t n) {
    for (size_t k = 0; k < n; ++k) b[offset + a + n + k] = b[offset + a + k];
  };
  const auto signed_edge = [&](size_t a) {
    b[offset + a] = 0x81;
    b[offset + a + 1] = 0x80;
  };
  const bool le = (i & 1) != 0, same = i % 16 == 5;
  switch (f) {
    case BcFormat::BC1_RGB:
    case BcFormat::BC1_RGBA: same ? equal(0, 2) : swap_if(0, 2, le); break;
    case BcFormat::BC2: same ? equal(8, 2) : swap_if(8, 2, le); break;
    case BcFormat::BC3:
      same ? equal(0, 1) : swap_if(0, 1, le);
      same ? equal(8, 2) : swap_if(8, 2, (i & 2) != 0);
      break;
    case BcFormat::BC4_UNORM: same ? equal(0, 1) : swap_if(0, 1, le); break;
    case BcFormat::BC5_UNORM:
      same ? equal(0, 1) : swap_if(0, 1, le);
      same ? equal(8, 1) : swap_if(8, 1, (i & 2) != 0);
      break;
    case BcFormat::BC4_SNORM:
      if (same) equal(0, 1);
      if (i % 16 == 9) signed_edge(0);
      break;
    case BcFormat::BC5_SNORM:
      if (same) equal(0, 1), equal(8, 1);
      if (i % 16 == 9) signed_edge(0), signed_edge(8);
      break;
    default: break;
  }
}

// Every rule and every pair of 5-bit and of 6-bit fields (exhaustive): exact is the nearest integer
// to the spec's formula on the widened endpoints (|3 c - (2 e0 + e1)| <= 1, |2 c - (e0 + e1)| <= 1
// with halves up), truncate its floor; nvidia and amd stay within 3 % of |e0 - e1| + 1 LSB of it (the
// D3D tolerance R. Geldreich's rgbcx allows for BC1), and every rule gives e0 for e0 = e1.
TEST(BcDecode, Bc1RulesOnEveryEndpointPair) {
  for (int bits : {5, 6}) {
    for (int v0 = 0; v0 < (1 << bits); ++v0) {
      for (int v1 = 0; v1 < (1 << bits); ++v1) {
        // The fields in B (5 bits) or G (6 bits); red 1 in color0 (4-colour) or in color1 (3-colour)
        // sets the mode whatever the fields' order.
        const int shift = bits == 5 ? 0 : 5;
        const int e0 = bits == 5 ? bc_widen5(v0) : bc_widen6(v0), e1 = bits == 5 ? bc_widen5(v1) : bc_widen6(v1);
        const auto colour = [&](Bc1Interpolation rule, bool four, int code) {
          const Block8 b = bc1_block(static_cast<uint16_t>((v0 << shift) | (four ? 1 << 11 : 0)),
                                     static_cast<uint16_t>((v1 << shift) | (four ? 0 : 1 << 11)), {code});
          const Rgba8 t = decode_bc1_block(b.data(), true, rule)[0];
          return bits == 5 ? t.b : t.g;
        };
        const int exact = colour(Bc1Interpolation::EXACT, true, 2), half = colour(Bc1Interpolation::EXACT, false, 2);
        ASSERT_LE(std::abs(3 * exact - (2 * e0 + e1)), 1) << bits << " " << v0 << " " << v1;
        ASSERT_EQ(half, (e0 + e1 + 1) / 2);
        ASSERT_EQ(colour(Bc1Interpolation::TRUNCATE, true, 2), (2 * e0 + e1) / 3);
        ASSERT_EQ(colour(Bc1Interpolation::TRUNCATE, true, 3), (e0 + 2 * e1) / 3);
        ASSERT_EQ(colour(Bc1Interpolation::TRUNCATE, false, 2), (e0 + e1) / 2);
        for (Bc1Interpolation rule : {Bc1Interpolation::NVIDIA, Bc1Interpolation::AMD}) {
          const int tolerance = 3 * std::abs(e0 - e1) / 100 + 1;
          ASSERT_LE(std::abs(colour(rule, true, 2) - exact), tolerance) << bits << " " << v0 << " " << v1;
          ASSERT_LE(std::abs(colour(rule, false, 2) - half), tolerance) << bits << " " << v0 << " " << v1;
        }
        if (v0 == v1) {
          for (Bc1Interpolation rule :
               {Bc1Interpolation::EXACT, Bc1Interpolation::TRUNCATE, Bc1Interpolation::NVIDIA, Bc1Interpolation::AMD}) {
            ASSERT_EQ(colour(rule, true, 3), e0);
          }
        }
      }
    }
  }
}

// Every (red0, red1, code), unsigned and signed (exhaustive): decode_bc4_exact is 35 times the spec's
// value in units of 1/255 (1/127), the exact 8-bit result is its nearest integer (never a tie), and
// truncate is the C quotient on the raw bytes.
TEST(BcDecode, Bc4RulesOnEveryEndpointPair) {
  for (int is_signed = 0; is_signed < 2; ++is_signed) {
    for (int r0 = 0; r0 < 256; ++r0) {
      for (int r1 = 0; r1 < 256; ++r1) {
        const Block8 b = bc4_block(static_cast<uint8_t>(r0), static_cast<uint8_t>(r1), {0, 1, 2, 3, 4, 5, 6, 7});
        const int s0 = is_signed ? static_cast<int8_t>(r0) : r0, s1 = is_signed ? static_cast<int8_t>(r1) : r1;
        const int a0 = std::max(s0, -127), a1 = std::max(s1, -127), full = is_signed ? 127 : 255;
        const std::array<int32_t, 16> n = decode_bc4_exact(b.data(), is_signed != 0);
        const std::array<int, 16> ex = [&] {
          std::array<int, 16> v{};
          if (is_signed) {
            const auto x = decode_bc4_snorm8(b.data(), Bc4Interpolation::EXACT);
            std::copy(x.begin(), x.end(), v.begin());
          } else {
            const auto x = decode_bc4_unorm8(b.data(), Bc4Interpolation::EXACT);
            std::copy(x.begin(), x.end(), v.begin());
          }
          return v;
        }();
        for (int code = 0; code < 8; ++code) {
          // The spec's value times 35 * full: numerator over 7 (8 values) or 5 (6 values).
          int64_t want;
          int truncated;
          if (code < 2) {
            want = 35 * (code == 0 ? a0 : a1);
            truncated = code == 0 ? s0 : s1;
          } else if (s0 > s1) {
            want = 5 * ((8 - code) * a0 + (code - 1) * a1);
            truncated = ((8 - code) * s0 + (code - 1) * s1) / 7;
          } else if (code < 6) {
            want = 7 * ((6 - code) * a0 + (code - 1) * a1);
            truncated = ((6 - code) * s0 + (code - 1) * s1) / 5;
          } else {
            want = 35 * (code == 6 ? -full * is_signed : full);
            truncated = code == 6 ? -full * is_signed : full;
          }
          ASSERT_EQ(n[code], want) << is_signed << " " << r0 << " " << r1 << " " << code;
          ASSERT_NE(std::abs(want) % 35 * 2, 35);  // never a tie
          ASSERT_LE(std::abs(35 * ex[code] - want), 17);
          const int t = is_signed ? decode_bc4_snorm8(b.data(), Bc4Interpolation::TRUNCATE)[code]
                                  : decode_bc4_unorm8(b.data(), Bc4Interpolation::TRUNCATE)[code];
          ASSERT_EQ(t, std::max(truncated, -127));
        }
      }
    }
  }
}

TEST(BcDecode, BitExactWithLibsquish) {
  // libsquish 1.15 follows the truncate rules for colour and alpha (kBcRulesLibsquish). Its kBc4 and
  // kBc5 decompression does not decode RGTC (squish.cpp Decompress has no BC4/BC5 branch: the block
  // is decoded as a BC1 colour block, see Bc4IsNotDecodedByLibsquish), so BC4 is checked through
  // kDxt5's alpha, which is the same block and rule.
  std::mt19937_64 rng(0x5bc1);
  const int n = tfu::test::iterations(20000);
  struct Case {
    BcFormat format;
    int flags;
  };
  for (const Case& c : {Case{BcFormat::BC1_RGBA, squish::kDxt1}, Case{BcFormat::BC2, squish::kDxt3},
                        Case{BcFormat::BC3, squish::kDxt5}}) {
    SCOPED_TRACE(kBcFormatNames.name(c.format));
    const size_t bytes = static_cast<size_t>(bc_block_bytes(c.format));
    std::vector<uint8_t> blocks = random_bytes(rng, bytes * static_cast<size_t>(n));
    int mismatches = 0;
    for (int i = 0; i < n; ++i) {
      const size_t off = bytes * static_cast<size_t>(i);
      shape_block(blocks, off, c.format, static_cast<size_t>(i));
      std::array<uint8_t, 64> ref{};
      squish::Decompress(ref.data(), blocks.data() + off, c.flags);
      const BcBlockTexels ours = decode_bc_block(c.format, blocks.data() + off, kBcRulesLibsquish);
      for (int t = 0; t < 16; ++t)
        if (ours[t] != (Rgba8{ref[4 * t], ref[4 * t + 1], ref[4 * t + 2], ref[4 * t + 3]}) && mismatches++ < 3)
          ADD_FAILURE() << "block " << i << " texel " << t;
    }
    EXPECT_EQ(mismatches, 0);
    // Whole images whose sizes are not multiples of 4, through DecompressImage.
    for (const auto& [w, h] : {std::pair{13, 7}, std::pair{1, 1}, std::pair{6, 10}}) {
      const size_t nb = bc_image_bytes(c.format, w, h);
      const std::span<const uint8_t> img_blocks(blocks.data(), nb);
      std::vector<uint8_t> ref(static_cast<size_t>(4 * w * h));
      squish::DecompressImage(ref.data(), w, h, img_blocks.data(), c.flags);
      const std::vector<Rgba8> ours = decode_bc_image(c.format, w, h, img_blocks, kBcRulesLibsquish);
      for (size_t p = 0; p < ours.size(); ++p)
        ASSERT_EQ(ours[p], (Rgba8{ref[4 * p], ref[4 * p + 1], ref[4 * p + 2], ref[4 * p + 3]})) << w << "x" << h;
    }
  }
  // BC4 / BC5 channels as the alpha block of a DXT5 block (colour half zero).
  int mismatches = 0;
  for (int i = 0; i < n; ++i) {
    std::vector<uint8_t> b = random_bytes(rng, 16);
    shape_block(b, 0, BcFormat::BC5_UNORM, static_cast<size_t>(i));
    const BcBlockTexels ours = decode_bc5_block(b.data(), false, Bc4Interpolation::TRUNCATE);
    for (int half = 0; half < 2; ++half) {
      std::array<uint8_t, 16> dxt5{};
      std::copy(b.begin() + 8 * half, b.begin() + 8 * half + 8, dxt5.begin());
      std::array<uint8_t, 64> ref{};
      squish::Decompress(ref.data(), dxt5.data(), squish::kDxt5);
      for (int t = 0; t < 16; ++t)
        if ((half == 0 ? ours[t].r : ours[t].g) != ref[4 * t + 3] && mismatches++ < 3)
          ADD_FAILURE() << "block " << i << " half " << half << " texel " << t;
    }
  }
  EXPECT_EQ(mismatches, 0);
}

// libsquish 1.15's Decompress(kBc4) decodes the 8 bytes as a BC1 colour block in 4-colour mode
// (alpha 255), not as BC4. The block red0 = 200, red1 = 10, codes 1 everywhere shows it: BC4 gives red
// 10 at every texel; libsquish gives colours from color0 = 0x0ac8, color1 = 0x9249 (bytes 2, 3).
TEST(BcDecode, Bc4IsNotDecodedByLibsquish) {
  const Block8 b = bc4_block(200, 10, {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1});
  std::array<uint8_t, 64> ref{};
  squish::Decompress(ref.data(), b.data(), squish::kBc4);
  Block16 as_bc2{};
  std::copy(b.begin(), b.end(), as_bc2.begin() + 8);
  const BcBlockTexels colour = decode_bc2_block(as_bc2.data(), Bc1Interpolation::TRUNCATE);
  for (int t = 0; t < 16; ++t)
    EXPECT_EQ((Rgba8{ref[4 * t], ref[4 * t + 1], ref[4 * t + 2], ref[4 * t + 3]}),
              (Rgba8{colour[t].r, colour[t].g, colour[t].b, 255}));
  EXPECT_EQ(decode_bc4_unorm8(b.data(), Bc4Interpolation::TRUNCATE)[0], 10);
  EXPECT_NE(ref[0], 10);
}

// ---- Mesa 22.3 (OSMesa softpipe) ----

constexpr uint32_t kGlRgba = 0x1908, kGlUnsignedByte = 0x1401, kGlByte = 0x1400;

uint32_t gl_internal_format(BcFormat f) {
  switch (f) {
    case BcFormat::BC1_RGB: return 0x83F0;    // GL_COMPRESSED_RGB_S3TC_DXT1_EXT
    case BcFormat::BC1_RGBA: return 0x83F1;   // GL_COMPRESSED_RGBA_S3TC_DXT1_EXT
    case BcFormat::BC2: return 0x83F2;        // GL_COMPRESSED_RGBA_S3TC_DXT3_EXT
    case BcFormat::BC3: return 0x83F3;        // GL_COMPRESSED_RGBA_S3TC_DXT5_EXT
    case BcFormat::BC4_UNORM: return 0x8DBB;  // GL_COMPRESSED_RED_RGTC1
    case BcFormat::BC4_SNORM: return 0x8DBC;  // GL_COMPRESSED_SIGNED_RED_RGTC1
    case BcFormat::BC5_UNORM: return 0x8DBD;  // GL_COMPRESSED_RG_RGTC2
    case BcFormat::BC5_SNORM: return 0x8DBE;  // GL_COMPRESSED_SIGNED_RG_RGTC2
    case BcFormat::BC7: return 0x8E8C;        // GL_COMPRESSED_RGBA_BPTC_UNORM
  }
  return 0;
}

bool is_signed(BcFormat f) { return f == BcFormat::BC4_SNORM || f == BcFormat::BC5_SNORM; }

// Mismatching texels between our decode (rules) and Mesa's of one image; the first few reported.
int compare_with_mesa(BcFormat f, int w, int h, std::span<const uint8_t> blocks, BcRules rules) {
  std::string why;
  const auto ref = tfu::test::mesa_decode(gl_internal_format(f), w, h, blocks, kGlRgba,
                                          is_signed(f) ? kGlByte : kGlUnsignedByte, &why);
  if (!ref) {
    ADD_FAILURE() << "Mesa refused " << kBcFormatNames.name(f) << ": " << why;
    return -1;
  }
  const std::vector<Rgba8> ours = decode_bc_image(f, w, h, blocks, rules);
  int mismatches = 0;
  for (size_t p = 0; p < ours.size(); ++p) {
    const Rgba8 m{(*ref)[4 * p], (*ref)[4 * p + 1], (*ref)[4 * p + 2], (*ref)[4 * p + 3]};
    if (ours[p] != m && mismatches++ < 3) {
      const size_t x = p % static_cast<size_t>(w), y = p / static_cast<size_t>(w);
      const size_t block = (y / 4) * static_cast<size_t>((w + 3) / 4) + x / 4;
      std::string hex;
      for (int k = 0; k < bc_block_bytes(f); ++k)
        hex += fmt::format("{:02x}", blocks[block * static_cast<size_t>(bc_block_bytes(f)) + static_cast<size_t>(k)]);
      ADD_FAILURE() << kBcFormatNames.name(f) << " " << w << "x" << h << " texel (" << x << ", " << y << ") block "
                    << hex << ": ours " << int(ours[p].r) << "," << int(ours[p].g) << "," << int(ours[p].b) << ","
                    << int(ours[p].a) << " mesa " << int(m.r) << "," << int(m.g) << "," << int(m.b) << "," << int(m.a);
    }
  }
  return mismatches;
}

// One test per format (each well under a second): 20,000 random blocks as a 400 x 200-texel image
// (100 x 50 blocks), then images whose sizes are not multiples of 4, in Mesa's rules (kBcRulesMesa).
class BcMesa : public ::testing::TestWithParam<BcFormat> {};

TEST_P(BcMesa, BitExactWithMesa) {
  if (!tfu::test::mesa_available()) GTEST_SKIP() << "no OSMesa context";
  const BcFormat f = GetParam();
  std::mt19937_64 rng(0x3e5a + static_cast<uint64_t>(f));
  const int blocks_x = 100, blocks_y = tfu::test::iterations(20000) / blocks_x;
  const size_t bytes = static_cast<size_t>(bc_block_bytes(f));
  std::vector<uint8_t> blocks = random_bytes(rng, bytes * static_cast<size_t>(blocks_x * blocks_y));
  for (size_t i = 0; i < blocks.size() / bytes; ++i) shape_block(blocks, i * bytes, f, i);
  EXPECT_EQ(compare_with_mesa(f, 4 * blocks_x, 4 * blocks_y, blocks, kBcRulesMesa), 0);
  for (const auto& [w, h] : {std::pair{13, 7}, std::pair{1, 1}, std::pair{2, 5}, std::pair{30, 17}})
    EXPECT_EQ(compare_with_mesa(f, w, h, std::span(blocks).first(bc_image_bytes(f, w, h)), kBcRulesMesa), 0);
}

INSTANTIATE_TEST_SUITE_P(S3tcRgtc, BcMesa,
                         ::testing::Values(BcFormat::BC1_RGB, BcFormat::BC1_RGBA, BcFormat::BC2, BcFormat::BC3,
                                           BcFormat::BC4_UNORM, BcFormat::BC4_SNORM, BcFormat::BC5_UNORM,
                                           BcFormat::BC5_SNORM),
                         [](const ::testing::TestParamInfo<BcFormat>& i) {
                           return std::string(kBcFormatNames.name(i.param));
                         });

// Where Mesa (and libsquish) and the spec disagree, on the hand-derived blocks above: Mesa truncates
// the BC1 thirds (block ffff2108 e4000000: code 2 red 172, spec 173; code 3 green 87, spec 88) and
// interpolates signed BC4 on the raw byte -128 with truncation toward zero (block 80 64 + codes
// 2, 3, 4, 5: Mesa -82, -36, 8, 54, spec -82, -36, 9, 55).
TEST(BcDecode, MesaDisagreesWithTheSpecAsDocumented) {
  if (!tfu::test::mesa_available()) GTEST_SKIP() << "no OSMesa context";
  const Block8 bc1 = bc1_block(0xffff, 0x0821, {0, 1, 2, 3});
  const auto m1 = tfu::test::mesa_decode(gl_internal_format(BcFormat::BC1_RGBA), 4, 1, bc1, kGlRgba, kGlUnsignedByte);
  ASSERT_TRUE(m1);
  EXPECT_EQ((std::vector<int>{(*m1)[8], (*m1)[9], (*m1)[12], (*m1)[13]}), (std::vector<int>{172, 171, 90, 87}));
  const BcBlockTexels spec1 = decode_bc1_block(bc1.data(), true, Bc1Interpolation::EXACT);
  EXPECT_EQ((std::vector<int>{spec1[2].r, spec1[2].g, spec1[3].r, spec1[3].g}), (std::vector<int>{173, 171, 90, 88}));

  const Block8 bc4 = bc4_block(0x80, 100, {2, 3, 4, 5});
  const auto m4 = tfu::test::mesa_decode(gl_internal_format(BcFormat::BC4_SNORM), 4, 1, bc4, kGlRgba, kGlByte);
  ASSERT_TRUE(m4);
  std::vector<int> mesa4;
  for (int t = 0; t < 4; ++t) mesa4.push_back(static_cast<int8_t>((*m4)[4 * t]));
  EXPECT_EQ(mesa4, (std::vector<int>{-82, -36, 8, 54}));
  const auto spec4 = decode_bc4_snorm8(bc4.data(), Bc4Interpolation::EXACT);
  EXPECT_EQ((std::vector<int>(spec4.begin(), spec4.begin() + 4)), (std::vector<int>{-82, -36, 9, 55}));
}

TEST(Bc7Decode, BitExactWithMesa) {
  if (!tfu::test::mesa_available()) GTEST_SKIP() << "no OSMesa context";
  std::mt19937_64 rng(0xb7);
  // Random 128-bit blocks with the mode field set to mode i % 8 (the other 128 - mode - 1 bits random),
  // so every mode is hit equally; every 97th block has the reserved mode byte 0 == 0.
  const int blocks_x = 100, blocks_y = tfu::test::iterations(20000) / blocks_x;
  std::vector<uint8_t> blocks = random_bytes(rng, 16 * static_cast<size_t>(blocks_x * blocks_y));
  std::array<int, 9> hits{};
  for (size_t i = 0; i < blocks.size() / 16; ++i) {
    uint8_t& b0 = blocks[16 * i];
    const int mode = static_cast<int>(i % 8);
    b0 = static_cast<uint8_t>(i % 97 == 0 ? 0 : ((b0 << (mode + 1)) | (1 << mode)) & 0xff);
    ++hits[static_cast<size_t>(bc7_mode(&b0) + 1)];
  }
  for (size_t m = 0; m < hits.size(); ++m) EXPECT_GT(hits[m], 0) << "mode " << static_cast<int>(m) - 1;
  EXPECT_EQ(compare_with_mesa(BcFormat::BC7, 4 * blocks_x, 4 * blocks_y, blocks, kBcRulesSpec), 0);
  // Unshaped random 128-bit blocks: the mode field as it falls (mode m with probability 2^-(m+1),
  // the reserved byte 0 == 0 with 1/256).
  const std::vector<uint8_t> raw = random_bytes(rng, 16 * static_cast<size_t>(blocks_x * blocks_y));
  EXPECT_EQ(compare_with_mesa(BcFormat::BC7, 4 * blocks_x, 4 * blocks_y, raw, kBcRulesSpec), 0);
  for (const auto& [w, h] : {std::pair{13, 7}, std::pair{1, 1}, std::pair{2, 5}, std::pair{30, 17}})
    EXPECT_EQ(compare_with_mesa(BcFormat::BC7, w, h, std::span(blocks).first(bc_image_bytes(BcFormat::BC7, w, h)),
                                kBcRulesSpec),
              0);
}

}  // namespace
}  // namespace tfu
