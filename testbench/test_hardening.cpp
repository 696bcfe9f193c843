// The model under absurd configurations: cache configuration products never
// wrap and every field is range-checked; the rasterizer never runs into undefined behaviour on
// absurd screen positions; thread counts are checked and a refused thread does not abort; a valid
// unit configuration never trips the watchdog, whatever its latency and bandwidth; the image does
// not depend on --units except under cache-aware shapes. Also the fuzzers' findings: the ideal
// sampler on non-finite coordinates, and the montage size.
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "testbench/input_error.hpp"
#include "cmodel/error.hpp"
#include "cmodel/kernel_error.hpp"
#include "cmodel/montage.hpp"
#include "cmodel/parallel.hpp"
#include "cmodel/procedural.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/texture_memory.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_config.hpp"
#include "rtl/unit_watchdog.hpp"

namespace tfu {
namespace {

// ---- Cache configuration ----

TEST(CacheConfig, ExtremeValuesAreRangeErrorsNotCrashes) {
  constexpr int kMax = std::numeric_limits<int>::max(), kMin = std::numeric_limits<int>::min();
  // Through the unit's field table (rtl/unit_config.cpp): every field range-checked before use.
  const auto err = [](auto set) {
    rtl::UnitConfig u;
    set(u);
    return input_error([&] { u.validate(); });
  };
  EXPECT_EQ(err([](rtl::UnitConfig& u) { u.cache.ways = kMax; }), "cache.ways: 2147483647 must be in 0..1024");
  EXPECT_EQ(err([](rtl::UnitConfig& u) { u.cache.ways = 67108864; }), "cache.ways: 67108864 must be in 0..1024");
  EXPECT_EQ(err([](rtl::UnitConfig& u) { u.cache.ways = kMin; }), "cache.ways: -2147483648 must be in 0..1024");
  EXPECT_EQ(err([](rtl::UnitConfig& u) { u.cache.capacity_bytes = kMax; }),
            "cache.capacity_bytes: 2147483647 must be in 64..1073741824");
  EXPECT_EQ(err([](rtl::UnitConfig& u) { u.cache.capacity_bytes = 0; }), "cache.capacity_bytes: 0 must be in 64..1073741824");
  EXPECT_EQ(err([](rtl::UnitConfig& u) { u.cache.line_bytes = kMax; }), "cache.line_bytes: 2147483647 must be one of 64, 256, 1024");
  EXPECT_EQ(err([](rtl::UnitConfig& u) { u.cache.banks = kMin; }), "cache.banks: -2147483648 must be one of 1, 4");
  // The cache's own check forms its products in 64 bits: ways x line bytes = 2^41 does not wrap
  // (it was `line_bytes() * ways` as int: SIGSEGV / SIGFPE).
  rtl::TexelCacheConfig c;
  c.line_bytes = 1024;
  c.ways = kMax;
  EXPECT_EQ(input_error([&] { c.validate(); }),
            "cache capacity 16384 bytes is below one set (2147483647 ways x 1024-byte lines)");
  c.ways = 67108864;  // x 64 = 2^32: wrapped to 0 as int (SIGFPE in the modulo)
  c.line_bytes = 64;
  EXPECT_EQ(input_error([&] { c.validate(); }), "cache capacity 16384 bytes is below one set (67108864 ways x 64-byte lines)");
  // The largest valid cache: 1 GiB, 1024 ways of 1024-byte lines (1024 sets) constructs and works.
  rtl::UnitConfig big;
  big.cache.line_bytes = 1024;
  big.cache.capacity_bytes = 1 << 30;
  big.cache.ways = 1024;
  EXPECT_NO_THROW(big.validate());
  EXPECT_EQ(big.cache.sets(), 1024);
  Texture t;
  t.tile_bytes = 1024;
  t.levels.emplace_back(64, 64);
  TextureMemory mem;
  rtl::TexelCache cache(big.cache, {place_texture(mem, t, 1024)});
  rtl::TapGrid g{};
  g.cols = g.rows = 2;
  g.x = {0, 1, 0, 0};
  g.y = {0, 1, 0, 0};
  g.used = rtl::square_cells(2, 2);
  EXPECT_EQ(cache.access(0, 0, g).misses, 1);  // one 16x16 tile holds all four taps
  EXPECT_EQ(cache.access(0, 0, g).hits, 1);
}

TEST(CacheConfig, UnitConfigFieldsAreRangeChecked) {
  const auto err = [](const std::string& json) { return input_error([&] { rtl::unit_config_from_json(json, "u.json"); }); };
  EXPECT_EQ(err(R"({"memory": {"latency": 1000001}})"), "u.json: 'memory.latency' 1000001 must be in 0..1000000");
  EXPECT_EQ(err(R"({"memory": {"bytes_per_cycle": 0}})"), "u.json: 'memory.bytes_per_cycle' 0 must be in 1..65536");
  EXPECT_EQ(err(R"({"channel_depth": 65})"), "u.json: 'channel_depth' 65 must be in 1..64");
  EXPECT_EQ(err(R"({"cache": {"ways": 2147483648}})"), "u.json: 'cache.ways' 2147483648 must be in 0..1024");
  EXPECT_EQ(err(R"({"cache": {"ways": 18446744073709551615}})"), "u.json: 'cache.ways' value 18446744073709551615 is out of range");
  EXPECT_EQ(err(R"({"miss_fifo_depth": -9223372036854775808})"), "u.json: 'miss_fifo_depth' -9223372036854775808 must be in 1..65536");
  EXPECT_EQ(err(R"({"cache": {"capacity_bytes": 1.5}})"), "u.json: 'cache.capacity_bytes' must be an integer");
  EXPECT_EQ(err(R"({"memory": {"latency": 1e400}})"), "u.json: line 1, column 28: at memory.latency: number overflow parsing '1e400'");
}

// ---- The rasterizer ----

TEST(Raster, AbsurdScreenPositionsAreSkippedNotOverflowed) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const ScreenVertex a{1, 1, 0.5}, b{10, 1, 0.5}, c{1, 10, 0.5};
  ASSERT_TRUE(setup_triangle({a, b, c}, 16, 16));
  for (const double bad : {1e308, -1e308, inf, -inf, nan, 1e7}) {
    ScreenVertex v = a;
    v.x = bad;
    EXPECT_FALSE(setup_triangle({v, b, c}, 16, 16)) << bad;
    v = a;
    v.y = bad;
    EXPECT_FALSE(setup_triangle({b, v, c}, 16, 16)) << bad;
  }
  // The largest accepted positions: edge functions still exact (twice the area of a right triangle
  // with legs of 2^21 pixels = 2^29 in Q.8), coverage right (the triangle is the half x > y).
  const double m = double{1 << 20};
  const auto t = setup_triangle({ScreenVertex{-m, -m, 0.5}, ScreenVertex{m, -m, 0.5}, ScreenVertex{m, m, 0.5}}, 16, 16);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->area, (int64_t{1} << 29) * (int64_t{1} << 29));
  EXPECT_TRUE(t->covers_pixel(1, 0));
  EXPECT_FALSE(t->covers_pixel(0, 1));
}

