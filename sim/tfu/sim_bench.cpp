#include "sim/tfu/sim_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include <sys/resource.h>
#include <unistd.h>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/parallel.hpp"
#include "rtl/golden_compare.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_stats.hpp"

namespace tfu::cli {

size_t peak_rss_bytes() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<size_t>(ru.ru_maxrss) * 1024;  // Linux: kilobytes
}

double process_cpu_seconds() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(ru.ru_utime) + seconds(ru.ru_stime);
}

namespace {

// The process's age: /proc/uptime (seconds since boot, to 10 ms) less /proc/self/stat's start
// time (field 22, clock ticks since boot; the file's second field, the command, is in parentheses
// and may hold spaces, so the fields are counted after its closing one). 0 where unreadable.
double process_age_seconds() {
  std::ifstream stat("/proc/self/stat"), uptime("/proc/uptime");
  std::string line;
  double up = 0;
  if (!std::getline(stat, line) || !(uptime >> up)) return 0;
  const size_t close = line.rfind(')');
  if (close == std::string::npos) return 0;
  std::istringstream fields(line.substr(close + 1));
  std::string field;
  for (int k = 3; k <= 22 && fields >> field; ++k)  // fields 3 (state) .. 22 (starttime)
    if (k == 22) return std::max(0.0, up - std::stod(field) / static_cast<double>(sysconf(_SC_CLK_TCK)));
  return 0;
}

const ProcessStart kAtStaticInit{process_age_seconds(), process_cpu_seconds()};

}  // namespace

const ProcessStart& process_start() { return kAtStaticInit; }

