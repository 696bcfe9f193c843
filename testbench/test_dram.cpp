// The DRAM model (rtl/dram): each timing rule on its own with hand-set state, the presets'
// clock counts against the datasheet figures worked by hand, the address mapping, and whole read
// streams whose cycles are derived by hand from the rules; then units whose misses go to a DRAM.
#include <gtest/gtest.h>

#include "cmodel/error.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/dram.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/unit_config.hpp"
#include "rtl/unit_stats.hpp"
#include "testbench/docs_text.hpp"

namespace tfu::rtl::dram {
namespace {

const Timing& ddr4() {
  static const Timing t = Timing::of(part("ddr4-2400-x64").sheet, 1200);
  return t;
}

TEST(DramPresets, Ddr4_2400ClocksAreTheDatasheetFiguresRoundedUp) {
  // tCK = 0.8333 ns: 13.32 ns -> 15.98 -> 16; 32 ns -> 38.4 -> 39; 45.32 -> 54.4 -> 55; tRTP
  // max(4, 7.5 ns -> 9); tCCD_L max(4, 5 ns -> 6); tRRD_S max(4, 3.3 ns -> 3.96 -> 4); tRRD_L max(4,
  // 4.9 ns -> 5.88 -> 6); tFAW max(20, 21 ns -> 25.2 -> 26); tREFI 7.8 us -> 9360; tRFC 260 ns -> 312.
  const Timing& t = ddr4();
  EXPECT_EQ(t.CL, 16);
  EXPECT_EQ(t.tRCD, 16);
  EXPECT_EQ(t.tRP, 16);
  EXPECT_EQ(t.tRAS, 39);
  EXPECT_EQ(t.tRC, 55);
  EXPECT_EQ(t.tRTP, 9);
  EXPECT_EQ(t.tCCD_S, 4);
  EXPECT_EQ(t.tCCD_L, 6);
  EXPECT_EQ(t.tRRD_S, 4);
  EXPECT_EQ(t.tRRD_L, 6);
  EXPECT_EQ(t.tFAW, 26);
  EXPECT_EQ(t.tREFI, 9360);
  EXPECT_EQ(t.tRFC, 312);
  EXPECT_EQ(t.burst, 4);
}

TEST(DramPresets, Lpddr4_3200ClocksAreTheStandardsFiguresRoundedUp) {
  // tCK = 0.625 ns: tRCD 18 ns -> 28.8 -> 29; tRAS 42 -> 67.2 -> 68; tRC 60 -> 96; tRTP max(8, 12);
  // tRRD 10 ns -> 16; tFAW 40 -> 64; tREFI 3.904 us -> 6246.4, down to 6246; tRFCab 180 ns -> 288.
  const Timing t = Timing::of(part("lpddr4-3200-x16").sheet, 1600);
  EXPECT_EQ(t.CL, 28);
  EXPECT_EQ(t.tRCD, 29);
  EXPECT_EQ(t.tRP, 29);
  EXPECT_EQ(t.tRAS, 68);
  EXPECT_EQ(t.tRC, 96);
  EXPECT_EQ(t.tRTP, 12);
  EXPECT_EQ(t.tCCD_S, 8);
  EXPECT_EQ(t.tCCD_L, 8);
  EXPECT_EQ(t.tRRD_S, 16);
  EXPECT_EQ(t.tFAW, 64);
  EXPECT_EQ(t.tREFI, 6246);
  EXPECT_EQ(t.tRFC, 288);
  EXPECT_EQ(t.burst, 8);
}

TEST(DramPresets, Gddr3_1400ClocksAreTheDatasheetClocks) {
  // tCK = 1.4286 ns; the row and column figures are the data sheet's clocks as printed; tREFI 3.9 us
  // x 700 MHz = 2730 exactly; tRFC 52.0 ns -> 36.4 -> 37. BL4 at two beats per clock: 2 clocks.
  const Timing t = Timing::of(part("gddr3-1400-x32").sheet, 700);
  EXPECT_EQ(t.CL, 11);
  EXPECT_EQ(t.tRCD, 11);
  EXPECT_EQ(t.tRP, 12);
  EXPECT_EQ(t.tRAS, 18);
  EXPECT_EQ(t.tRC, 30);
  EXPECT_EQ(t.tRC, t.tRAS + t.tRP);
  EXPECT_EQ(t.tRTP, 2);
  EXPECT_EQ(t.tCCD_S, 2);
  EXPECT_EQ(t.tCCD_L, 2);
  EXPECT_EQ(t.tRRD_S, 7);
  EXPECT_EQ(t.tRRD_L, 7);
  EXPECT_EQ(t.tFAW, 0);
  EXPECT_EQ(t.tREFI, 2730);
  EXPECT_EQ(t.tRFC, 37);
  EXPECT_EQ(t.burst, 2);
  EXPECT_EQ(t.tCCD_S, t.burst) << "back-to-back bursts fill the bus";
  const Geometry& g = part("gddr3-1400-x32").g;
  EXPECT_EQ(int64_t{g.banks()} * g.rows * g.row_bytes * 8, int64_t{512} << 20) << "512 Mbit";
  EXPECT_EQ(g.columns(), 128);
}

TEST(DramPresets, EveryPresetIsConsistent) {
  for (const Part& p : parts()) {
    SCOPED_TRACE(std::string(p.name));
    const Timing t = Timing::of(p.sheet, p.clock_mhz);
    EXPECT_GE(t.tRC, t.tRAS + t.tRP - 1) << "tRC is tRAS + tRP (one clock of rounding)";
    EXPECT_LE(t.tCCD_S, t.tCCD_L);
    EXPECT_LE(t.tRRD_S, t.tRRD_L);
    if (t.tFAW > 0) {  // 0: the part has no four-activate window
      EXPECT_GE(t.tFAW, 4 * t.tRRD_S) << "else tFAW never binds";
    }
    EXPECT_EQ(p.g.row_bytes % p.g.burst_bytes, 0);
    EXPECT_FALSE(p.source.empty());
  }
  EXPECT_THROW(part("ddr4-2400"), InputError);
  try {
    part("ddr4-2400-x46", "memory.dram");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("memory.dram: unknown DRAM part 'ddr4-2400-x46' (did you mean 'ddr4-2400-x64'?"),
              std::string::npos)
        << e.what();
  }
}

TEST(DramPresets, DocsShowThePresetTable) {
  EXPECT_NE(test::docs_text("memory-system.md").find(presets_markdown()), std::string::npos)
      << "docs/memory-system.md is stale: paste presets_markdown() (rtl/dram.cpp) under \"Presets\"";
}

// ---- The rules, one at a time ----

RankState rank_of(const Geometry& g) {
  RankState r;
  r.banks.resize(static_cast<size_t>(g.banks()));
  r.last_act_in_group.assign(static_cast<size_t>(g.bank_groups), kNever);
  r.last_rd_in_group.assign(static_cast<size_t>(g.bank_groups), kNever);
  return r;
}

TEST(DramRules, PrechargeWaitsForTrasAndTrtp) {
  const Timing& t = ddr4();
  BankState b;
  b.last_act = 100;
  EXPECT_EQ(earliest_precharge(t, b, 0), 139);    // tRAS 39
  EXPECT_EQ(earliest_precharge(t, b, 200), 200);  // already met
  b.last_rd = 135;
  EXPECT_EQ(earliest_precharge(t, b, 0), 144);    // tRTP 9 after the read binds
}

TEST(DramRules, ActivateWaitsForEachOfItsRules) {
  const Timing& t = ddr4();
  const Geometry& g = part("ddr4-2400-x64").g;
  RankState r = rank_of(g);
  BankState b;
  EXPECT_EQ(earliest_activate(t, r, 0, b, 7), 7);  // nothing binds
  b.last_pre = 100;
  EXPECT_EQ(earliest_activate(t, r, 0, b, 0), 116);  // tRP 16
  b.last_act = 70;
  EXPECT_EQ(earliest_activate(t, r, 0, b, 0), 125);  // tRC 55
  b = BankState{};
  r.last_act = 200;
  EXPECT_EQ(earliest_activate(t, r, 1, b, 0), 204);  // tRRD_S 4 (another group)
  r.last_act_in_group[1] = 200;
  EXPECT_EQ(earliest_activate(t, r, 1, b, 0), 206);  // tRRD_L 6 (the same group)
  r.act_window = {190, 194, 198, 200};
  EXPECT_EQ(earliest_activate(t, r, 2, b, 0), 216);  // tFAW 26 after the fourth-last (190)
  r.refresh_until = 300;
  EXPECT_EQ(earliest_activate(t, r, 2, b, 0), 300);  // tRFC
}

TEST(DramRules, ReadWaitsForTrcdTccdAndTheDataBus) {
  const Timing& t = ddr4();
  const Geometry& g = part("ddr4-2400-x64").g;
  RankState r = rank_of(g);
  ChannelState ch;
  BankState b;
  b.last_act = 50;
  EXPECT_EQ(earliest_read(t, r, 0, b, ch, 0), 66);  // tRCD 16
  r.last_rd = 70;
  EXPECT_EQ(earliest_read(t, r, 0, b, ch, 0), 74);  // tCCD_S 4
  r.last_rd_in_group[0] = 70;
  EXPECT_EQ(earliest_read(t, r, 0, b, ch, 0), 76);  // tCCD_L 6
  ch.data_free = 100;
  EXPECT_EQ(earliest_read(t, r, 0, b, ch, 0), 84);  // data 16 clocks later must not start before 100
}

TEST(DramRules, Gddr3HasNoFourActivateWindow) {
  // Four ACTIVATEs tRRD 7 apart: the fifth waits for tRRD only (28); on ddr4-2400-x64 the same
  // state (tRRD_S 4 apart) holds the fifth to the fourth-last + tFAW 26.
  const Timing t = Timing::of(part("gddr3-1400-x32").sheet, 700);
  RankState r = rank_of(part("gddr3-1400-x32").g);
  r.act_window = {0, 7, 14, 21};
  r.last_act = 21;
  r.last_act_in_group[0] = 21;
  EXPECT_EQ(earliest_activate(t, r, 0, BankState{}, 0), 28);
  RankState d = rank_of(part("ddr4-2400-x64").g);
  d.act_window = {0, 4, 8, 12};
  d.last_act = 12;
  EXPECT_EQ(earliest_activate(ddr4(), d, 1, BankState{}, 0), 26);
}

TEST(DramRules, RefreshPrechargesOpenBanksFirst) {
  const Timing& t = ddr4();
  const Geometry& g = part("ddr4-2400-x64").g;
  RankState r = rank_of(g);
  r.next_refresh = 1000;
  EXPECT_EQ(earliest_refresh(t, r, 0), 1000);
  r.banks[3].open_row = 5;
  r.banks[3].last_act = 990;  // PRE at 990 + tRAS 39 = 1029, REFRESH tRP 16 later
  EXPECT_EQ(earliest_refresh(t, r, 0), 1045);
}

// ---- Address mapping ----

TEST(DramAddressMap, FieldsAreTheBitsInTheGivenOrder) {
  const Geometry& g = part("ddr4-2400-x64").g;  // 64-byte bursts, 128 columns, 4 groups x 4 banks, 32768 rows
  const AddressMap m(g, "row:rank:bank:bank_group:column:channel");
  const uint64_t a = (uint64_t{12345} << 17) | (uint64_t{2} << 15) | (uint64_t{3} << 13) | (uint64_t{77} << 6) | 63;
  EXPECT_EQ(m.locate(a), (Location{.channel = 0, .rank = 0, .bank_group = 3, .bank = 2, .row = 12345, .column = 77}));
  const AddressMap groups_low(g, "row:rank:bank:column:bank_group:channel");
  EXPECT_EQ(groups_low.locate(64 * 5), (Location{.bank_group = 1, .column = 1}));
}

TEST(DramAddressMap, BadOrdersNameTheKey) {
  const Geometry& g = part("ddr4-2400-x64").g;
  auto message = [&](const char* order) {
    try {
      AddressMap m(g, order);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("row:rank:bank:bank_grup:column:channel").find("unknown field 'bank_grup' (did you mean 'bank_group'?"),
            std::string::npos);
  EXPECT_NE(message("row:row:bank:bank_group:column:channel").find("field 'row' appears twice"), std::string::npos);
  EXPECT_NE(message("row:bank:bank_group:column").find("every field once"), std::string::npos);
}

// ---- Whole streams, cycles derived by hand ----

TEST(DramModel, FirstReadRowHitAndRowConflictTakeTheRulesCycles) {
  DramModel d(Config{.part = "ddr4-2400-x64", .unit_clock_mhz = 1200});  // one unit clock = one DRAM clock
  // Empty bank: ACT 0, READ tRCD 16 later, data CL 16 later for 4 clocks: done at 36.
  EXPECT_EQ(d.read(0, 0, 64), 36u);
  // Next burst of the row, same bank group: READ at max(last command + 1, 16 + tCCD_L 6 = 22, data bus
  // 36 - 16 = 20) = 22, done 22 + 16 + 4 = 42.
  EXPECT_EQ(d.read(0, 64, 64), 42u);
  // Another row of the same bank: PRE at max(23, ACT 0 + tRAS 39, READ 22 + tRTP 9) = 39, ACT at
  // max(40, 39 + tRP 16, 0 + tRC 55) = 55, READ 71, done 91.
  EXPECT_EQ(d.read(0, uint64_t{1} << 17, 64), 91u);
  const Stats& s = d.stats();
  EXPECT_EQ(s.row_empty, 1u);
  EXPECT_EQ(s.row_hits, 1u);
  EXPECT_EQ(s.row_conflicts, 1u);
  EXPECT_EQ(s.activates, 2u);
  EXPECT_EQ(s.precharges, 1u);
  EXPECT_EQ(s.latency_max, 91u);
}

TEST(DramModel, Gddr3FirstReadRowHitAndRowConflictTakeTheRulesCycles) {
  DramModel d(Config{.part = "gddr3-1400-x32", .unit_clock_mhz = 700});
  // Idle bank: ACT 0, READ tRCD 11 later, data CL 11 later for 2 clocks: tRCD + CL + burst = 24.
  EXPECT_EQ(d.read(0, 0, 16), 24u);
  // The row's next burst: READ at max(last command + 1 = 12, 11 + tCCD 2, data bus 24 - CL 11 = 13)
  // = 13, done 13 + 11 + 2 = 26.
  EXPECT_EQ(d.read(0, 16, 16), 26u);
  // Another row of bank 0 (the row above 4 offset + 7 column + 3 bank bits): PRE at max(14, ACT 0 +
  // tRAS 18, READ 13 + tRTP 2) = 18, ACT at max(19, PRE + tRP 12, ACT 0 + tRC 30) = 30, READ 41,
  // done 54: the conflict waits out tRAS and adds tRP before the idle bank's tRCD + CL + burst.
  EXPECT_EQ(d.read(0, uint64_t{1} << 14, 16), 54u);
  EXPECT_EQ(d.stats().row_empty, 1u);
  EXPECT_EQ(d.stats().row_hits, 1u);
  EXPECT_EQ(d.stats().row_conflicts, 1u);
  // A 64-byte line in an idle bank: four bursts tCCD 2 apart, back to back on the bus: READs at
  // ACT + 11, 13, 15, 17 (ACT at 0 on a fresh model), done 17 + 11 + 2 = 30.
  DramModel line(Config{.part = "gddr3-1400-x32", .unit_clock_mhz = 700});
  EXPECT_EQ(line.read(0, 0, 64), 30u);
  EXPECT_EQ(line.stats().bursts, 4u);
}

TEST(DramModel, Gddr3RefreshAndStreaming) {
  // REFRESH at tREFI 2730, the rank busy for tRFC 37: ACT 2767, READ 2778, done 2791.
  DramModel d(Config{.part = "gddr3-1400-x32", .unit_clock_mhz = 700});
  EXPECT_EQ(d.read(2731, 0, 16), 2791u);
  EXPECT_EQ(d.stats().refreshes, 1u);
  // 64 KiB line by line: tCCD 2 = the burst, so a row streams at the peak 5.6 GB/s; each of the 32
  // rows (2 KB, 128 bursts) opens with an ACT tRCD before its first READ.
  const double peak = 700e6 * 2 * 4 / 1e9;
  DramModel s(Config{.part = "gddr3-1400-x32", .unit_clock_mhz = 700, .refresh = false});
  for (uint64_t i = 0; i < 1024; ++i) s.read(i, i * 64, 64);
  EXPECT_GT(s.bandwidth_gbps(), 0.9 * peak);
  EXPECT_LE(s.bandwidth_gbps(), peak + 1e-9);
  EXPECT_EQ(s.stats().activates, 32u);
}

TEST(DramModel, ClosePageMakesEveryBurstAnActivate) {
  DramModel d(Config{.part = "ddr4-2400-x64", .policy = PagePolicy::close, .unit_clock_mhz = 1200});
  EXPECT_EQ(d.read(0, 0, 64), 36u);
  // Auto-precharge at max(READ 16 + tRTP 9, ACT 0 + tRAS 39) = 39; ACT at max(39 + tRP 16, tRC 55) = 55.
  EXPECT_EQ(d.read(0, 64, 64), 55u + 16 + 16 + 4);
  EXPECT_EQ(d.stats().row_hits, 0u);
  EXPECT_EQ(d.stats().row_empty, 2u);
}

TEST(DramModel, RefreshBlocksTheRankForTrfc) {
  DramModel d(Config{.part = "ddr4-2400-x64", .unit_clock_mhz = 1200});
  // REFRESH at tREFI = 9360, the rank busy until 9672: ACT 9672, READ 9688, done 9708.
  EXPECT_EQ(d.read(9361, 0, 64), 9708u);
  EXPECT_EQ(d.stats().refreshes, 1u);
  DramModel off(Config{.part = "ddr4-2400-x64", .unit_clock_mhz = 1200, .refresh = false});
  EXPECT_EQ(off.read(9361, 0, 64), 9361u + 36);
}

TEST(DramModel, UnitClocksConvertAtThePortRoundingUp) {
  DramModel d(Config{.part = "ddr4-2400-x64", .unit_clock_mhz = 1000});
  EXPECT_EQ(d.to_dram_cycle(5), 6);     // 5 ns = 6 DRAM clocks
  EXPECT_EQ(d.to_dram_cycle(7), 9);     // 8.4 -> 9
  EXPECT_EQ(d.to_unit_cycle(36), 30u);  // 30 ns
  EXPECT_EQ(d.to_unit_cycle(37), 31u);  // 30.8 -> 31
  EXPECT_EQ(d.read(0, 0, 64), 30u);
}

TEST(DramModel, StreamingBandwidthFollowsTheMapping) {
  // 64 KiB read line by line, one request per clock. Along a row of one bank group, READs are
  // tCCD_L = 6 apart for 4 clocks of data: 4/6 of the peak 19.2 GB/s; with the bank group in the low
  // bits, tCCD_S = 4 = the burst: the peak, less the first row's opening and the row changes.
  const double peak = 1200e6 * 2 * 8 / 1e9;  // GB/s
  for (const auto& [order, lo, hi] : {std::tuple{"row:rank:bank:bank_group:column:channel", 0.60, 4.0 / 6.0},
                                      std::tuple{"row:rank:bank:column:bank_group:channel", 0.90, 1.0}}) {
    SCOPED_TRACE(order);
    DramModel d(Config{.part = "ddr4-2400-x64", .mapping = order, .unit_clock_mhz = 1200, .refresh = false});
    for (uint64_t i = 0; i < 1024; ++i) d.read(i, i * 64, 64);
    EXPECT_GT(d.bandwidth_gbps(), lo * peak);
    EXPECT_LE(d.bandwidth_gbps(), hi * peak + 1e-9);
    EXPECT_EQ(d.stats().bytes, 65536u);
    EXPECT_GT(d.stats().row_hit_rate(), 0.95);
  }
}

TEST(DramModel, ReadsSpanningBurstsAndPercentiles) {
  DramModel d(Config{.part = "ddr4-2400-x64", .unit_clock_mhz = 1200, .refresh = false});
  // 256 bytes from 32: bursts 0..4 (five), the request done when the last is.
  d.read(0, 32, 256);
  EXPECT_EQ(d.stats().bursts, 5u);
  EXPECT_EQ(d.stats().bytes, 320u);
  // Bursts at READ 16, 22, 28, 34, 40 (tCCD_L 6): last data 40 + 20 = 60.
  EXPECT_EQ(d.stats().last_data, 60);
  EXPECT_DOUBLE_EQ(d.latency_percentile_ns(0.5), 50.0);  // 60 clocks of 0.8333 ns
  EXPECT_THROW(d.read(1, 0, 0), InputError);
}

}  // namespace
}  // namespace tfu::rtl::dram

