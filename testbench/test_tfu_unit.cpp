// Cycle model (rtl/tfu_unit) against the golden sampler, bit for bit, on scene traces; rates.
#include <gtest/gtest.h>

#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/tfu_unit.hpp"

namespace tfu::rtl {
namespace {

struct SceneTrace {
  Scene scene;
  Trace trace;
};

SceneTrace scene_trace(const char* name, int w, int h) {
  SceneTrace st{load_scene(name), {}};
  st.scene.width = w;
  st.scene.height = h;
  RenderOptions o;
  o.trace = true;
  o.threads = 1;
  st.trace = render_scene(st.scene, o).trace;
  return st;
}

std::vector<Rgba8> golden(const Texture& tex, const SamplerConfig& cfg, const Trace& tr) {
  const Sampler smp(tex, cfg);
  const std::vector<int32_t> lam = trace_lambdas(tr, tex.width(), tex.height());
  std::vector<Rgba8> out;
  for (size_t i = 0; i < tr.requests.size(); ++i) out.push_back(smp.sample(tr.requests[i].s, tr.requests[i].t, lam[i]));
  return out;
}

TEST(TfuUnit, BitExactAgainstGoldenForNearestAndLinearFamilies) {
  for (const char* name : {"magnified", "ground_plane"}) {
    const SceneTrace st = scene_trace(name, 64, 48);
    const Mesh& mesh = st.scene.meshes.front();
    for (const char* mode : {"NEAREST", "LINEAR", "NEAREST_MIPMAP_NEAREST", "LINEAR_MIPMAP_NEAREST",
                             "NEAREST_MIPMAP_LINEAR", "LINEAR_MIPMAP_LINEAR"})
      for (int block : {4, 8}) {
        SamplerConfig cfg = mesh.sampler;
        cfg.mode = filter_mode_from_name(mode);
        UnitConfig u;
        u.cache.block = block;
        u.cache.capacity_bytes = 8192;
        u.cache.ways = 2;
        const UnitOutput got = run_unit(*mesh.texture, cfg, st.trace, u);
        const std::vector<Rgba8> want = golden(*mesh.texture, cfg, st.trace);
        ASSERT_EQ(got.pixels.size(), want.size());
        for (size_t i = 0; i < want.size(); ++i)
          ASSERT_EQ(got.pixels[i], want[i]) << name << " " << mode << " B=" << block << " request " << i;
        EXPECT_GT(got.stats.counter("cache_line_misses"), 0u);
      }
  }
}

TEST(TfuUnit, BitExactForEveryWrapMode) {
  const SceneTrace st = scene_trace("ground_plane", 48, 32);
  const Mesh& mesh = st.scene.meshes.front();
  for (WrapMode w : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge, WrapMode::ClampToBorder}) {
    SamplerConfig cfg = mesh.sampler;
    cfg.mode = filter_mode_from_name("LINEAR_MIPMAP_LINEAR");
    cfg.wrap_s = cfg.wrap_t = w;
    cfg.border = {10, 200, 30, 255};
    const UnitOutput got = run_unit(*mesh.texture, cfg, st.trace, UnitConfig{});
    EXPECT_EQ(got.pixels, golden(*mesh.texture, cfg, st.trace)) << wrap_mode_name(w);
  }
}

TEST(TfuUnit, OnePixelPerClockOnHitsTwoForTrilinear) {
  const SceneTrace st = scene_trace("magnified", 64, 64);
  const Mesh& mesh = st.scene.meshes.front();
  UnitConfig u;
  u.cache.capacity_bytes = 64 * 64 * 4 * 2;  // the whole 64x64 texture and its MIP chain
  u.memory.latency = 0;
  u.memory.bytes_per_cycle = 1024;
  SamplerConfig cfg = mesh.sampler;
  cfg.mode = filter_mode_from_name("LINEAR");
  const UnitOutput lin = run_unit(*mesh.texture, cfg, st.trace, u);
  const double n = static_cast<double>(st.trace.requests.size());
  // One pixel per clock except the cycles spent waiting for the 256 cold misses (1 cycle each here)
  // and the pipeline fill.
  const auto busy = static_cast<double>(lin.cycles - lin.stats.counter("stall_cache_miss"));
  EXPECT_NEAR(busy / n, 1.0, 0.01);
  EXPECT_EQ(lin.stats.counter("cache_line_misses"), 256u);  // every 4x4 block of the 64x64 level once
  EXPECT_EQ(lin.stats.counter("stall_bank_conflict"), 0u);  // a 2x2 footprint uses the 4 parity banks
  // Magnified: lambda < 0, so trilinear never blends and keeps 1 pixel/clock; force blending with
  // a bias so every pixel takes two footprints.
  cfg.mode = filter_mode_from_name("LINEAR_MIPMAP_LINEAR");
  cfg.lod.bias_q8 = 3 * 256 + 128;
  const UnitOutput tri = run_unit(*mesh.texture, cfg, st.trace, u);
  EXPECT_NEAR(static_cast<double>(tri.cycles) / n, 2.0, 0.1);
}

TEST(TfuUnit, UnsupportedModesAreInputErrors) {
  const SceneTrace st = scene_trace("magnified", 16, 16);
  const Mesh& mesh = st.scene.meshes.front();
  SamplerConfig cfg = mesh.sampler;
  cfg.mode = filter_mode_from_name("CUBIC");
  EXPECT_THROW(run_unit(*mesh.texture, cfg, st.trace, UnitConfig{}), InputError);
  UnitConfig bad;
  bad.cache.block = 5;
  cfg.mode = filter_mode_from_name("LINEAR");
  EXPECT_THROW(run_unit(*mesh.texture, cfg, st.trace, bad), InputError);
}

}  // namespace
}  // namespace tfu::rtl
