// scene_sim: a rendered scene's request trace through one or several texture filter units and the
// golden model, request for request, with the cycle model's image.
//
// The unit works as a GPU's does: every texture and sampler of the frame is resident (the render's
// frame: descriptors and one texel memory), and each unit receives, in the order the rasterizer
// issues them (RenderOptions::raster), the requests of every material stage of the quads in its
// screen tiles (by default 32x32-pixel tiles dealt round-robin over the units; `tiles`,
// cmodel/raster_order.hpp). Meshes follow each other in submission order with no
// cache flush between them. Units run on their own threads (the simulation of each is
// single-threaded and deterministic, so results do not depend on the thread count). Cycles = the
// slowest unit's; every other statistic is summed over units.
//
// With an L2 (l2.capacity_bytes > 0) or memory.shared, the units are simulated together: each keeps
// its texel cache, and their misses go through one memory system (rtl/shared_memory.hpp: the L2,
// then one memory), served in one global order (by issue cycle, rotating priority within a cycle),
// the same for any thread count and either engine. Its statistics are added: per unit (the L2's
// counters, the l2_units table) and in total (the L2's memory bytes, the shared DRAM's counters).
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cmodel/parallel.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/tfu_unit.hpp"

namespace tfu::rtl {

struct SceneSimOptions {
  int units = 1;
  UnitTiles tiles;  // which unit draws which screen tile (round-robin:32 by default)
  std::ostream* vcd = nullptr;  // VCD of unit 0
  std::vector<std::ostream*> unit_vcds;  // if not empty: unit k's VCD (nullptr: none); replaces `vcd`
  uint64_t vcd_from = 0, vcd_to = UINT64_MAX;  // cycles dumped, inclusive
  std::vector<std::string> vcd_signals;        // the signals dumped (VcdOptions::signals; empty: all)
  // The timing recurrences, as `tfu sim`, `tfu sweep` and UnitEngine{} (the clocked run's results,
  // tested); a unit that writes a waveform still runs clocked. Clocked: the reference blocks.
  UnitEngine engine = UnitEngine::Recurrence;
  // Also run each unit's requests through both engines with every event recorded; the first event,
  // pixel or statistic at which they differ is a mismatch (rtl/engine_compare.hpp; a debugging aid).
  bool compare_engines = false;
  // Units simulated at once (0: hardware_threads()); results do not depend on it. (A streamed
  // run, render_and_simulate_scene, runs every unit on a thread of its own.)
  int threads = 0;
  // render_and_simulate_scene: hold the whole frame's trace (simulate_scene) even where the run
  // could stream; the results are the same (tested).
  bool whole_frame = false;
};

struct SceneSimResult {
  Image image;             // the cycle model's outputs composed into the rendered frame
  size_t requests = 0;
  uint64_t cycles = 0;     // slowest unit
  sim::Stats stats;        // summed
  std::string mismatch;    // empty when every output equals the golden model's
  // Thread CPU seconds spent in the cycle model and in the golden model (LOD + sampler) on the
  // same requests, summed over units.
  double cycle_seconds = 0, golden_seconds = 0;
};

// CPU seconds used so far by the calling thread (cmodel/parallel.hpp).
using tfu::thread_cpu_seconds;

// `render` must come from render_scene(scene, {trace = true, line_bytes = u.cache.line_bytes}).
SceneSimResult simulate_scene(const Scene& scene, const RenderResult& render, const UnitConfig& u, const SceneSimOptions& opt);

// The scene rendered (`ro`, its trace recorded) and simulated (`opt`) together. Where the run
// streams (streams_scene: the timing recurrences, no waveform, no engine compare, no memory system
// shared by the units, the scanline raster order), the render hands its trace band by band to the
// units, which run on threads of their own beside it, each on a bounded window of its requests
// (rtl/request_stream.hpp), and the golden compare and the image take their results chunk by
// chunk: the working set does not grow with the frame (docs/cycle-model.md, "Streaming"), and the
// render, the units and the compare overlap. Otherwise: render_scene, then simulate_scene. The
// results, statistics and image are the same either way (tested); a streamed render has no trace
// (RenderResult::trace and quad_targets empty).
// A streamed run's threads, for speed measurements only (no result depends on them; `tfu sim
// --bench`): the wall seconds of the whole call (the render's upload, RenderTimes::upload,
// included), the CPU seconds of each unit's thread (its cycle model, golden compare and image
// chunks), and the wall seconds the threads stood waiting: each unit for requests, and the
// render's hand-off (TraceSink::band) for room in the units' windows. The render's band workers'
// CPU seconds are RenderTimes::bands_cpu.
struct StreamTimes {
  double wall = 0;
  std::vector<double> unit_cpu, unit_wait;
  double handoff_wait = 0;
};

struct RenderedSceneSim {
  RenderResult render;
  SceneSimResult sim;
  bool streamed = false;
  StreamTimes times;  // a streamed run's
};
RenderedSceneSim render_and_simulate_scene(const Scene& scene, RenderOptions ro, const UnitConfig& u, const SceneSimOptions& opt);
bool streams_scene(const RenderOptions& ro, const UnitConfig& u, const SceneSimOptions& opt);

}  // namespace tfu::rtl
