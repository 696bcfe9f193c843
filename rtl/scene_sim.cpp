#include "rtl/scene_sim.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <deque>
#include <future>
#include <mutex>
#include <memory>
#include <thread>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/parallel.hpp"
#include "rtl/engine_compare.hpp"
#include "rtl/golden_compare.hpp"
#include "rtl/shared_memory.hpp"
#include "rtl/unit_stats.hpp"

namespace tfu::rtl {

namespace {

// One unit's share of the frame: its quads' requests in trace order.
struct Job {
  int unit = 0;
  size_t requests = 0;  // its share of the frame's requests
  Trace trace;                // whole-frame runs
  std::vector<size_t> quads;  // indices into render.quad_targets (whole-frame runs)
  UnitOutput out;
  std::string mismatch;
  double cycle_seconds = 0, golden_seconds = 0;
  double thread_seconds = 0, wait_seconds = 0;  // a streamed unit's thread: CPU, and waiting for requests
};

// The shared memory system's counters per unit: the L2's (added to each unit's statistics, so that
// the scene's sums are the totals).
void publish_shared(const SharedMemorySystem& shared, std::vector<Job>& jobs) {
  const L2Cache* l2 = shared.l2();
  if (l2 == nullptr) return;
  for (Job& job : jobs) {
    if (job.requests == 0) continue;
    const L2Cache::Counters& c = l2->unit_counters(job.unit);
    sim::Stats& st = job.out.stats;
    add(st, UnitStat::L2Requests, c.requests);
    add(st, UnitStat::L2Hits, c.hits);
    add(st, UnitStat::L2Misses, c.misses);
    add(st, UnitStat::L2BankConflicts, c.bank_conflicts);
    add(st, UnitStat::L2QueueCycles, c.queue_cycles);
  }
}

// The shared memory system's totals: the units sharing it, the L2's per-unit table and memory
// bytes, and the one DRAM's counters.
void publish_shared_totals(const SharedMemorySystem& shared, sim::Stats& st) {
  add(st, UnitStat::MemorySharedBy, static_cast<uint64_t>(shared.units()));
  if (const L2Cache* l2 = shared.l2()) {
    sim::Stats::Table t{{"unit", "l2_requests", "l2_hits", "l2_misses", "l2_bank_conflicts", "l2_queue_cycles"}, {}};
    for (int k = 0; k < shared.units(); ++k) {
      const L2Cache::Counters& c = l2->unit_counters(k);
      t.rows.emplace_back(fmt::format("unit {}", k), std::vector<uint64_t>{static_cast<uint64_t>(k), c.requests, c.hits,
                                                                           c.misses, c.bank_conflicts, c.queue_cycles});
    }
    st.set_table(stat_key(UnitStat::L2Units), std::move(t));
    add(st, UnitStat::L2MemoryBytes, shared.memory().bytes_read());
  }
  if (const dram::DramModel* d = shared.memory().dram()) publish_dram_stats(st, *d);
}

// The units' results summed (cycles: the slowest unit's), with the derived rates; the first
// mismatch in unit order.
void merge_jobs(const std::vector<Job>& jobs, const SharedMemorySystem* shared, int units, SceneSimResult& res) {
  for (const Job& job : jobs) {
    res.cycle_seconds += job.cycle_seconds;
    res.golden_seconds += job.golden_seconds;
    if (!job.mismatch.empty() && res.mismatch.empty()) res.mismatch = job.mismatch;
    if (job.requests == 0) continue;
    res.cycles = std::max(res.cycles, job.out.cycles);
    res.stats.merge(job.out.stats);
  }
  // Sums are right for every counter but cycles (the slowest unit's) and the derived rates.
  sim::Stats st;
  for (const auto& [k, v] : res.stats.counters())
    if (k != stat_key(UnitStat::Cycles)) st.add(k, v);
  st.merge(res.stats, false);
  add(st, UnitStat::Cycles, res.cycles);
  add(st, UnitStat::Units, static_cast<uint64_t>(units));
  if (shared) publish_shared_totals(*shared, st);
  derive_rates(st, res.requests, res.cycles);
  derive_group_rates(st);  // the groups' counters summed over units, cycles too (unit_stats.hpp)
  res.stats = std::move(st);
}

void check_unit_tiles(const SceneSimOptions& opt) {
  if (opt.units < 1 || opt.units > 256) throw InputError(fmt::format("units {} must be in 1..256", opt.units));
  if (opt.tiles.tile < 2 || opt.tiles.tile > kMaxRasterTile || opt.tiles.tile % 2 != 0)
    throw InputError(fmt::format("unit tile size {} outside the even sizes 2..{}", opt.tiles.tile, kMaxRasterTile));
}

}  // namespace

SceneSimResult simulate_scene(const Scene& scene, const RenderResult& render, const UnitConfig& u, const SceneSimOptions& opt) {
  check_unit_tiles(opt);
  if (!render.frame || render.quad_targets.size() * 4 != render.trace.requests.size())
    throw InputError("scene simulation needs a render with RenderOptions::trace");
  u.validate();
  const Frame& frame = render.frame->frame;
  std::vector<Job> jobs(static_cast<size_t>(opt.units));
  for (size_t j = 0; j < jobs.size(); ++j) {
    jobs[j].unit = static_cast<int>(j);
    jobs[j].trace.mode = TraceMode::Quad;
  }
  for (size_t q = 0; q < render.quad_targets.size(); ++q) {
    const QuadTarget& t = render.quad_targets[q];
    Job& job = jobs[static_cast<size_t>(unit_of_quad(opt.tiles, opt.units, scene.width, scene.height, t.x, t.y))];
    job.quads.push_back(q);
    for (size_t k = 0; k < 4; ++k) job.trace.requests.push_back(render.trace.requests[q * 4 + k]);
  }
  for (Job& job : jobs) job.requests = job.trace.requests.size();
  const GoldenUnit golden(frame);
  // One memory system for all units (the L2 and/or memory.shared), or none (each unit its own).
  const bool sharing = u.l2.enabled() || u.memory.shared != 0;
  if (sharing && opt.compare_engines)
    throw InputError("--compare-engines runs each unit alone; with an L2 or memory.shared the units share one memory: "
                     "compare whole runs with --engine recurrence and --engine clocked");
  const int threads = opt.threads > 0 ? std::min(opt.threads, kMaxThreads) : hardware_threads();
  std::unique_ptr<SharedMemorySystem> shared;
  if (sharing) shared = std::make_unique<SharedMemorySystem>(u, frame.regs.textures.size(), opt.units, threads);
  const auto run_job = [&](Job& job) {
    if (job.quads.empty()) return;
    const double t0 = thread_cpu_seconds();
    const auto k = static_cast<size_t>(job.unit);
    std::ostream* vcd = opt.unit_vcds.empty() ? (job.unit == 0 ? opt.vcd : nullptr) : (k < opt.unit_vcds.size() ? opt.unit_vcds[k] : nullptr);
    // The waveform's screen positions: pixel k of a quad at (x + (k & 1), y + (k >> 1)) (raster.hpp).
    std::vector<ScreenPosition> positions;
    if (vcd != nullptr) {
      positions.reserve(job.trace.requests.size());
      for (const size_t q : job.quads)
        for (int p = 0; p < 4; ++p) {
          const QuadTarget& t = render.quad_targets[q];
          positions.push_back({static_cast<uint16_t>(t.x + (p & 1)), static_cast<uint16_t>(t.y + (p >> 1))});
        }
    }
    const VcdOptions vcd_options{vcd, opt.vcd_from, opt.vcd_to, opt.vcd_signals, &positions};
    if (shared) {  // this unit's turns in the shared memory's order (finish: also in guarded_job)
      shared->start(job.unit);
      job.out = run_unit(frame, job.trace, u, opt.engine, vcd_options, MemoryBinding{shared.get(), job.unit});
      shared->finish(job.unit);
    } else {
      job.out = run_unit(frame, job.trace, u, opt.engine, vcd_options);
    }
    const double t1 = thread_cpu_seconds();
    // The golden model on the same requests: LOD unit and sampler (the same work the cycle model
    // does, without timing), timed separately for the cost-of-cycle-accuracy ratio.
    const std::vector<Rgba8> want = golden_outputs(golden, job.trace, job.out);
    const double t2 = thread_cpu_seconds();
    job.cycle_seconds = t1 - t0;
    job.golden_seconds = t2 - t1;
    job.mismatch = first_mismatch(job.trace, want, job.out, fmt::format("unit {}", job.unit));
    if (job.mismatch.empty() && opt.compare_engines)  // both engines again, every event (rtl/engine_compare.hpp)
      if (const std::string d = rtl::compare_engines(frame, job.trace, u); !d.empty())
        job.mismatch = fmt::format("unit {}: {}", job.unit, d);
  };
  // Units are handed out to up to hardware_threads() workers (each unit on
  // one thread); results do not depend on which worker runs which unit.
  std::vector<std::exception_ptr> errors(static_cast<size_t>(opt.units));
  const auto guarded_job = [&](int unit) {
    try {
      run_job(jobs[static_cast<size_t>(unit)]);
    } catch (...) {
      errors[static_cast<size_t>(unit)] = std::current_exception();
    }
    if (shared) shared->finish(unit);  // done (a unit without quads, or one that threw, too)
  };
  if (shared) {
    // Every unit on a thread of its own (a unit waits for the others' progress at its misses); at
    // most `threads` of them run at once (SharedMemorySystem). The threads start only once all exist.
    std::promise<bool> all_started;
    const std::shared_future<bool> go = all_started.get_future().share();
    std::vector<std::thread> pool;
    pool.reserve(static_cast<size_t>(opt.units));
    try {
      for (int unit = 0; unit < opt.units; ++unit)
        pool.emplace_back([&, go, unit] {
          if (go.get()) guarded_job(unit);
        });
    } catch (const std::system_error&) {
      all_started.set_value(false);
      for (std::thread& t : pool) t.join();
      throw InputError(fmt::format("{} units sharing one memory need a thread each; the system refused thread {}",
                                   opt.units, pool.size()));
    }
    all_started.set_value(true);
    for (std::thread& t : pool) t.join();
  } else {
    std::atomic<int> next_unit{0};
    run_workers(std::min(opt.units, threads), [&](int) {
      for (int unit = next_unit++; unit < opt.units; unit = next_unit++) guarded_job(unit);
    });
  }
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);

