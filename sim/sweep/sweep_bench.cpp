#include "sim/sweep/sweep_bench.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <thread>

#include <fmt/format.h>

#include "cmodel/raster.hpp"
#include "cmodel/scene_source.hpp"
#include "cmodel/temp_paths.hpp"
#include "rtl/kernel/kernel.hpp"
#include "rtl/scene_sim.hpp"
#include "sim/sweep/sweep_run.hpp"

namespace tfu::sweep {
namespace {

using Clock = std::chrono::steady_clock;

// One point as `tfu sim` runs it: open the scene, render with the trace, simulate with the golden compare.
double single_run(const Spec& s, const Point& p) {
  const auto t0 = Clock::now();
  const Scene scene = open_scene({p.scene_path, p.width, p.height, s.game_dir});
  RenderOptions ro;
  ro.trace = true;
  ro.threads = 1;
  ro.line_bytes = p.config.cache.line_bytes;
  ro.raster = p.raster;
  if (p.texture_layout != "own") ro.texture_layout = memory_layout_from_name(p.texture_layout);
  ro.sampler_overrides = p.sampler;
  if (p.filter != kSceneFilter) ro.filter = filter_mode_from_name(p.filter);
  const RenderResult render = render_scene(scene, ro);
  const rtl::SceneSimOptions so = scene_sim_options(p);
  (void)rtl::simulate_scene(scene, render, p.config, so);
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

BenchFigures bench(const Spec& spec, const std::vector<Point>& points, int workers) {
  BenchFigures f;
  f.points = points.size();
  double load[1] = {0};
  if (::getloadavg(load, 1) == 1) f.load_before = load[0];
  sim::set_progress_bars(false);
  const std::clock_t c0 = std::clock();
  for (size_t i = 0; i < points.size(); ++i) {
    f.single_sum += single_run(spec, points[i]);
    std::fprintf(stderr, "\rbench: single runs %zu/%zu (%.1f s)   ", i + 1, points.size(), f.single_sum);
  }
  std::fputc('\n', stderr);
  const std::clock_t c1 = std::clock();
  f.single_cpu = static_cast<double>(c1 - c0) / CLOCKS_PER_SEC;
  RunOptions opt;
  opt.workers = workers;
  opt.progress = true;
  const RunSummary sum = [&] {
    const TempDir dir("tfu-sweep-bench");  // the sweep's point files: a private directory, removed after
    return run_points(spec, points, dir.path().string(), opt);
  }();
  f.sweep_cpu = static_cast<double>(std::clock() - c1) / CLOCKS_PER_SEC;
  f.workers = static_cast<int>(std::min<size_t>(points.size(), opt.workers > 0 ? static_cast<size_t>(opt.workers)
                                                                              : std::max(1u, std::thread::hardware_concurrency())));
  f.wall = sum.wall_seconds;
  for (const PointTiming& t : sum.timings) {
    f.simulation_sum += t.simulation_seconds;
    f.point_sum += t.seconds;
  }
  return f;
}

std::string bench_report(const BenchFigures& f) {
  return fmt::format(
      "tfu sweep --bench: {} points, {} worker(s), {} hardware thread(s)\n"
      "  single runs, one after the other (as tfu sim, in-process): {:.2f} s in all\n"
      "  the sweep on the local runner: wall {:.2f} s = {:.3f} x the sum of the single runs (target <= 0.6)\n"
      "  inside the sweep: simulation {:.2f} s, points in all {:.2f} s: overhead beyond the simulation {:.1f} % (target <= 20 %)\n"
      "  CPU: single runs {:.2f} s, the sweep {:.2f} s ({:.3f} x); the sweep used {:.2f} cores on average; load average {:.2f} "
      "before the bench (other work on the machine takes cores from both)\n",
      f.points, f.workers, std::thread::hardware_concurrency(), f.single_sum, f.wall, f.wall_ratio(), f.simulation_sum,
      f.point_sum, 100.0 * f.overhead(), f.single_cpu, f.sweep_cpu, f.single_cpu > 0 ? f.sweep_cpu / f.single_cpu : 0,
      f.wall > 0 ? f.sweep_cpu / f.wall : 0, f.load_before);
}

}  // namespace tfu::sweep
