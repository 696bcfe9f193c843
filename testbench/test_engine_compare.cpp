// The engine compare (rtl/engine_compare.hpp): both engines record the same events, item by item,
// on scenes of every filter family; the report names the earliest differing event (hand-made
// event lists), and, between runs whose configurations differ in one block's timing, that block.
#include <gtest/gtest.h>

#include "cmodel/frame.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/engine_compare.hpp"
#include "rtl/tfu_unit.hpp"
#include "testbench/one_texture.hpp"
#include "testbench/scene_trace.hpp"

namespace tfu::rtl {
namespace {

// A built-in scene's trace at a small size, its first mesh's texture bound as texture 0 with the
// scene's sampler under filter mode `mode` as sampler 0.
using OneTextureRun = test::OneTexture;
OneTextureRun scene_run(const std::string& scene_name, const char* mode, const UnitConfig& u) {
  const test::SceneTrace st = test::scene_trace(scene_name, 48, 32);
  return test::one_texture(st.scene.meshes.front(), mode, st.trace, u);
}

size_t row(const UnitEvents& e, UnitEvent which) { return e[static_cast<size_t>(which)].size(); }

TEST(EngineCompare, BothEnginesRecordTheSameEventsOnEveryFilterFamily) {
  UnitConfig u;
  u.cache.capacity_bytes = 4096;  // misses and back-pressure
  u.memory.latency = 40;
  for (const char* mode :
       {"NEAREST", "LINEAR_MIPMAP_LINEAR", "CUBIC_MIPMAP_NEAREST", "EDGE_PRESERVING_MIPMAP_LINEAR"}) {
    const OneTextureRun run = scene_run("ground_plane", mode, u);
    UnitEvents clocked, rec;
    const UnitOutput a = run_unit_recording(run.frame, run.trace, u, UnitEngine::Clocked, clocked);
    const UnitOutput b = run_unit_recording(run.frame, run.trace, u, UnitEngine::Recurrence, rec);
    EXPECT_EQ(first_event_difference(clocked, rec), "") << mode;
    EXPECT_EQ(clocked, rec) << mode;
    EXPECT_EQ(compare_engines(run.frame, run.trace, u), "") << mode;
    // Recording changes nothing.
    const UnitOutput plain = run_unit(run.frame, run.trace, u);
    EXPECT_EQ(a.stats.json_text(), plain.stats.json_text()) << mode;
    EXPECT_EQ(b.response_cycle, plain.response_cycle) << mode;
    // The counts follow from the trace and the statistics: one quad push and take per quad, one
    // pixel per request, every footprint through kernel_select and both sides of the cache, then
    // through the filter or the edge median, one retire per request.
    const size_t requests = run.trace.requests.size();
    const bool edge = std::string(mode).starts_with("EDGE");
    EXPECT_EQ(row(clocked, UnitEvent::RequestFifoPushesQuad), requests / 4) << mode;
    EXPECT_EQ(row(clocked, UnitEvent::LodUnitTakesQuad), requests / 4) << mode;
    EXPECT_EQ(row(clocked, UnitEvent::AddressGenTakesPixel), requests) << mode;
    const size_t footprints = row(clocked, UnitEvent::KernelSelectTakesFootprint);
    EXPECT_GE(footprints, requests) << mode;
    EXPECT_EQ(row(clocked, UnitEvent::CacheAcceptsFootprint), footprints) << mode;
    EXPECT_EQ(row(clocked, UnitEvent::CacheEmitsFootprint), footprints) << mode;
    EXPECT_EQ(row(clocked, edge ? UnitEvent::EdgeMedianTakesFootprint : UnitEvent::FilterFinishesFootprint), footprints)
        << mode;
    EXPECT_EQ(row(clocked, edge ? UnitEvent::FilterFinishesFootprint : UnitEvent::EdgeMedianTakesFootprint), 0u)
        << mode;
    EXPECT_EQ(row(clocked, edge ? UnitEvent::ResponseRetiresEdgePixel : UnitEvent::ResponseRetiresFilterPixel),
              requests)
        << mode;
    // At most one item per cycle on each channel, and the last retire is the run's last cycle.
    for (const std::vector<int64_t>& cycles : clocked)
      for (size_t i = 1; i < cycles.size(); ++i) ASSERT_LT(cycles[i - 1], cycles[i]) << mode;
    const auto& retires = clocked[static_cast<size_t>(edge ? UnitEvent::ResponseRetiresEdgePixel
                                                           : UnitEvent::ResponseRetiresFilterPixel)];
    EXPECT_EQ(static_cast<uint64_t>(retires.back()) + 1, a.cycles) << mode;
  }
}

TEST(EngineCompare, FirstDifferenceIsTheEarliestCycle) {
  UnitEvents a, b;
  EXPECT_EQ(first_event_difference(a, b), "");
  a[static_cast<size_t>(UnitEvent::LodUnitTakesQuad)] = {1, 2, 3};
  b[static_cast<size_t>(UnitEvent::LodUnitTakesQuad)] = {1, 2, 4};
  a[static_cast<size_t>(UnitEvent::CacheAcceptsFootprint)] = {5, 9};
  b[static_cast<size_t>(UnitEvent::CacheAcceptsFootprint)] = {5, 8};
  // The texel cache's difference comes later (cycle 8) than lod_unit's (cycle 3).
  EXPECT_EQ(
      first_event_difference(a, b),
      "the engines first disagree where lod_unit takes quad #2: at cycle 3 clocked, at cycle 4 by the recurrences");
  b[static_cast<size_t>(UnitEvent::CacheAcceptsFootprint)] = {2, 8};
  EXPECT_EQ(first_event_difference(a, b),
            "the engines first disagree where texel_cache accepts footprint #0: at cycle 5 clocked, at cycle 2 by the "
            "recurrences");
  // An item one run never moved.
  UnitEvents c, d;
  c[static_cast<size_t>(UnitEvent::ResponseRetiresEdgePixel)] = {7, 8};
  d[static_cast<size_t>(UnitEvent::ResponseRetiresEdgePixel)] = {7};
  EXPECT_EQ(
      first_event_difference(c, d),
      "the engines first disagree where response retires edge pixel #1: at cycle 8 clocked, never by the recurrences");
}

// The datapaths at the SV tops' deeper pipelines (filter.edge_stages 8, filter.bilinear_stages 4):
// both engines record the same events and agree on everything, misses included. One datapath per
// run never stalls (the response block takes a pixel per clock from one path), so every footprint
// leaves the texel cache when it did at the default depths and every pixel retires exactly the
// extra clocks later.
TEST(EngineCompare, BothEnginesAgreeOnTheDeeperDatapaths) {
  UnitConfig deep;
  deep.cache.capacity_bytes = 4096;  // misses and back-pressure
  deep.memory.latency = 40;
  deep.filter = {8, 4};
  for (const char* mode : {"LINEAR", "LINEAR_MIPMAP_LINEAR", "EDGE_PRESERVING", "EDGE_PRESERVING_MIPMAP_LINEAR"}) {
    const OneTextureRun run = scene_run("ground_plane", mode, deep);
    UnitEvents clocked, rec;
    const UnitOutput a = run_unit_recording(run.frame, run.trace, deep, UnitEngine::Clocked, clocked);
    const UnitOutput b = run_unit_recording(run.frame, run.trace, deep, UnitEngine::Recurrence, rec);
    EXPECT_EQ(first_event_difference(clocked, rec), "") << mode;
    EXPECT_EQ(clocked, rec) << mode;
    EXPECT_EQ(a.cycles, b.cycles) << mode;
    EXPECT_EQ(compare_engines(run.frame, run.trace, deep), "") << mode;
    // Against the default depths: later by edge 8 - 3 or bilinear 4 - 2 clocks.
    UnitConfig base = deep;
    base.filter = {};
    UnitEvents shallow;
    const UnitOutput c = run_unit_recording(run.frame, run.trace, base, UnitEngine::Recurrence, shallow);
    const bool edge = std::string(mode).starts_with("EDGE");
    const int64_t extra = edge ? 5 : 2;
    const size_t retire =
        static_cast<size_t>(edge ? UnitEvent::ResponseRetiresEdgePixel : UnitEvent::ResponseRetiresFilterPixel);
    const size_t emits = static_cast<size_t>(UnitEvent::CacheEmitsFootprint);
    EXPECT_EQ(rec[emits], shallow[emits]) << mode;
    ASSERT_EQ(rec[retire].size(), shallow[retire].size()) << mode;
    for (size_t i = 0; i < rec[retire].size(); ++i)
      ASSERT_EQ(rec[retire][i], shallow[retire][i] + extra) << mode << " #" << i;
    EXPECT_EQ(a.cycles, c.cycles + static_cast<uint64_t>(extra)) << mode;
  }
}

// Two runs whose configurations differ in one block's timing first differ at that block.
TEST(EngineCompare, NamesTheBlockWhoseTimingDiffers) {
  UnitConfig u;
  u.memory.latency = 30;
  const OneTextureRun run = scene_run("ground_plane", "CUBIC_MIPMAP_NEAREST", u);
  UnitEvents base;
  run_unit_recording(run.frame, run.trace, u, UnitEngine::Recurrence, base);
  const size_t emits = static_cast<size_t>(UnitEvent::CacheEmitsFootprint);
  const size_t finishes = static_cast<size_t>(UnitEvent::FilterFinishesFootprint);
  // One more cycle of memory latency: the first footprint (a miss) leaves the miss FIFO a cycle
  // later; nothing before it moves differently.
  UnitConfig slower = u;
  slower.memory.latency = 31;
  UnitEvents later;
  run_unit_recording(run.frame, run.trace, slower, UnitEngine::Recurrence, later);
  EXPECT_EQ(first_event_difference(base, later),
            fmt::format(
                "the engines first disagree where texel_cache emits footprint #0: at cycle {} clocked, at cycle {} by "
                "the recurrences",
                base[emits][0], base[emits][0] + 1));
  // Four filter lanes instead of one: a 4 x 4 cubic footprint keeps the lanes 1 cycle instead of
  // 4, so the first footprint finishes 3 cycles earlier.
  UnitConfig wide = u;
  wide.filter_lanes = 4;
  UnitEvents lanes;
  run_unit_recording(run.frame, run.trace, wide, UnitEngine::Clocked, lanes);
  EXPECT_EQ(
      first_event_difference(base, lanes),
      fmt::format("the engines first disagree where filter finishes footprint #0: at cycle {} clocked, at cycle {} by "
                  "the recurrences",
                  base[finishes][0], base[finishes][0] - 3));
}

}  // namespace
}  // namespace tfu::rtl
