// The off switch for every fast path (cmodel/fast_paths.hpp, TFU_PLAIN=1, the CLI's --plain): every
// built-in scene renders to the same bytes with the fast paths on and off, and the cycle model (both
// engines) gives the same image and cycles and equals the golden model either way; the golden
// compare follows the switch.
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "cmodel/fast_paths.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/golden_compare.hpp"
#include "rtl/scene_sim.hpp"

using namespace tfu;

namespace {

struct FastPathsGuard {
  bool saved = fast_paths_enabled();
  explicit FastPathsGuard(bool on) { set_fast_paths(on); }
  ~FastPathsGuard() { set_fast_paths(saved); }
  FastPathsGuard(const FastPathsGuard&) = delete;
  FastPathsGuard& operator=(const FastPathsGuard&) = delete;
};

struct PathsRun {
  RenderResult render;
  rtl::SceneSimResult clocked, recurrence;
};

PathsRun run_scene(const Scene& scene, bool fast, const std::map<std::string, std::string>& sampler_overrides = {}) {
  const FastPathsGuard guard(fast);
  EXPECT_EQ(fast_paths_enabled(), fast);
  PathsRun r;
  RenderOptions o;
  o.sampler_overrides = sampler_overrides;
  o.trace = true;
  o.line_bytes = rtl::UnitConfig{}.cache.line_bytes;
  r.render = render_scene(scene, o);
  rtl::SceneSimOptions so;
  so.engine = rtl::UnitEngine::Clocked;
  r.clocked = rtl::simulate_scene(scene, r.render, rtl::UnitConfig{}, so);
  so.engine = rtl::UnitEngine::Recurrence;
  r.recurrence = rtl::simulate_scene(scene, r.render, rtl::UnitConfig{}, so);
  return r;
}

}  // namespace

// The anisotropic probe threshold (aniso_threshold) on the tunnel and the grazing scene: both
// golden paths, both engines, the same bytes and cycles; the threshold takes probes away.
TEST(PlainPaths, AnisotropicThresholdIsTheSameWithAndWithoutFastPaths) {
  for (const char* name : {"tunnel", "grazing"})
    for (const char* max_aniso : {"2", "16"}) {
      Scene scene = load_scene(name);
      scene.width = 96;
      scene.height = 64;
      const std::map<std::string, std::string> literal{{"max_aniso", max_aniso}},
          thresholded{{"max_aniso", max_aniso}, {"aniso_threshold", "4"}};
      const PathsRun fast = run_scene(scene, true, thresholded), plain = run_scene(scene, false, thresholded);
      EXPECT_EQ(fast.render.image.texels, plain.render.image.texels) << name << " " << max_aniso;
      for (const rtl::SceneSimResult* s : {&fast.clocked, &fast.recurrence, &plain.clocked, &plain.recurrence}) {
        EXPECT_EQ(s->mismatch, "") << name;
        EXPECT_EQ(s->image.texels, fast.render.image.texels) << name;
        EXPECT_EQ(s->cycles, fast.clocked.cycles) << name;
      }
      const PathsRun lit = run_scene(scene, true, literal);
      EXPECT_LT(fast.clocked.cycles, lit.clocked.cycles) << name << " " << max_aniso;  // fewer probes, fewer clocks
    }
}

// The ellipse axes change only the LOD unit's N and lambda: the fast and plain probe paths and
// both cycle-model engines agree on them as on the screen axes'.
TEST(PlainPaths, AnisotropicEllipseAxesAreTheSameWithAndWithoutFastPaths) {
  for (const char* name : {"tunnel", "grazing"}) {
    Scene scene = load_scene(name);
    scene.width = 96;
    scene.height = 64;
    const std::map<std::string, std::string> ellipse{{"max_aniso", "16"}, {"aniso_axes", "ellipse"}};
    const PathsRun fast = run_scene(scene, true, ellipse), plain = run_scene(scene, false, ellipse);
    EXPECT_EQ(fast.render.image.texels, plain.render.image.texels) << name;
    for (const rtl::SceneSimResult* s : {&fast.clocked, &fast.recurrence, &plain.clocked, &plain.recurrence}) {
      EXPECT_EQ(s->mismatch, "") << name;
      EXPECT_EQ(s->image.texels, fast.render.image.texels) << name;
      EXPECT_EQ(s->cycles, fast.clocked.cycles) << name;
    }
  }
}

TEST(PlainPaths, EveryBuiltinSceneIsTheSameWithAndWithoutFastPaths) {
  for (const std::string& name : builtin_scene_names()) {
    Scene scene = load_scene(name);
    scene.width = 96;
    scene.height = 64;
    const PathsRun fast = run_scene(scene, true), plain = run_scene(scene, false);
    EXPECT_EQ(fast.render.image.texels, plain.render.image.texels) << name;
    EXPECT_EQ(fast.render.trace.requests.size(), plain.render.trace.requests.size()) << name;
    for (const rtl::SceneSimResult* s : {&fast.clocked, &fast.recurrence, &plain.clocked, &plain.recurrence}) {
      EXPECT_EQ(s->mismatch, "") << name;
      EXPECT_EQ(s->image.texels, fast.render.image.texels) << name;
      EXPECT_EQ(s->cycles, fast.clocked.cycles) << name;
    }
  }
}

// The golden compare (rtl::golden_outputs) runs Sampler::sample with the fast paths on and the plain
// datapath with them off, whatever the sampler was built with. The two datapaths are equal on
// every valid texture, so the test tells them apart on a texture whose format changes from RGBA8 to
// VS16X2 after its sampler was built with the fast paths on: the LINEAR fast path chosen then keeps
// lerping 8-bit words, the plain datapath decodes the signed pairs the format now names.
TEST(PlainPaths, GoldenCompareRunsThePlainDatapathWithTheSwitchOff) {
  const FastPathsGuard fast(true);
  auto tex = std::make_shared<Texture>();
  tex->format = TexelFormat::RGBA8;
  tex->levels.emplace_back(8, 8);
  std::mt19937 rng(5);
  for (Rgba8& w : tex->levels[0].texels)
    w = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()),
         static_cast<uint8_t>(rng())};
  FrameBuilder b(64);
  b.add_texture(tex, {"test", {}});
  SamplerDescriptor cfg;
  cfg.mode = filter_mode_from_name("LINEAR");
  b.add_sampler(cfg);
  Trace tr;
  tr.mode = TraceMode::Lod;
  for (int i = 0; i < 16; ++i) {
    TraceRequest r;
    r.s = (static_cast<float>(i) + 0.3f) / 16.0f;
    r.t = (static_cast<float>(i % 5) + 0.7f) / 5.0f;
    tr.requests.push_back(r);
  }
  bind_requests(b, tr);
  const Frame frame = b.finish();
  const GoldenUnit golden(frame);
  const Sampler& smp = golden.sampler(0, 0);  // built now, with the fast paths on
  tex->format = TexelFormat::VS16X2;
  std::vector<Rgba8> fast_path, plain;
  for (const TraceRequest& r : tr.requests) {
    fast_path.push_back(smp.sample(r.s, r.t, 0));
    plain.push_back(encode_texel(smp.sample_channels(r.s, r.t, 0), TexelFormat::VS16X2));
  }
  ASSERT_NE(fast_path, plain);  // the two datapaths differ here, so the compare's choice shows
  const rtl::UnitOutput none;   // no cache-aware edge shapes: a LINEAR trace
  EXPECT_EQ(rtl::golden_outputs(golden, tr, none), fast_path);
  set_fast_paths(false);
  EXPECT_EQ(rtl::golden_outputs(golden, tr, none), plain);
}
