// The filter datapaths' pipeline depth (unit configuration filter.edge_stages, filter.bilinear_stages;
// rtl/datapath_depth.hpp, rtl/pipeline_registers.hpp): the offered depths are the SV tops'
// latencies as their parameters give them; a deeper datapath adds its extra clocks to each
// request's latency and nothing to the rate, in both engines, with every pixel the golden model's.
#include <gtest/gtest.h>

#include <bit>
#include <fstream>
#include <regex>
#include <sstream>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/scene.hpp"
#include "rtl/datapath_depth.hpp"
#include "rtl/golden_compare.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_config.hpp"
#include "testbench/one_texture.hpp"
#include "testbench/scene_trace.hpp"

namespace tfu::rtl {
namespace {

std::string sv_source(const std::string& path) {
  std::ifstream f(std::string(TFU_DOCS_DIR) + "/../rtl/sv/" + path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The first match of `pattern`'s group 1 in `text` as binary digits ('_' skipped); -1 if none.
int binary_parameter(const std::string& text, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(text, m, std::regex(pattern))) return -1;
  int v = 0;
  for (const char c : m[1].str())
    if (c != '_') v = 2 * v + (c - '0');
  return v;
}

// The latency of each SV top as its parameters set it: tfu_edge_interp_top's LATENCY =
// 1 + popcount(CUTS) (default CUTS, or the wrapper's), tfu_bilinear_top's 3 + CUT_V.
int sv_latency(const std::string& top) {
  if (top.starts_with("tfu_edge_interp_top")) {
    const std::string text = sv_source("edge/" + top + ".sv");
    int cuts = binary_parameter(text, R"(parameter logic \[7:0\] CUTS = 8'b([01_]+))");
    if (cuts < 0) cuts = binary_parameter(text, R"(tfu_edge_interp_top #\(\.CUTS\(8'b([01_]+)\)\))");
    return cuts < 0 ? -1 : 1 + std::popcount(static_cast<unsigned>(cuts));
  }
  const std::string text = sv_source(top + ".sv");
  int cut_v = binary_parameter(text, R"(parameter bit CUT_V = 1'b([01]))");
  if (cut_v < 0) cut_v = binary_parameter(text, R"(tfu_bilinear_top #\(\.CUT_V\(1'b([01])\)\))");
  return cut_v < 0 ? -1 : 3 + cut_v;
}

TEST(DatapathDepth, OfferedDepthsAreTheSvTopsLatencies) {
  // The SV tops' testbenches measure these latencies in simulation (sv.edge TopBench, sv
  // bilinear top); here the model's table is held to the tops' parameters.
  for (const OfferedDepth& d : kEdgeDepths) EXPECT_EQ(sv_latency(d.sv_top), d.clocks) << d.sv_top;
  for (const OfferedDepth& d : kBilinearDepths) EXPECT_EQ(sv_latency(d.sv_top), d.clocks) << d.sv_top;
  EXPECT_EQ(sv_latency("tfu_edge_interp_top"), 3);  // Lee & Jen Sec. 6: three clocks
  EXPECT_EQ(sv_latency("tfu_edge_interp_top_l8"), 8);
  EXPECT_EQ(sv_latency("tfu_bilinear_top"), 3);
  EXPECT_EQ(sv_latency("tfu_bilinear_top_l4"), 4);
  // The fields allow the model's own depth and the tops'; the defaults are the model's blocks.
  EXPECT_EQ(find_unit_field("filter.edge_stages")->allowed, (std::vector<int64_t>{3, 8}));
  EXPECT_EQ(find_unit_field("filter.bilinear_stages")->allowed, (std::vector<int64_t>{2, 3, 4}));
  EXPECT_EQ(UnitConfig{}.filter.edge_stages, 3);
  EXPECT_EQ(UnitConfig{}.filter.bilinear_stages, 2);
  const auto error = test::unit_config_error;
  EXPECT_EQ(error(R"({"filter": {"edge_stages": 4}})"), "c.json: 'filter.edge_stages' 4 must be one of 3, 8");
  EXPECT_EQ(error(R"({"filter": {"bilinear_stages": 1}})"),
            "c.json: 'filter.bilinear_stages' 1 must be one of 2, 3, 4");
  EXPECT_EQ(error(R"({"filter": {"edge_stages": "8"}})"), "c.json: 'filter.edge_stages' must be an integer");
  EXPECT_EQ(error(R"({"filter": {"depth": 8}})").find("unknown key 'filter.depth'") != std::string::npos, true);
  UnitConfig deep;
  deep.filter = {8, 4};
  EXPECT_EQ(unit_config_from_json(unit_config_to_json(deep), "deep"), deep);
}

using test::one_texture;
using test::OneTexture;

// Both engines: equal outputs, cycles and statistics, every pixel the golden model's; the run.
UnitOutput run_both(const OneTexture& one, const UnitConfig& u, const std::string& what) {
  const UnitOutput c = run_unit(one.frame, one.trace, u, UnitEngine::Clocked, VcdOptions{});
  const UnitOutput r = run_unit(one.frame, one.trace, u, UnitEngine::Recurrence, VcdOptions{});
  EXPECT_EQ(c.cycles, r.cycles) << what;
  EXPECT_EQ(c.response_cycle, r.response_cycle) << what;
  EXPECT_EQ(c.stats.json_text(), r.stats.json_text()) << what;
  const GoldenUnit golden(one.frame);
  EXPECT_EQ(first_mismatch(one.trace, golden_outputs(golden, one.trace, c), c), "") << what;
  EXPECT_EQ(c.pixels, r.pixels) << what;
  return c;
}

// A cache holding the whole texture and a memory without latency: only the datapath remains.
UnitConfig hot_cache(int edge_stages, int bilinear_stages) {
  UnitConfig u;
  u.cache.capacity_bytes = 64 * 64 * 4 * 2;
  u.memory.latency = 0;
  u.memory.bytes_per_cycle = 1024;
  u.filter = {edge_stages, bilinear_stages};
  return u;
}

TEST(DatapathDepth, IsolatedRequestLatencyGrowsByTheExtraClocks) {
  // One request whose every footprint lies inside block (1, 1) of level 0 (as TfuUnit.LatencyPerMode):
  // accepted at cycle 0, one clock in each of lod_unit, address_gen, kernel_select, texel_cache,
  // the one-cycle miss, the filter's clock and response: 7 for LINEAR; EDGE_PRESERVING two more
  // (three edge blocks). Each register beyond the blocks adds one clock.
  const test::SceneTrace st = test::scene_trace("magnified", 16, 16);
  Trace one;
  one.mode = TraceMode::Lod;
  TraceRequest r;
  r.s = r.t = 6.0f / 64.0f;
  r.lod = -1.0f;
  one.requests.push_back(r);
  const auto latency = [&](const char* mode, int edge_stages, int bilinear_stages) {
    const UnitConfig u = hot_cache(edge_stages, bilinear_stages);
    const UnitOutput o = run_both(one_texture(st.scene.meshes.front(), mode, one, u), u, mode);
    EXPECT_EQ(o.stats.counter("cache_line_misses"), 1u) << mode;
    return o.stats.value("latency_max");
  };
  EXPECT_EQ(latency("EDGE_PRESERVING", 3, 2), 9.0);
  EXPECT_EQ(latency("EDGE_PRESERVING", 8, 2), 14.0);  // tfu_edge_interp_top_l8: five clocks more
  EXPECT_EQ(latency("EDGE_PRESERVING", 8, 4), 14.0);  // the filter's depth is not the edge path's
  EXPECT_EQ(latency("LINEAR", 3, 2), 7.0);
  EXPECT_EQ(latency("LINEAR", 3, 3), 8.0);  // tfu_bilinear_top: S2 and S3 after the cache's register
  EXPECT_EQ(latency("LINEAR", 3, 4), 9.0);  // tfu_bilinear_top_l4
  EXPECT_EQ(latency("LINEAR", 8, 2), 7.0);
  EXPECT_EQ(latency("NEAREST", 3, 4), 9.0);  // one filter pipeline for every mode it filters
  EXPECT_EQ(latency("CUBIC", 3, 4), 12.0);   // four clocks in one lane, then the two registers
}

TEST(DatapathDepth, LongRunsKeepOnePixelPerClock) {
  // 4096 requests on hits: a pipelined datapath takes one footprint per clock at any depth, so the
  // whole run is longer by the extra clocks once (the last pixel's), not once per request.
  const test::SceneTrace st = test::scene_trace("magnified", 64, 64);
  const Mesh& mesh = st.scene.meshes.front();
  Trace twice = st.trace;  // the second pass hits everywhere
  twice.requests.insert(twice.requests.end(), st.trace.requests.begin(), st.trace.requests.end());
  const auto cycles = [&](const char* mode, int edge_stages, int bilinear_stages) {
    const UnitConfig u = hot_cache(edge_stages, bilinear_stages);
    const OneTexture one = one_texture(mesh, mode, twice, u);
    const UnitOutput o = run_both(one, u, mode);
    // Clocks per pixel of the second pass: 1.
    const uint64_t n = st.trace.requests.size();
    EXPECT_EQ(o.response_cycle[2 * n - 1] - o.response_cycle[n - 1], n) << mode;
    return static_cast<int64_t>(o.cycles);
  };
  EXPECT_EQ(cycles("EDGE_PRESERVING", 8, 2) - cycles("EDGE_PRESERVING", 3, 2), 5);
  EXPECT_EQ(cycles("LINEAR", 3, 4) - cycles("LINEAR", 3, 2), 2);
  EXPECT_EQ(cycles("LINEAR", 3, 3) - cycles("LINEAR", 3, 2), 1);
}

TEST(DatapathDepth, FilterAndEdgeSamplersInterleavedAtEveryDepth) {
  // Filter and edge footprints in one stream, each datapath at its own depth: the response block
  // takes the pixels in request order from paths of different latencies; with a small cache, a
  // one-entry channel depth and misses, the registers stall too.
  const test::SceneTrace st = test::scene_trace("ground_plane", 48, 32);
  const Mesh& mesh = st.scene.meshes.front();
  for (const int channel_depth : {1, 2})
    for (const int edge_stages : {3, 8})
      for (const int bilinear_stages : {2, 3, 4}) {
        UnitConfig u;
        u.cache.capacity_bytes = 2048;
        u.memory.latency = 30;
        u.channel_depth = channel_depth;
        u.filter = {edge_stages, bilinear_stages};
        FrameBuilder b(u.cache.line_bytes);
        b.add_texture(mesh.stages[0].texture, {"test", {}});
        for (const char* mode :
             {"LINEAR_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_LINEAR", "NEAREST", "EDGE_PRESERVING"}) {
          SamplerDescriptor s = mesh.stages[0].sampler;
          s.mode = filter_mode_from_name(mode);
          b.add_sampler(s);
        }
        Trace tr = st.trace;
        for (size_t i = 0; i < tr.requests.size(); ++i) {
          tr.requests[i].texture = 0;
          tr.requests[i].sampler = static_cast<uint8_t>((i / 4) % 4);  // per quad
        }
        bind_requests(b, tr);
        const OneTexture one{b.finish(), std::move(tr)};
        run_both(one, u,
                 fmt::format("channel depth {}, edge {}, bilinear {}", channel_depth, edge_stages, bilinear_stages));
      }
}

}  // namespace
}  // namespace tfu::rtl