TEST(Raster, AbsurdScenesRenderOrAreRejected) {
  // Through the parser: the scene file and key are named.
  EXPECT_EQ(input_error([] {
              parse_scene(R"({"meshes": [{"primitive": "quad", "corners": [[1e308,0,0],[1,0,0],[1,1,0],[0,1,0]],
                                          "texture": {"procedural": "checkerboard", "size": 8}}]})",
                          "v.json");
            }),
            "v.json: meshes[0].corners[0]: expected finite numbers within +-1e+06, found 1e+308");
  // Built in code (no parser): a vertex at 1e308 and a NaN UV render without undefined behaviour
  // (the sanitizer build checks that) and draw nothing from the broken triangle.
  Scene s = parse_scene(R"({"width": 16, "height": 16, "meshes": [{"primitive": "quad",
      "corners": [[-1,-1,0],[1,-1,0],[1,1,0],[-1,1,0]], "texture": {"procedural": "checkerboard", "size": 8}}]})",
                        "ok.json");
  RenderOptions o;
  o.threads = 1;
  const RenderResult clean = render_scene(s, o);
  EXPECT_GT(clean.stats.pixels, 0);
  s.meshes[0].vertices[0].pos = {1e308, 0, 0};
  s.meshes[0].vertices[2].uv = {std::nan(""), 0};
  o.ground_truth = true;
  const RenderResult r = render_scene(s, o);
  EXPECT_EQ(r.stats.triangles, 2);
}

// ---- Threads ----

TEST(Threads, CountsAreRangeChecked) {
  EXPECT_EQ(checked_thread_count("--threads", 256, true), 256);
  EXPECT_EQ(checked_thread_count("--threads", 0, true), 0);
  EXPECT_EQ(input_error([] { checked_thread_count("--threads", 100000, true); }),
            "--threads must be in 0..256 (0: all hardware threads), got 100000");
  EXPECT_EQ(input_error([] { checked_thread_count("--units", 0, false); }), "--units must be in 1..256, got 0");
  KernelErrorSpec k;
  k.threads = -1;
  EXPECT_NE(input_error([&] { k.validate(); }).find("--threads must be in 0..256"), std::string::npos);
  Scene s = load_scene("magnified");
  RenderOptions o;
  o.threads = 100000;
  EXPECT_NE(input_error([&] { render_scene(s, o); }).find("render threads 100000 outside 0..256"), std::string::npos);
}

