// Cycle model (rtl/) against the golden model, bit for bit: every scene x every filter mode x two
// cache line sizes (the CI matrix of the cycle model), every kernel-shape policy, vs16x2, lod and grad
// traces, every wrap mode; requests of several textures (formats, layouts) and samplers
// interleaved at random; rates, latencies, the Lee & Jen bandwidth claim; the edge datapath's
// blocks against the cmodel functions they implement; config and VCD; anisotropic pixels (N = 1..16
// on random derivative requests and scenes, degenerate gradients, probe statistics, rates on hits).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/procedural.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/address_gen.hpp"
#include "rtl/edge_datapath.hpp"
#include "rtl/engine_compare.hpp"
#include "rtl/golden_compare.hpp"
#include "rtl/median_network.hpp"
#include "rtl/tfu_unit.hpp"
#include "testbench/docs_text.hpp"
#include "testbench/iterations.hpp"
#include "testbench/one_texture.hpp"
#include "testbench/scene_trace.hpp"

namespace tfu::rtl {
namespace {

using test::scene_trace;
using test::SceneTrace;

using test::one_texture;
using test::OneTexture;

// Checks every output of a run against the golden model.
void expect_golden(const Frame& frame, const Trace& tr, const UnitOutput& got, const std::string& what) {
  ASSERT_EQ(got.pixels.size(), tr.requests.size()) << what;
  const GoldenUnit golden(frame);
  const std::string mismatch = first_mismatch(tr, golden_outputs(golden, tr, got), got);
  EXPECT_TRUE(mismatch.empty()) << what << ": " << mismatch;
}

UnitOutput run_one(const Texture& tex, const SamplerDescriptor& cfg, const Trace& tr, const UnitConfig& u,
                   std::ostream* vcd = nullptr, const ClockedOptions& clocked = {}) {
  const OneTexture one = one_texture(tex, cfg, tr, u);
  return run_unit(one.frame, one.trace, u, VcdOptions{vcd}, clocked);
}

// Runs the unit and checks every pixel against the golden model; returns the run.
UnitOutput run_and_compare(const Texture& tex, const SamplerDescriptor& cfg, const Trace& tr, const UnitConfig& u,
                           const std::string& what) {
  const OneTexture one = one_texture(tex, cfg, tr, u);
  UnitOutput got = run_unit(one.frame, one.trace, u);
  expect_golden(one.frame, one.trace, got, what);
  return got;
}

// B = 4: 64-byte lines (4x4 RGBA8 tiles); B = 8: 256-byte lines (8x8).
UnitConfig small_cache(int block) {
  UnitConfig u;
  u.cache.line_bytes = block * block * 4;
  u.cache.capacity_bytes = 8192;
  u.cache.ways = 2;
  return u;
}

// The CI matrix: every scene x every filter mode x B = 4 and 8, at a reduced resolution.
class EveryModeAndBlock : public ::testing::TestWithParam<const char*> {};

TEST_P(EveryModeAndBlock, BitExactAgainstGolden) {
  const SceneTrace st = scene_trace(GetParam(), 64, 48);
  const Mesh& mesh = st.scene.meshes.front();
  for (const FilterMode& m : all_filter_modes())
    for (int block : {4, 8}) {
      SamplerDescriptor cfg = mesh.stages[0].sampler;
      cfg.mode = m;
      const UnitOutput got =
          run_and_compare(*mesh.stages[0].texture, cfg, st.trace, small_cache(block),
                          fmt::format("{} {} B={}", GetParam(), filter_mode_name(m), block));
      EXPECT_GT(got.stats.counter("cache_line_misses"), 0u);
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, EveryModeAndBlock,
                         ::testing::Values("magnified", "ground_plane", "text_quad", "object", "text_patch"));

TEST(TfuUnit, EveryShapePolicyAndBankMapping) {
  const SceneTrace st = scene_trace("text_quad", 64, 48);
  const Mesh& mesh = st.scene.meshes.front();
  for (const char* mode : {"EDGE_PRESERVING", "EDGE_PRESERVING_MIPMAP_LINEAR"})
    for (EdgeShape p : {EdgeShape::Static, EdgeShape::CacheAware, EdgeShape::Cross})
      for (BankMapping b : {BankMapping::TexelParity, BankMapping::BlockParity}) {
        SamplerDescriptor cfg = mesh.stages[0].sampler;
        cfg.mode = filter_mode_from_name(mode);
        cfg.edge_shape = p;
        UnitConfig u = small_cache(4);
        u.cache.bank_mapping = b;
        const UnitOutput got = run_and_compare(*mesh.stages[0].texture, cfg, st.trace, u, fmt::format("{} {}", mode, edge_shape_name(p)));
        const uint64_t cross = got.stats.counter("shape_cross"), t = got.stats.counter("shape_T"),
                       l = got.stats.counter("shape_L");
        EXPECT_GT(cross + t + l, 0u);
        if (p == EdgeShape::Cross) {
          EXPECT_EQ(t + l, 0u);
        }
        if (p == EdgeShape::Static) {
          EXPECT_GT(t + l, 0u);  // a 64x64 texture magnified: block edges are common
        }
      }
}

TEST(TfuUnit, CacheAwareShapesContainTheStaticShapes) {
  const SceneTrace st = scene_trace("text_patch", 48, 32);
  const Mesh& mesh = st.scene.meshes.front();
  SamplerDescriptor cfg = mesh.stages[0].sampler;
  cfg.mode = filter_mode_from_name("EDGE_PRESERVING");
  const UnitConfig u = small_cache(4);
  cfg.edge_shape = EdgeShape::CacheAware;
  const UnitOutput aware = run_and_compare(*mesh.stages[0].texture, cfg, st.trace, u, "cache-aware");
  // The static run: its requests name a static sampler; a cache-aware one is bound beside it
  // (unused), so that the unit records the shapes (UnitOutput::edge_shapes).
  cfg.edge_shape = EdgeShape::Static;
  EXPECT_TRUE(run_one(*mesh.stages[0].texture, cfg, st.trace, u).edge_shapes.empty());  // not recorded
  FrameBuilder b(u.cache.line_bytes);
  b.add_texture(std::make_shared<const Texture>(*mesh.stages[0].texture), {"test", {}});
  b.add_sampler(cfg);
  SamplerDescriptor unused = cfg;
  unused.edge_shape = EdgeShape::CacheAware;
  b.add_sampler(unused);
  Trace tr = st.trace;
  for (TraceRequest& r : tr.requests) r.texture = r.sampler = 0;
  bind_requests(b, tr);
  const UnitOutput fixed = run_unit(b.finish(), tr, u);
  ASSERT_EQ(aware.edge_shapes.size(), tr.requests.size());
  ASSERT_EQ(aware.edge_shapes.size(), fixed.edge_shapes.size());
  size_t wider = 0;
  for (size_t i = 0; i < aware.edge_shapes.size(); ++i) {
    ASSERT_EQ(aware.edge_shapes[i][0] & fixed.edge_shapes[i][0], fixed.edge_shapes[i][0]);
    wider += aware.edge_shapes[i][0] != fixed.edge_shapes[i][0];
  }
  EXPECT_GT(wider, 0u);  // some arms were resident
  EXPECT_LT(aware.stats.counter("shape_T") + aware.stats.counter("shape_L"),
            fixed.stats.counter("shape_T") + fixed.stats.counter("shape_L"));
}

// Lee & Jen Sec. 3: with the static policy the edge-preserving filter reads exactly the lines the
// bilinear footprint reads, so memory traffic is identical; full-cross reads more.
TEST(TfuUnit, StaticShapesReadExactlyTheBilinearBytes) {
  for (const char* scene : {"text_quad", "ground_plane"}) {
    const SceneTrace st = scene_trace(scene, 64, 48);
    const Mesh& mesh = st.scene.meshes.front();
    for (int block : {4, 8}) {
      const UnitConfig u = small_cache(block);
      SamplerDescriptor cfg = mesh.stages[0].sampler;
      cfg.mode = filter_mode_from_name("LINEAR");
      const uint64_t bilinear = run_one(*mesh.stages[0].texture, cfg, st.trace, u).stats.counter("memory_bytes");
      cfg.mode = filter_mode_from_name("EDGE_PRESERVING");
      cfg.edge_shape = EdgeShape::Static;
      const uint64_t edge = run_one(*mesh.stages[0].texture, cfg, st.trace, u).stats.counter("memory_bytes");
      cfg.edge_shape = EdgeShape::Cross;
      const uint64_t full = run_one(*mesh.stages[0].texture, cfg, st.trace, u).stats.counter("memory_bytes");
      EXPECT_EQ(edge, bilinear) << scene << " B=" << block;
      // Full-cross fetches the neighbouring blocks' lines; on a magnified texture (text_quad) the
      // cache keeps them until the bilinear footprint needs them anyway, on the minified plane not.
      if (std::string(scene) == "ground_plane") {
        EXPECT_GT(full, bilinear) << scene << " B=" << block;
      } else {
        EXPECT_GE(full, bilinear) << scene << " B=" << block;
      }
    }
  }
}

TEST(TfuUnit, BitExactForEveryWrapModeAndFilterFamily) {
  const SceneTrace st = scene_trace("ground_plane", 48, 32);
  const Mesh& mesh = st.scene.meshes.front();
  for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "CUBIC_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_LINEAR", "NEAREST"})
    for (WrapMode w : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge, WrapMode::ClampToBorder}) {
      SamplerDescriptor cfg = mesh.stages[0].sampler;
      cfg.mode = filter_mode_from_name(mode);
      cfg.wrap_s = cfg.wrap_t = w;
      cfg.border = {10, 200, 30, 255};
      run_and_compare(*mesh.stages[0].texture, cfg, st.trace, UnitConfig{}, fmt::format("{} {}", mode, wrap_mode_name(w)));
    }
}

TEST(TfuUnit, CubicKernelsRomReconstructionAndBsplineInterp) {
  const SceneTrace st = scene_trace("magnified", 48, 32);
  const Mesh& mesh = st.scene.meshes.front();
  for (const char* kernel : {"catmull-rom", "bspline", "mitchell", kBsplineInterp}) {
    SamplerDescriptor cfg = mesh.stages[0].sampler;
    cfg.mode = filter_mode_from_name("CUBIC_MIPMAP_LINEAR");
    cfg.kernel = kernel;
    for (RomRecon r : {RomRecon::Nearest, RomRecon::Linear}) {
      cfg.cubic_recon = r;
      run_and_compare(*mesh.stages[0].texture, cfg, st.trace, UnitConfig{}, kernel);
    }
  }
}

