// The whole unit's cost at a real node (rtl/cost_model.hpp, unit_cost; docs/design-space.md, "The
// whole unit at a node"): every figure derived by hand from the committed block table
// (rtl/sv/silicon_gates.json), the OSU liberty figures and the published SRAM sources' figures.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "rtl/cost_model.hpp"
#include "rtl/dram.hpp"

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
  // LINEAR needs bilinear_top: 343,372 um^2, 148.4 MHz register-to-register (764.2 input-to-register),
  // 705.59 nW (rtl/sv/silicon_gates.json, osu018). Miss FIFO: 128 x 265 DFFPOSX1 of 96 um^2.
  rtl::UnitConfig c;
  rtl::RunCounts run;
  run.cycles = 1000;
  run.pixels = 400;
  run.line_lookups = 500;
  run.line_misses = 20;
  const rtl::UnitCost k = rtl::unit_cost(rtl::Node::Osu018, c, {sampler("LINEAR")}, 1, run);
  ASSERT_EQ(k.instances.size(), 1u);
  EXPECT_EQ(k.instances[0].first, "bilinear_top");
  EXPECT_DOUBLE_EQ(k.datapath_um2, 343372.0);
  EXPECT_DOUBLE_EQ(k.miss_fifo_um2, 128.0 * 265 * 96);  // 3,256,320 um^2
  EXPECT_DOUBLE_EQ(k.logic_um2, 343372.0 + 3256320.0);  // 3,599,692 um^2
  EXPECT_DOUBLE_EQ(k.fmax_mhz, 148.4);
  // Leakage 705.59 + 33,920 x 0.160725 nW; switching 0.1 x (logic / 24 um^2) x 0.0125 pF x 1.8^2 V^2 per clock.
  const double leak_nw = 705.59 + 33920 * 0.160725;
  const double per_clock = leak_nw / 148.4 * 1e-3 + 0.1 * (3599692.0 / 24) * 0.0125 * 1.8 * 1.8;
  EXPECT_NEAR(k.logic_pj, 1000 * per_clock, 1e-6 * k.logic_pj);
  // SRAM: 139,008 bits (the default cache) + 64 x 512 bits (the default line buffer: 64 lines of
  // 64 bytes) = 171,776 bits at 209,400.2768 um^2 per 4,096 bits.
  EXPECT_EQ(rtl::line_buffer_sram_bits(c), 32768u);
  ASSERT_TRUE(k.sram_um2.has_value());
  EXPECT_NEAR(*k.sram_um2, 171776 * 209400.2768 / 4096, 1e-6);
  EXPECT_NEAR(*k.area_mm2, (3599692.0 + 171776 * 209400.2768 / 4096) * 1e-6, 1e-12);
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
  const double cubic = 1237123.0, blend = 132346.0;  // osu018
  c.filter_lanes = 1;
  rtl::UnitCost k = rtl::unit_cost(rtl::Node::Osu018, c, {sampler("CUBIC_MIPMAP_LINEAR")}, 1, run);
  EXPECT_DOUBLE_EQ(k.datapath_um2, blend + cubic / 4);
  EXPECT_DOUBLE_EQ(k.fmax_mhz, 120.6);  // cubic_filter's slowest part (cubic_weights)
  c.filter_lanes = 4;
  k = rtl::unit_cost(rtl::Node::Osu018, c, {sampler("CUBIC_MIPMAP_LINEAR")}, 1, run);
  EXPECT_DOUBLE_EQ(k.datapath_um2, 4 * blend + cubic);
  c.filter_lanes = 2;
  k = rtl::unit_cost(rtl::Node::Osu018, c, {sampler("LINEAR"), sampler("EDGE_PRESERVING")}, 3, run);
  EXPECT_DOUBLE_EQ(k.datapath_um2, 3 * 2 * (343372.0 + 1581843.0));  // bilinear_top + edge_interp_top
  EXPECT_DOUBLE_EQ(k.miss_fifo_um2, 3 * 128.0 * 265 * 96);
  EXPECT_DOUBLE_EQ(k.fmax_mhz, 75.2);  // edge_interp_top is the slowest (bilinear_top 148.4)
}