// A refused thread (std::thread throws) must not abort: the workers started so far do the work.
TEST(Threads, ARefusedThreadLeavesTheWorkToTheOthers) {
  KernelErrorSpec k;
  k.kernel = "catmull-rom";
  k.locations = 128;
  k.threads = 1;
  const double one = kernel_error_scaled(k);
  k.threads = 8;
  for (int limit : {0, 1, 3}) {
    detail::set_thread_start_limit(limit);
    EXPECT_EQ(kernel_error_scaled(k), one) << limit;
    int ran = 0;
    EXPECT_EQ(run_workers(8, [&](int) { ++ran; }), limit + 1);
    EXPECT_EQ(ran, limit + 1);
  }
  // The scene simulation hands its units to the workers that exist.
  Scene s = load_scene("magnified");
  s.width = s.height = 64;
  RenderOptions ro;
  ro.trace = true;
  const RenderResult render = render_scene(s, ro);
  rtl::SceneSimOptions so;
  so.units = 4;
  detail::set_thread_start_limit(0);
  const rtl::SceneSimResult alone = rtl::simulate_scene(s, render, rtl::UnitConfig{}, so);
  detail::set_thread_start_limit(-1);
  const rtl::SceneSimResult all = rtl::simulate_scene(s, render, rtl::UnitConfig{}, so);
  EXPECT_TRUE(alone.mismatch.empty());
  EXPECT_EQ(alone.image.texels, all.image.texels);
  EXPECT_EQ(alone.cycles, all.cycles);
  // Exceptions of any worker reach the caller.
  EXPECT_THROW(run_workers(4, [](int w) {
                 if (w == 2) throw InputError("w2");
               }),
               InputError);
}

// ---- No false deadlock on valid configurations ----

TEST(Watchdog, ValidExtremeConfigurationsRunToTheEnd) {
  Scene s = load_scene("text_quad");
  s.width = s.height = 16;
  RenderOptions ro;
  ro.trace = true;
  const RenderResult render = render_scene(s, ro);
  struct Case {
    int line_bytes, capacity, ways, latency, bandwidth, fifo;
  };
  for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "EDGE_PRESERVING", "CUBIC"}) {
    ro.filter = filter_mode_from_name(mode);
    ro.line_bytes = 64;
    const RenderResult render64 = render_scene(s, ro);
    ro.line_bytes = 256;
    const RenderResult render256 = render_scene(s, ro);
    // Latencies of 300,000 cycles: three times the old fixed 100,000-cycle watchdog, with the clocked
    // engine stepping every cycle (10^6 took 48 s of CI time; TheLimitCoversTheSlowestMemoryResponse
    // checks the limit at 10^6).
    for (const Case& c : {Case{64, 64, 1, 5000, 16, 128}, Case{256, 256, 1, 300000, 1, 1}, Case{256, 256, 1, 300000, 1, 1024},
                          Case{64, 16384, 4, 300000, 65536, 1}}) {
      rtl::UnitConfig u;
      u.cache.line_bytes = c.line_bytes;
      u.cache.capacity_bytes = c.capacity;
      u.cache.ways = c.ways;
      u.memory.latency = c.latency;
      u.memory.bytes_per_cycle = c.bandwidth;
      u.miss_fifo_depth = c.fifo;
      u.line_buffer_depth = 65536;  // the largest: the 1,024-entry FIFO's misses all overlap (a smaller one serializes them)
      ASSERT_NO_THROW(u.validate());
      const std::string what = fmt::format("{} line={} cap={} lat={} bw={} fifo={}", mode, c.line_bytes, c.capacity, c.latency,
                                           c.bandwidth, c.fifo);
      rtl::SceneSimResult r;
      rtl::SceneSimOptions so;
      so.engine = rtl::UnitEngine::Clocked;  // the clocked unit's watchdog
      ASSERT_NO_THROW(r = rtl::simulate_scene(s, c.line_bytes == 64 ? render64 : render256, u, so)) << what;
      EXPECT_TRUE(r.mismatch.empty()) << what;
      // Every miss waits at least the latency: the run is long (the old fixed 100,000-cycle watchdog
      // failed these latencies).
      EXPECT_GE(r.cycles, static_cast<uint64_t>(c.latency)) << what;
    }
  }
}