  SceneSimResult res;
  res.image = render.image;
  res.requests = render.trace.requests.size();
  std::vector<Rgba8> outputs(res.requests);
  if (shared) publish_shared(*shared, jobs);
  for (const Job& job : jobs)
    for (size_t qi = 0; qi < job.quads.size(); ++qi)
      std::copy_n(job.out.pixels.begin() + static_cast<ptrdiff_t>(qi * 4), 4,
                  outputs.begin() + static_cast<ptrdiff_t>(job.quads[qi] * 4));
  compose_quad_outputs(scene, render.quad_targets, outputs, res.image);
  merge_jobs(jobs, shared.get(), opt.units, res);
  return res;
}

bool streams_scene(const RenderOptions& ro, const UnitConfig& u, const SceneSimOptions& opt) {
  const bool vcd = opt.vcd != nullptr || std::any_of(opt.unit_vcds.begin(), opt.unit_vcds.end(), [](std::ostream* v) { return v != nullptr; });
  return !opt.whole_frame && opt.engine == UnitEngine::Recurrence && !vcd && !opt.compare_engines && !u.l2.enabled() &&
         u.memory.shared == 0 && ro.raster.traversal == RasterTraversal::Scanline;
}

namespace {

// The streamed run: the render hands each band's trace to a TraceSink that deals its quads to
// the units' request streams; each unit runs on its own thread on its stream, and hands its
// results on chunk by chunk to the golden compare and to the image (compose_quad_outputs of the
// chunk's whole shaded quads). What is held: per unit a window of kStreamWindow requests and the
// quad targets queued with them, one chunk of results, and the render's bands ahead of the last
// one handed on.
class StreamedUnits final : public TraceSink {
 public:
  StreamedUnits(const Scene& scene, const UnitConfig& u, const SceneSimOptions& opt)
      : scene_(scene), u_(u), opt_(opt), image_(scene.width, scene.height, background_rgba8(scene)),
        units_(static_cast<size_t>(opt.units)), jobs_(static_cast<size_t>(opt.units)) {
    for (size_t k = 0; k < units_.size(); ++k) jobs_[k].unit = static_cast<int>(k);
  }
  ~StreamedUnits() override { stop(); }