// ---- The DRAM behind a unit (memory.dram) ----


namespace tfu::rtl {
namespace {

// A scene through units whose misses go to a DDR4 part: both engines give the same cycles and
// statistics, the golden compare holds, every 64-byte line is one 64-byte burst, each burst is a
// row hit, a row-empty or a row conflict, and the run takes longer than with an ideal memory of
// latency 0 (the DRAM adds at least tRCD + CL + the burst to a first miss).
TEST(DramUnit, SceneThroughDdr4IsBitExactInBothEnginesAndCountsEveryBurst) {
  Scene s = load_scene("ground_plane");
  s.width = 96;
  s.height = 64;
  RenderOptions ro;
  ro.trace = true;
  const RenderResult render = render_scene(s, ro);
  UnitConfig u;
  u.memory.dram = 1;  // ddr4-2400-x64
  const UnitField* f = find_unit_field("memory.dram");
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->value_text(u), "\"ddr4-2400-x64\"");
  for (int units : {1, 2}) {
    SceneSimOptions so;
    so.units = units;
    so.engine = UnitEngine::Recurrence;
    const SceneSimResult rec = simulate_scene(s, render, u, so);
    so.engine = UnitEngine::Clocked;
    const SceneSimResult clk = simulate_scene(s, render, u, so);
    ASSERT_TRUE(rec.mismatch.empty()) << rec.mismatch;
    ASSERT_TRUE(clk.mismatch.empty()) << clk.mismatch;
    EXPECT_EQ(rec.cycles, clk.cycles) << units;
    EXPECT_EQ(rec.stats.counters(), clk.stats.counters()) << units;
    const sim::Stats& st = rec.stats;
    const uint64_t bursts = counter(st, UnitStat::DramBursts);
    EXPECT_EQ(bursts * 64, counter(st, UnitStat::MemoryBytes));
    EXPECT_EQ(counter(st, UnitStat::DramRowHits) + counter(st, UnitStat::DramRowEmpty) +
                  counter(st, UnitStat::DramRowConflicts),
              bursts);
    EXPECT_GT(value(st, UnitStat::DramRowHitRate), 0.0);
    EXPECT_GE(value(st, UnitStat::DramLatencyMean), 16.0 + 4.0);  // CL + the burst at least (a row hit)
    UnitConfig ideal;
    ideal.memory.latency = 0;
    SceneSimOptions io;
    io.units = units;
    EXPECT_GT(rec.cycles, simulate_scene(s, render, ideal, io).cycles);
  }
  // The ideal memory publishes no DRAM statistics.
  const SceneSimResult plain = simulate_scene(s, render, UnitConfig{}, SceneSimOptions{});
  EXPECT_EQ(plain.stats.counters().count("dram_bursts"), 0u);
}

// The same scene through the GDDR3 part: bit-exact in both engines, a 64-byte line is four 16-byte
// bursts, no DRAM energy (no power sheet) but every DRAM statistic.
TEST(DramUnit, SceneThroughGddr3IsBitExactInBothEngines) {
  Scene s = load_scene("ground_plane");
  s.width = 64;
  s.height = 48;
  RenderOptions ro;
  ro.trace = true;
  const RenderResult render = render_scene(s, ro);
  UnitConfig u = unit_config_from_json(R"({"memory.dram": "gddr3-1400-x32", "memory.unit_clock_mhz": 700})", "c.json");
  EXPECT_EQ(u.memory.dram, 3);
  SceneSimOptions so;
  so.engine = UnitEngine::Recurrence;
  const SceneSimResult rec = simulate_scene(s, render, u, so);
  so.engine = UnitEngine::Clocked;
  const SceneSimResult clk = simulate_scene(s, render, u, so);
  ASSERT_TRUE(rec.mismatch.empty()) << rec.mismatch;
  ASSERT_TRUE(clk.mismatch.empty()) << clk.mismatch;
  EXPECT_EQ(rec.cycles, clk.cycles);
  EXPECT_EQ(rec.stats.counters(), clk.stats.counters());
  const uint64_t bursts = counter(rec.stats, UnitStat::DramBursts);
  EXPECT_GT(bursts, 0u);
  EXPECT_EQ(bursts * 16, counter(rec.stats, UnitStat::MemoryBytes));
  // At the unit's 700 MHz one unit clock is one DRAM clock: every read waits CL 11 + 4 bursts of 2.
  EXPECT_GE(value(rec.stats, UnitStat::DramLatencyMean), 11.0 + 8.0);
}

TEST(DramUnit, ConfigNamesThePartPolicyAndMapping) {
  UnitConfig u = unit_config_from_json(
      R"({"memory.dram": "lpddr4-3200-x16", "memory.dram_policy": "close", "memory.dram_mapping": "row:column:rank:bank:bank_group:channel"})",
      "c.json");
  EXPECT_EQ(u.memory.dram, 2);
  EXPECT_EQ(u.memory.dram_policy, 1);
  EXPECT_EQ(u.memory.dram_mapping, 2);
  EXPECT_EQ(u.memory.dram_config().part, "lpddr4-3200-x16");
  try {
    (void)unit_config_from_json(R"({"memory.dram": "ddr5"})", "c.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("memory.dram"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tfu::rtl
