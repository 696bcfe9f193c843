// The L2 shared by the units and the shared memory system (rtl/l2_cache.hpp, rtl/shared_memory.hpp):
// the L2's timing and replacement on a hand-derived request sequence, then scenes whose units go
// through one memory system: the same result for any thread count and either engine, contention
// that costs cycles, bytes that are the L2's misses times its line, and the golden compare.
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "cmodel/error.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/l2_cache.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/shared_memory.hpp"
#include "rtl/unit_config.hpp"
#include "rtl/unit_stats.hpp"
#include "rtl/unit_watchdog.hpp"

namespace tfu::rtl {
namespace {

// Two banks of one set of two ways, 64-byte lines, two requests per cycle, hits in 5 cycles; the
// ideal memory behind it: one line per cycle on the interface, then 100 cycles.
L2Config tiny_l2(L2Replacement r) {
  L2Config c;
  c.capacity_bytes = 2 * 2 * 64;
  c.line_bytes = 64;
  c.ways = 2;
  c.banks = 2;
  c.hit_latency = 5;
  c.requests_per_cycle = 2;
  c.replacement = static_cast<int>(r);
  return c;
}
MemoryModel line_per_cycle_memory() {
  MemoryConfig m;
  m.latency = 100;
  m.bytes_per_cycle = 64;
  return MemoryModel(m, 1);
}

// Lines: 0 and 2 and 4 in bank 0, 1 in bank 1 (line mod 2). Worked by the rules of l2_cache.hpp:
//   u0 t0   line 0  input 0 (slot 1), bank 0 looks up at 0: miss; memory from 0, in at 1 + 100
//   u1 t0   line 2  input 0 (slot 2), bank 0 busy: lookup 1 (conflict, queued 1): miss; interface
//                   free at 1: in at 2 + 100
//   u1 t0   line 1  no slot left at 0: input 1, bank 1 looks up at 1 (queued 1): miss; in at 3 + 100
//   u0 t10  line 0  hit on the line in flight: its fill, 101 (> 10 + 5)
//   u0 t200 line 4  miss: LRU evicts line 2 (line 0 was looked up at t10); in at 201 + 100
//   u1 t201 line 2  miss again, evicts line 0 (older than line 4); in at 202 + 100
//   u0 t300 line 0  miss again; in at 301 + 100
// FIFO keeps the fill order instead: line 4 evicts line 0 (filled first), so line 2 at t201 hits
// (max(206, its fill 102) = 206), and line 0 at t300 misses, evicting line 2 (filled before 4).
TEST(L2Cache, HandDerivedSequenceHitsMissesLruAndBankConflicts) {
  struct Step {
    int unit;
    uint64_t now, address, lru_done, fifo_done;
  };
  const Step steps[] = {{0, 0, 0, 101, 101},      {1, 0, 128, 102, 102},     {1, 0, 64, 103, 103},
                        {0, 10, 0, 101, 101},     {0, 200, 256, 301, 301},   {1, 201, 128, 302, 206},
                        {0, 300, 0, 401, 401}};
  for (const L2Replacement r : {L2Replacement::Lru, L2Replacement::Fifo}) {
    const bool lru = r == L2Replacement::Lru;
    L2Cache l2(tiny_l2(r), 2);
    MemoryModel mem = line_per_cycle_memory();
    for (const Step& s : steps)
      EXPECT_EQ(l2.read(s.unit, s.now, 64, 0, s.address, mem), lru ? s.lru_done : s.fifo_done)
          << (lru ? "lru" : "fifo") << " unit " << s.unit << " at " << s.now;
    const L2Cache::Counters& u0 = l2.unit_counters(0);
    const L2Cache::Counters& u1 = l2.unit_counters(1);
    EXPECT_EQ(u0.requests, 4u);
    EXPECT_EQ(u0.hits, 1u);
    EXPECT_EQ(u0.misses, 3u);
    EXPECT_EQ(u0.bank_conflicts, 0u);
    EXPECT_EQ(u0.queue_cycles, 0u);
    EXPECT_EQ(u1.requests, 3u);
    EXPECT_EQ(u1.hits, lru ? 0u : 1u);
    EXPECT_EQ(u1.misses, lru ? 3u : 2u);
    EXPECT_EQ(u1.bank_conflicts, 1u);
    EXPECT_EQ(u1.queue_cycles, 2u);
    EXPECT_EQ(mem.bytes_read(), 64u * (u0.misses + u1.misses));  // the misses' lines, nothing else
  }
}

// An L1 line larger than the L2's is a request per L2 line it covers; the lookups take the input
// slots and banks one after the other.
TEST(L2Cache, ARequestCoveringSeveralLinesLooksUpEach) {
  L2Cache l2(tiny_l2(L2Replacement::Lru), 1);
  MemoryModel mem = line_per_cycle_memory();
  // Lines 4..7: inputs 0, 0, 1, 1; banks 0, 1, 0, 1: lookups 0, 0, 1, 1 (no conflict: each bank's
  // second lookup enters a cycle later); memory in at 1, 2, 3, 4 + 100.
  EXPECT_EQ(l2.read(0, 0, 256, 0, 256, mem), 104u);
  EXPECT_EQ(l2.unit_counters(0).requests, 4u);
  EXPECT_EQ(l2.unit_counters(0).misses, 4u);
  EXPECT_EQ(l2.unit_counters(0).bank_conflicts, 0u);
  EXPECT_EQ(l2.unit_counters(0).queue_cycles, 2u);
}

TEST(L2Cache, ConfigurationErrorsNameTheKey) {
  const auto error = [](const char* json) {
    try {
      (void)unit_config_from_json(json, "c.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error(R"({"l2": {"capacity_bytes": 1000}})").find("l2.capacity_bytes"), std::string::npos);
  EXPECT_NE(error(R"({"l2": {"capacity_bytes": 65536, "line_bytes": 96}})").find("l2.line_bytes"), std::string::npos);
  EXPECT_NE(error(R"({"l2": {"replacement": "random"}})").find("l2.replacement"), std::string::npos);
  EXPECT_NE(error(R"({"memory": {"shared": "yes"}})").find("memory.shared"), std::string::npos);
  const UnitConfig u = unit_config_from_json(
      R"({"l2": {"capacity_bytes": 262144, "line_bytes": 128, "ways": 8, "banks": 8, "replacement": "fifo"}})", "c.json");
  EXPECT_TRUE(u.l2.enabled());
  EXPECT_EQ(u.l2.sets(), 32);
  EXPECT_EQ(u.l2.replacement, 1);
  EXPECT_FALSE(UnitConfig{}.l2.enabled());  // off by default
  EXPECT_EQ(UnitConfig{}.memory.shared, 0);
}

// A scene at a small size, rendered once for the tests below.
struct Rendered {
  Scene scene;
  RenderResult render;
};
const Rendered& ground_plane() {
  static const Rendered r = [] {
    Rendered x{load_scene("ground_plane"), {}};
    x.scene.width = 96;
    x.scene.height = 64;
    RenderOptions ro;
    ro.trace = true;
    ro.threads = 1;
    x.render = render_scene(x.scene, ro);
    return x;
  }();
  return r;
}

SceneSimResult run(const UnitConfig& u, int units, UnitEngine engine = UnitEngine::Recurrence, int threads = 0) {
  const Rendered& r = ground_plane();
  SceneSimOptions so;
  so.units = units;
  so.engine = engine;
  so.threads = threads;
  so.tiles.tile = 16;
  SceneSimResult res = simulate_scene(r.scene, r.render, u, so);
  EXPECT_TRUE(res.mismatch.empty()) << res.mismatch;  // golden compare: all equal
  return res;
}

UnitConfig with_l2_and_dram() {
  UnitConfig u;
  u.l2.capacity_bytes = 16 * 1024;
  u.l2.line_bytes = 128;
  u.l2.ways = 4;
  u.l2.banks = 4;
  u.memory.dram = 1;  // ddr4-2400-x64
  return u;
}

// With the L2 off and the memory private (the defaults), results are today's: the figures below are
// those of the model before the L2 existed (`tfu sim --scene ground_plane --width 96 --height 64
// --unit-tiles round-robin:16`, with the units and memory of each case), for three memories.
TEST(SharedMemory, L2OffAndPrivateMemoryGiveTodaysFigures) {
  struct Case {
    int dram, latency, units;
    uint64_t cycles, memory_bytes, stall_cache_miss;
  };
  for (const Case& c : {Case{0, 100, 1, 6601, 14528, 118}, Case{0, 400, 4, 5086, 26496, 13409},
                        Case{1, 100, 4, 1736, 26496, 297}}) {
    UnitConfig u;
    u.memory.dram = c.dram;
    u.memory.latency = c.latency;
    const SceneSimResult r = run(u, c.units);
    EXPECT_EQ(r.cycles, c.cycles) << c.dram << " " << c.latency << " " << c.units;
    EXPECT_EQ(counter(r.stats, UnitStat::MemoryBytes), c.memory_bytes);
    EXPECT_EQ(counter(r.stats, UnitStat::StallCacheMiss), c.stall_cache_miss);
    EXPECT_EQ(r.stats.counters().count(stat_key(UnitStat::L2Requests)), 0u);
  }
}

// One unit through the shared memory system (memory.shared, no L2) is the unit alone: every
// counter, cycle and pixel equal, with the ideal memory and with a DRAM.
TEST(SharedMemory, OneUnitSharingItsMemoryEqualsThePrivateRun) {
  for (const int dram : {0, 1}) {
    UnitConfig priv;
    priv.memory.dram = dram;
    UnitConfig shared = priv;
    shared.memory.shared = 1;
    for (const UnitEngine e : {UnitEngine::Recurrence, UnitEngine::Clocked}) {
      const SceneSimResult a = run(priv, 1, e), b = run(shared, 1, e);
      EXPECT_EQ(a.cycles, b.cycles) << dram;
      std::map<std::string, uint64_t> counters = b.stats.counters();
      EXPECT_EQ(counters[stat_key(UnitStat::MemorySharedBy)], 1u);  // the one counter the shared run adds
      counters.erase(stat_key(UnitStat::MemorySharedBy));
      EXPECT_EQ(a.stats.counters(), counters) << dram;
      EXPECT_EQ(a.image.texels, b.image.texels) << dram;
    }
  }
}

// Shared memory and L2: the same cycles, statistics and image for 1, 2 and 5 threads and both
// engines; 4 units on one memory take at least the cycles they take on four (the interface and the
// DRAM serve every unit's misses); the bytes the memory reads are the L2's misses times its line.
TEST(SharedMemory, DeterministicOverThreadsAndEnginesContentionAndBytes) {
  constexpr int kUnits = 4;
  for (const bool l2 : {false, true}) {
    UnitConfig u = with_l2_and_dram();
    if (!l2) {
      u.l2 = {};
      u.memory.shared = 1;
    }
    const SceneSimResult ref = run(u, kUnits, UnitEngine::Recurrence, 1);
    for (const int threads : {2, 5})
      for (const UnitEngine e : {UnitEngine::Recurrence, UnitEngine::Clocked}) {
        if (threads == 5 && e == UnitEngine::Clocked) continue;  // the clocked run once is enough
        const SceneSimResult r = run(u, kUnits, e, threads);
        EXPECT_EQ(r.cycles, ref.cycles) << l2 << " " << threads << " " << unit_engine_name(e);
        EXPECT_EQ(r.stats.counters(), ref.stats.counters()) << l2 << " " << threads << " " << unit_engine_name(e);
        EXPECT_EQ(r.image.texels, ref.image.texels);
      }
    UnitConfig priv = u;
    priv.l2 = {};
    priv.memory.shared = 0;
    const SceneSimResult alone = run(priv, kUnits);
    const sim::Stats& st = ref.stats;
    if (!l2) {
      EXPECT_GE(ref.cycles, alone.cycles);
      // The L1s are the same: the same misses and bytes, now through one DRAM.
      EXPECT_EQ(counter(st, UnitStat::MemoryBytes), counter(alone.stats, UnitStat::MemoryBytes));
      EXPECT_EQ(counter(st, UnitStat::DramBursts) * 64, counter(st, UnitStat::MemoryBytes));
      continue;
    }
    const uint64_t l2_misses = counter(st, UnitStat::L2Misses);
    EXPECT_EQ(counter(st, UnitStat::L2Requests), counter(st, UnitStat::L2Hits) + l2_misses);
    // Every L1 miss is one L2 request (128-byte L2 lines hold a 64-byte L1 line).
    EXPECT_EQ(counter(st, UnitStat::L2Requests), counter(st, UnitStat::MemoryRequests));
    EXPECT_EQ(counter(st, UnitStat::L2MemoryBytes), l2_misses * 128);
    EXPECT_EQ(counter(st, UnitStat::DramBursts) * 64, l2_misses * 128);  // two 64-byte bursts per line
    EXPECT_GT(counter(st, UnitStat::L2Hits), 0u);
    EXPECT_GT(counter(st, UnitStat::L2BankConflicts), 0u);
    // The per-unit table adds up to the totals.
    const sim::Stats::Table* t = st.table(stat_key(UnitStat::L2Units));
    ASSERT_NE(t, nullptr);
    ASSERT_EQ(t->rows.size(), static_cast<size_t>(kUnits));
    uint64_t requests = 0, hits = 0;
    for (const auto& row : t->rows) {
      requests += row.second[1];
      hits += row.second[2];
    }
    EXPECT_EQ(requests, counter(st, UnitStat::L2Requests));
    EXPECT_EQ(hits, counter(st, UnitStat::L2Hits));
  }
}

// Many units on few threads (a unit waits for a thread slot and for its turn), some without quads
// (40 units, 24 tiles of 16x16): the same result on 1 and 3 threads.
TEST(SharedMemory, ManyUnitsOnFewThreads) {
  const UnitConfig u = with_l2_and_dram();
  const SceneSimResult a = run(u, 40, UnitEngine::Recurrence, 1), b = run(u, 40, UnitEngine::Recurrence, 3);
  EXPECT_EQ(a.cycles, b.cycles);
  EXPECT_EQ(a.stats.counters(), b.stats.counters());
  EXPECT_EQ(counter(a.stats, UnitStat::MemorySharedBy), 40u);
}

// Contention with the ideal memory (a max-plus system: later data never makes a unit faster): two
// units on one 4-byte/cycle interface against each on its own.
TEST(SharedMemory, SharingOneInterfaceCostsCycles) {
  UnitConfig u;
  u.memory.bytes_per_cycle = 4;
  const SceneSimResult alone = run(u, 2);
  u.memory.shared = 1;
  const SceneSimResult shared = run(u, 2);
  EXPECT_GT(shared.cycles, alone.cycles);
  EXPECT_EQ(counter(shared.stats, UnitStat::MemoryBytes), counter(alone.stats, UnitStat::MemoryBytes));
}

// The watchdog of a unit sharing its memory allows for the other units' outstanding lines
// (unit_watchdog.hpp): alone 2 x (16 x 4 + 100 + 16 + 64) + 10000 = 10488; each of 3 other units
// 128 footprints x 16 lines of ceil(64 / 16) + 64 cycles (+ the L2's 20), twice.
TEST(SharedMemory, WatchdogAllowsForTheOtherUnitsLines) {
  UnitConfig u;
  EXPECT_EQ(no_progress_limit(u, 1), 10488u);
  EXPECT_EQ(no_progress_limit(u, 4), 10488u + 2u * 3 * 128 * 16 * (4 + 64));
  u.l2.capacity_bytes = 8192;
  EXPECT_EQ(no_progress_limit(u, 4), 10488u + 2u * 3 * 128 * 16 * (4 + 64 + 20));
}

}  // namespace
}  // namespace tfu::rtl