TEST(TfuUnit, Vs16x2Textures) {
  // A signed two-channel texture (Strzodka 2002): values from a random field.
  Image img(32, 32);
  std::mt19937 rng(3);
  for (Rgba8& t : img.texels)
    t = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng())};
  Texture tex;
  tex.format = TexelFormat::VS16X2;
  tex.levels.push_back(std::move(img));
  generate_mipmaps(tex, MipMethod::Box);
  const SceneTrace st = scene_trace("ground_plane", 48, 32);
  for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "CUBIC", "EDGE_PRESERVING_MIPMAP_LINEAR", "NEAREST_MIPMAP_NEAREST"}) {
    SamplerDescriptor cfg;
    cfg.mode = filter_mode_from_name(mode);
    run_and_compare(tex, cfg, st.trace, UnitConfig{}, mode);
  }
}

TEST(TfuUnit, LodAndGradTraces) {
  const SceneTrace st = scene_trace("ground_plane", 32, 32);
  const Mesh& mesh = st.scene.meshes.front();
  Trace lod, grad;
  lod.mode = TraceMode::Lod;
  grad.mode = TraceMode::Grad;
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> uni(-0.5f, 1.5f), l(-2.0f, 8.0f), g(-0.05f, 0.05f);
  for (int i = 0; i < 600; ++i) {
    TraceRequest r;
    r.s = uni(rng);
    r.t = uni(rng);
    r.lod = l(rng);
    lod.requests.push_back(r);
    r.dsdx = g(rng);
    r.dtdx = g(rng);
    r.dsdy = g(rng);
    r.dtdy = g(rng);
    grad.requests.push_back(r);
  }
  for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "CUBIC_MIPMAP_NEAREST", "EDGE_PRESERVING_MIPMAP_LINEAR"}) {
    SamplerDescriptor cfg = mesh.stages[0].sampler;
    cfg.mode = filter_mode_from_name(mode);
    run_and_compare(*mesh.stages[0].texture, cfg, lod, UnitConfig{}, fmt::format("lod {}", mode));
    run_and_compare(*mesh.stages[0].texture, cfg, grad, UnitConfig{}, fmt::format("grad {}", mode));
  }
}

// A texture's name reaches the statistics as the file system or archive spelled it; JSON output is
// UTF-8 (cmodel/json_output.hpp), so a byte that is not UTF-8 (a Latin-1 file name) is written as
// U+FFFD, and a UTF-8 name exactly. Before, nlohmann threw on the byte after the run: exit 3.
TEST(TfuUnit, TextureNamesThatAreNotUtf8StillGiveValidStatistics) {
  const auto tex = std::make_shared<Texture>(make_procedural("checkerboard", 16).texture);
  const auto tex2 = std::make_shared<Texture>(make_procedural("text", 16).texture);
  FrameBuilder fb(64);
  const std::string latin1 = "textures/\xff\xfe.png", utf8 = "textures/caf\xc3\xa9.png";
  fb.add_texture(tex, TextureSpec{latin1, {}});
  fb.add_texture(tex2, TextureSpec{utf8, {}});
  fb.add_sampler(SamplerDescriptor{}, false);
  Trace tr;
  tr.mode = TraceMode::Lod;
  for (int t = 0; t < 2; ++t) {
    TraceRequest r;
    r.texture = static_cast<uint16_t>(t);
    r.s = r.t = 0.3f;
    tr.requests.push_back(r);
  }
  const Frame frame = fb.finish();
  const UnitOutput out = run_unit(frame, tr, UnitConfig{});
  const nlohmann::json j = nlohmann::json::parse(out.stats.json_text());
  const nlohmann::json& rows = j["tables"]["textures"];
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0]["name"], "0 textures/\xef\xbf\xbd\xef\xbf\xbd.png");
  EXPECT_EQ(rows[1]["name"], "1 textures/caf\xc3\xa9.png");
}

// A cache holding the whole texture and a memory without latency: only the datapath rates remain.
UnitConfig hot_cache() {
  UnitConfig u;
  u.cache.capacity_bytes = 64 * 64 * 4 * 2;
  u.memory.latency = 0;
  u.memory.bytes_per_cycle = 1024;
  return u;
}

// Clocks per pixel on hits: the trace twice through a cache that holds the whole texture, minus
// the trace once (the second pass hits everywhere).
double clocks_per_pixel_on_hits(const Texture& tex, const SamplerDescriptor& cfg, const Trace& tr, const UnitConfig& u,
                                const std::string& what) {
  Trace twice = tr;
  twice.requests.insert(twice.requests.end(), tr.requests.begin(), tr.requests.end());
  const UnitOutput a = run_and_compare(tex, cfg, tr, u, what), b = run_and_compare(tex, cfg, twice, u, what);
  return static_cast<double>(b.cycles - a.cycles) / static_cast<double>(tr.requests.size());
}

TEST(TfuUnit, RatesOnHits) {
  const SceneTrace st = scene_trace("magnified", 64, 64);
  const Mesh& mesh = st.scene.meshes.front();
  SamplerDescriptor cfg = mesh.stages[0].sampler;
  UnitConfig u = hot_cache();
  const auto rate = [&](const char* mode, const UnitConfig& uc) {
    cfg.mode = filter_mode_from_name(mode);
    return clocks_per_pixel_on_hits(*mesh.stages[0].texture, cfg, st.trace, uc, mode);
  };
  EXPECT_NEAR(rate("LINEAR", u), 1.0, 0.01);
  EXPECT_NEAR(rate("NEAREST", u), 1.0, 0.01);
  EXPECT_NEAR(rate("EDGE_PRESERVING", u), 1.0, 0.01);  // Lee & Jen: fully pipelined
  EXPECT_NEAR(rate("CUBIC", u), 4.0, 0.1);             // 16 taps, one lane of 4
  u.filter_lanes = 4;
  EXPECT_NEAR(rate("CUBIC", u), 1.0, 0.01);
  u = hot_cache();
  u.cache.bank_mapping = BankMapping::TexelParity;  // one texel per bank and clock
  EXPECT_NEAR(rate("EDGE_PRESERVING", u), 3.0, 0.05);  // the 12-texel cross over 4 banks
  EXPECT_NEAR(rate("LINEAR", u), 1.0, 0.01);
  // Magnified: lambda < 0, so trilinear never blends; force blending with a bias.
  cfg.lod.bias_q8 = 3 * 256 + 128;
  EXPECT_NEAR(rate("LINEAR_MIPMAP_LINEAR", hot_cache()), 2.0, 0.05);
  EXPECT_NEAR(rate("EDGE_PRESERVING_MIPMAP_LINEAR", hot_cache()), 2.0, 0.05);
}

TEST(TfuUnit, LatencyPerMode) {
  // One request whose every footprint (bilinear 2x2, cubic 4x4, edge cross) lies inside block (1, 1)
  // of level 0: one line, one miss of one cycle (zero-latency memory), then the pipeline.
  const SceneTrace st = scene_trace("magnified", 16, 16);
  const Mesh& mesh = st.scene.meshes.front();
  Trace one;
  one.mode = TraceMode::Lod;
  TraceRequest r;
  r.s = r.t = 6.0f / 64.0f;
  r.lod = -1.0f;
  one.requests.push_back(r);
  SamplerDescriptor cfg = mesh.stages[0].sampler;
  const auto latency = [&](const char* mode, int lanes) {
    cfg.mode = filter_mode_from_name(mode);
    UnitConfig u = hot_cache();
    u.filter_lanes = lanes;
    const UnitOutput o = run_and_compare(*mesh.stages[0].texture, cfg, one, u, mode);
    EXPECT_EQ(o.stats.counter("cache_line_misses"), 1u) << mode;
    return o.stats.value("latency_max");
  };
  // Accepted by request_fifo at cycle 0, then one clock in each of lod_unit, address_gen,
  // kernel_select, texel_cache, filter and response (6), plus the one-cycle miss.
  const double lin = latency("LINEAR", 1);
  EXPECT_EQ(lin, 7.0);
  EXPECT_EQ(latency("NEAREST", 1), lin);
  EXPECT_EQ(latency("EDGE_PRESERVING", 1), lin + 2);  // three edge stages instead of one filter stage
  EXPECT_EQ(latency("CUBIC", 1), lin + 3);            // four clocks in one lane
  EXPECT_EQ(latency("CUBIC", 4), lin);
}

// Idle-cycle skipping is a simulation speed-up only: every output, cycle and statistic is the same.
TEST(TfuUnit, IdleSkippingChangesNothing) {
  const SceneTrace st = scene_trace("text_patch", 48, 32);
  const Mesh& mesh = st.scene.meshes.front();
  for (const char* mode : {"LINEAR", "CUBIC_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_LINEAR"}) {
    SamplerDescriptor cfg = mesh.stages[0].sampler;
    cfg.mode = filter_mode_from_name(mode);
    UnitConfig u = small_cache(4);
    u.memory.latency = 300;  // memory-bound: long idle stretches
    u.memory.bytes_per_cycle = 4;
    u.miss_fifo_depth = 8;
    const UnitOutput slow = run_one(*mesh.stages[0].texture, cfg, st.trace, u, nullptr, ClockedOptions{false});
    const UnitOutput fast = run_one(*mesh.stages[0].texture, cfg, st.trace, u, nullptr, ClockedOptions{true});
    EXPECT_EQ(fast.pixels, slow.pixels) << mode;
    EXPECT_EQ(fast.response_cycle, slow.response_cycle) << mode;
    EXPECT_EQ(fast.cycles, slow.cycles) << mode;
    EXPECT_EQ(fast.stats.counters(), slow.stats.counters()) << mode;
    EXPECT_EQ(*fast.stats.histogram("latency"), *slow.stats.histogram("latency")) << mode;
    EXPECT_GT(fast.stats.counter("stall_cache_miss"), fast.cycles / 4) << mode;  // really memory-bound
  }
}

TEST(TfuUnit, DirectionSelectTreeEqualsTheGoldenArgmin) {
  std::mt19937 rng(21);
  for (int it = 0; it < 20000; ++it) {
    std::array<Texel4, lee_jen::kTexels> c{};
    const int range = it % 2 ? 256 : 3;  // small ranges: many equal costs, the tie-break decides
    for (auto& t : c) t = {static_cast<int32_t>(rng() % range), static_cast<int32_t>(rng() % range),
                           static_cast<int32_t>(rng() % range), 255};
    const uint32_t fu = rng() % 256, fv = rng() % 256;
    for (const lee_jen::KernelShape& s : lee_jen::kernel_shapes()) {
      const lee_jen::LowIndex low = lee_jen::median_low_pass(lee_jen::luma_keys(c, s.mask, TexelFormat::RGBA8), s.mask);
      const lee_jen::EdgeDecision want = lee_jen::select_direction(c, low, s.mask, fu, fv, TexelFormat::RGBA8);
      const lee_jen::EdgeDecision got = direction_select(c, low, s.mask, fu, fv, TexelFormat::RGBA8);
      ASSERT_EQ(got.direction, want.direction) << s.name();
      ASSERT_EQ(got.cost, want.cost);
    }
  }
}