SceneRun render_and_simulate(const Scene& scene, RenderOptions ro, const rtl::UnitConfig& unit, rtl::SceneSimOptions so,
                             bool bench) {
  const RenderOptions plain_ro = ro;
  const rtl::SceneSimOptions plain_so = so;
  if (bench) ro.threads = 1;  // the golden render's time, one thread, for the end-to-end ratio
  // --bench: the units one at a time, so that the CPU seconds are those of one core. Units sharing
  // a memory then take turns at their misses on that core, and their hand-overs are in the figure.
  // (A streamed run gives each unit a thread of its own beside the render: its figures are still
  // each thread's CPU seconds.)
  if (bench) so.threads = 1;
  // --bench: best of kBenchRuns runs of the golden render and of the simulation, in thread CPU
  // seconds, so that the figures do not depend on other work on the machine; the two alternate
  // run by run, so that a slow spell of the (virtual) machine falls on both sides of the ratio.
  SceneRun out;
  out.runs = bench ? kBenchRuns : 1;
  out.render_secs = 1e300;
  out.clocked_secs = 1e300;
  // --bench with the timing recurrences also times the clocked blocks on the same requests.
  out.clocked = bench && so.engine == rtl::UnitEngine::Recurrence;
  rtl::SceneSimResult& res = out.res;
  out.plain.wall = 1e300;
  for (int run = 0; run < out.runs; ++run) {
    double render_secs = 0;
    double wall = 0;
    rtl::SceneSimResult r;
    if (rtl::streams_scene(ro, unit, so)) {
      // The render and the units together (rtl/scene_sim.hpp): the render's figure is the calling
      // thread's (the render's, dealing its bands to the units included), the wall clock both.
      const auto t0 = std::chrono::steady_clock::now();
      const double tr = rtl::thread_cpu_seconds();
      rtl::RenderedSceneSim both = rtl::render_and_simulate_scene(scene, ro, unit, so);
      render_secs = rtl::thread_cpu_seconds() - tr;
      wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      out.render = std::move(both.render);
      r = std::move(both.sim);
      out.streamed = true;
    } else {
      RenderOptions traced = ro;
      traced.trace = true;
      const double tr = rtl::thread_cpu_seconds();
      out.render = render_scene(scene, traced);
      render_secs = rtl::thread_cpu_seconds() - tr;
      const auto t0 = std::chrono::steady_clock::now();
      r = rtl::simulate_scene(scene, out.render, unit, so);
      wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    out.render_secs = std::min(out.render_secs, render_secs);
    if (run == 0) {
      out.wall = wall;
      out.peak_rss_bytes = peak_rss_bytes();
      res = std::move(r);
    } else {
      res.cycle_seconds = std::min(res.cycle_seconds, r.cycle_seconds);
      res.golden_seconds = std::min(res.golden_seconds, r.golden_seconds);
    }
    out.pair_ratio.push_back(r.cycle_seconds / r.golden_seconds);
    if (out.clocked) {
      rtl::SceneSimOptions clocked = so;
      clocked.engine = rtl::UnitEngine::Clocked;  // on the whole frame's trace
      const rtl::SceneSimResult c = rtl::render_and_simulate_scene(scene, ro, unit, clocked).sim;
      if (c.cycles != res.cycles || c.stats.json_text() != res.stats.json_text())
        throw CheckFailed("--bench: the clocked unit and the timing recurrences disagree (cycles or statistics)");
      out.clocked_secs = std::min(out.clocked_secs, c.cycle_seconds);
      out.clocked_ratio.push_back(c.cycle_seconds / c.golden_seconds);
    }
    if (bench && out.streamed) {  // as a plain `tfu sim` runs it: its wall clock, part by part
      rtl::RenderedSceneSim p = rtl::render_and_simulate_scene(scene, plain_ro, unit, plain_so);
      if (p.sim.cycles != res.cycles || p.sim.image.texels != res.image.texels)
        throw CheckFailed("--bench: a run on the default threads gave other cycles or another image");
      if (p.times.wall < out.plain.wall) {
        out.plain = std::move(p.times);
        out.plain_upload = p.render.times.upload;
        out.plain_bands_cpu = p.render.times.bands_cpu;
      }
    }
  }
  out.plain_render_threads = plain_ro.threads > 0 ? plain_ro.threads : hardware_threads();
  std::sort(out.pair_ratio.begin(), out.pair_ratio.end());
  std::sort(out.clocked_ratio.begin(), out.clocked_ratio.end());
  return out;
}

namespace {

// The streamed run as a plain `tfu sim` makes it: its wall clock, the start-up before it, where the
// threads' CPU seconds went, how long they waited, and which bound the wall clock sits at. On C
// cores the streamed part takes at least max(work / C, the busiest unit's thread, the render's
// workers' share of theirs); more units lower only the second, so --units N helps while a unit's
// thread is the longest of the three.
void print_streamed_wall(const SceneRun& run, int units) {
  const rtl::StreamTimes& t = run.plain;
  double unit_cpu = 0, unit_max = 0, unit_wait = 0;
  for (size_t k = 0; k < t.unit_cpu.size(); ++k) {
    unit_cpu += t.unit_cpu[k];
    unit_max = std::max(unit_max, t.unit_cpu[k]);
    unit_wait += t.unit_wait[k];
  }
  const int cores = hardware_threads();
  const double streamed = t.wall - run.plain_upload;  // from the first band on
  const double work = run.plain_bands_cpu + unit_cpu;
  const double by_cores = work / cores, by_render = run.plain_bands_cpu / std::min(cores, run.plain_render_threads);
  const double bound = std::max({by_cores, unit_max, by_render});
  std::string limit;
  if (bound == unit_max)
    limit = fmt::format("the busiest unit's thread ({:.3f} s CPU): more units (up to {} cores) would split it", unit_max, cores);
  else if (bound == by_cores)
    limit = fmt::format("the CPU: {:.3f} s of work on {} core(s) (render {:.0f} %, units {:.0f} %); more units cannot "
                        "lower it, less work can (the render's shading and golden sampler, the units' golden compare)",
                        work, cores, 100 * run.plain_bands_cpu / work, 100 * unit_cpu / work);
  else
    limit = fmt::format("the render's band workers ({:.3f} s CPU on {} thread(s))", run.plain_bands_cpu,
                        std::min(cores, run.plain_render_threads));
  double load[1] = {0};
  const bool has_load = getloadavg(load, 1) == 1;
  const ProcessStart& ps = process_start();
  std::cout << fmt::format(
      "  wall clock as `tfu sim` runs it ({} render thread(s), {} unit thread(s), {} core(s); best of {} runs{}):\n"
      "    start-up: {:.2f} s before main ({:.2f} s CPU: the dynamic loader and the shared libraries' initialisers), "
      "level load {:.3f} s, texture upload {:.3f} s\n"
      "    streamed part {:.3f} s (render, units and golden compare together; with the upload {:.3f} s)\n"
      "    CPU: render band workers {:.3f} s, units {:.3f} s (busiest {:.3f} s): {:.3f} s, {:.2f} cores busy\n"
      "    waits: units for requests {:.3f} s (summed), the render's hand-off for room in the units' windows {:.3f} s\n"
      "    bound: {:.3f} s, set by {}\n",
      run.plain_render_threads, units, cores, run.runs,
      has_load ? fmt::format(", load average {:.2f}", load[0]) : std::string(), ps.age, ps.cpu, run.load_wall,
      run.plain_upload, streamed, t.wall, run.plain_bands_cpu, unit_cpu, unit_max, work, work / streamed, unit_wait,
      t.handoff_wait, bound, limit);
}

}  // namespace

void print_bench(const SceneRun& run, rtl::UnitEngine engine, int units) {
  const rtl::SceneSimResult& res = run.res;
  const auto n = static_cast<double>(res.requests);
  std::cout << fmt::format(
      "  speed, one thread each, CPU seconds, best of {} runs, on the same {} requests:\n"
      "    cycle model ({}) {:.3f} s = {:.2f} M simulated requests/s\n"
      "    golden LOD + sampler {:.3f} s = {:.2f} M requests/s\n"
      "    cost of cycle accuracy: cycle model / golden LOD + sampler = {:.2f}x (per run: median {:.2f}x, range "
      "{:.2f}-{:.2f}x)\n",
      run.runs, res.requests, rtl::unit_engine_name(engine), res.cycle_seconds, n / res.cycle_seconds / 1e6,
      res.golden_seconds, n / res.golden_seconds / 1e6, res.cycle_seconds / res.golden_seconds,
      run.pair_ratio[run.pair_ratio.size() / 2], run.pair_ratio.front(), run.pair_ratio.back());
  if (run.clocked)
    std::cout << fmt::format(
        "    the clocked blocks on the same requests (the reference; same cycles and statistics): {:.3f} s = {:.2f} M "
        "simulated requests/s, {:.2f}x the golden (per run: median {:.2f}x)\n",
        run.clocked_secs, n / run.clocked_secs / 1e6, run.clocked_secs / res.golden_seconds,
        run.clocked_ratio[run.clocked_ratio.size() / 2]);
  std::cout << fmt::format(
      "    (for scale, not in the ratio: the golden render of the scene, rasterizer included, {:.3f} s)\n"
      "    wall {:.3f} s for {} unit(s) (first run: {})\n",
      run.render_secs, run.wall, units,
      run.streamed ? "render, cycle model and golden compare streamed together" : "cycle model + golden compare");
  if (run.streamed) print_streamed_wall(run, units);
  // The process's peak resident set after the first run (before the clocked blocks' whole-frame
  // runs): the scene, its textures and the working set of the run (docs/cycle-model.md, "Streaming").
  std::cout << fmt::format("    peak RSS {:.1f} MB after the first run ({}), {:.1f} bytes per request\n",
                           static_cast<double>(run.peak_rss_bytes) / 1e6,
                           run.streamed ? "streamed: the working set does not grow with the frame" : "whole-frame trace",
                           static_cast<double>(run.peak_rss_bytes) / n);
  if (const uint64_t probes = rtl::counter(res.stats, rtl::UnitStat::Probes); probes != res.requests) {
    const std::string clocked =
        run.clocked ? fmt::format(" (clocked blocks {:.2f} M)", static_cast<double>(probes) / run.clocked_secs / 1e6)
                    : std::string();
    std::cout << fmt::format("    anisotropic: {} probes ({:.2f} per pixel): cycle model {:.2f} M simulated probes/s{}\n",
                             probes, static_cast<double>(probes) / n, static_cast<double>(probes) / res.cycle_seconds / 1e6,
                             clocked);
  }
}

void bench_gl_trace(const std::string& trace, int frame, const gl::ReplayOptions& ro, const gl::Replay& first,
                    const rtl::UnitConfig& unit, rtl::UnitEngine engine, const std::vector<Rgba8>& outputs) {
  // The replay, part by part: each part's best over the replays (the first one included).
  gl::ReplayTimes best = first.times;
  double best_total =
      first.times.dump_cpu + first.times.parse + first.times.state + first.times.place + first.times.raster;
  for (int i = 1; i < kGlBenchReplays; ++i) {
    const gl::Replay again = gl::replay_frame(trace, frame, ro);
    if (again.image.texels != first.image.texels)
      throw CheckFailed("--bench: a second replay of the frame gave another image");
    const gl::ReplayTimes& t = again.times;
    best.dump_wall = std::min(best.dump_wall, t.dump_wall), best.dump_cpu = std::min(best.dump_cpu, t.dump_cpu);
    best.parse = std::min(best.parse, t.parse), best.state = std::min(best.state, t.state);
    best.place = std::min(best.place, t.place), best.raster = std::min(best.raster, t.raster);
    best_total = std::min(best_total, t.dump_cpu + t.parse + t.state + t.place + t.raster);
  }
  // The models alone on the frame's requests, alternating run by run.
  const Frame& f = *first.unit_frame;
  const GoldenUnit golden(f);
  double cycle = 1e300, sampling = 1e300;
  for (int run = 0; run < kBenchRuns; ++run) {
    const double t0 = rtl::thread_cpu_seconds();
    const rtl::UnitOutput got = rtl::run_unit(f, first.requests, unit, engine, rtl::VcdOptions{});
    const double t1 = rtl::thread_cpu_seconds();
    const std::vector<Rgba8> want = rtl::golden_outputs(golden, first.requests, got);
    const double t2 = rtl::thread_cpu_seconds();
    if (got.pixels != outputs || want != outputs)
      throw CheckFailed("--bench: a model's outputs differ from the first run's");
    cycle = std::min(cycle, t1 - t0), sampling = std::min(sampling, t2 - t1);
  }
  const auto n = static_cast<double>(first.requests.requests.size());
  std::cout << fmt::format(
      "  speed (--bench), one thread, CPU seconds (the dump: apitrace's process), best of {} replays and of {} model "
      "runs, "
      "{} requests, {} covered pixels, {}x{}:\n"
      "    trace parse: apitrace dump {:.3f} s CPU ({:.3f} s wall, two dumps: the frame boundaries, the calls with "
      "their blobs), "
      "its text parsed {:.3f} s\n"
      "    GL state: every call executed (state, texture levels decoded from the blobs, draws fetched, transformed, "
      "clipped, "
      "snapped) {:.3f} s; textures placed {:.3f} s\n"
      "    rasterisation with sampling: quads, depth test, requests, golden LOD + sampler inline, the renderer after "
      "it {:.3f} s; "
      "of it the golden LOD + sampler (the same work measured alone) {:.3f} s, so rasterisation and renderer {:.3f} s "
      "(by difference)\n"
      "    the golden model's frame, trace to image: {:.3f} s CPU (best replay; best parts summed: {:.3f} s)\n"
      "    cycle model ({}) alone on the requests {:.3f} s = {:.2f} M requests/s; golden LOD + sampler alone {:.3f} s "
      "= {:.2f} M "
      "requests/s\n",
      kGlBenchReplays, kBenchRuns, first.requests.requests.size(), first.stats.pixels, first.width, first.height,
      best.dump_cpu, best.dump_wall, best.parse, best.state, best.place, best.raster, sampling, best.raster - sampling,
      best_total, best.dump_cpu + best.parse + best.state + best.place + best.raster, rtl::unit_engine_name(engine),
      cycle, n / cycle / 1e6, sampling, n / sampling / 1e6);
}

}  // namespace tfu::cli