  void begin(const SceneFrame& frame) override {
    frame_ = &frame.frame;
    golden_ = std::make_unique<GoldenUnit>(*frame_);
    for (size_t k = 0; k < units_.size(); ++k) {
      units_[k].stream = std::make_unique<RequestStream>(TraceMode::Quad, kStreamWindow, &room_);
      units_[k].thread = std::thread([this, k] { run(k); });
    }
  }

  void band(const std::vector<TraceRequest>& requests, const std::vector<QuadTarget>& targets) override {
    for (StreamUnit& su : units_) su.requests.clear();
    std::vector<std::vector<QuadTarget>> dealt(units_.size());
    for (size_t q = 0; q < targets.size(); ++q) {
      const QuadTarget& t = targets[q];
      const auto k = static_cast<size_t>(unit_of_quad(opt_.tiles, opt_.units, scene_.width, scene_.height, t.x, t.y));
      dealt[k].push_back(t);
      units_[k].requests.insert(units_[k].requests.end(), requests.begin() + static_cast<ptrdiff_t>(q * 4),
                                requests.begin() + static_cast<ptrdiff_t>(q * 4 + 4));
    }
    std::vector<StreamPart> parts;
    for (size_t k = 0; k < units_.size(); ++k) {
      StreamUnit& su = units_[k];
      if (su.requests.empty()) continue;
      check_requests(*frame_, su.requests.data(), su.requests.size(), jobs_[k].requests);
      jobs_[k].requests += su.requests.size();
      {
        const std::lock_guard lock(su.targets_mutex);
        su.targets.insert(su.targets.end(), dealt[k].begin(), dealt[k].end());
      }
      parts.push_back({su.stream.get(), su.requests.data(), su.requests.size()});
    }
    // Every unit's share at once: waits only while all the units it still has requests for are full.
    producer_wait_ += push_each(room_, std::move(parts));
  }