// The edge datapath's three stages in one call (edge_stages_fused: the recurrences' edge
// footprints unless TFU_PLAIN=1) equal the stages' own combinational parts in turn
// (EdgeMedian::stage, EdgeDirection::stage, EdgeMerge::merge, as the clocked blocks call them):
// random footprints in sequences of pixels (one level, blending pairs, anisotropic probes of one
// or two levels), every kernel shape, RGBA8, L8 and VS16X2 words, fractions and blend weights,
// four statistics slots, texels drawn from a few values (ties for the medians and the
// direction costs) or from all; the pixels retired, their responses, and the direction histograms.
TEST(TfuUnit, EdgeFusedStagesEqualThePlainStages) {
  sim::Simulator sim;
  sim::Channel<EdgeMedianOut> median_out("edge_median_out", 2);
  sim::Channel<EdgeDirectionOut> direction_out("edge_direction_out", 2);
  sim::Channel<Response> response("edge_response", 2);
  EdgeDirection plain_direction(sim, median_out, direction_out, 1), fused_direction(sim, median_out, direction_out, 1);
  EdgeMerge plain_merge(sim, direction_out, response), fused_merge(sim, direction_out, response);
  const std::vector<lee_jen::KernelShape>& shapes = lee_jen::kernel_shapes();
  std::mt19937 rng(29);
  int retired = 0;
  for (int pixel = 0; pixel < test::iterations(20000); ++pixel) {
    const TexelFormat fmt = std::array{TexelFormat::RGBA8, TexelFormat::L8, TexelFormat::VS16X2}[rng() % 3];
    const uint32_t range = pixel % 2 == 0 ? 3 : 256;
    const int probes = pixel % 5 == 0 ? 1 + static_cast<int>(rng() % 4) : 1;
    const bool blends = rng() % 2 == 0;
    const int blend = static_cast<int>(rng() % 256);
    for (int probe = 0; probe < probes; ++probe)
      for (int level = 0; level < (blends ? 2 : 1); ++level) {
        FilterReq r{};
        r.tag.id = static_cast<uint32_t>(pixel);
        r.tag.req.stage = static_cast<uint8_t>(rng() % kStatStages);
        r.tag.base = BaseFilter::EdgePreserving;
        r.tag.format = fmt;
        r.tag.fu = rng() % 256;
        r.tag.fv = rng() % 256;
        r.tag.blends = blends;
        r.tag.is_level1 = level == 1;
        r.tag.blend = blend;
        r.tag.probes = static_cast<uint8_t>(probes);
        r.tag.probe = static_cast<uint8_t>(probe);
        r.tag.shape = shapes[rng() % shapes.size()].mask;
        r.ntaps = lee_jen::kTexels;
        for (size_t k = 0; k < lee_jen::kTexels; ++k) {
          const auto v = [&] { return static_cast<uint8_t>(rng() % range * (range == 3 ? 100 : 1)); };
          r.texels[k] = ((r.tag.shape >> k) & 1u) ? Rgba8{v(), v(), v(), v()} : Rgba8{0, 0, 0, 0};
        }
        EdgeMedianOut m;
        EdgeDirectionOut d;
        EdgeMedian::stage(r, m);
        plain_direction.stage(m, d);
        Response want{}, got{};
        const bool plain_retires = plain_merge.merge(d, want);
        const bool fused_retires = edge_stages_fused(r, fused_direction, fused_merge, got);
        ASSERT_EQ(fused_retires, plain_retires) << pixel;
        ASSERT_EQ(fused_retires, r.tag.emits()) << pixel;
        if (!plain_retires) continue;
        ASSERT_EQ(got.id, want.id) << pixel;
        ASSERT_EQ(got.rgba, want.rgba) << pixel << " format " << static_cast<int>(fmt);
        ++retired;
      }
  }
  EXPECT_EQ(retired, test::iterations(20000));
  EXPECT_EQ(fused_direction.chosen, plain_direction.chosen);
  uint64_t chosen = 0, directions_used = 0;
  for (const auto& slot : plain_direction.chosen)
    for (const uint64_t n : slot) {
      chosen += n;
      directions_used += n != 0;
    }
  EXPECT_GT(chosen, static_cast<uint64_t>(test::iterations(20000)));
  EXPECT_GT(directions_used, 40u);  // most of the 22 directions, in more than one slot
}

// The grid fields of two footprint requests the same (sub-texel fractions, edge cross, the grid's
// columns, rows, used taps and coordinates); the first difference named otherwise.
::testing::AssertionResult same_grid(const FootprintReq& got, const FootprintReq& want) {
  const auto differs = [](const char* field, auto g, auto w) {
    return ::testing::AssertionFailure() << field << " " << g << " != " << w;
  };
  if (got.tag.fu != want.tag.fu) return differs("fu", got.tag.fu, want.tag.fu);
  if (got.tag.fv != want.tag.fv) return differs("fv", got.tag.fv, want.tag.fv);
  if (got.cross != want.cross) return differs("cross", got.cross, want.cross);
  if (got.grid.cols != want.grid.cols) return differs("cols", got.grid.cols, want.grid.cols);
  if (got.grid.rows != want.grid.rows) return differs("rows", got.grid.rows, want.grid.rows);
  if (got.grid.used != want.grid.used) return differs("used", got.grid.used, want.grid.used);
  for (size_t i = 0; i < static_cast<size_t>(want.grid.cols); ++i)
    if (got.grid.x[i] != want.grid.x[i]) return differs("x", got.grid.x[i], want.grid.x[i]) << " at column " << i;
  for (size_t j = 0; j < static_cast<size_t>(want.grid.rows); ++j)
    if (got.grid.y[j] != want.grid.y[j]) return differs("y", got.grid.y[j], want.grid.y[j]) << " at row " << j;
  return ::testing::AssertionSuccess();
}

// The address generator's per-wrap-pair grid functions (LINEAR, the edge cross, CUBIC of a 4-tap
// ROM) form the grids of the plain unit, grid_any, for every pair of wrap modes, power-of-two and
// other level sizes, coordinates inside and outside [0, 1], with and without an anisotropic probe
// offset; and LINEAR's quad form (AddressGen::quad_grid_function, four pixels at once) likewise.
TEST(TfuUnit, FixedWrapGridsEqualThePlainAddressUnit) {
  Registers regs;
  for (const char* mode : {"LINEAR", "EDGE_PRESERVING", "CUBIC"})  // CUBIC: a 4-tap ROM (catmull-rom)
    for (int k = 0; k < 16; ++k) {
      SamplerDescriptor c;
      c.mode = filter_mode_from_name(mode);
      c.wrap_s = static_cast<WrapMode>(k / 4);
      c.wrap_t = static_cast<WrapMode>(k % 4);
      regs.samplers.push_back(c);
    }
  const WeightRomBank roms(regs.samplers);
  sim::Simulator sim;
  sim::Channel<PixelReq> in("pixel", 2);
  sim::Channel<FootprintReq> out("footprint", 2);
  const AddressGen gen(sim, in, out, regs, roms);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coord(-2.5f, 3.5f);
  std::uniform_int_distribution<int64_t> offset(-3000, 3000);
  int compared = 0, compared_quad = 0;
  for (int it = 0; it < test::iterations(4000); ++it)
    for (size_t k = 0; k < regs.samplers.size(); ++k) {
      const SamplerDescriptor& c = regs.samplers[k];
      const int w = std::array{1, 2, 5, 8, 40, 64, 1024}[static_cast<size_t>(it % 7)];
      const int h = std::array{1, 3, 4, 16, 24, 2048}[static_cast<size_t>(it % 6)];
      const float s = coord(rng), t = coord(rng);
      const ProbeLevelOffset probe{offset(rng), offset(rng)};
      const ProbeLevelOffset* o = it % 3 == 0 ? &probe : nullptr;
      FootprintReq want{}, got{};
      const int taps = c.mode.base == BaseFilter::Cubic ? 4 : 0, first_tap = c.mode.base == BaseFilter::Cubic ? -1 : 0;
      AddressGen::grid_any(c, taps, first_tap, want, w, h, s, t, o);
      gen.grid_function(k)(c, taps, first_tap, got, w, h, s, t, o);
      ASSERT_NE(gen.grid_function(k), &AddressGen::grid_any);
      const auto where = [&] { return fmt::format("{} wraps {} {}, {}x{}, s {} t {}", filter_mode_name(c.mode), static_cast<int>(c.wrap_s), static_cast<int>(c.wrap_t), w, h, s, t); };
      ASSERT_TRUE(same_grid(got, want)) << where();
      ++compared;
      // LINEAR's quad form (the LINEAR quad path's), four pixels at once without a probe offset.
      if (c.mode.base != BaseFilter::Linear || o != nullptr) continue;
      ASSERT_NE(gen.quad_grid_function(k), nullptr);
      std::array<float, 4> s4{}, t4{};
      for (size_t p = 0; p < 4; ++p) {
        s4[p] = coord(rng);
        t4[p] = coord(rng);
      }
      std::array<FootprintReq, 4> got4{};
      gen.quad_grid_function(k)(got4.data(), w, h, s4.data(), t4.data());
      for (size_t p = 0; p < 4; ++p) {
        FootprintReq want1{};
        AddressGen::grid_any(c, 0, 0, want1, w, h, s4[p], t4[p], nullptr);
        ASSERT_TRUE(same_grid(got4[p], want1))
            << fmt::format("quad, {} wraps {} {}, {}x{}, pixel {} s {} t {}", filter_mode_name(c.mode), static_cast<int>(c.wrap_s),
                           static_cast<int>(c.wrap_t), w, h, p, s4[p], t4[p]);
        ++compared_quad;
      }
    }
  EXPECT_EQ(compared, test::iterations(4000) * 48);
  EXPECT_GT(compared_quad, test::iterations(4000) * 16 * 4 / 2);  // LINEAR's 16 wrap pairs, 2/3 of the iterations
}

// A 32 x 32 checkerboard in L8 texels, linear rows, no MIP chain yet.
Texture l8_linear_checkerboard() {
  Texture lum = make_procedural("checkerboard", 32).texture;
  for (Rgba8& t : lum.levels[0].texels) t = {t.r, t.r, t.r, 255};
  lum.format = TexelFormat::L8;
  lum.layout = MemoryLayout::Linear;
  return lum;
}

