// tfu sim --bench: the speed of the cycle model against the golden model on one scene's requests
// (docs/cycle-model.md). The scene is rendered by the golden model and simulated once, or with
// --bench kBenchRuns times; the figures are the best runs in thread CPU seconds, and with the timing
// recurrences the clocked blocks run on the same requests too (they must give the same cycles and
// statistics).
#pragma once

#include <vector>

#include "cmodel/gl_replay.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/unit_config.hpp"

namespace tfu::cli {

inline constexpr int kBenchRuns = 7;  // --bench: best of this many runs

// The process's peak resident set so far (getrusage), bytes.
size_t peak_rss_bytes();

struct SceneRun {
  RenderResult render;     // the last run's golden render
  rtl::SceneSimResult res; // the first run's simulation; with --bench its seconds the best of all runs
  // --bench only:
  int runs = 1;
  double render_secs = 0, wall = 0;  // best golden render; the first simulation's wall clock
  std::vector<double> pair_ratio;    // cycle model / golden LOD + sampler of each run, sorted
  bool clocked = false;              // the clocked blocks were timed too (the recurrences ran)
  double clocked_secs = 0;           // their best run
  bool streamed = false;             // the render and the units ran together (rtl::render_and_simulate_scene)
  size_t peak_rss_bytes = 0;         // the process's peak resident set after the first run
  std::vector<double> clocked_ratio; // their ratio of each run, sorted
  // --bench of a streamed run: the run as a plain `tfu sim` makes it (the render on its default
  // threads, every unit on a thread of its own), best of kBenchRuns by wall clock, alternating
  // with the runs above; its render's upload, band workers' CPU and threads; and the start-up:
  // the level's load (open_scene, set by the caller), the process's age and CPU seconds when the
  // program's own initialisers ran (the dynamic loader and the shared libraries' initialisers).
  rtl::StreamTimes plain;
  double plain_upload = 0, plain_bands_cpu = 0;
  int plain_render_threads = 0;
  double load_wall = 0;
};

// The process's age (wall seconds since it was started) and CPU seconds (user + system, every
// thread's) when the program's static initialisers ran, i.e. what the dynamic loader and the
// shared libraries' initialisers took before them; the age to the kernel's clock tick (10 ms).
struct ProcessStart {
  double age = 0, cpu = 0;
};
const ProcessStart& process_start();
// The process's CPU seconds so far (getrusage: user + system, every thread's).
double process_cpu_seconds();

// Renders the scene (`ro`, one thread with `bench`) and simulates its trace (`so`; one thread with `bench`),
// streamed where the run allows (rtl::render_and_simulate_scene).
SceneRun render_and_simulate(const Scene& scene, RenderOptions ro, const rtl::UnitConfig& unit, rtl::SceneSimOptions so,
                             bool bench);
// The --bench lines of a run of `units` units by `engine`.
void print_bench(const SceneRun& run, rtl::UnitEngine engine, int units);

// tfu sim --gl-trace --bench: the replay of one frame timed part by part (best of kGlBenchReplays
// replays), then the cycle model and the golden model alone on its requests (best of kBenchRuns each,
// alternating); prints what each figure includes. The models must give the outputs of the first run.
inline constexpr int kGlBenchReplays = 3;
void bench_gl_trace(const std::string& trace, int frame, const gl::ReplayOptions& ro, const gl::Replay& first,
                    const rtl::UnitConfig& unit, rtl::UnitEngine engine, const std::vector<Rgba8>& outputs);

}  // namespace tfu::cli
