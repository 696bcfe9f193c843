#include "rtl/scene_sim.hpp"

#include <algorithm>
#include <atomic>

#include <time.h>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/parallel.hpp"

namespace tfu::rtl {

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

namespace {

struct Job {
  int unit = 0, mesh = 0;
  Trace trace;
  std::vector<size_t> quads;  // indices into render.quad_targets
  UnitOutput out;
  std::string mismatch;
  double cycle_seconds = 0, golden_seconds = 0;
};

void merge(sim::Stats& into, const sim::Stats& from) {
  for (const auto& [k, v] : from.counters())
    if (k != "cycles") into.add(k, v);
}

}  // namespace

SceneSimResult simulate_scene(const Scene& scene, const RenderResult& render, const UnitConfig& u,
                              const SceneSimOptions& opt) {
  if (opt.units < 1 || opt.units > 256) throw InputError(fmt::format("units {} must be in 1..256", opt.units));
  if (render.quad_targets.size() * 4 != render.trace.requests.size())
    throw InputError("scene simulation needs a render with RenderOptions::trace");
  u.validate();
  const auto nmesh = scene.meshes.size();
  std::vector<Job> jobs(static_cast<size_t>(opt.units) * nmesh);
  for (size_t j = 0; j < jobs.size(); ++j) {
    jobs[j].unit = static_cast<int>(j / nmesh);
    jobs[j].mesh = static_cast<int>(j % nmesh);
    jobs[j].trace.mode = TraceMode::Quad;
  }
  const int tiles_x = (scene.width + opt.tile - 1) / opt.tile;
  for (size_t q = 0; q < render.quad_targets.size(); ++q) {
    const QuadTarget& t = render.quad_targets[q];
    const int tile = (t.y / opt.tile) * tiles_x + t.x / opt.tile;
    Job& job = jobs[static_cast<size_t>(tile % opt.units) * nmesh + static_cast<size_t>(t.mesh)];
    job.quads.push_back(q);
    for (size_t k = 0; k < 4; ++k) job.trace.requests.push_back(render.trace.requests[q * 4 + k]);
  }
  const auto run_job = [&](Job& job) {
    if (job.quads.empty()) return;
    const Mesh& mesh = scene.meshes[static_cast<size_t>(job.mesh)];
    SamplerConfig cfg = mesh.sampler;
    if (opt.filter) cfg.mode = *opt.filter;
    std::ostream* vcd = (job.unit == 0 && &job == &jobs[0]) ? opt.vcd : nullptr;
    const double t0 = thread_cpu_seconds();
    job.out = run_unit(*mesh.texture, cfg, job.trace, u, vcd);
    const double t1 = thread_cpu_seconds();
    // The golden model on the same requests: LOD unit and sampler (the same work the cycle model
    // does, without timing), timed separately for the cost-of-cycle-accuracy ratio.
    const Sampler golden(*mesh.texture, golden_sampler_config(cfg, u));
    const std::vector<int32_t> lam = trace_lambdas(job.trace, mesh.texture->width(), mesh.texture->height());
    std::vector<Rgba8> want(job.trace.requests.size());
    for (size_t i = 0; i < job.trace.requests.size(); ++i)
      want[i] = golden_pixel(golden, u, job.out, job.trace.requests[i], lam[i], i);
    const double t2 = thread_cpu_seconds();
    job.cycle_seconds = t1 - t0;
    job.golden_seconds = t2 - t1;
    for (size_t i = 0; i < job.trace.requests.size(); ++i) {
      const TraceRequest& r = job.trace.requests[i];
      const Rgba8 have = job.out.pixels[i];
      if (want[i] != have) {
        job.mismatch = fmt::format(
            "unit {} mesh {} request {} (s={:.9g}, t={:.9g}) at cycle {}: cycle model {},{},{},{} vs golden {},{},{},{}",
            job.unit, job.mesh, i, r.s, r.t, job.out.response_cycle[i], have.r, have.g, have.b, have.a, want[i].r,
            want[i].g, want[i].b, want[i].a);
        return;
      }
    }
  };
  // Units are handed out to up to hardware_threads() workers (each unit runs its meshes in order on
  // one thread); results do not depend on which worker runs which unit.
  std::vector<std::exception_ptr> errors(static_cast<size_t>(opt.units));
  std::atomic<int> next_unit{0};
  run_workers(std::min(opt.units, hardware_threads()), [&](int) {
    for (int unit = next_unit++; unit < opt.units; unit = next_unit++) {
      try {
        for (size_t m = 0; m < nmesh; ++m) run_job(jobs[static_cast<size_t>(unit) * nmesh + m]);
      } catch (...) {
        errors[static_cast<size_t>(unit)] = std::current_exception();
      }
    }
  });
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);

  SceneSimResult res;
  res.image = render.image;
  res.requests = render.trace.requests.size();
  std::vector<uint64_t> unit_cycles(static_cast<size_t>(opt.units), 0);
  std::vector<uint64_t> latency;
  for (const Job& job : jobs) {
    res.cycle_seconds += job.cycle_seconds;
    res.golden_seconds += job.golden_seconds;
    if (!job.mismatch.empty() && res.mismatch.empty()) res.mismatch = job.mismatch;
    if (job.quads.empty()) continue;
    unit_cycles[static_cast<size_t>(job.unit)] += job.out.cycles;
    merge(res.stats, job.out.stats);
    if (const auto* h = job.out.stats.histogram("latency")) {
      if (latency.size() < h->size()) latency.resize(h->size());
      for (size_t c = 0; c < h->size(); ++c) latency[c] += (*h)[c];
    }
    for (size_t qi = 0; qi < job.quads.size(); ++qi) {
      const QuadTarget& t = render.quad_targets[job.quads[qi]];
      for (int k = 0; k < 4; ++k)
        if ((t.mask >> k) & 1u) {
          const int x = t.x + (k & 1), y = t.y + (k >> 1);
          res.image.texels[static_cast<size_t>(y) * static_cast<size_t>(res.image.width) + static_cast<size_t>(x)] =
              job.out.pixels[qi * 4 + static_cast<size_t>(k)];
        }
    }
  }
  res.cycles = *std::max_element(unit_cycles.begin(), unit_cycles.end());
  const auto n = static_cast<double>(res.requests);
  res.stats.add("cycles", res.cycles);
  res.stats.add("units", static_cast<uint64_t>(opt.units));
  res.stats.set_histogram("latency", latency);
  res.stats.set("pixels_per_clock", res.cycles ? n / static_cast<double>(res.cycles) : 0.0);
  res.stats.set("memory_bytes_per_pixel", n > 0 ? static_cast<double>(res.stats.counter("memory_bytes")) / n : 0.0);
  const uint64_t h = res.stats.counter("cache_line_hits"), m = res.stats.counter("cache_line_misses");
  res.stats.set("cache_hit_rate", h + m ? static_cast<double>(h) / static_cast<double>(h + m) : 1.0);
  uint64_t lat_sum = 0;
  for (size_t c = 0; c < latency.size(); ++c) lat_sum += c * latency[c];
  res.stats.set("latency_mean", n > 0 ? static_cast<double>(lat_sum) / n : 0.0);
  return res;
}

}  // namespace tfu::rtl