// A random unit configuration around `base` (its line size kept): channel and miss-FIFO depths
// down to 1 (the miss FIFO up to its 65,536), the line buffer from 16 to 65,536 slots, filter lanes, memory latency and
// bandwidth, cache size, ways, banks and bank mapping, the filter datapaths' depths; so that stalls of every kind,
// back-pressure included, occur. `clocked`, if given, receives a random idle-skip option of the clocked run (drawn
// either way: the same configurations follow).
UnitConfig random_unit_config(std::mt19937& rng, const UnitConfig& base, ClockedOptions* clocked = nullptr) {
  UnitConfig c = base;
  const auto pick = [&rng](std::initializer_list<int> v) { return *(v.begin() + rng() % v.size()); };
  c.channel_depth = pick({1, 1, 2, 3, 4});
  c.miss_fifo_depth = pick({1, 2, 3, 8, 128});
  c.filter_lanes = pick({1, 2, 4});
  c.memory.latency = pick({0, 1, 7, 100, 300});
  c.memory.bytes_per_cycle = pick({1, 4, 16, 64});
  c.cache.ways = pick({1, 2, 4});
  c.cache.capacity_bytes = c.cache.line_bytes * c.cache.ways * pick({1, 2, 8, 32});
  c.cache.banks = pick({1, 4});
  c.cache.bank_mapping = rng() % 2 ? BankMapping::TexelParity : BankMapping::BlockParity;
  const bool idle_skip = rng() % 2 != 0;
  if (clocked) clocked->idle_skip = idle_skip;
  // The line buffer from its least (one footprint's lines) to the largest, and now and then the
  // deepest miss FIFO.
  c.line_buffer_depth = pick({16, 17, 24, 64, 65536});
  if (rng() % 8 == 0) c.miss_fifo_depth = 65536;
  // Now and then the datapaths at the SV tops' deeper pipelines (filter.edge_stages, bilinear_stages).
  if (rng() % 3 == 0) c.filter = {pick({3, 8}), pick({2, 3, 4})};
  return c;
}

// Every texture and sampler of a test frame into `b`, in order (the trace's texture and sampler
// indices).
void add_frame(FrameBuilder& b, const std::vector<std::shared_ptr<Texture>>& textures, const std::vector<SamplerDescriptor>& samplers) {
  for (const auto& t : textures) b.add_texture(t, {"test", {}});
  for (const SamplerDescriptor& s : samplers) b.add_sampler(s, false);
}

// A quad's four requests (r's texture, sampler and stage): pixel k at (s0, t0) + ((k & 1) step,
// (k >> 1) step / 2).
void push_quad(Trace& tr, TraceRequest r, float s0, float t0, float step) {
  for (size_t k = 0; k < 4; ++k) {
    r.s = s0 + static_cast<float>(k & 1) * step;
    r.t = t0 + static_cast<float>(k >> 1) * step * 0.5f;
    tr.requests.push_back(r);
  }
}

// Requests to textures of every format and both layouts, through samplers of all 12 modes (and
// bspline-interp, cache-aware edge shapes, every wrap mode), interleaved at random in one stream,
// in quad, lod and grad traces: every output equals the golden model's, and the per-texture
// statistics add up to the totals.
TEST(TfuUnit, InterleavedTexturesFormatsLayoutsAndSamplers) {
  std::mt19937 rng(77);
  const auto random_image = [&rng](int w, int h) {
    Image img(w, h);
    for (Rgba8& t : img.texels)
      t = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng())};
    return img;
  };
  std::vector<std::shared_ptr<Texture>> textures;
  {
    Texture text = make_procedural("text", 64).texture;  // RGBA8, tiled
    generate_mipmaps(text, MipMethod::Box);
    textures.push_back(std::make_shared<Texture>(std::move(text)));
    Texture lum = l8_linear_checkerboard();
    generate_mipmaps(lum, MipMethod::Box);
    textures.push_back(std::make_shared<Texture>(std::move(lum)));
    Texture npot;  // RGBA8 40 x 24, linear rows
    npot.levels.push_back(random_image(40, 24));
    npot.layout = MemoryLayout::Linear;
    generate_mipmaps(npot, MipMethod::Box);
    textures.push_back(std::make_shared<Texture>(std::move(npot)));
    Texture vs;  // two signed 16-bit channels, tiled
    vs.format = TexelFormat::VS16X2;
    vs.levels.push_back(random_image(32, 32));
    generate_mipmaps(vs, MipMethod::Box);
    textures.push_back(std::make_shared<Texture>(std::move(vs)));
  }
  std::vector<SamplerDescriptor> samplers;
  for (const FilterMode& m : all_filter_modes()) {
    SamplerDescriptor s;
    s.mode = m;
    s.wrap_s = static_cast<WrapMode>(rng() % 4);
    s.wrap_t = static_cast<WrapMode>(rng() % 4);
    s.border = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), 255};
    s.lod.bias_q8 = static_cast<int32_t>(rng() % 512) - 256;
    s.edge_shape = static_cast<EdgeShape>(rng() % 3);
    samplers.push_back(s);
  }
  for (const FilterMode& m : all_filter_modes()) {  // anisotropic samplers of every MIP mode
    if (m.mip == MipMode::None) continue;
    SamplerDescriptor s;
    s.mode = m;
    s.wrap_s = static_cast<WrapMode>(rng() % 4);
    s.wrap_t = static_cast<WrapMode>(rng() % 4);
    s.max_aniso = 2 + static_cast<int>(rng() % 15);
    s.aniso_rounding = static_cast<AnisoRounding>(rng() % 2);
    s.aniso_threshold = static_cast<int>(rng() % 8);
    s.edge_shape = static_cast<EdgeShape>(rng() % 3);
    samplers.push_back(s);
  }
  SamplerDescriptor interp;
  interp.mode = filter_mode_from_name("CUBIC_MIPMAP_LINEAR");
  interp.kernel = kBsplineInterp;
  interp.wrap_s = WrapMode::MirroredRepeat;
  samplers.push_back(interp);
  for (const int line : {64, 256})
    for (const TraceMode mode : {TraceMode::Quad, TraceMode::Lod, TraceMode::Grad}) {
      FrameBuilder b(line);
      add_frame(b, textures, samplers);
      Trace tr;
      tr.mode = mode;
      std::uniform_real_distribution<float> uni(-0.25f, 1.25f), lod(-2.0f, 7.0f), d(-0.08f, 0.08f);
      const size_t per = mode == TraceMode::Quad ? 4 : 1;
      for (int n = 0; n < 1200; ++n) {
        TraceRequest r;
        do {
          r.texture = static_cast<uint16_t>(rng() % textures.size());
          r.sampler = static_cast<uint8_t>(rng() % samplers.size());
        } while (textures[r.texture]->format == TexelFormat::VS16X2 && samplers[r.sampler].kernel == kBsplineInterp);
        r.stage = static_cast<uint8_t>(rng() % 2);
        const float s0 = uni(rng), t0 = uni(rng), step = std::abs(d(rng));
        for (size_t k = 0; k < per; ++k) {
          r.s = s0 + static_cast<float>(k & 1) * step;
          r.t = t0 + static_cast<float>(k >> 1) * step * 0.5f;
          r.lod = lod(rng);
          r.dsdx = d(rng), r.dtdx = d(rng), r.dsdy = d(rng), r.dtdy = d(rng);
          tr.requests.push_back(r);
        }
      }
      bind_requests(b, tr);
      const Frame frame = b.finish();
      UnitConfig u = small_cache(line == 64 ? 4 : 8);
      const UnitOutput got = run_unit(frame, tr, u);
      expect_golden(frame, tr, got, fmt::format("line {} {}", line, trace_mode_name(mode)));
      // The unit's static schedule is the generic module list's result, in either order.
      for (const bool reverse : {false, true}) {
        const UnitOutput generic = run_unit_generic_schedule(frame, tr, u, reverse);
        EXPECT_EQ(generic.pixels, got.pixels) << reverse;
        EXPECT_EQ(generic.response_cycle, got.response_cycle) << reverse;
        EXPECT_EQ(generic.cycles, got.cycles) << reverse;
        EXPECT_EQ(generic.stats.json_text(), got.stats.json_text()) << reverse;
      }
      // The timing recurrences (rtl/unit_recurrence.cpp) give the clocked run's pixels, response
      // cycles, cycles, edge shapes and statistics, on this configuration and on random ones:
      // channel and miss-FIFO depths down to 1, filter lanes, memory latency and bandwidth,
      // cache size, ways, banks and bank mapping, idle skipping (so that stalls of every kind,
      // back-pressure included, occur).
      const auto same_as_clocked = [&](const UnitConfig& c, const UnitOutput& clocked, const std::string& what) {
        const UnitOutput rec = run_unit_recurrence(frame, tr, c);
        EXPECT_EQ(rec.pixels, clocked.pixels) << what;
        EXPECT_EQ(rec.response_cycle, clocked.response_cycle) << what;
        EXPECT_EQ(rec.cycles, clocked.cycles) << what;
        EXPECT_EQ(rec.edge_shapes, clocked.edge_shapes) << what;
        EXPECT_EQ(rec.stats.json_text(), clocked.stats.json_text()) << what;
      };
      same_as_clocked(u, got, "default");
      for (int k = 0; k < 12; ++k) {
        ClockedOptions opt;
        const UnitConfig c = random_unit_config(rng, u, &opt);
        const std::string what = fmt::format("line {} {} config {}: {}", line, trace_mode_name(mode), k, unit_config_to_json(c));
        const UnitOutput clocked = run_unit(frame, tr, c, VcdOptions{}, opt);
        expect_golden(frame, tr, clocked, what);
        // Idle-cycle skipping changes nothing (it once jumped over a cycle in which the texel
        // cache could act: a head whose lines arrived, or a port that freed, that very cycle).
        const UnitOutput other = run_unit(frame, tr, c, VcdOptions{}, ClockedOptions{!opt.idle_skip});
        EXPECT_EQ(other.response_cycle, clocked.response_cycle) << what;
        EXPECT_EQ(other.stats.json_text(), clocked.stats.json_text()) << what;
        same_as_clocked(c, clocked, what);
      }
      // The per-texture and per-stage tables add up to the totals.
      uint64_t requests = 0, bytes = 0, stage_bytes = 0, misses = 0;
      for (const auto& [label, v] : got.stats.table("textures")->rows) {
        requests += v[1];
        misses += v[3];
        bytes += v[4];
      }
      for (const auto& [label, v] : got.stats.table("stages")->rows) stage_bytes += v[4];
      EXPECT_EQ(requests, tr.requests.size());
      EXPECT_EQ(misses, got.stats.counter("cache_line_misses"));
      EXPECT_EQ(bytes, got.stats.counter("memory_bytes"));
      EXPECT_EQ(stage_bytes, got.stats.counter("memory_bytes"));
      EXPECT_GE(got.stats.table("textures")->rows.size(), 5u);  // four textures and a coefficient texture
    }
}

