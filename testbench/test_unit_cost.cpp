// The whole unit's cost at a real node (rtl/cost_model.hpp, unit_cost; docs/design-space.md, "The
// whole unit at a node"): every figure derived by hand from the committed block table
// (rtl/sv/silicon_gates.json), the OSU liberty figures and the published SRAM macro's figures.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cmodel/error.hpp"
#include "rtl/cost_model.hpp"

namespace tfu {
namespace {

SamplerDescriptor sampler(const char* mode, int max_aniso = 1) {
  SamplerDescriptor d;
  d.mode = filter_mode_from_name(mode);
  d.max_aniso = max_aniso;
  return d;
}

TEST(UnitCost, NodeNames) {
  EXPECT_EQ(rtl::node_from_name("osu035"), rtl::Node::Osu035);
  EXPECT_EQ(rtl::node_from_name("osu018"), rtl::Node::Osu018);
  EXPECT_STREQ(rtl::node_name(rtl::Node::Osu018), "osu018");
  EXPECT_THROW((void)rtl::node_from_name("generic"), InputError);
}

TEST(UnitCost, MissFifoEntryIsTheFootprintFieldsHardwareStores) {
  // LevelTag: id 32 + texture 12 + sampler 8 + stage 2 + base 2 + format 2 + fu 8 + fv 8 + blend 9
  // + blends 1 + is_level1 1 + shape 12 + probes 5 + probe 4; then level 4, grid x/y 8 x 15,
  // cols 3, rows 3, used 16, cross 1, optional 12.
  EXPECT_EQ(rtl::kMissFifoEntryBits, 106 + 4 + 120 + 3 + 3 + 16 + 1 + 12);
  EXPECT_EQ(rtl::kMissFifoEntryBits, 265);
}

TEST(UnitCost, BilinearOneLaneAtOsu018ByHand) {
  // LINEAR needs bilinear_top: 329,341 um^2, 143.1 MHz register-to-register (715.3 input-to-register),
  // 680.84 nW (rtl/sv/silicon_gates.json, osu018). Miss FIFO: 128 x 265 DFFPOSX1 of 96 um^2.
  rtl::UnitConfig c;
  rtl::RunCounts run;
  run.cycles = 1000;
  run.pixels = 400;
  run.line_lookups = 500;
  run.line_misses = 20;
  const rtl::UnitCost k = rtl::unit_cost(rtl::Node::Osu018, c, {sampler("LINEAR")}, 1, run);
  ASSERT_EQ(k.instances.size(), 1u);
  EXPECT_EQ(k.instances[0].first, "bilinear_top");
  EXPECT_DOUBLE_EQ(k.datapath_um2, 329341.0);
  EXPECT_DOUBLE_EQ(k.miss_fifo_um2, 128.0 * 265 * 96);  // 3,256,320 um^2
  EXPECT_DOUBLE_EQ(k.logic_um2, 329341.0 + 3256320.0);
  EXPECT_DOUBLE_EQ(k.fmax_mhz, 143.1);
  // Leakage 680.84 + 33,920 x 0.160725 nW; switching 0.1 x (logic / 24 um^2) x 0.0125 pF x 1.8^2 V^2 per clock.
  const double leak_nw = 680.84 + 33920 * 0.160725;
  const double per_clock = leak_nw / 143.1 * 1e-3 + 0.1 * (3585661.0 / 24) * 0.0125 * 1.8 * 1.8;
  EXPECT_NEAR(k.logic_pj, 1000 * per_clock, 1e-6 * k.logic_pj);
  // SRAM: 139,008 bits (the default cache) + 64 x 512 bits (the default line buffer: 64 lines of
  // 64 bytes) = 171,776 bits at 209,400.2768 um^2 per 4,096 bits.
  EXPECT_EQ(rtl::line_buffer_sram_bits(c), 32768u);
  ASSERT_TRUE(k.sram_um2.has_value());
  EXPECT_NEAR(*k.sram_um2, 171776 * 209400.2768 / 4096, 1e-6);
  EXPECT_NEAR(*k.area_mm2, (3585661.0 + 171776 * 209400.2768 / 4096) * 1e-6, 1e-12);
  // A lookup reads 4 x (28 tag + 1 valid) + 8 LRU bits = 124 bits = 16 words, and 64 line words,
  // and writes 1 LRU word; a fill writes 64 line words and 4 words of tag and valid.
  // Read 2 x 103.176 pJ, write 2 x 112.563 pJ per word (both clock edges). A fill also writes the
  // line's 64 words into the line buffer and reads them out of it.
  const double sram = 500 * (80 * 206.352 + 1 * 225.126) + 20 * (68 * 225.126) + 20 * 64 * (225.126 + 206.352);
  EXPECT_NEAR(*k.sram_pj, sram, 1e-6 * sram);
  EXPECT_NEAR(*k.energy_pj_per_pixel, (k.logic_pj + sram) / 400, 1e-9 * sram);
}

TEST(UnitCost, SramAccessWordsOfOtherCaches) {
  const rtl::SramMacro& m = *rtl::sram_macro(rtl::Node::Osu018);
  rtl::TexelCacheConfig c;
  c.capacity_bytes = 4096;
  c.ways = 1;  // 29 tag + valid bits, no LRU: 4 words; line 64 words
  rtl::SramAccessWords a = rtl::sram_access_words(c, m);
  EXPECT_EQ(a.lookup_reads, 4u + 64);
  EXPECT_EQ(a.lookup_writes, 0u);
  EXPECT_EQ(a.fill_writes, 64u + 4);
  c.capacity_bytes = 16384;
  c.line_bytes = 256;
  c.ways = 16;  // 64 lines, 4 sets: tag 32 - 2 = 30 bits; 16 x 31 + 16 x 4 LRU = 560 bits = 70 words; line 256 words
  a = rtl::sram_access_words(c, m);
  EXPECT_EQ(a.lookup_reads, 70u + 256);
  EXPECT_EQ(a.lookup_writes, 8u);
  EXPECT_EQ(a.fill_writes, 256u + 4);
}

TEST(UnitCost, LanesAreDatapathsAndOneLaneCubicIsAQuarterOfTheFourLaneBlock) {
  rtl::UnitConfig c;
  const rtl::RunCounts run;
  const double cubic = 1237123.0, blend = 73014.0;  // osu018
  c.filter_lanes = 1;
  rtl::UnitCost k = rtl::unit_cost(rtl::Node::Osu018, c, {sampler("CUBIC_MIPMAP_LINEAR")}, 1, run);
  EXPECT_DOUBLE_EQ(k.datapath_um2, blend + cubic / 4);
  EXPECT_DOUBLE_EQ(k.fmax_mhz, 120.6);  // cubic_filter's slowest part (cubic_weights)
  c.filter_lanes = 4;
  k = rtl::unit_cost(rtl::Node::Osu018, c, {sampler("CUBIC_MIPMAP_LINEAR")}, 1, run);
  EXPECT_DOUBLE_EQ(k.datapath_um2, 4 * blend + cubic);
  c.filter_lanes = 2;
  k = rtl::unit_cost(rtl::Node::Osu018, c, {sampler("LINEAR"), sampler("EDGE_PRESERVING")}, 3, run);
  EXPECT_DOUBLE_EQ(k.datapath_um2, 3 * 2 * (329341.0 + 1556370.0));
  EXPECT_DOUBLE_EQ(k.miss_fifo_um2, 3 * 128.0 * 265 * 96);
  EXPECT_DOUBLE_EQ(k.fmax_mhz, 75.2);  // edge_interp_top is the slowest
}

TEST(UnitCost, AnisotropicBlocksOncePerUnitAndOsu035HasNoSramModel) {
  rtl::UnitConfig c;
  c.filter_lanes = 2;
  const rtl::RunCounts run{100, 10, 20, 1, 640};
  const rtl::UnitCost k = rtl::unit_cost(rtl::Node::Osu035, c, {sampler("LINEAR_MIPMAP_LINEAR", 4)}, 1, run);
  // osu035: bilinear_top 1,305,308 and level_blend 285,724 per lane; aniso_major_select 94,448,
  // aniso_count 977,364, aniso_lambda 88,540, aniso_probe 1,144,940 once; DFFPOSX1 384 um^2.
  EXPECT_DOUBLE_EQ(k.datapath_um2, 2 * (1305308.0 + 285724.0) + 94448.0 + 977364.0 + 88540.0 + 1144940.0);
  EXPECT_DOUBLE_EQ(k.miss_fifo_um2, 128.0 * 265 * 384);
  EXPECT_DOUBLE_EQ(k.fmax_mhz, 47.4);  // aniso_count
  EXPECT_EQ(rtl::sram_macro(rtl::Node::Osu035), nullptr);
  EXPECT_FALSE(k.sram_um2.has_value());
  EXPECT_FALSE(k.area_mm2.has_value());
  EXPECT_FALSE(k.energy_pj_per_pixel.has_value());
  EXPECT_GT(k.logic_pj, 0.0);
}

}  // namespace
}  // namespace tfu
