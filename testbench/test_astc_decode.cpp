// ASTC LDR 2D decoder (cmodel/astc_decode.hpp; docs/compressed-astc.md) bit-exact against ARM's
// libastcenc 4.2.0 (Debian libastcenc-dev: astcenc_decompress_image to ASTCENC_TYPE_U8 with
// ASTCENC_PRF_LDR or ASTCENC_PRF_LDR_SRGB): random legal blocks packed field by field from
// parameters drawn within the spec's legal ranges (every footprint, partition count, dual plane and
// endpoint mode counted), random 128-bit blocks and legal blocks with flipped bits, every UNORM16
// void-extent colour, hand-made edge cases (void extent, each illegal encoding, HDR endpoint modes,
// one block per partition count), and astcenc-encoded images of sizes that are not a multiple of
// the footprint. The block configuration the decoder reads is checked against the packer's
// parameters and against astcenc_get_block_info.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "cmodel/astc_decode.hpp"
#include "cmodel/astc_tables.hpp"
#include "testbench/astc_reference.hpp"
#include "testbench/iterations.hpp"

namespace tfu {
namespace {

using Block = std::array<uint8_t, kAstcBlockBytes>;

using test::astcenc_ctx;
using test::astcenc_decode_image;
using test::is_hdr_cem;
constexpr astcenc_swizzle kIdentity = test::kAstcencIdentity;

// Texels where libastcenc gives (254, 0, 254, 254) and the decoder the error colour
// (test::is_known_hdr_partition_difference), counted over the whole run.
int g_hdr_partition_differences = 0;

std::string fmt_byte(uint8_t b) {
  char s[3];
  std::snprintf(s, sizeof s, "%02x", b);
  return s;
}

// Both decoders on a list of blocks (laid out 64 blocks to a row); returns the number of blocks
// that differ and reports the first few.
int compare_blocks(const std::vector<Block>& blocks, int bw, int bh, bool srgb) {
  constexpr int kRow = 64;
  const int n = static_cast<int>(blocks.size());
  const int rows = (n + kRow - 1) / kRow;
  std::vector<uint8_t> data(static_cast<size_t>(rows * kRow) * kAstcBlockBytes, 0);  // padding: reserved, error
  for (int i = 0; i < n; ++i)
    std::memcpy(&data[static_cast<size_t>(i) * kAstcBlockBytes], blocks[static_cast<size_t>(i)].data(),
                kAstcBlockBytes);
  const int width = kRow * bw, height = rows * bh;
  const std::vector<Rgba8> ref = astcenc_decode_image(data.data(), data.size(), width, height, bw, bh, srgb);
  int bad = 0;
  std::array<Rgba8, kAstcMaxTexels> mine{};
  for (int i = 0; i < n; ++i) {
    decode_astc_block(blocks[static_cast<size_t>(i)].data(), bw, bh, srgb, mine.data());
    const int x0 = (i % kRow) * bw, y0 = (i / kRow) * bh;
    for (int t = 0; t < bw * bh; ++t) {
      const Rgba8 r = ref[static_cast<size_t>((y0 + t / bw) * width + x0 + t % bw)];
      const Rgba8 m = mine[static_cast<size_t>(t)];
      if (r == m) continue;
      if (test::is_known_hdr_partition_difference(blocks[static_cast<size_t>(i)].data(), bw, bh, srgb, r, m)) {
        ++g_hdr_partition_differences;
        continue;
      }
      if (++bad <= 5) {
        std::string hex;
        for (uint8_t b : blocks[static_cast<size_t>(i)]) hex += fmt_byte(b);
        ADD_FAILURE() << bw << "x" << bh << (srgb ? " srgb" : " linear") << " block " << hex << " texel " << t
                      << ": astcenc " << int(r.r) << "," << int(r.g) << "," << int(r.b) << "," << int(r.a)
                      << " decoder " << int(m.r) << "," << int(m.g) << "," << int(m.b) << "," << int(m.a) << " ("
                      << astc_illegal_name(astc_block_config(blocks[static_cast<size_t>(i)].data(), bw, bh).illegal)
                      << ")";
      }
      break;
    }
  }
  return bad;
}

// ---- A packer of legal blocks (test side, from the spec's tables read in the encoding direction) --

struct Bits {
  uint64_t lo = 0, hi = 0;
  void set(int pos, int n, uint32_t v) {
    for (int i = 0; i < n; ++i, ++pos) {
      const uint64_t bit = (v >> i) & 1u;
      uint64_t& w = pos < 64 ? lo : hi;
      const int s = pos & 63;
      w = (w & ~(uint64_t{1} << s)) | (bit << s);
    }
  }
  Block bytes() const {
    Block b{};
    for (int i = 0; i < 8; ++i) {
      b[static_cast<size_t>(i)] = static_cast<uint8_t>(lo >> (8 * i));
      b[static_cast<size_t>(8 + i)] = static_cast<uint8_t>(hi >> (8 * i));
    }
    return b;
  }
};

struct LegalParams {
  int w = 0, h = 0, rho = 0, p = 0;
  bool dual = false;
  int partitions = 1, seed = 0, ccs = 0;
  std::array<int, 4> cem{};
};

// The ten 2D block-mode rows (KDFS Table "ASTC 2D block mode layout"): grid ranges and the packing.
struct ModeRow {
  int w_lo, w_hi, h_lo, h_hi;
  bool plain_only;  // row 10: no dual plane, P = 0
};
constexpr std::array<ModeRow, 10> kModeRows{{{4, 7, 2, 5, false},
                                             {8, 11, 2, 5, false},
                                             {2, 5, 8, 11, false},
                                             {2, 5, 6, 7, false},
                                             {2, 3, 2, 5, false},
                                             {12, 12, 2, 5, false},
                                             {2, 5, 12, 12, false},
                                             {6, 6, 10, 10, false},
                                             {10, 10, 6, 6, false},
                                             {6, 9, 6, 9, true}}};

uint32_t pack_mode(int row, const LegalParams& q) {
  const uint32_t r0 = q.rho & 1, r1 = (q.rho >> 1) & 1, r2 = (q.rho >> 2) & 1;
  const uint32_t dp = q.dual ? 1u : 0u, p = static_cast<uint32_t>(q.p);
  const uint32_t hi = dp << 10 | p << 9, w = static_cast<uint32_t>(q.w), h = static_cast<uint32_t>(q.h);
  const uint32_t lo12 = r0 << 4 | r2 << 1 | r1;        // rows 1-5: rho2 rho1 in bits 1, 0
  const uint32_t lo610 = r0 << 4 | r2 << 3 | r1 << 2;  // rows 6-10: in bits 3, 2
  switch (row) {
    case 0: return hi | (w - 4) << 7 | (h - 2) << 5 | 0u << 2 | lo12;
    case 1: return hi | (w - 8) << 7 | (h - 2) << 5 | 1u << 2 | lo12;
    case 2: return hi | (h - 8) << 7 | (w - 2) << 5 | 2u << 2 | lo12;
    case 3: return hi | 0u << 8 | (h - 6) << 7 | (w - 2) << 5 | 3u << 2 | lo12;
    case 4: return hi | 1u << 8 | (w - 2) << 7 | (h - 2) << 5 | 3u << 2 | lo12;
    case 5: return hi | 0u << 7 | (h - 2) << 5 | lo610;
    case 6: return hi | 1u << 7 | (w - 2) << 5 | lo610;
    case 7: return hi | 3u << 7 | 0u << 5 | lo610;
    case 8: return hi | 3u << 7 | 1u << 5 | lo610;
    default: return (h - 6) << 9 | 2u << 7 | (w - 6) << 5 | lo610;
  }
}

constexpr std::array<std::array<int, 3>, 4> kLdrCemsByClass{{{0, 1, -1}, {4, 5, 6}, {8, 9, 10}, {12, 13, -1}}};

// Draws a legal block for footprint bw x bh (rejection over the legality rules of KDFS "Illegal
// Encodings"); hdr_rate is the chance that an endpoint mode is drawn from all 16 instead of the
// ten LDR ones.
std::pair<Block, LegalParams> random_legal_block(std::mt19937_64& rng, int bw, int bh, double hdr_rate) {
  std::uniform_real_distribution<double> u01(0, 1);
  const auto pick = [&rng](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  for (;;) {
    LegalParams q;
    const int row = pick(0, 9);
    const ModeRow& mr = kModeRows[static_cast<size_t>(row)];
    if (mr.w_lo > bw || mr.h_lo > bh) continue;
    q.w = pick(mr.w_lo, std::min(mr.w_hi, bw));
    q.h = pick(mr.h_lo, std::min(mr.h_hi, bh));
    q.rho = pick(2, 7);
    q.p = mr.plain_only ? 0 : pick(0, 1);
    q.dual = !mr.plain_only && pick(0, 2) == 0;
    const int planes = q.dual ? 2 : 1, count = q.w * q.h * planes;
    const int wrange = astc::weight_range_index(q.rho, q.p);
    if (count > 64) continue;
    const int wbits = astc::ise_sequence_bits(count, wrange);
    if (wbits < 24 || wbits > 96) continue;
    q.partitions = pick(1, q.dual ? 3 : 4);
    int values = 0, config = 17, extra = 0;
    const auto draw_cem = [&](int cls) {
      if (u01(rng) < hdr_rate) return cls * 4 + pick(0, 3);
      const auto& l = kLdrCemsByClass[static_cast<size_t>(cls)];
      return l[static_cast<size_t>(pick(0, l[2] < 0 ? 1 : 2))];
    };
    bool same = true;
    if (q.partitions == 1) {
      q.cem[0] = draw_cem(pick(0, 3));
    } else {
      q.seed = pick(0, 1023);
      same = pick(0, 1) == 0;
      if (same) {
        const int cem = draw_cem(pick(0, 3));
        for (int i = 0; i < q.partitions; ++i) q.cem[static_cast<size_t>(i)] = cem;
        config = 29;
      } else {
        const int base = pick(0, 2);
        for (int i = 0; i < q.partitions; ++i) q.cem[static_cast<size_t>(i)] = draw_cem(base + pick(0, 1));
        extra = 3 * q.partitions - 4;
        config = 25 + 3 * q.partitions;
      }
    }
    if (q.dual) config += 2, q.ccs = pick(0, 3);
    for (int i = 0; i < q.partitions; ++i) values += 2 * (q.cem[static_cast<size_t>(i)] / 4 + 1);
    if (values > 18) continue;
    if (128 - config - wbits < (13 * values + 4) / 5) continue;

    Bits b{rng(), rng()};  // weights, endpoints and unused bits random
    b.set(0, 11, pack_mode(row, q));
    b.set(11, 2, static_cast<uint32_t>(q.partitions - 1));
    if (q.partitions == 1) {
      b.set(13, 4, static_cast<uint32_t>(q.cem[0]));
    } else {
      b.set(13, 10, static_cast<uint32_t>(q.seed));
      if (same) {
        b.set(23, 6, static_cast<uint32_t>(q.cem[0]) << 2);
      } else {
        int minc = 3;
        for (int i = 0; i < q.partitions; ++i) minc = std::min(minc, q.cem[static_cast<size_t>(i)] / 4);
        // A selector of base class `minc` (all partitions of one class c > 0 may use base c - 1 or c).
        uint32_t combined = 0;
        for (int i = 0; i < q.partitions; ++i) {
          combined |= static_cast<uint32_t>(q.cem[static_cast<size_t>(i)] / 4 - minc) << i;
          combined |= static_cast<uint32_t>(q.cem[static_cast<size_t>(i)] & 3) << (q.partitions + 2 * i);
        }
        if (minc == 3) {  // every partition class 3: base class 2, all class bits 1
          for (int i = 0; i < q.partitions; ++i) combined |= 1u << i;
          minc = 2;
        }
        b.set(23, 2, static_cast<uint32_t>(minc + 1));
        b.set(25, 4, combined & 0xFu);
        b.set(128 - wbits - extra, extra, combined >> 4);
      }
    }
    if (q.dual) b.set(128 - wbits - extra - 2, 2, static_cast<uint32_t>(q.ccs));
    return {b.bytes(), q};
  }
}

// The configuration the decoder reads equals the packer's parameters and libastcenc's block info.
void check_config(const Block& blk, const LegalParams& q, int bw, int bh) {
  const AstcBlockConfig c = astc_block_config(blk.data(), bw, bh);
  ASSERT_EQ(c.illegal, AstcIllegal::None);
  ASSERT_FALSE(c.void_extent);
  ASSERT_EQ(c.grid_w, q.w);
  ASSERT_EQ(c.grid_h, q.h);
  ASSERT_EQ(c.weight_range, astc::weight_range_index(q.rho, q.p));
  ASSERT_EQ(c.dual_plane, q.dual);
  ASSERT_EQ(c.partitions, q.partitions);
  for (int i = 0; i < q.partitions; ++i) ASSERT_EQ(c.cem[static_cast<size_t>(i)], q.cem[static_cast<size_t>(i)]);
  if (q.partitions > 1) {
    ASSERT_EQ(c.partition_seed, q.seed);
  }
  if (q.dual) {
    ASSERT_EQ(c.ccs, q.ccs);
  }

  astcenc_block_info info{};
  ASSERT_EQ(astcenc_get_block_info(astcenc_ctx(bw, bh, false, false), blk.data(), &info), ASTCENC_SUCCESS);
  ASSERT_FALSE(info.is_error_block);
  ASSERT_EQ(static_cast<int>(info.weight_x), c.grid_w);
  ASSERT_EQ(static_cast<int>(info.weight_y), c.grid_h);
  ASSERT_EQ(static_cast<int>(info.weight_level_count), astc::kIseRanges[static_cast<size_t>(c.weight_range)].levels);
  ASSERT_EQ(static_cast<int>(info.color_level_count), astc::kIseRanges[static_cast<size_t>(c.endpoint_range)].levels);
  ASSERT_EQ(info.is_dual_plane_block, c.dual_plane);
  ASSERT_EQ(static_cast<int>(info.partition_count), c.partitions);
  for (int i = 0; i < c.partitions; ++i)
    ASSERT_EQ(static_cast<int>(info.color_endpoint_modes[i]), c.cem[static_cast<size_t>(i)]);
  if (c.partitions > 1) {
    ASSERT_EQ(static_cast<int>(info.partition_index), c.partition_seed);
  }
  if (c.dual_plane) {
    ASSERT_EQ(static_cast<int>(info.dual_plane_component), c.ccs);
  }
}

// ---- (1) random legal blocks -----------------------------------------------------------------------

TEST(AstcDecode, RandomLegalBlocksMatchLibastcenc) {
  const int total = tfu::test::iterations(105000);
  const int per = (total + static_cast<int>(kAstcFootprints.size()) - 1) / static_cast<int>(kAstcFootprints.size());
  std::mt19937_64 rng(0xA57C'0001);
  std::array<int, 5> by_partitions{};
  std::array<int, 16> by_cem{};
  std::array<int, 4> by_ccs{};
  std::array<int, astc::kIseRangeCount> by_weight_range{}, by_endpoint_range{};
  std::set<std::tuple<int, int, int, int>> grids;  // footprint w, h, grid W, H
  int dual = 0, legal = 0, mismatched = 0;
  for (const AstcFootprint f : kAstcFootprints) {
    std::vector<Block> blocks;
    for (int i = 0; i < per; ++i) {
      // About one block in ten draws an endpoint mode from all 16 (HDR ones decode to the error
      // colour for their partition); the rest only LDR modes.
      const auto [blk, q] = random_legal_block(rng, f.w, f.h, i % 10 == 0 ? 1.0 : 0.0);
      if (i % 8 == 0) check_config(blk, q, f.w, f.h);  // astcenc_get_block_info is slow: one in eight
      ++by_partitions[static_cast<size_t>(q.partitions)];
      for (int p = 0; p < q.partitions; ++p) ++by_cem[static_cast<size_t>(q.cem[static_cast<size_t>(p)])];
      if (q.dual) ++dual, ++by_ccs[static_cast<size_t>(q.ccs)];
      const AstcBlockConfig c = astc_block_config(blk.data(), f.w, f.h);
      ++by_weight_range[static_cast<size_t>(c.weight_range)];
      ++by_endpoint_range[static_cast<size_t>(c.endpoint_range)];
      grids.insert({f.w, f.h, q.w, q.h});
      blocks.push_back(blk);
    }
    legal += static_cast<int>(blocks.size());
    // Half the blocks in each operation mode.
    const std::vector<Block> a(blocks.begin(), blocks.begin() + per / 2), b(blocks.begin() + per / 2, blocks.end());
    mismatched += compare_blocks(a, f.w, f.h, false);
    mismatched += compare_blocks(b, f.w, f.h, true);
  }
  std::printf(
      "ASTC legal blocks: %d, HDR-partition texels where libastcenc gives 254,0,254,254: %d (partitions 1-4: %d %d %d "
      "%d; dual plane %d; CCS %d %d %d %d)\nCEM 0..15:",
      legal, g_hdr_partition_differences, by_partitions[1], by_partitions[2], by_partitions[3], by_partitions[4], dual,
      by_ccs[0], by_ccs[1], by_ccs[2], by_ccs[3]);
  for (int n : by_cem) std::printf(" %d", n);
  std::printf("\n");
  EXPECT_EQ(mismatched, 0);
  EXPECT_GE(legal, tfu::test::iterations(100000));
  for (int p = 1; p <= 4; ++p) EXPECT_GT(by_partitions[static_cast<size_t>(p)], 0) << p;
  for (int cem = 0; cem < 16; ++cem) EXPECT_GT(by_cem[static_cast<size_t>(cem)], 0) << cem;
  for (int ccs = 0; ccs < 4; ++ccs) EXPECT_GT(by_ccs[static_cast<size_t>(ccs)], 0) << ccs;
  for (int r = 0; r < astc::kWeightRangeCount; ++r) EXPECT_GT(by_weight_range[static_cast<size_t>(r)], 0) << r;
  // The rarer cases below need the full count (a sanitizer build's tenth leaves some grids with an
  // expectation of a few blocks): every endpoint range and every weight grid of every footprint that
  // some weight range and plane count make legal.
  if (tfu::test::kIterationDivisor != 1) return;
  for (int r = astc::kMinEndpointRange; r < astc::kIseRangeCount; ++r)
    EXPECT_GT(by_endpoint_range[static_cast<size_t>(r)], 0) << r;
  int grid_count = 0;
  for (const AstcFootprint f : kAstcFootprints)
    for (const ModeRow& mr : kModeRows)
      for (int w = mr.w_lo; w <= std::min(mr.w_hi, f.w); ++w)
        for (int h = mr.h_lo; h <= std::min(mr.h_hi, f.h); ++h) {
          bool legal_somehow = false;
          for (int planes = 1; planes <= (mr.plain_only ? 1 : 2); ++planes)
            for (int r = 0; r < (mr.plain_only ? 6 : astc::kWeightRangeCount); ++r) {
              const int n = w * h * planes, bits = astc::ise_sequence_bits(n, r);
              legal_somehow |= n <= 64 && bits >= 24 && bits <= 96;
            }
          if (!legal_somehow) continue;
          ++grid_count;
          EXPECT_TRUE(grids.count({f.w, f.h, w, h})) << f.w << "x" << f.h << " grid " << w << "x" << h;
        }
  std::printf("ASTC weight grids: %d (footprint, grid) pairs, all hit\n", grid_count);
}

// ---- (2) arbitrary blocks --------------------------------------------------------------------------

TEST(AstcDecode, RandomArbitraryAndMutatedBlocksMatchLibastcenc) {
  const int per = tfu::test::iterations(3000);
  std::mt19937_64 rng(0xA57C'0002);
  std::map<AstcIllegal, int> kinds;
  int mismatched = 0, total = 0;
  for (const AstcFootprint f : kAstcFootprints) {
    for (const bool srgb : {false, true}) {
      std::vector<Block> blocks;
      for (int i = 0; i < per; ++i) {
        Bits b{rng(), rng()};
        if (i % 2 == 1) {  // a legal block with one to three bits flipped
          const Block legal = random_legal_block(rng, f.w, f.h, 0.1).first;
          std::memcpy(&b.lo, legal.data(), 8);
          std::memcpy(&b.hi, legal.data() + 8, 8);
          for (int k = std::uniform_int_distribution<int>(1, 3)(rng); k > 0; --k) {
            const int pos = std::uniform_int_distribution<int>(0, 127)(rng);
            (pos < 64 ? b.lo : b.hi) ^= uint64_t{1} << (pos & 63);
          }
        } else if (i % 4 == 2) {  // a void extent with random colour, coordinates, D and reserved bits
          b.lo = (b.lo & ~uint64_t{0x1FF}) | 0x1FC;
        }
        blocks.push_back(b.bytes());
        ++kinds[astc_block_config(blocks.back().data(), f.w, f.h).illegal];
      }
      total += static_cast<int>(blocks.size());
      mismatched += compare_blocks(blocks, f.w, f.h, srgb);
    }
  }
  std::printf("ASTC arbitrary blocks: %d;", total);
  for (const auto& [k, n] : kinds) std::printf(" %s %d;", astc_illegal_name(k), n);
  std::printf("\n");
  EXPECT_EQ(mismatched, 0);
  for (int k = 0; k <= static_cast<int>(AstcIllegal::TooFewEndpointBits); ++k)
    EXPECT_GT(kinds[static_cast<AstcIllegal>(k)], 0) << astc_illegal_name(static_cast<AstcIllegal>(k));
}

// Every UNORM16 void-extent value in each channel, both modes: the decode_float16 -> UNORM8 rule
// (linear) and the top-8-bits rule (sRGB) over their whole input range.
TEST(AstcDecode, EveryVoidExtentValueMatchesLibastcenc) {
  std::mt19937_64 rng(0xA57C'0003);
  std::vector<Block> blocks;
  for (uint32_t v = 0; v < 65536; ++v) {
    Bits b{0xFFFF'FFFF'FFFF'FDFCull, rng()};  // LDR void extent, reserved bits 1, coordinates all ones
    b.set(64 + 16 * static_cast<int>(v % 4), 16, v);
    blocks.push_back(b.bytes());
  }
  EXPECT_EQ(compare_blocks(blocks, 4, 4, false), 0);
  EXPECT_EQ(compare_blocks(blocks, 4, 4, true), 0);
}

// The figures docs/compressed-astc.md quotes about the decode modes, from the decoder's own
// conversion (checked against libastcenc above on every UNORM16 value).
TEST(AstcDecode, DecodeModeFiguresOfTheDoc) {
  // decode_unorm8 (the top 8 bits) against decode_float16 + rounding: 17,716 of 65,536 differ, by
  // one either way.
  int unorm8_differs = 0;
  for (uint32_t c = 0; c < 65536; ++c) {
    const int d = int(astc_unorm16_to_unorm8(c)) - int(c >> 8);
    ASSERT_LE(std::abs(d), 1) << c;
    unorm8_differs += d != 0;
  }
  EXPECT_EQ(unorm8_differs, 17716);
  EXPECT_EQ(astc_unorm16_to_unorm8(129), 1);
  // sRGB alpha, KDFS 1.3 (bit replication, decode_float16) against KDFS 1.4.0 (e << 8 | 0x80, top 8
  // bits = 8-bit interpolation): 299,988 of 256 x 256 x 65 cases differ, by 1.
  int alpha_differs = 0;
  for (int e0 = 0; e0 < 256; ++e0)
    for (int e1 = 0; e1 < 256; ++e1)
      for (int i = 0; i <= 64; ++i) {
        const auto c13 = static_cast<uint32_t>((e0 * 257 * (64 - i) + e1 * 257 * i + 32) >> 6);
        const int kdfs13 = astc_unorm16_to_unorm8(c13);
        const int kdfs14 = (((e0 << 8) | 0x80) * (64 - i) + ((e1 << 8) | 0x80) * i + 32) >> 14;
        ASSERT_EQ(kdfs14, (e0 * (64 - i) + e1 * i + 32) >> 6);
        ASSERT_LE(std::abs(kdfs13 - kdfs14), 1);
        alpha_differs += kdfs13 != kdfs14;
      }
  EXPECT_EQ(alpha_differs, 299988);
  EXPECT_EQ(astc_unorm16_to_unorm8((12 * 257 * 56 + 32) >> 6), 10);  // alpha endpoints 0, 12, weight 56
  EXPECT_EQ((12 * 56 + 32) >> 6, 11);
}

// ---- (3) hand-made edge cases ----------------------------------------------------------------------

std::vector<Rgba8> decode(const Block& b, int bw, int bh, bool srgb) {
  std::vector<Rgba8> out(static_cast<size_t>(bw * bh));
  decode_astc_block(b.data(), bw, bh, srgb, out.data());
  return out;
}

TEST(AstcDecode, VoidExtentBlocks) {
  // Colour R 0x8000, G 0x7FFF, B 0x0003, A 0xFFFF; extent s 0..100, t 5..4000 (legal: min < max).
  Bits b;
  b.set(0, 12, 0xDFC);  // void extent, D = 0, reserved bits 10, 11 = 1
  b.set(12, 13, 0), b.set(25, 13, 100), b.set(38, 13, 5), b.set(51, 13, 4000);
  b.set(64, 16, 0x8000), b.set(80, 16, 0x7FFF), b.set(96, 16, 0x0003), b.set(112, 16, 0xFFFF);
  EXPECT_EQ(astc_block_config(b.bytes().data(), 6, 6).illegal, AstcIllegal::None);
  // Linear, decode_float16: 0x8000 -> 0.5 -> floor(127.5 + 0.5) = 128; 0x7FFF -> FP16 0x7FF0 / 65536
  // (round toward zero) -> 127.94 -> 127; 3 -> 3 / 65536 -> 0; 0xFFFF -> 1.0 -> 255.
  for (const Rgba8 t : decode(b.bytes(), 6, 6, false)) EXPECT_EQ(t, (Rgba8{128, 127, 0, 255}));
  // sRGB: the top 8 bits.
  for (const Rgba8 t : decode(b.bytes(), 6, 6, true)) EXPECT_EQ(t, (Rgba8{128, 127, 0, 255}));
  EXPECT_EQ(compare_blocks({b.bytes()}, 6, 6, false), 0);
  EXPECT_EQ(compare_blocks({b.bytes()}, 6, 6, true), 0);

  Bits bad = b;  // min t >= max t
  bad.set(38, 13, 4000);
  EXPECT_EQ(astc_block_config(bad.bytes().data(), 6, 6).illegal, AstcIllegal::VoidExtentCoordinates);
  bad = b;  // reserved bit 11 clear
  bad.set(11, 1, 0);
  EXPECT_EQ(astc_block_config(bad.bytes().data(), 6, 6).illegal, AstcIllegal::VoidExtentReservedBits);
  bad = b;  // HDR (FP16) void extent in an LDR operation mode
  bad.set(9, 1, 1);
  EXPECT_EQ(astc_block_config(bad.bytes().data(), 6, 6).illegal, AstcIllegal::VoidExtentHdr);
}

// One hand-packed block per illegal encoding: the reason, the all-error-colour result and libastcenc.
TEST(AstcDecode, IllegalEncodingsGiveTheErrorColor) {
  struct Case {
    const char* what;
    int bw, bh;
    uint32_t mode;  // bits 0..10
    int partitions;
    uint32_t cem_bits;  // bits 13.. (one partition: the 4-bit CEM; else seed + 6-bit field)
    AstcIllegal why;
  };
  // Modes: row 1 (W = B + 4, H = A + 2), rho = 5 (0..4 quints) unless noted.
  const auto row1 = [](int w, int h, int rho, int p, bool dual) {
    return static_cast<uint32_t>((dual ? 1 : 0) << 10 | p << 9 | (w - 4) << 7 | (h - 2) << 5 | (rho & 1) << 4 |
                                 ((rho >> 2) & 1) << 1 | ((rho >> 1) & 1));
  };
  const std::vector<Case> cases{
      {"reserved block mode (bits [3:0] = 0000)", 8, 8, 0x5F0, 1, 0, AstcIllegal::ReservedBlockMode},
      {"reserved block mode (1 1 1 x x x x 0 0)", 8, 8, 0x1C4, 1, 0, AstcIllegal::ReservedBlockMode},
      {"7 x 5 grid of 0..7 weights, 105 bits", 8, 8, row1(7, 5, 7, 0, false), 1, 0, AstcIllegal::WeightBitsOutOfRange},
      {"4 x 2 grid of 0..1 weights, 8 bits", 8, 8, row1(4, 2, 2, 0, false), 1, 0, AstcIllegal::WeightBitsOutOfRange},
      {"7 x 5 grid on a 6 x 6 footprint", 6, 6, row1(7, 5, 3, 0, false), 1, 0, AstcIllegal::GridExceedsFootprint},
      {"dual plane with 4 partitions", 8, 8, row1(4, 4, 3, 0, true), 4, 0, AstcIllegal::DualPlaneFourPartitions},
      {"4 partitions of RGBA (32 values)", 8, 8, row1(4, 4, 3, 0, false), 4, (12u << 2) << 10,
       AstcIllegal::TooManyEndpointValues},
      {"RGBA beside 96 weight bits (15 bits for 8 values)", 12, 12, row1(6, 4, 4, 1, false), 1, 12,
       AstcIllegal::TooFewEndpointBits},
  };
  for (const Case& k : cases) {
    Bits b{0x0123'4567'89AB'CDEFull, 0xFEDC'BA98'7654'3210ull};
    b.set(0, 11, k.mode);
    b.set(11, 2, static_cast<uint32_t>(k.partitions - 1));
    if (k.partitions == 1)
      b.set(13, 4, k.cem_bits);
    else
      b.set(13, 16, k.cem_bits);
    const Block blk = b.bytes();
    EXPECT_EQ(astc_block_config(blk.data(), k.bw, k.bh).illegal, k.why) << k.what;
    for (const bool srgb : {false, true}) {
      for (const Rgba8 t : decode(blk, k.bw, k.bh, srgb)) ASSERT_EQ(t, kAstcErrorColor) << k.what;
      EXPECT_EQ(compare_blocks({blk}, k.bw, k.bh, srgb), 0) << k.what;
    }
  }
  // More than 64 weights: only row 10 (W, H = 6..9) reaches it in one plane, 9 x 9 = 81 here.
  Bits b{0x0123'4567'89AB'CDEFull, 0xFEDC'BA98'7654'3210ull};
  b.set(0, 11, 3u << 9 | 2u << 7 | 3u << 5 | 1u << 2);  // row 10, W = H = 9, rho = 2 (0..1)
  b.set(11, 2, 0);
  EXPECT_EQ(astc_block_config(b.bytes().data(), 10, 10).illegal, AstcIllegal::TooManyWeights);
  for (const Rgba8 t : decode(b.bytes(), 10, 10, false)) ASSERT_EQ(t, kAstcErrorColor);
  EXPECT_EQ(compare_blocks({b.bytes()}, 10, 10, false), 0);
}

// HDR endpoint modes in an LDR operation mode: the whole block with one partition; only the HDR
// partition's texels with two partitions of an LDR and an HDR mode.
TEST(AstcDecode, HdrEndpointModesGiveTheErrorColorPerPartition) {
  std::mt19937_64 rng(0xA57C'0004);
  const int differences_before = g_hdr_partition_differences;
  for (const int cem : {2, 3, 7, 11, 14, 15}) {
    Block blk{};
    for (;;) {
      auto [candidate, q] = random_legal_block(rng, 8, 8, 1.0);
      if (q.partitions == 1 && q.cem[0] == cem) {
        blk = candidate;
        break;
      }
    }
    for (const Rgba8 t : decode(blk, 8, 8, false)) ASSERT_EQ(t, kAstcErrorColor) << cem;
    EXPECT_EQ(compare_blocks({blk}, 8, 8, false), 0);
    EXPECT_EQ(compare_blocks({blk}, 8, 8, true), 0);
  }
  // Two partitions, one with an LDR and one with an HDR endpoint mode.
  int found = 0;
  for (int tries = 0; found < 20 && tries < 200000; ++tries) {
    auto [blk, q] = random_legal_block(rng, 8, 8, 1.0);
    if (q.partitions != 2 || is_hdr_cem(q.cem[0]) == is_hdr_cem(q.cem[1])) continue;
    // Blocks whose pattern gives both partitions texels: some texels error colour, not all (an LDR
    // texel equal to magenta is possible but not with these seeds).
    int error_texels = 0;
    for (const Rgba8 x : decode(blk, 8, 8, false)) error_texels += x == kAstcErrorColor;
    if (error_texels == 0 || error_texels == 64) continue;
    ++found;
    EXPECT_EQ(compare_blocks({blk}, 8, 8, false), 0) << q.cem[0] << " " << q.cem[1];
    EXPECT_EQ(compare_blocks({blk}, 8, 8, true), 0) << q.cem[0] << " " << q.cem[1];
  }
  EXPECT_EQ(found, 20);
  // libastcenc's (254, 0, 254, 254) for those texels in the linear profile (is_known_hdr_partition_difference).
  EXPECT_GT(g_hdr_partition_differences, differences_before);
}

TEST(AstcDecode, OneBlockPerPartitionCount) {
  std::mt19937_64 rng(0xA57C'0005);
  for (int parts = 1; parts <= 4; ++parts) {
    for (const AstcFootprint f : {AstcFootprint{4, 4}, AstcFootprint{12, 12}}) {  // small_block and not
      for (;;) {
        auto [blk, q] = random_legal_block(rng, f.w, f.h, 0.0);
        if (q.partitions != parts) continue;
        check_config(blk, q, f.w, f.h);
        EXPECT_EQ(compare_blocks({blk}, f.w, f.h, false), 0);
        EXPECT_EQ(compare_blocks({blk}, f.w, f.h, true), 0);
        break;
      }
    }
  }
}

// ---- (4) astcenc-encoded images --------------------------------------------------------------------

// A procedural RGBA image: gradients, a ring pattern and hash noise; alpha varies too.
std::vector<uint8_t> procedural_image(int w, int h) {
  std::vector<uint8_t> px(static_cast<size_t>(w * h * 4));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint32_t n = (static_cast<uint32_t>(x) * 73856093u) ^ (static_cast<uint32_t>(y) * 19349663u);
      const int noise = static_cast<int>((n >> 7) & 31) - 16;
      const int ring = ((x - w / 2) * (x - w / 2) + (y - h / 2) * (y - h / 2)) / 8 % 64;
      uint8_t* p = &px[static_cast<size_t>((y * w + x) * 4)];
      p[0] = static_cast<uint8_t>(std::clamp(x * 255 / w + noise, 0, 255));
      p[1] = static_cast<uint8_t>(std::clamp(y * 255 / h + ring, 0, 255));
      p[2] = static_cast<uint8_t>(std::clamp(128 + ring * 2 - noise, 0, 255));
      p[3] = static_cast<uint8_t>(std::clamp(255 - (x + y) * 2, 0, 255));
    }
  return px;
}

TEST(AstcDecode, EncodedImagesMatchLibastcenc) {
  struct Case {
    int bw, bh, w, h;
    bool srgb;
  };
  for (const Case k :
       {Case{4, 4, 37, 29, false}, Case{5, 4, 41, 30, true}, Case{6, 6, 50, 43, false}, Case{8, 8, 61, 35, true},
        Case{10, 5, 33, 27, false}, Case{12, 12, 53, 47, false}, Case{12, 10, 25, 21, true}}) {
    std::vector<uint8_t> src = procedural_image(k.w, k.h);
    void* slice = src.data();
    astcenc_image img{static_cast<unsigned>(k.w), static_cast<unsigned>(k.h), 1, ASTCENC_TYPE_U8, &slice};
    const size_t blocks = static_cast<size_t>((k.w + k.bw - 1) / k.bw) * static_cast<size_t>((k.h + k.bh - 1) / k.bh);
    std::vector<uint8_t> data(blocks * kAstcBlockBytes);
    astcenc_context* ctx = astcenc_ctx(k.bw, k.bh, k.srgb, true);
    ASSERT_EQ(astcenc_compress_image(ctx, &img, &kIdentity, data.data(), data.size(), 0), ASTCENC_SUCCESS);
    astcenc_compress_reset(ctx);
    const Image mine = decode_astc_image(data.data(), data.size(), k.w, k.h, k.bw, k.bh, k.srgb);
    const std::vector<Rgba8> ref = astcenc_decode_image(data.data(), data.size(), k.w, k.h, k.bw, k.bh, k.srgb);
    ASSERT_EQ(mine.texels.size(), ref.size());
    int diff = 0;
    long abs_err = 0;
    for (size_t i = 0; i < ref.size(); ++i) {
      diff += !(mine.texels[i] == ref[i]);
      abs_err += std::abs(int(mine.texels[i].g) - int(src[i * 4 + 1]));
    }
    EXPECT_EQ(diff, 0) << k.bw << "x" << k.bh << " " << k.w << "x" << k.h;
    // The encoder worked: green within a mean 24 of the source (the noise and ring are hard at 12x12).
    EXPECT_LT(abs_err / static_cast<long>(ref.size()), 24) << k.bw << "x" << k.bh;
  }
}

TEST(AstcDecode, ImageSizeErrors) {
  std::vector<uint8_t> data(4 * kAstcBlockBytes);
  EXPECT_THROW(decode_astc_image(data.data(), data.size(), 9, 8, 8, 8, false), InputError);  // 2x1 blocks != 4
  EXPECT_NO_THROW(decode_astc_image(data.data(), data.size(), 9, 9, 8, 8, false));
  EXPECT_THROW(decode_astc_image(data.data(), data.size(), 8, 8, 7, 7, false), InputError);  // not a footprint
  EXPECT_THROW(decode_astc_image(data.data(), data.size(), 0, 8, 4, 4, false), InputError);
  const Image img = decode_astc_image(data.data(), data.size(), 9, 9, 8, 8, false);  // all-zero blocks: reserved
  for (const Rgba8 t : img.texels) EXPECT_EQ(t, kAstcErrorColor);
}

// Decode speed of 8x8 blocks on one core (reported, not asserted: the bench measures speed).
TEST(AstcDecode, DecodeSpeed8x8) {
  std::mt19937_64 rng(0xA57C'0006);
  std::vector<Block> blocks;
  for (int i = 0; i < 4096; ++i) blocks.push_back(random_legal_block(rng, 8, 8, 0.0).first);
  std::array<Rgba8, 64> out{};
  uint32_t sum = 0;
  const int rounds = tfu::test::iterations(10);
  const auto t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < rounds; ++r)
    for (const Block& b : blocks) {
      decode_astc_block(b.data(), 8, 8, false, out.data());
      sum += out[static_cast<size_t>(r & 63)].g;
    }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("ASTC 8x8 decode: %.1f M texels/s (checksum %u)\n", rounds * 4096.0 * 64 / s / 1e6, sum);
  EXPECT_GT(sum, 0u);
}

}  // namespace
}  // namespace tfu