// The equality test of the timing recurrences' quad paths (software speed only): on `configs` unit
// configurations, the first small_cache(4) and the rest random (stalls of every kind), the
// recurrences with their fast paths, without them (the plain twin) and the clocked blocks give the
// same pixels, response cycles, cycles and statistics, every pixel the golden model's. `also` sees
// each fast-path run with its configuration's name.
void expect_quad_paths_equal_the_plain_blocks(
    const Frame& frame, const Trace& tr, std::mt19937& rng, int configs,
    const std::function<void(const UnitOutput&, const std::string&)>& also = {}) {
  for (int k = 0; k < configs; ++k) {
    ClockedOptions opt;
    const UnitConfig c = k == 0 ? small_cache(4) : random_unit_config(rng, small_cache(4), &opt);
    const std::string what = fmt::format("config {}: {}", k, unit_config_to_json(c));
    const UnitOutput quad_path = run_unit_recurrence(frame, tr, c, true);
    const UnitOutput plain = run_unit_recurrence(frame, tr, c, false);
    const UnitOutput clocked = run_unit(frame, tr, c, VcdOptions{}, opt);
    expect_golden(frame, tr, quad_path, what);
    if (also) also(quad_path, what);
    for (const UnitOutput* other : {&plain, &clocked}) {
      EXPECT_EQ(quad_path.pixels, other->pixels) << what;
      EXPECT_EQ(quad_path.response_cycle, other->response_cycle) << what;
      EXPECT_EQ(quad_path.cycles, other->cycles) << what;
      EXPECT_EQ(quad_path.stats.json_text(), other->stats.json_text()) << what;
    }
  }
}

// The quad paths' equality tests' textures, box MIP-mapped: RGBA8 tiled, L8 linear rows, RGBA8
// 40 x 24 of random texels in linear rows, and VS16X2 tiled (which no quad path takes).
std::vector<std::shared_ptr<Texture>> quad_path_textures(std::mt19937& rng) {
  std::vector<std::shared_ptr<Texture>> textures;
  textures.push_back(std::make_shared<Texture>(make_procedural("text", 64).texture));
  textures.push_back(std::make_shared<Texture>(l8_linear_checkerboard()));
  Texture npot = make_procedural("checkerboard", 64).texture;
  npot.levels[0] = Image(40, 24);
  for (Rgba8& t : npot.levels[0].texels)
    t = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng())};
  npot.layout = MemoryLayout::Linear;
  textures.push_back(std::make_shared<Texture>(std::move(npot)));
  Texture vs = make_procedural("checkerboard", 32).texture;
  vs.format = TexelFormat::VS16X2;
  textures.push_back(std::make_shared<Texture>(std::move(vs)));
  for (auto& t : textures) generate_mipmaps(*t, MipMethod::Box);
  return textures;
}

// Samplers of filter mode `mode` with every wrap pair (a quad path takes all but the border pairs),
// each with a random border colour.
std::vector<SamplerDescriptor> every_wrap_pair(const char* mode, std::mt19937& rng) {
  std::vector<SamplerDescriptor> samplers;
  for (int ws = 0; ws < 4; ++ws)
    for (int wt = 0; wt < 4; ++wt) {
      SamplerDescriptor s;
      s.mode = filter_mode_from_name(mode);
      s.wrap_s = static_cast<WrapMode>(ws);
      s.wrap_t = static_cast<WrapMode>(wt);
      s.border = {static_cast<uint8_t>(rng()), 7, 9, 255};
      samplers.push_back(s);
    }
  return samplers;
}

// The timing recurrences' LINEAR quad path (rtl/unit_recurrence_linear_quads.hpp: isotropic
// LINEAR, LINEAR_MIPMAP_NEAREST and LINEAR_MIPMAP_LINEAR without clamp-to-border, 8-bit textures,
// four pixels a quad; software speed only) gives the plain per-pixel path's and the clocked
// blocks' pixels, response cycles, cycles and statistics: every non-border wrap pair, LOD biases
// and clamps, on RGBA8 tiled, L8 linear-row and non-power-of-two textures, interleaved quad by quad
// with quads the path does not take (clamp-to-border, anisotropic, edge-preserving, NEAREST,
// VS16X2), on random unit configurations (stalls of every kind; channel depths 1 and more, 1, 2
// or 4 lanes and filter pipeline registers or none, where the lockstep footprint of
// rtl/unit_recurrence.cpp does and does not apply; both bank mappings for the batched tag lookup).
TEST(TfuUnit, LinearQuadPathEqualsThePlainBlocks) {
  std::mt19937 rng(4242);
  const std::vector<std::shared_ptr<Texture>> textures = quad_path_textures(rng);
  std::vector<SamplerDescriptor> samplers = every_wrap_pair("LINEAR", rng);
  for (const char* mode : {"LINEAR_MIPMAP_NEAREST", "LINEAR_MIPMAP_LINEAR"})
    for (int k = 0; k < 4; ++k) {  // MIP-mapped, taken: random non-border wraps, LOD bias, clamps
      SamplerDescriptor s;
      s.mode = filter_mode_from_name(mode);
      s.wrap_s = static_cast<WrapMode>(rng() % 3);
      s.wrap_t = static_cast<WrapMode>(rng() % 3);
      s.lod.bias_q8 = static_cast<int32_t>(rng() % 1024) - 512;
      if (k == 3) s.lod.max_lod_q8 = 256;
      samplers.push_back(s);
    }
  for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "EDGE_PRESERVING", "NEAREST"}) {  // not taken
    SamplerDescriptor s;
    s.mode = filter_mode_from_name(mode);
    if (s.mode.mip == MipMode::Linear) s.max_aniso = 4;
    samplers.push_back(s);
  }
  const auto taken = [&](const TraceRequest& r) {
    const SamplerDescriptor& s = samplers[r.sampler];
    return s.mode.base == BaseFilter::Linear && s.max_aniso == 1 && s.wrap_s != WrapMode::ClampToBorder &&
           s.wrap_t != WrapMode::ClampToBorder && textures[r.texture]->format != TexelFormat::VS16X2;
  };
  FrameBuilder b(64);
  add_frame(b, textures, samplers);
  Trace tr;
  tr.mode = TraceMode::Quad;
  std::uniform_real_distribution<float> uni(-1.5f, 2.5f), d(-0.08f, 0.08f);
  int quads_taken = 0;
  for (int n = 0; n < 1500; ++n) {
    TraceRequest r;
    r.texture = static_cast<uint16_t>(rng() % textures.size());
    r.sampler = static_cast<uint8_t>(rng() % samplers.size());
    r.stage = static_cast<uint8_t>(rng() % 2);
    quads_taken += taken(r) ? 1 : 0;
    const float s0 = uni(rng), t0 = uni(rng), step = std::abs(d(rng));
    push_quad(tr, r, s0, t0, step);
  }
  EXPECT_GT(quads_taken, 650);  // the path carries about half of the quads (17/27 samplers x 3/4 textures)
  EXPECT_LT(quads_taken, 1100);
  bind_requests(b, tr);
  expect_quad_paths_equal_the_plain_blocks(b.finish(), tr, rng, 16);
  // Long runs of the path's quads (linear_run: one lent copy of the timing per run), seven of eight
  // quads taken, the statistics slot (the stage) changing within a run.
  FrameBuilder b2(64);
  add_frame(b2, textures, samplers);
  Trace runs;
  runs.mode = TraceMode::Quad;
  int runs_taken = 0;
  for (int n = 0; n < 1200; ++n) {
    TraceRequest r;
    do {
      r.texture = static_cast<uint16_t>(rng() % textures.size());
      r.sampler = static_cast<uint8_t>(rng() % samplers.size());
    } while (!taken(r) && rng() % 8 != 0);
    r.stage = static_cast<uint8_t>(rng() % 8 == 0 ? 1 : 0);
    runs_taken += taken(r) ? 1 : 0;
    const float s0 = uni(rng), t0 = uni(rng), step = std::abs(d(rng));
    push_quad(runs, r, s0, t0, step);
  }
  EXPECT_GT(runs_taken, 1000);
  bind_requests(b2, runs);
  expect_quad_paths_equal_the_plain_blocks(b2.finish(), runs, rng, 6);
}

// The timing recurrences' CUBIC quad path (rtl/unit_recurrence_cubic_quads.hpp: isotropic CUBIC,
// CUBIC_MIPMAP_NEAREST and CUBIC_MIPMAP_LINEAR with a 4-tap weight ROM, without clamp-to-border,
// uncompressed 8-bit textures, four pixels a quad; software speed only) gives the plain
// per-pixel path's and the clocked blocks' pixels, response cycles, cycles and statistics: every
// non-border wrap pair, LOD biases and clamps, the 4-tap kernels, ROMs of 16 to 512 samples and 4
// to 16 bits, both reconstructions, bspline-interp (its coefficient textures), on RGBA8 tiled, L8
// linear-row and non-power-of-two textures, interleaved quad by quad with quads the path does not
// take (2-tap and 1-tap kernels, clamp-to-border, anisotropic, VS16X2; and LINEAR, which the
// LINEAR quad path takes), on random unit configurations (stalls of every kind).
TEST(TfuUnit, CubicQuadPathEqualsThePlainBlocks) {
  std::mt19937 rng(4343);
  const std::vector<std::shared_ptr<Texture>> textures = quad_path_textures(rng);
  std::vector<SamplerDescriptor> samplers = every_wrap_pair("CUBIC", rng);
  const std::vector<TileRomSpec> roms{{}, {16, 4, SamplePos::Corner}, {512, 16}, {64, 12, SamplePos::Centre, RomRounding::Nearest}};
  for (const char* mode : {"CUBIC_MIPMAP_NEAREST", "CUBIC_MIPMAP_LINEAR"})
    for (int k = 0; k < 6; ++k) {  // MIP-mapped, taken: random non-border wraps, kernels, ROMs, LOD bias, clamps
      SamplerDescriptor s;
      s.mode = filter_mode_from_name(mode);
      s.wrap_s = static_cast<WrapMode>(rng() % 3);
      s.wrap_t = static_cast<WrapMode>(rng() % 3);
      s.kernel = std::array{"catmull-rom", "bspline", "mitchell", "kaiser", "blackman", "catmull-rom"}[static_cast<size_t>(k)];
      s.cubic_rom = roms[static_cast<size_t>(k) % roms.size()];
      s.cubic_recon = k % 2 ? RomRecon::Linear : RomRecon::Nearest;
      s.lod.bias_q8 = static_cast<int32_t>(rng() % 1024) - 512;
      if (k == 3) s.lod.max_lod_q8 = 256;
      samplers.push_back(s);
    }
  SamplerDescriptor interp;  // taken: the coefficient textures of the 8-bit textures
  interp.mode = filter_mode_from_name("CUBIC_MIPMAP_LINEAR");
  interp.kernel = kBsplineInterp;
  interp.wrap_s = WrapMode::MirroredRepeat;
  samplers.push_back(interp);
  const size_t interp_index = samplers.size() - 1;
  for (const char* kernel : {"tent", "box"}) {  // not taken: 2 and 1 taps
    SamplerDescriptor s;
    s.mode = filter_mode_from_name("CUBIC_MIPMAP_LINEAR");
    s.kernel = kernel;
    samplers.push_back(s);
  }
  for (const char* mode : {"CUBIC_MIPMAP_LINEAR", "LINEAR_MIPMAP_LINEAR", "EDGE_PRESERVING"}) {  // not taken
    SamplerDescriptor s;
    s.mode = filter_mode_from_name(mode);
    if (s.mode.base == BaseFilter::Cubic) s.max_aniso = 4;
    samplers.push_back(s);
  }
  const auto taken = [&](const TraceRequest& r) {
    const SamplerDescriptor& s = samplers[r.sampler];
    return s.mode.base == BaseFilter::Cubic && s.max_aniso == 1 && s.wrap_s != WrapMode::ClampToBorder &&
           s.wrap_t != WrapMode::ClampToBorder && s.kernel != "tent" && s.kernel != "box" &&
           textures[r.texture]->format != TexelFormat::VS16X2;
  };
  FrameBuilder b(64);
  add_frame(b, textures, samplers);
  Trace tr;
  tr.mode = TraceMode::Quad;
  std::uniform_real_distribution<float> uni(-1.5f, 2.5f), d(-0.08f, 0.08f);
  int quads_taken = 0;
  for (int n = 0; n < 1500; ++n) {
    TraceRequest r;
    do {
      r.texture = static_cast<uint16_t>(rng() % textures.size());
      r.sampler = static_cast<uint8_t>(rng() % samplers.size());
    } while (r.sampler == interp_index && textures[r.texture]->format == TexelFormat::VS16X2);
    r.stage = static_cast<uint8_t>(rng() % 2);
    quads_taken += taken(r) ? 1 : 0;
    const float s0 = uni(rng), t0 = uni(rng), step = std::abs(d(rng));
    push_quad(tr, r, s0, t0, step);
  }
  EXPECT_GT(quads_taken, 600);  // the path carries about half of the quads (22/34 samplers x 3/4 textures)
  EXPECT_LT(quads_taken, 1050);
  bind_requests(b, tr);
  expect_quad_paths_equal_the_plain_blocks(b.finish(), tr, rng, 10);
}

