// scene_sim: a rendered scene's request trace through one or several texture filter units and the
// golden model, pixel for pixel, with the cycle model's image.
//
// Each traced quad goes to the unit that owns its screen tile (32x32-pixel tiles dealt round-robin
// over the units) and, within a unit, to the mesh it samples; a unit draws its meshes one after
// another with the cache flushed between them (a texture switch). Units run on their own threads
// (the simulation of each is single-threaded and deterministic, so results do not depend on the
// thread count). Cycles = the slowest unit's; every other statistic is summed over units and meshes.
#pragma once

#include <optional>
#include <ostream>
#include <string>

#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/tfu_unit.hpp"

namespace tfu::rtl {

struct SceneSimOptions {
  std::optional<FilterMode> filter;  // replaces every mesh's filter mode
  int units = 1;
  int tile = 32;
  std::ostream* vcd = nullptr;  // VCD of unit 0's first mesh
};

struct SceneSimResult {
  Image image;             // the cycle model's output written into the rendered frame
  size_t requests = 0;
  uint64_t cycles = 0;     // slowest unit
  sim::Stats stats;        // summed
  std::string mismatch;    // empty when every output equals the golden model's
  // Thread CPU seconds spent in the cycle model and in the golden model (LOD + sampler) on the
  // same requests, summed over units and meshes.
  double cycle_seconds = 0, golden_seconds = 0;
};

// CPU seconds used so far by the calling thread (CLOCK_THREAD_CPUTIME_ID).
double thread_cpu_seconds();

SceneSimResult simulate_scene(const Scene& scene, const RenderResult& render, const UnitConfig& u,
                              const SceneSimOptions& opt);

}  // namespace tfu::rtl