  // The end of the render (or its failure): the streams close, the units finish.
  void stop() {
    for (StreamUnit& su : units_) {
      if (su.stream) su.stream->close();
      if (su.thread.joinable()) su.thread.join();
    }
  }

  // After stop(): the units' results (rethrows the first unit's error).
  std::vector<Job>& jobs() {
    for (const StreamUnit& su : units_)
      if (su.error) std::rethrow_exception(su.error);
    return jobs_;
  }
  Image& image() { return image_; }
  double handoff_wait() const { return producer_wait_; }

 private:
  struct StreamUnit {
    std::unique_ptr<RequestStream> stream;
    std::vector<TraceRequest> requests;  // the producer's: a band's share
    std::mutex targets_mutex;
    std::deque<QuadTarget> targets;      // pushed with the requests, taken by the unit's chunks
    std::vector<QuadTarget> pending;     // the unit's: targets of a shaded quad not yet complete
    std::vector<Rgba8> pending_outputs;  // and their outputs
    std::thread thread;
    std::exception_ptr error;
  };

  void run(size_t k) {
    StreamUnit& su = units_[k];
    Job& job = jobs_[k];
    try {
      // The thread's CPU seconds: the cycle model's (the unit, handing on its chunks included),
      // the golden model's (golden_outputs), and the rest (the compare and the image) in neither.
      const double t0 = thread_cpu_seconds();
      double golden = 0, sink_total = 0;
      const UnitChunkSink sink = [&](const UnitChunk& c) {
        const double g0 = thread_cpu_seconds();
        const std::vector<Rgba8> want = golden_outputs(*golden_, c.trace, c.out);
        const double g1 = thread_cpu_seconds();
        if (job.mismatch.empty()) job.mismatch = first_mismatch(c.trace, want, c.out, fmt::format("unit {}", job.unit), c.first);
        compose(su, c);
        golden += g1 - g0;
        sink_total += thread_cpu_seconds() - g0;
      };
      job.out = run_unit_stream(*frame_, *su.stream, u_, sink);
      job.thread_seconds = thread_cpu_seconds() - t0;
      job.cycle_seconds = job.thread_seconds - sink_total;
      job.golden_seconds = golden;
      job.wait_seconds = su.stream->unit_wait_seconds();
    } catch (...) {
      su.error = std::current_exception();
    }
  }