// ---- Anisotropic filtering (docs/anisotropic.md) ----

// A 64 x 64 random RGBA8 texture (or VS16X2) with box MIP-maps: holds in hot_cache().
Texture random_mip_texture(TexelFormat fmt, unsigned seed) {
  Texture t;
  t.format = fmt;
  t.levels.emplace_back(64, 64);
  std::mt19937 rng(seed);
  for (Rgba8& x : t.levels[0].texels)
    x = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng())};
  generate_mipmaps(t, MipMethod::Box);
  return t;
}

// A gradient request whose footprint is exactly n probes: du/dx = 1.5 n texels, dv/dy = 1.5 texels
// (exact in binary32 and in Q.16), so N = n and lambda = log2(1.5) (levels 0 and 1, blend 150).
TraceRequest aniso_request(float s, float t, int n, int width) {
  TraceRequest r;
  r.s = s;
  r.t = t;
  r.dsdx = 1.5f * static_cast<float>(n) / static_cast<float>(width);
  r.dtdy = 1.5f / static_cast<float>(width);
  return r;
}

// Gradient requests: exactly N = 1..16 (aniso_request, axes swapped for every other one) and
// footprints of random length, elongation and direction; positions across and beyond the texture.
Trace aniso_grad_trace(unsigned seed, int per_n) {
  Trace tr;
  tr.mode = TraceMode::Grad;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-0.3f, 1.3f), len(0.002f, 0.1f), ratio(1.0f, 20.0f), angle(0.0f, 6.2831853f);
  for (int n = 1; n <= kMaxAniso; ++n)
    for (int k = 0; k < per_n; ++k) {
      TraceRequest r = aniso_request(pos(rng), pos(rng), n, 64);
      if (k % 2) std::swap(r.dsdx, r.dtdy);  // major along y
      tr.requests.push_back(r);
      const float minor = len(rng), a = angle(rng), major = minor * ratio(rng);
      r.dsdx = major * std::cos(a);
      r.dtdx = major * std::sin(a);
      r.dsdy = -minor * std::sin(a);
      r.dtdy = minor * std::cos(a);
      if (k % 3 == 0) std::swap(r.dsdx, r.dsdy), std::swap(r.dtdx, r.dtdy);
      tr.requests.push_back(r);
    }
  return tr;
}

// The N histogram the golden model's LOD unit gives for a trace (pixels per N).
std::vector<uint64_t> golden_probe_histogram(const Frame& frame, const Trace& tr) {
  const GoldenUnit golden(frame);
  std::vector<uint64_t> h(kMaxAniso + 1, 0);
  for (size_t i = 0; i < tr.requests.size(); ++i) ++h[static_cast<size_t>(golden.lod(tr, i).probes)];
  return h;
}

// Golden and cycle model bit for bit on random derivative requests, N = 1..16, every wrap mode, the
// MIP-mapped families (probes of NEAREST, bilinear, trilinear, cubic, edge-preserving with static,
// cache-aware and cross shapes), both probe-count roundings, RGBA8 and VS16X2; the statistics count
// the golden model's probes.
TEST(TfuUnit, AnisotropicEveryNWrapModeAndFamily) {
  const Trace tr = aniso_grad_trace(5, 6);
  for (TexelFormat fmt : {TexelFormat::RGBA8, TexelFormat::VS16X2}) {
    const Texture tex = random_mip_texture(fmt, 11);
    for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "LINEAR_MIPMAP_NEAREST", "NEAREST_MIPMAP_LINEAR", "CUBIC_MIPMAP_LINEAR",
                             "EDGE_PRESERVING_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_NEAREST"})
      for (WrapMode w : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge, WrapMode::ClampToBorder}) {
        SamplerDescriptor cfg;
        cfg.mode = filter_mode_from_name(mode);
        cfg.wrap_s = w;
        cfg.wrap_t = static_cast<WrapMode>((static_cast<int>(w) + 1) % 4);
        cfg.border = {10, 200, 30, 255};
        cfg.max_aniso = 16;
        cfg.aniso_rounding = w == WrapMode::ClampToEdge ? AnisoRounding::PowerOfTwo : AnisoRounding::Integer;
        cfg.edge_shape = static_cast<EdgeShape>(static_cast<int>(w) % 3);
        const std::string what = fmt::format("{} {} {}", texel_format_name(fmt), mode, wrap_mode_name(w));
        const OneTexture one = one_texture(tex, cfg, tr, small_cache(4));
        const UnitOutput got = run_unit(one.frame, one.trace, small_cache(4));
        expect_golden(one.frame, one.trace, got, what);
        const std::vector<uint64_t> want = golden_probe_histogram(one.frame, one.trace);
        ASSERT_NE(got.stats.histogram("aniso_probes"), nullptr) << what;
        EXPECT_EQ(*got.stats.histogram("aniso_probes"), want) << what;
        uint64_t probes = 0;
        for (size_t n = 1; n < want.size(); ++n) {
          probes += n * want[n];
          if (cfg.aniso_rounding == AnisoRounding::Integer) {
            EXPECT_GT(want[n], 0u) << what << " N " << n;
          }
        }
        EXPECT_EQ(got.stats.counter("probes"), probes) << what;
        EXPECT_DOUBLE_EQ(got.stats.value("probes_per_pixel"), static_cast<double>(probes) / static_cast<double>(tr.requests.size()));
      }
  }
}

// sRGB textures (SRGBA8, docs/srgb.md): decoded to linear unorm12 before the filter and encoded at
// the output, in both models; every mode the format takes (edge-preserving is refused), isotropic
// quads and anisotropic gradients, every wrap mode; both engines of the cycle model agree.
TEST(TfuUnit, SrgbTexturesBitExactInBothEngines) {
  const Texture tex = random_mip_texture(TexelFormat::SRGBA8, 13);
  const SceneTrace st = scene_trace("ground_plane", 48, 32);
  const Trace aniso = aniso_grad_trace(3, 2);
  int k = 0;
  for (const FilterMode& m : all_filter_modes()) {
    if (!filters_format(m.base, TexelFormat::SRGBA8)) continue;
    SamplerDescriptor cfg;
    cfg.mode = m;
    cfg.wrap_s = static_cast<WrapMode>(k % 4);
    cfg.wrap_t = static_cast<WrapMode>((k + 1) % 4);
    cfg.border = {200, 30, 90, 128};
    cfg.max_aniso = m.mip == MipMode::None ? 1 : 8;
    ++k;
    for (const Trace* tr : {&st.trace, &aniso}) {
      const std::string what = fmt::format("{} {}", filter_mode_name(m), trace_mode_name(tr->mode));
      const OneTexture one = one_texture(tex, cfg, *tr, small_cache(4));
      const UnitOutput got = run_unit(one.frame, one.trace, small_cache(4));
      EXPECT_GE(got.pixels.size(), 64u) << what;
      expect_golden(one.frame, one.trace, got, what);
      EXPECT_EQ(compare_engines(one.frame, one.trace, small_cache(4)), "") << what;
    }
  }
  SamplerDescriptor edge;
  edge.mode = filter_mode_from_name("EDGE_PRESERVING");
  const OneTexture one = one_texture(tex, edge, st.trace, UnitConfig{});
  EXPECT_THROW(run_unit(one.frame, one.trace, UnitConfig{}), InputError);
}

// Built-in scenes (quad traces: one LOD result per quad) with maxAniso 16 and 4 rounded to powers of
// two, in the trilinear, cubic and edge-preserving MIP modes, and the edge modes' shape policies.
TEST(TfuUnit, AnisotropicScenesBitExact) {
  for (const char* scene : {"ground_plane", "text_patch", "object", "grazing"}) {
    const SceneTrace st = scene_trace(scene, 64, 48);
    const Mesh& mesh = st.scene.meshes.front();
    for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "CUBIC_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_LINEAR"})
      for (const auto& [max_aniso, rounding] : {std::pair{16, AnisoRounding::Integer}, std::pair{4, AnisoRounding::PowerOfTwo}}) {
        SamplerDescriptor cfg = mesh.stages[0].sampler;
        cfg.mode = filter_mode_from_name(mode);
        cfg.max_aniso = max_aniso;
        cfg.aniso_rounding = rounding;
        for (EdgeShape p : {EdgeShape::Static, EdgeShape::CacheAware}) {
          if (p == EdgeShape::CacheAware && cfg.mode.base != BaseFilter::EdgePreserving) continue;
          cfg.edge_shape = p;
          const UnitOutput got = run_and_compare(*mesh.stages[0].texture, cfg, st.trace, small_cache(4),
                                                 fmt::format("{} {} max {} {}", scene, mode, max_aniso, edge_shape_name(p)));
          EXPECT_GT(got.stats.counter("probes"), st.trace.requests.size()) << scene << " " << mode;  // some N > 1
        }
      }
  }
}