TEST(UnitCost, AnisotropicBlocksOncePerUnitAtOsu035) {
  rtl::UnitConfig c;
  c.filter_lanes = 2;
  const rtl::RunCounts run{100, 10, 20, 1, 640};
  const rtl::UnitCost k = rtl::unit_cost(rtl::Node::Osu035, c, {sampler("LINEAR_MIPMAP_LINEAR", 4)}, 1, run);
  // osu035: bilinear_top 1,349,588 and level_blend 539,552 per lane; aniso_major_select 94,448,
  // aniso_count 1,476,344, aniso_lambda 87,708, aniso_probe 1,144,940 once; DFFPOSX1 384 um^2.
  EXPECT_DOUBLE_EQ(k.datapath_um2, 2 * (1349588.0 + 539552.0) + 94448.0 + 1476344.0 + 87708.0 + 1144940.0);
  EXPECT_DOUBLE_EQ(k.miss_fifo_um2, 128.0 * 265 * 384);
  EXPECT_DOUBLE_EQ(k.fmax_mhz, 35.8);  // aniso_count (its 112-cell compare path; the others 59.8-112.3)
  EXPECT_GT(k.logic_pj, 0.0);
  // On the footprint's true axes the unit holds tfu_aniso_lod's ellipse parts too, once: osu035
  // aniso_dot_cross 3,739,728, aniso_ellipse_major 1,248,216 (its four parts), aniso_count_ellipse
  // 1,104,248; the clock is still aniso_count's (the hypot's root 36.9 MHz, the ellipse count 44.2).
  SamplerDescriptor on_axes = sampler("LINEAR_MIPMAP_LINEAR", 4);
  on_axes.aniso_axes = AnisoAxes::Ellipse;
  const rtl::UnitCost e = rtl::unit_cost(rtl::Node::Osu035, c, {on_axes}, 1, run);
  EXPECT_DOUBLE_EQ(e.datapath_um2, k.datapath_um2 + 3739728.0 + 1248216.0 + 1104248.0);
  EXPECT_DOUBLE_EQ(e.fmax_mhz, 35.8);
  EXPECT_EQ(e.instances.size(), k.instances.size() + 3);
}

TEST(UnitCost, Osu035SramIsOpenRamCellsWithTheGf180PeripheryAt3V3) {
  // Bit cell: OpenRAM scn4m_subm cell_1rw, 34 x 52 lambda at 0.2 um = 6.8 x 10.4 um = 70.72 um^2.
  // Periphery: the GF180 512 x 8 macro's 209,400.2768 um^2 less its 4,096 cells of 13.5 um^2 =
  // 154,104.2768 um^2. Macro: 4,096 x 70.72 + 154,104.2768 = 443,773.3968 um^2 (108.34 um^2 per bit).
  const rtl::SramMacro* m = rtl::sram_macro(rtl::Node::Osu035);
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->words, 512);
  EXPECT_EQ(m->bits_per_word, 8);
  EXPECT_NEAR(m->area_um2, 443773.3968, 1e-6);
  // GF180 liberty tt_025C_3v30: CLK internal_power per edge 369.6 (read), 408.606 (write).
  EXPECT_DOUBLE_EQ(m->read_pj, 739.2);
  EXPECT_DOUBLE_EQ(m->write_pj, 817.212);
  EXPECT_STREQ(m->corner, "tt_025C_3v30");
  // The whole unit with the default cache (139,008 bits) and line buffer (32,768 bits), LINEAR at
  // osu035: bilinear_top 1,349,588 um^2 + 128 x 265 DFFPOSX1 of 384 um^2.
  rtl::UnitConfig c;
  rtl::RunCounts run;
  run.cycles = 1000;
  run.pixels = 400;
  run.line_lookups = 500;
  run.line_misses = 20;
  const rtl::UnitCost k = rtl::unit_cost(rtl::Node::Osu035, c, {sampler("LINEAR")}, 1, run);
  const double sram_um2 = 171776 * 443773.3968 / 4096;
  ASSERT_TRUE(k.sram_um2.has_value());
  EXPECT_NEAR(*k.sram_um2, sram_um2, 1e-6);
  EXPECT_NEAR(*k.area_mm2, (1349588.0 + 128.0 * 265 * 384 + sram_um2) * 1e-6, 1e-12);
  // Words per access as in the osu018 test (80 read + 1 written per lookup, 68 written per fill, 64
  // written and read in the line buffer per fill).
  const double sram = 500 * (80 * 739.2 + 1 * 817.212) + 20 * (68 * 817.212) + 20 * 64 * (817.212 + 739.2);
  EXPECT_NEAR(*k.sram_pj, sram, 1e-9 * sram);
  EXPECT_NEAR(*k.energy_pj_per_pixel, (k.logic_pj + sram) / 400, 1e-9 * sram);
}

