// The off switch for every fast path (cmodel/fast_paths.hpp, TFU_PLAIN=1, the CLI's --plain): every
// built-in scene renders to the same bytes with the fast paths on and off, and the cycle model (both
// engines) gives the same image and cycles and equals the golden model either way.
#include <gtest/gtest.h>

#include <string>

#include "cmodel/fast_paths.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
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

PathsRun run_scene(const Scene& scene, bool fast) {
  const FastPathsGuard guard(fast);
  EXPECT_EQ(fast_paths_enabled(), fast);
  PathsRun r;
  RenderOptions o;
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