// The probe threshold (aniso_threshold, docs/anisotropic.md): the cycle model equals the golden model
// in both engines at every threshold; the threshold never adds probes and at maxAniso 2 removes
// most of the barely anisotropic pixels' second probe.
TEST(TfuUnit, AnisotropicThresholdBitExactInBothEngines) {
  for (const char* scene : {"ground_plane", "grazing"}) {
    const SceneTrace st = scene_trace(scene, 64, 48);
    const Mesh& mesh = st.scene.meshes.front();
    for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_LINEAR"})
      for (int max_aniso : {2, 16}) {
        uint64_t prev = ~uint64_t{0}, first = 0;
        for (int t : {0, 3, 7}) {
          SamplerDescriptor cfg = mesh.stages[0].sampler;
          cfg.mode = filter_mode_from_name(mode);
          cfg.max_aniso = max_aniso;
          cfg.aniso_threshold = t;
          const std::string what = fmt::format("{} {} max {} t {}", scene, mode, max_aniso, t);
          const UnitOutput got = run_and_compare(*mesh.stages[0].texture, cfg, st.trace, small_cache(4), what);
          const OneTexture one = one_texture(*mesh.stages[0].texture, cfg, st.trace, small_cache(4));
          EXPECT_EQ(compare_engines(one.frame, one.trace, small_cache(4)), "") << what;
          const uint64_t probes = got.stats.counter("probes");
          EXPECT_LE(probes, prev) << what;
          if (t == 0) first = probes;
          if (t == 7) {
            EXPECT_LT(probes, first) << what;
          }
          prev = probes;
        }
      }
  }
}

// The ellipse axes (aniso_axes ellipse) through the cycle model: the LOD unit calls aniso_lod, so
// both engines equal the golden model; on the tunnel (every angle against the screen axes) the
// pixels take other probe counts than with the screen axes.
TEST(TfuUnit, AnisotropicEllipseAxesBitExactInBothEngines) {
  for (const char* scene : {"tunnel", "grazing"}) {
    const SceneTrace st = scene_trace(scene, 48, 48);
    const Mesh& mesh = st.scene.meshes.front();
    for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_LINEAR"})
      for (const auto& [max_aniso, t] : {std::pair{16, 0}, std::pair{4, 4}}) {
        SamplerDescriptor cfg = mesh.stages[0].sampler;
        cfg.mode = filter_mode_from_name(mode);
        cfg.max_aniso = max_aniso;
        cfg.aniso_threshold = t;
        const SamplerDescriptor screen = cfg;
        cfg.aniso_axes = AnisoAxes::Ellipse;
        const std::string what = fmt::format("{} {} max {} t {}", scene, mode, max_aniso, t);
        const UnitOutput got = run_and_compare(*mesh.stages[0].texture, cfg, st.trace, small_cache(4), what);
        const OneTexture one = one_texture(*mesh.stages[0].texture, cfg, st.trace, small_cache(4));
        EXPECT_EQ(compare_engines(one.frame, one.trace, small_cache(4)), "") << what;
        const UnitOutput scr = run_and_compare(*mesh.stages[0].texture, screen, st.trace, small_cache(4), what + " screen");
        if (std::string(scene) == "tunnel") {
          EXPECT_NE(got.stats.counter("probes"), scr.stats.counter("probes")) << what;
        }
      }
  }
}

// The timing recurrences' probe quad path (rtl/unit_recurrence_probes.hpp: anisotropic
// LINEAR_MIPMAP_NEAREST and LINEAR_MIPMAP_LINEAR without clamp-to-border, uncompressed 8-bit
// textures, four pixels a quad; software speed only) gives the plain per-footprint path's and the
// clocked blocks' pixels, response cycles, cycles and statistics: random max anisotropy, probe-count
// rounding, threshold, screen and ellipse axes, every wrap pair, LOD biases and clamps, quads of random
// length, elongation and direction (N = 1..16) on RGBA8 tiled, L8 linear-row and non-power-of-two
// textures, interleaved quad by quad with quads the path does not take (clamp-to-border, isotropic,
// NEAREST and edge-preserving probes, VS16X2), on random unit configurations (stalls of every kind;
// channel depths 1 and more and 1, 2 or 4 lanes, where the lockstep footprint of
// rtl/unit_recurrence.cpp does and does not apply; both bank mappings for the batched tag lookup).
TEST(TfuUnit, ProbeQuadPathEqualsThePlainBlocks) {
  std::mt19937 rng(6161);
  std::vector<std::shared_ptr<Texture>> textures;
  {
    textures.push_back(std::make_shared<Texture>(random_mip_texture(TexelFormat::RGBA8, 3)));  // tiled
    Texture lum = l8_linear_checkerboard();
    generate_mipmaps(lum, MipMethod::Box);
    textures.push_back(std::make_shared<Texture>(std::move(lum)));
    Texture npot = make_procedural("checkerboard", 64).texture;  // RGBA8 40 x 24, linear rows
    npot.levels[0] = Image(40, 24);
    for (Rgba8& t : npot.levels[0].texels)
      t = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng())};
    npot.layout = MemoryLayout::Linear;
    generate_mipmaps(npot, MipMethod::Box);
    textures.push_back(std::make_shared<Texture>(std::move(npot)));
    textures.push_back(std::make_shared<Texture>(random_mip_texture(TexelFormat::VS16X2, 5)));  // not taken
  }
  std::vector<SamplerDescriptor> samplers;
  for (const char* mode : {"LINEAR_MIPMAP_NEAREST", "LINEAR_MIPMAP_LINEAR", "LINEAR_MIPMAP_LINEAR"})
    for (int k = 0; k < 4; ++k) {  // taken unless a wrap mode clamps to the border (1 in 4 each)
      SamplerDescriptor s;  // the first of each mode taken with every N, 1..16
      s.mode = filter_mode_from_name(mode);
      s.max_aniso = k == 0 ? 16 : 2 + static_cast<int>(rng() % 15);
      s.aniso_rounding = k > 0 && rng() % 3 == 0 ? AnisoRounding::PowerOfTwo : AnisoRounding::Integer;
      s.aniso_threshold = k > 0 && rng() % 2 ? static_cast<int>(rng() % 8) : 0;
      s.aniso_axes = k > 0 && rng() % 2 ? AnisoAxes::Ellipse : AnisoAxes::Screen;
      s.wrap_s = static_cast<WrapMode>(rng() % (k == 0 ? 3 : 4));
      s.wrap_t = static_cast<WrapMode>(rng() % (k == 0 ? 3 : 4));
      s.border = {static_cast<uint8_t>(rng()), 7, 9, 255};
      s.lod.bias_q8 = static_cast<int32_t>(rng() % 1024) - 512;
      if (k == 3) s.lod.max_lod_q8 = 256;
      samplers.push_back(s);
    }
  for (SamplerDescriptor s : every_wrap_pair("LINEAR_MIPMAP_LINEAR", rng)) {  // every wrap pair, border pairs not taken
    s.max_aniso = 2 + static_cast<int>(rng() % 15);
    s.aniso_axes = rng() % 2 ? AnisoAxes::Ellipse : AnisoAxes::Screen;
    samplers.push_back(s);
  }
  for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "NEAREST_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_LINEAR"}) {
    SamplerDescriptor s;  // not taken: isotropic (the LINEAR quad path), NEAREST and edge probes
    s.mode = filter_mode_from_name(mode);
    s.max_aniso = s.mode.base == BaseFilter::Linear ? 1 : 8;
    samplers.push_back(s);
  }
  const auto taken = [&](const TraceRequest& r) {
    const SamplerDescriptor& s = samplers[r.sampler];
    return s.mode.base == BaseFilter::Linear && s.max_aniso > 1 && s.wrap_s != WrapMode::ClampToBorder &&
           s.wrap_t != WrapMode::ClampToBorder && textures[r.texture]->format != TexelFormat::VS16X2;
  };
  FrameBuilder b(64);
  add_frame(b, textures, samplers);
  Trace tr;
  tr.mode = TraceMode::Quad;
  std::uniform_real_distribution<float> pos(-1.5f, 2.5f), len(0.001f, 0.03f), ratio(1.0f, 24.0f), angle(0.0f, 6.2831853f);
  const int quads = test::iterations(900);
  int quads_taken = 0;
  for (int n = 0; n < quads; ++n) {
    TraceRequest r;
    r.texture = static_cast<uint16_t>(rng() % textures.size());
    r.sampler = static_cast<uint8_t>(rng() % samplers.size());
    r.stage = static_cast<uint8_t>(rng() % 2);
    // The quad's pixel steps (ds, dt)/dx = major (cos a, sin a), (ds, dt)/dy = minor (-sin a, cos a).
    float s0 = pos(rng), t0 = pos(rng), minor = len(rng), elongation = ratio(rng), a = angle(rng);
    if (n < 2 * kMaxAniso) {  // first every N = 1..16 through the path's samplers 0 and 4 (screen axes, t = 0)
      r.texture = 0;
      r.sampler = static_cast<uint8_t>(n < kMaxAniso ? 0 : 4);
      elongation = static_cast<float>(n % kMaxAniso) + 0.5f;  // N = ceil(elongation), 2..16
      if (n % kMaxAniso == 0) {  // N = 1: a square footprint, exact in binary32 (steps of 1/64 texture)
        elongation = 1.0f, minor = 1.0f / 64, a = 0.0f;
        s0 = std::round(s0 * 64) / 64, t0 = std::round(t0 * 64) / 64;
      }
    }
    const float major = minor * elongation;
    const float dsdx = major * std::cos(a), dtdx = major * std::sin(a), dsdy = -minor * std::sin(a), dtdy = minor * std::cos(a);
    quads_taken += taken(r) ? 1 : 0;
    for (size_t k = 0; k < 4; ++k) {
      const auto x = static_cast<float>(k & 1), y = static_cast<float>(k >> 1);
      r.s = s0 + x * dsdx + y * dsdy;
      r.t = t0 + x * dtdx + y * dtdy;
      tr.requests.push_back(r);
    }
  }
  EXPECT_GT(quads_taken, quads / 4);  // the first 32, then about 16/31 samplers x 3/4 textures of the quads
  EXPECT_LT(quads_taken, quads);
  bind_requests(b, tr);
  // Every probe count occurs (the histogram of pixels per N; the first quads above).
  const auto every_probe_count = [](const UnitOutput& quad_path, const std::string& what) {
    const std::vector<uint64_t>* hist = quad_path.stats.histogram("aniso_probes");
    ASSERT_NE(hist, nullptr) << what;
    ASSERT_EQ(hist->size(), static_cast<size_t>(kMaxAniso + 1)) << what;
    for (size_t n = 1; n <= static_cast<size_t>(kMaxAniso); ++n) EXPECT_GT((*hist)[n], 0u) << what << " N = " << n;
  };
  expect_quad_paths_equal_the_plain_blocks(b.finish(), tr, rng, 8, every_probe_count);
}

