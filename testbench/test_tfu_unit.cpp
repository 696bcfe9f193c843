// Cycle model (rtl/) against the golden sampler, bit for bit: every scene x every filter mode x two
// cache block sizes (the CI matrix of TFU-C), every kernel-shape policy, vs16x2, lod and grad
// traces, every wrap mode; rates, latencies, the Lee & Jen bandwidth claim; the edge datapath's
// blocks against the cmodel functions they implement; config and VCD.
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "cmodel/error.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/edge_datapath.hpp"
#include "rtl/median_network.hpp"
#include "rtl/tfu_unit.hpp"

namespace tfu::rtl {
namespace {

struct SceneTrace {
  Scene scene;
  Trace trace;
};

SceneTrace scene_trace(const std::string& name, int w, int h) {
  SceneTrace st{load_scene(name), {}};
  st.scene.width = w;
  st.scene.height = h;
  RenderOptions o;
  o.trace = true;
  o.threads = 1;
  st.trace = render_scene(st.scene, o).trace;
  return st;
}

// Runs the unit and checks every pixel against the golden model; returns the run.
UnitOutput run_and_compare(const Texture& tex, const SamplerDescriptor& cfg, const Trace& tr, const UnitConfig& u,
                           const std::string& what) {
  UnitOutput got = run_unit(tex, cfg, tr, u);
  const Sampler golden(tex, golden_sampler_config(cfg, u));
  const std::vector<int32_t> lam = trace_lambdas(tr, tex.width(), tex.height());
  EXPECT_EQ(got.pixels.size(), tr.requests.size()) << what;
  for (size_t i = 0; i < tr.requests.size() && i < got.pixels.size(); ++i) {
    const Rgba8 want = golden_pixel(golden, u, got, tr.requests[i], lam[i], i);
    if (got.pixels[i] != want) {
      ADD_FAILURE() << what << ": request " << i << " at cycle " << got.response_cycle[i];
      break;
    }
  }
  return got;
}

UnitConfig small_cache(int block) {
  UnitConfig u;
  u.cache.block = block;
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
      SamplerDescriptor cfg = mesh.sampler;
      cfg.mode = m;
      const UnitOutput got =
          run_and_compare(*mesh.texture, cfg, st.trace, small_cache(block),
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
    for (ShapePolicy p : {ShapePolicy::Static, ShapePolicy::CacheAware, ShapePolicy::FullCross})
      for (BankMapping b : {BankMapping::TexelParity, BankMapping::BlockParity}) {
        SamplerDescriptor cfg = mesh.sampler;
        cfg.mode = filter_mode_from_name(mode);
        UnitConfig u = small_cache(4);
        u.shape_policy = p;
        u.cache.bank_mapping = b;
        const UnitOutput got = run_and_compare(*mesh.texture, cfg, st.trace, u, fmt::format("{} {}", mode, shape_policy_name(p)));
        const uint64_t cross = got.stats.counter("shape_cross"), t = got.stats.counter("shape_T"),
                       l = got.stats.counter("shape_L");
        EXPECT_GT(cross + t + l, 0u);
        if (p == ShapePolicy::FullCross) {
          EXPECT_EQ(t + l, 0u);
        }
        if (p == ShapePolicy::Static) {
          EXPECT_GT(t + l, 0u);  // a 64x64 texture magnified: block edges are common
        }
      }
}

TEST(TfuUnit, CacheAwareShapesContainTheStaticShapes) {
  const SceneTrace st = scene_trace("text_patch", 48, 32);
  const Mesh& mesh = st.scene.meshes.front();
  SamplerDescriptor cfg = mesh.sampler;
  cfg.mode = filter_mode_from_name("EDGE_PRESERVING");
  UnitConfig u = small_cache(4);
  u.shape_policy = ShapePolicy::CacheAware;
  const UnitOutput aware = run_and_compare(*mesh.texture, cfg, st.trace, u, "cache-aware");
  u.shape_policy = ShapePolicy::Static;
  const UnitOutput fixed = run_unit(*mesh.texture, cfg, st.trace, u);
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
      UnitConfig u = small_cache(block);
      SamplerDescriptor cfg = mesh.sampler;
      cfg.mode = filter_mode_from_name("LINEAR");
      const uint64_t bilinear = run_unit(*mesh.texture, cfg, st.trace, u).stats.counter("memory_bytes");
      cfg.mode = filter_mode_from_name("EDGE_PRESERVING");
      const uint64_t edge = run_unit(*mesh.texture, cfg, st.trace, u).stats.counter("memory_bytes");
      u.shape_policy = ShapePolicy::FullCross;
      const uint64_t full = run_unit(*mesh.texture, cfg, st.trace, u).stats.counter("memory_bytes");
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
      SamplerDescriptor cfg = mesh.sampler;
      cfg.mode = filter_mode_from_name(mode);
      cfg.wrap_s = cfg.wrap_t = w;
      cfg.border = {10, 200, 30, 255};
      run_and_compare(*mesh.texture, cfg, st.trace, UnitConfig{}, fmt::format("{} {}", mode, wrap_mode_name(w)));
    }
}

TEST(TfuUnit, CubicKernelsRomReconstructionAndBsplineInterp) {
  const SceneTrace st = scene_trace("magnified", 48, 32);
  const Mesh& mesh = st.scene.meshes.front();
  for (const char* kernel : {"catmull-rom", "bspline", "mitchell", kBsplineInterp}) {
    SamplerDescriptor cfg = mesh.sampler;
    cfg.mode = filter_mode_from_name("CUBIC_MIPMAP_LINEAR");
    cfg.kernel = kernel;
    for (RomRecon r : {RomRecon::Nearest, RomRecon::Linear}) {
      cfg.cubic_recon = r;
      run_and_compare(*mesh.texture, cfg, st.trace, UnitConfig{}, kernel);
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
    SamplerDescriptor cfg = mesh.sampler;
    cfg.mode = filter_mode_from_name(mode);
    run_and_compare(*mesh.texture, cfg, lod, UnitConfig{}, fmt::format("lod {}", mode));
    run_and_compare(*mesh.texture, cfg, grad, UnitConfig{}, fmt::format("grad {}", mode));
  }
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
  SamplerDescriptor cfg = mesh.sampler;
  UnitConfig u = hot_cache();
  const auto rate = [&](const char* mode, const UnitConfig& uc) {
    cfg.mode = filter_mode_from_name(mode);
    return clocks_per_pixel_on_hits(*mesh.texture, cfg, st.trace, uc, mode);
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
  SamplerDescriptor cfg = mesh.sampler;
  const auto latency = [&](const char* mode, int lanes) {
    cfg.mode = filter_mode_from_name(mode);
    UnitConfig u = hot_cache();
    u.filter_lanes = lanes;
    const UnitOutput o = run_and_compare(*mesh.texture, cfg, one, u, mode);
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
    SamplerDescriptor cfg = mesh.sampler;
    cfg.mode = filter_mode_from_name(mode);
    UnitConfig u = small_cache(4);
    u.memory.latency = 300;  // memory-bound: long idle stretches
    u.memory.bytes_per_cycle = 4;
    u.miss_fifo_depth = 8;
    u.idle_skip = false;
    const UnitOutput slow = run_unit(*mesh.texture, cfg, st.trace, u);
    u.idle_skip = true;
    const UnitOutput fast = run_unit(*mesh.texture, cfg, st.trace, u);
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
    const uint32_t xf = rng() % 256, yf = rng() % 256;
    for (const lee_jen::KernelShape& s : lee_jen::kernel_shapes()) {
      const lee_jen::LowIndex low = lee_jen::median_low_pass(lee_jen::luma_keys(c, s.mask, TexelFormat::RGBA8), s.mask);
      const lee_jen::EdgeDecision want = lee_jen::select_direction(c, low, s.mask, xf, yf, TexelFormat::RGBA8);
      const lee_jen::EdgeDecision got = direction_select(c, low, s.mask, xf, yf, TexelFormat::RGBA8);
      ASSERT_EQ(got.direction, want.direction) << s.name();
      ASSERT_EQ(got.cost, want.cost);
    }
  }
}

TEST(TfuUnit, ConfigJsonRoundTripAndErrors) {
  UnitConfig c;
  c.cache.block = 8;
  c.cache.capacity_bytes = 32768;
  c.cache.bank_mapping = BankMapping::TexelParity;
  c.filter_lanes = 4;
  c.shape_policy = ShapePolicy::CacheAware;
  const UnitConfig back = unit_config_from_json(unit_config_to_json(c), "cfg");
  EXPECT_EQ(unit_config_to_json(back), unit_config_to_json(c));
  const auto error = [](const std::string& text) {
    try {
      unit_config_from_json(text, "c.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("{\"cache\": {\"block\": 6}}").find("block 6"), std::string::npos);
  EXPECT_NE(error("{\"cache\": {\"capacity_bytes\": 32}}").find("capacity 32"), std::string::npos);
  EXPECT_NE(error("{\"cache\": {\"banks\": 0}}").find("banks 0"), std::string::npos);
  EXPECT_NE(error("{\"cache\": {\"size\": 1}}").find("unknown key 'size'"), std::string::npos);
  EXPECT_NE(error("{\"shape_policy\": \"round\"}").find("round"), std::string::npos);
  EXPECT_NE(error("{\"filter_lanes\": 3}").find("filter_lanes 3"), std::string::npos);
  EXPECT_NE(error("{\"cache\": ").find("malformed"), std::string::npos);
  EXPECT_NE(error("[1]").find("object"), std::string::npos);
}

TEST(TfuUnit, VcdDumpsEveryChannel) {
  const SceneTrace st = scene_trace("magnified", 16, 16);
  const Mesh& mesh = st.scene.meshes.front();
  SamplerDescriptor cfg = mesh.sampler;
  cfg.mode = filter_mode_from_name("EDGE_PRESERVING");
  std::ostringstream vcd;
  const UnitOutput o = run_unit(*mesh.texture, cfg, st.trace, UnitConfig{}, &vcd);
  const std::string v = vcd.str();
  for (const char* sig : {"$scope module tfu", "edge_s1", "texel_cache", "$enddefinitions", "valid", "ready"})
    EXPECT_NE(v.find(sig), std::string::npos) << sig;
  EXPECT_NE(v.find(fmt::format("#{}", o.cycles - 1)), std::string::npos);  // sampled up to the end
}

TEST(TfuUnit, ErrorsAreInputErrors) {
  const SceneTrace st = scene_trace("magnified", 16, 16);
  const Mesh& mesh = st.scene.meshes.front();
  SamplerDescriptor cfg = mesh.sampler;
  UnitConfig bad;
  bad.cache.block = 5;
  EXPECT_THROW(run_unit(*mesh.texture, cfg, st.trace, bad), InputError);
  Trace odd = st.trace;
  odd.requests.pop_back();
  EXPECT_THROW(run_unit(*mesh.texture, cfg, odd, UnitConfig{}), InputError);
}

}  // namespace
}  // namespace tfu::rtl