TEST(Watchdog, TheLimitCoversTheSlowestMemoryResponse) {
  rtl::UnitConfig u;
  u.cache.line_bytes = 256;
  u.memory.latency = 1000000;
  u.memory.bytes_per_cycle = 1;
  // 16 lines of 256 bytes at one byte per cycle plus the latency, twice, plus slack.
  EXPECT_EQ(rtl::no_progress_limit(u), 2 * (16 * 256 + 1000000 + 16 + 64) + 10000u);
  u = rtl::UnitConfig{};
  EXPECT_EQ(rtl::no_progress_limit(u), 2 * (16 * 4 + 100 + 16 + 64) + 10000u);
}

}  // namespace
}  // namespace tfu

namespace tfu {
namespace {

// Units (docs/cycle-model.md "Units and threads"): the cycle model's image does not depend on the
// number of units (nor on threads: each unit is deterministic), except for EDGE_PRESERVING under
// the cache-aware shape policy, whose T/L choices depend on what each unit's own cache holds.
TEST(Units, TheImageDependsOnUnitsOnlyUnderCacheAwareShapes) {
  Scene s = load_scene("text_quad");
  s.width = 64;
  s.height = 64;
  RenderOptions ro;
  ro.trace = true;
  bool cache_aware_differs = false;
  for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "CUBIC", "NEAREST_MIPMAP_NEAREST", "EDGE_PRESERVING", "EDGE_PRESERVING_MIPMAP_LINEAR"}) {
    ro.filter = filter_mode_from_name(mode);
    for (const char* policy : {"static", "cross", "cache-aware"}) {
      ro.sampler_overrides["edge_shape"] = policy;
      const RenderResult render = render_scene(s, ro);
      rtl::SceneSimOptions so;
      so.units = 1;
      const rtl::SceneSimResult one = rtl::simulate_scene(s, render, rtl::UnitConfig{}, so);
      so.units = 3;
      const rtl::SceneSimResult three = rtl::simulate_scene(s, render, rtl::UnitConfig{}, so);
      EXPECT_TRUE(one.mismatch.empty() && three.mismatch.empty()) << mode;
      const bool same = one.image.texels == three.image.texels;
      if (std::string(policy) == "cache-aware" && ro.filter->base == BaseFilter::EdgePreserving) {
        cache_aware_differs = cache_aware_differs || !same;
      } else {
        EXPECT_TRUE(same) << mode << " " << policy;
      }
    }
  }
  EXPECT_TRUE(cache_aware_differs);  // the documented exception is real on this scene
}

}  // namespace
}  // namespace tfu

namespace tfu {
namespace {

// Found by the trace fuzzer (corpus/trace/found-nan-inf-ideal-path.txt): the ideal path converted a
// NaN coordinate to an integer (undefined behaviour). It now treats non-finite coordinates as the
// datapath does: NaN -> 0, +-Inf saturates.
TEST(Sampler, IdealPathTakesNonFiniteCoordinates) {
  Procedural p = make_procedural("checkerboard", 16);
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  for (const char* mode : {"NEAREST", "LINEAR_MIPMAP_LINEAR", "CUBIC", "EDGE_PRESERVING"}) {
    SamplerDescriptor cfg;
    cfg.mode = filter_mode_from_name(mode);
    const Sampler smp(p.texture, cfg);
    EXPECT_EQ(smp.sample_ideal(nan, 0.3, 0), smp.sample_ideal(0, 0.3, 0)) << mode;
    EXPECT_EQ(smp.sample_ideal(0.3, nan, 0), smp.sample_ideal(0.3, 0, 0)) << mode;
    for (const float v : {inf, -inf}) {
      const auto c = smp.sample_ideal(v, 0.3, 0);
      for (double x : c) EXPECT_TRUE(std::isfinite(x)) << mode;
    }
  }
}

}  // namespace
}  // namespace tfu

namespace tfu {
namespace {

// The montage's size is computed in 64 bits and bounded (many wide images must not wrap an int).
TEST(Montage, TheLayoutSizeIsBounded) {
  const std::vector<Image> wide(3, Image(16384, 1));
  EXPECT_EQ(input_error([&] { montage_layout(wide, 3, 0); }),
            "montage would be 49168x9 pixels, more than 32768 per side (use fewer or smaller images, or --columns)");
  EXPECT_EQ(montage_layout(wide, 1, 0).width, 4 + 16384 + 4);
}

}  // namespace
}  // namespace tfu
