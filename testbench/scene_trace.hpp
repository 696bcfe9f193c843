// A built-in scene rendered by the golden model at a given size, with its request trace (the
// tests' common workload; one thread, so the trace order is the rasterizer's).
#pragma once

#include <string>

#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"

namespace tfu::test {

struct SceneTrace {
  Scene scene;
  Trace trace;
};

inline SceneTrace scene_trace(const std::string& name, int w, int h) {
  SceneTrace st{load_scene(name), {}};
  st.scene.width = w;
  st.scene.height = h;
  RenderOptions o;
  o.trace = true;
  o.threads = 1;
  st.trace = render_scene(st.scene, o).trace;
  return st;
}

}  // namespace tfu::test