  // The chunk's outputs into the image: its quad targets (in order) appended to those of a shaded
  // quad still incomplete, and every shaded quad whose last stage is in composed.
  void compose(StreamUnit& su, const UnitChunk& c) {
    const size_t quads = c.trace.requests.size() / 4;
    {
      const std::lock_guard lock(su.targets_mutex);
      su.pending.insert(su.pending.end(), su.targets.begin(), su.targets.begin() + static_cast<ptrdiff_t>(quads));
      su.targets.erase(su.targets.begin(), su.targets.begin() + static_cast<ptrdiff_t>(quads));
    }
    su.pending_outputs.insert(su.pending_outputs.end(), c.out.pixels.begin(), c.out.pixels.end());
    size_t complete = su.pending.size();
    while (complete > 0) {
      const QuadTarget& t = su.pending[complete - 1];
      if (t.stage + 1u == scene_.meshes.at(static_cast<size_t>(t.mesh)).stages.size()) break;
      --complete;
    }
    if (complete == 0) return;
    const std::vector<QuadTarget> done(su.pending.begin(), su.pending.begin() + static_cast<ptrdiff_t>(complete));
    const std::vector<Rgba8> outputs(su.pending_outputs.begin(), su.pending_outputs.begin() + static_cast<ptrdiff_t>(complete * 4));
    // Units draw disjoint screen tiles, so their threads write disjoint pixels.
    compose_quad_outputs(scene_, done, outputs, image_);
    su.pending.erase(su.pending.begin(), su.pending.begin() + static_cast<ptrdiff_t>(complete));
    su.pending_outputs.erase(su.pending_outputs.begin(), su.pending_outputs.begin() + static_cast<ptrdiff_t>(complete * 4));
  }

  const Scene& scene_;
  const UnitConfig& u_;
  const SceneSimOptions& opt_;
  const Frame* frame_ = nullptr;
  std::unique_ptr<GoldenUnit> golden_;
  Image image_;
  RoomSignal room_;  // the units' streams tell the producer of freed room
  double producer_wait_ = 0;
  std::vector<StreamUnit> units_;
  std::vector<Job> jobs_;
};

}  // namespace

RenderedSceneSim render_and_simulate_scene(const Scene& scene, RenderOptions ro, const UnitConfig& u, const SceneSimOptions& opt) {
  ro.trace = true;
  RenderedSceneSim r;
  if (!streams_scene(ro, u, opt)) {
    r.render = render_scene(scene, ro);
    r.sim = simulate_scene(scene, r.render, u, opt);
    return r;
  }
  check_unit_tiles(opt);
  u.validate();
  const auto t0 = std::chrono::steady_clock::now();
  StreamedUnits units(scene, u, opt);
  ro.sink = &units;
  try {
    r.render = render_scene(scene, ro);
  } catch (...) {
    units.stop();
    throw;
  }
  units.stop();
  std::vector<Job>& jobs = units.jobs();
  r.streamed = true;
  r.times.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.times.handoff_wait = units.handoff_wait();
  for (const Job& job : jobs) {
    r.times.unit_cpu.push_back(job.thread_seconds);
    r.times.unit_wait.push_back(job.wait_seconds);
  }
  r.sim.image = std::move(units.image());
  r.sim.requests = 0;
  for (const Job& job : jobs) r.sim.requests += job.requests;
  merge_jobs(jobs, nullptr, opt.units, r.sim);
  return r;
}

}  // namespace tfu::rtl