// Anisotropic probes: Lee & Jen's static shapes stay within the lines of each probe's bilinear footprint,
// so anisotropic EDGE_PRESERVING_MIPMAP_LINEAR probes read exactly the bytes of trilinear probes on
// the same footprints (the same probes per pixel); the full cross reads more on minified scenes.
TEST(TfuUnit, AnisotropicStaticEdgeProbesReadExactlyTheTrilinearBytes) {
  for (const char* scene : {"grazing", "ground_plane"}) {
    const SceneTrace st = scene_trace(scene, 64, 48);
    const Mesh& mesh = st.scene.meshes.front();
    for (int block : {4, 8}) {
      const UnitConfig u = small_cache(block);
      SamplerDescriptor cfg = mesh.stages[0].sampler;
      cfg.max_aniso = 16;
      cfg.mode = filter_mode_from_name("LINEAR_MIPMAP_LINEAR");
      const UnitOutput tri = run_one(*mesh.stages[0].texture, cfg, st.trace, u);
      cfg.mode = filter_mode_from_name("EDGE_PRESERVING_MIPMAP_LINEAR");
      cfg.edge_shape = EdgeShape::Static;
      const UnitOutput edge = run_one(*mesh.stages[0].texture, cfg, st.trace, u);
      cfg.edge_shape = EdgeShape::Cross;
      const UnitOutput cross = run_one(*mesh.stages[0].texture, cfg, st.trace, u);
      const std::string what = fmt::format("{} B={}", scene, block);
      ASSERT_GT(tri.stats.counter("probes"), st.trace.requests.size()) << what;  // anisotropic pixels exist
      EXPECT_EQ(edge.stats.counter("probes"), tri.stats.counter("probes")) << what;
      EXPECT_EQ(edge.stats.counter("memory_bytes"), tri.stats.counter("memory_bytes")) << what;
      EXPECT_GT(cross.stats.counter("memory_bytes"), tri.stats.counter("memory_bytes")) << what;
    }
  }
}

// Degenerate gradients (zero, equal axes, infinite, NaN, a line) through both models.
TEST(TfuUnit, AnisotropicDegenerateGradients) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  Trace tr;
  tr.mode = TraceMode::Grad;
  for (const std::array<float, 4> g : {std::array<float, 4>{0, 0, 0, 0}, {nan, nan, nan, nan}, {0.125f, 0.0625f, -0.0625f, 0.125f},
                                       {inf, 0, 0, 0.01f}, {inf, -inf, inf, inf}, {-inf, nan, 0, 0}, {0.5f, 0, 0, 0}, {0, 0, 0, -0.5f},
                                       {1e-30f, 0, 0, 1e-38f}, {3e38f, 3e38f, -3e38f, 1}})
    for (const float s : {0.3f, -7.0f, 1e9f, nan}) {
      TraceRequest r;
      r.s = s;
      r.t = 0.6f;
      r.dsdx = g[0], r.dtdx = g[1], r.dsdy = g[2], r.dtdy = g[3];
      tr.requests.push_back(r);
    }
  const Texture tex = random_mip_texture(TexelFormat::RGBA8, 4);
  for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "NEAREST_MIPMAP_NEAREST", "CUBIC_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_LINEAR"})
    for (WrapMode w : {WrapMode::Repeat, WrapMode::ClampToBorder}) {
      SamplerDescriptor cfg;
      cfg.mode = filter_mode_from_name(mode);
      cfg.wrap_s = cfg.wrap_t = w;
      cfg.max_aniso = 16;
      run_and_compare(tex, cfg, tr, UnitConfig{}, fmt::format("{} {}", mode, wrap_mode_name(w)));
    }
}

// Rates on hits: an anisotropic pixel of N probes takes N times its mode's clocks (one probe's
// level footprints per clock after the other): N for a bilinear or edge-preserving probe on one
// level, 2N for a trilinear one.
TEST(TfuUnit, AnisotropicRatesOnHits) {
  const Texture tex = random_mip_texture(TexelFormat::RGBA8, 6);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> pos(0.0f, 1.0f);
  for (const int n : {1, 2, 3, 4, 8, 16}) {
    Trace tr;
    tr.mode = TraceMode::Grad;
    for (int k = 0; k < 400; ++k) tr.requests.push_back(aniso_request(pos(rng), pos(rng), n, 64));
    const auto rate = [&](const char* mode, int max_aniso) {
      SamplerDescriptor cfg;
      cfg.mode = filter_mode_from_name(mode);
      cfg.max_aniso = max_aniso;
      return clocks_per_pixel_on_hits(tex, cfg, tr, hot_cache(), fmt::format("{} N {}", mode, n));
    };
    // Isotropic (maxAniso 1) on the same requests: one probe, lambda log2(1.5 n) instead.
    EXPECT_NEAR(rate("LINEAR_MIPMAP_NEAREST", 1), 1.0, 0.01);
    EXPECT_NEAR(rate("LINEAR_MIPMAP_NEAREST", 16), n, 0.01 * n) << n;
    EXPECT_NEAR(rate("LINEAR_MIPMAP_LINEAR", 16), 2.0 * n, 0.02 * n) << n;  // lambda log2(1.5): blends
    EXPECT_NEAR(rate("EDGE_PRESERVING_MIPMAP_NEAREST", 16), n, 0.01 * n) << n;
    EXPECT_NEAR(rate("EDGE_PRESERVING_MIPMAP_LINEAR", 16), 2.0 * n, 0.02 * n) << n;
  }
}

TEST(TfuUnit, ConfigJsonRoundTripAndErrors) {
  UnitConfig c;
  c.cache.line_bytes = 256;
  c.cache.capacity_bytes = 32768;
  c.cache.bank_mapping = BankMapping::TexelParity;
  c.filter_lanes = 4;
  const UnitConfig back = unit_config_from_json(unit_config_to_json(c), "cfg");
  EXPECT_EQ(back, c);
  EXPECT_EQ(unit_config_to_json(back), unit_config_to_json(c));
  // Every field of the table appears in the JSON, and the JSON of the defaults reads back to them.
  const std::string j = unit_config_to_json(UnitConfig{});
  for (const UnitField& f : unit_config_fields()) {
    const std::string key = f.key;
    EXPECT_NE(j.find(fmt::format("\"{}\"", key.substr(key.rfind('.') + 1))), std::string::npos) << key;
  }
  EXPECT_EQ(unit_config_from_json(j, "defaults"), UnitConfig{});
  const auto error = test::unit_config_error;
  EXPECT_NE(error("{\"cache\": {\"line_bytes\": 6}}").find("c.json: 'cache.line_bytes' 6 must be one of 64, 256, 1024"),
            std::string::npos);
  EXPECT_NE(error("{\"cache\": {\"capacity_bytes\": 32}}").find("'cache.capacity_bytes' 32 must be in"), std::string::npos);
  EXPECT_NE(error("{\"cache\": {\"capacity_bytes\": 1000}}").find("not a whole number"), std::string::npos);
  EXPECT_NE(error("{\"cache\": {\"banks\": 0}}").find("'cache.banks' 0"), std::string::npos);
  EXPECT_NE(error("{\"cache\": {\"size\": 1}}").find("unknown key 'cache.size'"), std::string::npos);
  EXPECT_NE(error("{\"shape_policy\": \"static\"}").find("unknown key 'shape_policy'"), std::string::npos);
  EXPECT_NE(error("{\"filter_lanes\": 3}").find("'filter_lanes' 3"), std::string::npos);
  EXPECT_NE(error("{\"cache\": {\"ways\": 18446744073709551615}}").find("out of range"), std::string::npos);
  EXPECT_NE(error("{\"cache\": {\"bank_mapping\": \"odd\"}}").find("'odd' is not one of texel-parity, block-parity"),
            std::string::npos);
  EXPECT_NE(error("{\"cache\": ").find("malformed"), std::string::npos);
  EXPECT_NE(error("[1]").find("object"), std::string::npos);
}

TEST(Docs, CycleModelShowsTheConfigFields) {
  EXPECT_NE(test::docs_text("cycle-model.md").find(unit_config_markdown()), std::string::npos)
      << "docs/cycle-model.md is stale: paste `tfu sim --config-fields` between the generated markers";
}

TEST(TfuUnit, VcdDumpsEveryChannel) {
  const SceneTrace st = scene_trace("magnified", 16, 16);
  const Mesh& mesh = st.scene.meshes.front();
  SamplerDescriptor cfg = mesh.stages[0].sampler;
  cfg.mode = filter_mode_from_name("EDGE_PRESERVING");
  std::ostringstream vcd;
  const UnitOutput o = run_one(*mesh.stages[0].texture, cfg, st.trace, UnitConfig{}, &vcd);
  const std::string v = vcd.str();
  for (const char* sig : {"$scope module tfu", "edge_median_out", "texel_cache", "$enddefinitions", "valid", "ready"})
    EXPECT_NE(v.find(sig), std::string::npos) << sig;
  EXPECT_NE(v.find(fmt::format("#{}\n", 2 * (o.cycles - 1) + 1)), std::string::npos);  // sampled up to the end (2 stamps per cycle)
}

TEST(TfuUnit, ErrorsAreInputErrors) {
  const SceneTrace st = scene_trace("magnified", 16, 16);
  const Mesh& mesh = st.scene.meshes.front();
  SamplerDescriptor cfg = mesh.stages[0].sampler;
  UnitConfig bad;
  bad.cache.line_bytes = 5;
  EXPECT_THROW(run_one(*mesh.stages[0].texture, cfg, st.trace, bad), InputError);
  Trace odd = st.trace;
  odd.requests.pop_back();
  EXPECT_THROW(run_one(*mesh.stages[0].texture, cfg, odd, UnitConfig{}), InputError);
  // A frame tiled for other lines, a request naming an unbound descriptor.
  const OneTexture one = one_texture(*mesh.stages[0].texture, cfg, st.trace, UnitConfig{});
  EXPECT_THROW(run_unit(one.frame, one.trace, small_cache(8)), InputError);
  Trace stray = one.trace;
  stray.requests[4].texture = 7;
  EXPECT_THROW(run_unit(one.frame, stray, UnitConfig{}), InputError);
}

}  // namespace
}  // namespace tfu::rtl
