// The streamed scene simulation (rtl/scene_sim.hpp, render_and_simulate_scene; docs/cycle-model.md,
// "Streaming"): the render hands its trace band by band to the units, each unit runs on a bounded
// window of its requests, and the golden compare and the image take the results chunk by chunk.
// Its results must be those of the whole-frame path byte for byte (image, cycles, every statistic)
// for any number of units and threads, and those recorded from the whole-frame implementation
// before streaming existed; and the request stream itself must hand over every request in order
// through a window much smaller than the run, never leave its producer waiting on a unit that
// stopped, and (push_each) never hold one unit's requests behind another unit's full window.
#include <chrono>
#include <cstdint>
#include <future>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/request_stream.hpp"
#include "rtl/scene_sim.hpp"

namespace tfu::rtl {
namespace {

// FNV-1a, 64 bits.
uint64_t stream_fnv1a(const void* data, size_t n) {
  uint64_t h = 0xcbf29ce484222325ull;
  const auto* p = static_cast<const uint8_t*>(data);
  for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}
uint64_t stream_image_hash(const Image& im) { return stream_fnv1a(im.texels.data(), im.texels.size() * sizeof(Rgba8)); }
// The hash of a section of the statistics ("counters", "histograms") as compact JSON with sorted
// keys (Python's json.dumps(sort_keys=True, separators=(',', ':')) of the same section).
uint64_t stream_section_hash(const sim::Stats& st, const char* section) {
  const std::string s = nlohmann::json::parse(st.json_text()).at(section).dump();
  return stream_fnv1a(s.data(), s.size());
}

struct StreamCase {
  const char* scene;
  int width, height;
  const char* filter;  // nullptr: the scene's own
  const char* policy;  // edge shapes
  const char* max_aniso;
};

RenderedSceneSim run_case(const StreamCase& c, int units, int threads, bool whole_frame) {
  Scene s = load_scene(c.scene);
  s.width = c.width;
  s.height = c.height;
  RenderOptions ro;
  if (c.filter != nullptr) ro.filter = filter_mode_from_name(c.filter);
  if (c.policy != nullptr) ro.sampler_overrides["edge_shape"] = c.policy;
  if (c.max_aniso != nullptr) ro.sampler_overrides["max_aniso"] = c.max_aniso;
  ro.threads = threads;
  SceneSimOptions so;
  so.units = units;
  so.threads = threads;
  so.whole_frame = whole_frame;
  return render_and_simulate_scene(s, ro, UnitConfig{}, so);
}

// Streamed against whole-frame: the same image, requests, cycles and statistics (every counter,
// value, histogram, table and group), for 1 and 3 units and 1 or 3 threads, on a scene of two
// stages per pixel (base x light map), on cache-aware edge-preserving shapes (recorded per request
// in the window) and on anisotropic probes. One unit on the light-mapped scene takes 134,312
// requests: twice round its window of kStreamWindow.
TEST(SceneStream, SameResultsAsTheWholeFrame) {
  const StreamCase cases[] = {{"lightmapped", 384, 288, nullptr, nullptr, nullptr},
                              {"text_quad", 256, 192, "EDGE_PRESERVING_MIPMAP_LINEAR", "cache-aware", nullptr},
                              {"grazing", 192, 128, "LINEAR_MIPMAP_LINEAR", nullptr, "8"}};
  for (const StreamCase& c : cases)
    for (const int units : {1, 3}) {
      const RenderedSceneSim whole = run_case(c, units, 2, true);
      ASSERT_FALSE(whole.streamed);
      ASSERT_TRUE(whole.sim.mismatch.empty()) << whole.sim.mismatch;
      for (const int threads : {1, 3}) {
        const RenderedSceneSim streamed = run_case(c, units, threads, false);
        const std::string what =
            fmt::format("{} {} units {} threads {}", c.scene, c.filter ? c.filter : "", units, threads);
        ASSERT_TRUE(streamed.streamed) << what;
        EXPECT_TRUE(streamed.render.trace.requests.empty()) << what;  // the render held no trace
        EXPECT_TRUE(streamed.sim.mismatch.empty()) << what << ": " << streamed.sim.mismatch;
        EXPECT_EQ(streamed.sim.requests, whole.sim.requests) << what;
        EXPECT_EQ(streamed.sim.cycles, whole.sim.cycles) << what;
        EXPECT_EQ(streamed.sim.stats.json_text(), whole.sim.stats.json_text()) << what;
        EXPECT_TRUE(streamed.sim.image.texels == whole.sim.image.texels) << what;
        EXPECT_TRUE(streamed.render.image.texels == whole.render.image.texels) << what;
      }
    }
}

// Recorded with `tfu sim --out --stats` of the whole-frame implementation before streaming existed
// (main at 3e5f1a3): the image's FNV-1a and the counters' and histograms' hashes (stream_section_hash,
// computed by Python from the statistics file), cycles and requests.
TEST(SceneStream, SameResultsAsRecordedBeforeStreaming) {
  struct StreamRecorded {
    StreamCase c;
    int units;
    size_t requests;
    uint64_t cycles, image, counters, histograms;
  };
  const StreamRecorded recorded[] = {
      {{"lightmapped", 384, 288, nullptr, nullptr, nullptr},
       1,
       134312,
       200749,
       0xe1eafc5a15234b33ull,
       0xbd6976aae13091c5ull,
       0xc4a5b1e5595d69b9ull},
      {{"text_quad", 448, 336, "EDGE_PRESERVING", "cache-aware", nullptr},
       2,
       83272,
       41852,
       0x5007b0d692efe9c1ull,
       0x62246f6f6f6fd685ull,
       0x6ca558c70ab8faacull},
  };
  for (const StreamRecorded& r : recorded) {
    const RenderedSceneSim got = run_case(r.c, r.units, 2, false);
    ASSERT_TRUE(got.streamed) << r.c.scene;
    EXPECT_TRUE(got.sim.mismatch.empty()) << got.sim.mismatch;
    EXPECT_EQ(got.sim.requests, r.requests) << r.c.scene;
    EXPECT_EQ(got.sim.cycles, r.cycles) << r.c.scene;
    EXPECT_EQ(stream_image_hash(got.sim.image), r.image) << r.c.scene;
    EXPECT_EQ(stream_section_hash(got.sim.stats, "counters"), r.counters) << r.c.scene;
    EXPECT_EQ(stream_section_hash(got.sim.stats, "histograms"), r.histograms) << r.c.scene;
  }
}

// What does not stream runs on the whole frame (and says so): a waveform, the clocked engine, the
// engine compare, a memory system the units share, a raster order other than scanline.
TEST(SceneStream, WhatStreams) {
  RenderOptions ro;
  SceneSimOptions so;
  UnitConfig u;
  EXPECT_TRUE(streams_scene(ro, u, so));
  SceneSimOptions clocked = so;
  clocked.engine = UnitEngine::Clocked;
  EXPECT_FALSE(streams_scene(ro, u, clocked));
  SceneSimOptions compare = so;
  compare.compare_engines = true;
  EXPECT_FALSE(streams_scene(ro, u, compare));
  UnitConfig shared = u;
  shared.memory.shared = 1;
  EXPECT_FALSE(streams_scene(ro, shared, so));
  RenderOptions tiled = ro;
  tiled.raster = raster_order_from_name("tiled:8");
  EXPECT_FALSE(streams_scene(tiled, u, so));
}

// The request stream: a producer pushing in uneven batches through a window of 16 requests, the
// consumer reading each request once it exists and releasing them 8 at a time, sees every request
// in order; a consumer that gives up releases a producer waiting on a full window.
TEST(SceneStream, TheStreamHandsOverEveryRequestInOrder) {
  constexpr size_t kWindow = 16, kTotal = 10000;
  RequestStream stream(TraceMode::Quad, kWindow);
  std::thread producer([&] {
    std::vector<TraceRequest> batch;
    for (size_t next = 0, size = 1; next < kTotal; size = size % 37 + 1) {
      batch.clear();
      for (size_t k = 0; k < size && next < kTotal; ++k, ++next) {
        TraceRequest r;
        r.x = static_cast<uint16_t>(next & 0xFFFF);
        r.s = static_cast<float>(next);
        batch.push_back(r);
      }
      EXPECT_TRUE(stream.push(batch.data(), batch.size()));
    }
    stream.close();
  });
  size_t seen = 0;
  for (size_t i = 0; stream.has(i); ++i) {
    EXPECT_EQ(stream[i].s, static_cast<float>(i));
    ++seen;
    if ((i + 1) % 8 == 0) stream.release(i + 1);
  }
  producer.join();
  EXPECT_EQ(seen, kTotal);
  EXPECT_EQ(stream.produced(), kTotal);

  RequestStream stuck(TraceMode::Quad, 4);
  std::thread waiting([&] {
    const std::vector<TraceRequest> eight(8);
    EXPECT_FALSE(stuck.push(eight.data(), eight.size()));  // waits for room, then is told to stop
  });
  ASSERT_TRUE(stuck.has(3));
  stuck.abandon();
  waiting.join();
  EXPECT_EQ(stuck.produced(), 4u);
}

// push_each, one producer handing a band's shares of 5,000 requests each to two units' streams of
// 16-request windows: unit A reads nothing until unit B has read all of its share, so B's requests
// must get past A's full window (push() stream after stream would wait on A's window for ever: A
// would wait out its 30 s and the first expectation fail). Both see every request in order; an
// offer to a full window takes nothing, and one to a unit that gave up takes (drops) everything.
TEST(SceneStream, PushEachFeedsEveryUnitPastAFullWindow) {
  constexpr size_t kWindow = 16, kTotal = 5000;
  RoomSignal room;
  RequestStream a(TraceMode::Quad, kWindow, &room), b(TraceMode::Quad, kWindow, &room);
  std::promise<void> b_done;
  std::future<void> b_finished = b_done.get_future();
  std::vector<TraceRequest> for_a(kTotal), for_b(kTotal);
  for (size_t i = 0; i < kTotal; ++i) {
    for_a[i].s = for_b[i].s = static_cast<float>(i);
    for_b[i].t = 1;
  }
  std::thread producer([&] {
    push_each(room, {{&a, for_a.data(), for_a.size()}, {&b, for_b.data(), for_b.size()}});
    a.close();
    b.close();
  });
  // Reads the kTotal requests (the stream closes only once both shares are in).
  const auto read_all = [](RequestStream& st, float unit) {
    size_t seen = 0;
    for (size_t i = 0; i < kTotal && st.has(i); ++i) {
      EXPECT_EQ(st[i].s, static_cast<float>(i));
      EXPECT_EQ(st[i].t, unit);
      ++seen;
      if ((i + 1) % 4 == 0) st.release(i + 1);
    }
    return seen;
  };
  size_t seen_a = 0;
  std::thread unit_a([&] {
    EXPECT_EQ(b_finished.wait_for(std::chrono::seconds(30)), std::future_status::ready)
        << "unit B's requests were held behind unit A's full window";
    seen_a = read_all(a, 0);
  });
  EXPECT_EQ(read_all(b, 1), kTotal);
  b_done.set_value();
  unit_a.join();
  producer.join();
  EXPECT_EQ(seen_a, kTotal);
  EXPECT_FALSE(a.has(kTotal));  // closed after the last
  EXPECT_FALSE(b.has(kTotal));
  EXPECT_EQ(a.produced(), kTotal);
  EXPECT_EQ(b.produced(), kTotal);

  RequestStream full(TraceMode::Quad, 4, &room);
  const std::vector<TraceRequest> six(6);
  EXPECT_EQ(full.offer(six.data(), six.size()), 4u);  // room for 4
  EXPECT_EQ(full.offer(six.data(), six.size()), 0u);  // none left: takes nothing, does not wait
  const uint64_t before = room.generation();
  full.release(2);  // frees 2 and tells the producer
  EXPECT_GT(room.generation(), before);
  EXPECT_EQ(full.offer(six.data(), six.size()), 2u);
  full.abandon();
  EXPECT_EQ(full.offer(six.data(), six.size()), 6u);  // dropped: the unit has given up
  EXPECT_EQ(full.produced(), 6u);
}

// A streamed run's speed figures (StreamTimes, RenderTimes::bands_cpu; `tfu sim --bench`) are
// there: one entry per unit, CPU seconds spent by the band workers and by every unit that drew
// something, a wall clock at least the upload's, and no negative wait.
TEST(SceneStream, StreamedRunReportsItsThreadsTimes) {
  const RenderedSceneSim r = run_case({"lightmapped", 192, 144, nullptr, nullptr, nullptr}, 2, 2, false);
  ASSERT_TRUE(r.streamed);
  ASSERT_EQ(r.times.unit_cpu.size(), 2u);
  ASSERT_EQ(r.times.unit_wait.size(), 2u);
  EXPECT_GT(r.render.times.bands_cpu, 0.0);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_GT(r.times.unit_cpu[k], 0.0) << k;
    EXPECT_GE(r.times.unit_wait[k], 0.0) << k;
  }
  EXPECT_GE(r.times.handoff_wait, 0.0);
  EXPECT_GE(r.times.wall, r.render.times.upload);
}

}  // namespace
}  // namespace tfu::rtl