TEST(UnitCost, DramCommandEnergiesByTheMethodOfTn4007) {
  // ddr4-2400-x64 (DRAMPower's MICRON_4Gb_DDR4-2400_8bit_A): 8 devices at 1.2 V, 1200 MHz.
  // READ: (IDD4R 184.5 - IDD3N 44.0) mA x 1.2 V x 4 clocks of 0.8333 ns = 562.0 pJ a device, 4,496 pJ
  // per 64-byte burst. ACTIVATE: (IDD0 60.75 x tRC 55 - IDD3N 44.0 x tRAS 39 - IDD2N 38.25 x 16)
  // mA x clocks = 1,013.25 mA x clocks x 0.8333 ns x 1.2 V = 1,013.25 pJ a device, 8,106 pJ.
  ASSERT_TRUE(rtl::dram_command_energy(1).has_value());
  const rtl::DramCommandEnergy ddr4 = *rtl::dram_command_energy(1);
  EXPECT_NEAR(ddr4.read_burst_pj, 4496.0, 1e-9);
  EXPECT_NEAR(ddr4.activate_pj, 8106.0, 1e-9);
  EXPECT_EQ(ddr4.burst_bytes, 64);
  // lpddr4-3200-x16 (MICRON_6Gb_LPDDR4-3200_32bit_A), one x16 channel, 1600 MHz (0.625 ns).
  // READ, 8 clocks = 5 ns: VDD1 (2.25 - 2.25) x 1.8 + VDD2 (275 - 30) x 1.1 = 269.5 mW -> 1,347.5 pJ per
  // 32 bytes. ACTIVATE: 0.625 x (1.8 x (3.5 x 97 - 2.25 x 68 - 2.0 x 29) + 1.1 x (45 x 97 - 30 x 68
  // - 27 x 29)) = 0.625 x (231.3 + 1,696.2) = 1,204.6875 pJ.
  ASSERT_TRUE(rtl::dram_command_energy(2).has_value());
  const rtl::DramCommandEnergy lp4 = *rtl::dram_command_energy(2);
  EXPECT_NEAR(lp4.read_burst_pj, 1347.5, 1e-9);
  EXPECT_NEAR(lp4.activate_pj, 1204.6875, 1e-9);
  EXPECT_EQ(lp4.burst_bytes, 32);
  // Every preset with a power sheet costs a burst; gddr3-1400-x32 has none (no cited IDD table).
  for (size_t k = 1; k <= rtl::dram::parts().size(); ++k) {
    const std::optional<rtl::DramCommandEnergy> e = rtl::dram_command_energy(static_cast<int>(k));
    EXPECT_EQ(e.has_value(), rtl::dram::parts()[k - 1].name != "gddr3-1400-x32") << k;
    if (e) {
      EXPECT_GT(e->read_burst_pj, 0.0);
    }
  }
}

TEST(UnitCost, DramEnergyIsAddedPerBurstAndActivate) {
  rtl::UnitConfig c;
  rtl::RunCounts run;
  run.cycles = 1000;
  run.pixels = 400;
  run.line_lookups = 500;
  run.line_misses = 20;
  run.dram_bursts = 20;
  run.dram_activates = 3;
  const rtl::UnitCost ideal = rtl::unit_cost(rtl::Node::Osu018, c, {sampler("LINEAR")}, 1, run);
  EXPECT_FALSE(ideal.dram_pj.has_value());  // the ideal memory: no part to cost
  c.memory.dram = 1;                        // ddr4-2400-x64
  const rtl::UnitCost k = rtl::unit_cost(rtl::Node::Osu018, c, {sampler("LINEAR")}, 1, run);
  ASSERT_TRUE(k.dram_pj.has_value());
  EXPECT_NEAR(*k.dram_pj, 20 * 4496.0 + 3 * 8106.0, 1e-6);
  EXPECT_NEAR(*k.energy_pj_per_pixel, *ideal.energy_pj_per_pixel + (20 * 4496.0 + 3 * 8106.0) / 400, 1e-6);
  // A part without a power sheet: no DRAM energy, and no total that would leave it out.
  c.memory.dram = 3;  // gddr3-1400-x32
  const rtl::UnitCost g = rtl::unit_cost(rtl::Node::Osu018, c, {sampler("LINEAR")}, 1, run);
  EXPECT_FALSE(g.dram_pj.has_value());
  EXPECT_FALSE(g.energy_pj_per_pixel.has_value());
  EXPECT_TRUE(g.sram_pj.has_value());
}


// Every block of the SV manifests scripts/gate_count reads (composites included) has its row in
// rtl/sv/silicon_gates.json at the generic library and at both nodes, with a positive area and,
// at the nodes, a positive register-to-register fmax: docs/silicon.md's table is the whole design.
TEST(UnitCost, EveryManifestBlockHasARowAtEveryLibrary) {
  const std::filesystem::path root = std::filesystem::path(TFU_DOCS_DIR).parent_path();
  const auto parse = [&](const char* rel) {
    std::ifstream in(root / rel);
    std::stringstream text;
    text << in.rdbuf();
    return nlohmann::json::parse(text.str());
  };
  const nlohmann::json table = parse("rtl/sv/silicon_gates.json");
  size_t blocks = 0;
  for (const char* manifest :
       {"rtl/sv/blocks.json", "rtl/sv/edge/blocks.json", "rtl/sv/aniso/blocks.json", "rtl/sv/srgb/blocks.json"})
    for (const nlohmann::json& b : parse(manifest)) {
      const std::string name = b.at("block").get<std::string>();
      ++blocks;
      for (const char* lib : {"generic", "osu035", "osu018"}) {
        const nlohmann::json* row = nullptr;
        for (const nlohmann::json& r : table.at(lib))
          if (r.at("block") == name) row = &r;
        ASSERT_NE(row, nullptr) << manifest << ": " << name << " has no " << lib << " row";
        if (std::string(lib) == "generic") {
          EXPECT_GT(row->at("ge").get<double>(), 0.0) << name;
        } else {
          EXPECT_GT(row->at("area_um2").get<double>(), 0.0) << name << " " << lib;
          EXPECT_GT(row->at("fmax_reg2reg_mhz").get<double>(), 0.0) << name << " " << lib;
        }
      }
    }
  EXPECT_GE(blocks, 47u);
}
}  // namespace
}  // namespace tfu
