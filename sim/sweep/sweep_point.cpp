#include "sim/sweep/sweep_point.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/json_output.hpp"
#include "cmodel/metrics.hpp"
#include "cmodel/parallel.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene_source.hpp"
#include "rtl/cost_model.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/unit_stats.hpp"
#include "sim/sweep/provenance.hpp"

namespace tfu::sweep {
namespace {

namespace fs = std::filesystem;

std::string scene_key(const Spec&, const Point& p) { return fmt::format("{}\n{}x{}", p.scene_path, p.width, p.height); }

std::string truth_key(const Spec& s, const Point& p) {
  std::string k = scene_key(s, p);
  for (const auto& [key, value] : p.sampler) k += fmt::format("\n{}={}", key, value);
  return k;
}

std::string render_key(const Spec& s, const Point& p) {
  return fmt::format("{}\nfilter={}\nline_bytes={}\nraster={}\nlayout={}", truth_key(s, p), p.filter, p.config.cache.line_bytes,
                     raster_order_name(p.raster), p.texture_layout);
}

// Made once under the cache's lock; other threads wait on the shared future.
template <typename T, typename Make>
std::shared_ptr<const T> once(std::mutex& m, std::map<std::string, std::shared_future<std::shared_ptr<const T>>>& map,
                              const std::string& key, Make&& make) {
  std::promise<std::shared_ptr<const T>> promise;
  std::shared_future<std::shared_ptr<const T>> fut;
  bool mine = false;
  {
    const std::lock_guard lock(m);
    auto it = map.find(key);
    if (it == map.end()) {
      fut = promise.get_future().share();
      map.emplace(key, fut);
      mine = true;
    } else {
      fut = it->second;
    }
  }
  if (mine) {
    try {
      promise.set_value(make());
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
  }
  return fut.get();
}

RenderOptions render_options(const Point& p, bool truth) {
  RenderOptions ro;
  ro.threads = 1;  // the sweep's parallelism is across points
  ro.sampler_overrides = p.sampler;
  if (truth) {
    // Every worker that reaches a scene waits for its truth (made once, shared), so it is made
    // on every core: bands of rows, the same image for any thread count.
    ro.threads = 0;
    ro.ground_truth = true;
  } else {
    ro.trace = true;
    ro.line_bytes = p.config.cache.line_bytes;
    ro.raster = p.raster;
    if (p.texture_layout != "own") ro.texture_layout = memory_layout_from_name(p.texture_layout);
    if (p.filter != kSceneFilter) ro.filter = filter_mode_from_name(p.filter);
  }
  return ro;
}

nlohmann::json point_json(const Spec& s, const Point& p) {
  nlohmann::json keys = nlohmann::json::object();
  for (size_t k = 0; k < s.keys.size(); ++k) keys[s.keys[k].name] = p.values[k];
  return {{"id", p.id}, {"index", p.index}, {"scene", p.scene}, {"filter", p.filter}, {"keys", keys}};
}

RunRecord run_record(const Spec& s, const Point& p, int width, int height) {
  RunRecord r;
  r.command = "sweep";
  r.scene = {p.scene_path, p.width, p.height, s.game_dir};
  r.width = width;
  r.height = height;
  r.filter = p.filter;
  r.sampler_overrides = p.sampler;
  r.units = p.units;
  r.raster = raster_order_name(p.raster);
  r.unit_tiles = unit_tiles_name(p.unit_tiles);
  r.texture_layout = p.texture_layout;
  r.config = &p.config;
  r.engine = scene_sim_options(p).engine;
  return r;
}

// The point's figures beside its statistics (what results.csv shows).
nlohmann::json result_json(const Spec& s, const Point& p, const rtl::SceneSimResult& res, const Truths& truth, const Frame& frame) {
  const sim::Stats& st = res.stats;
  nlohmann::json r;
  r["cycles"] = res.cycles;
  r["pixels"] = res.requests;
  r["pixels_per_clock"] = rtl::value(st, rtl::UnitStat::PixelsPerClock);
  r["hit_rate"] = rtl::value(st, rtl::UnitStat::CacheHitRate);
  r["sector_hit_rate"] = rtl::value(st, rtl::UnitStat::CacheSectorHitRate);
  r["bytes_per_pixel"] = rtl::value(st, rtl::UnitStat::MemoryBytesPerPixel);
  r["memory_bytes"] = rtl::counter(st, rtl::UnitStat::MemoryBytes);
  for (const rtl::UnitStat c : {rtl::UnitStat::StallCacheMiss, rtl::UnitStat::StallBankConflict, rtl::UnitStat::StallBackpressure})
    r[rtl::stat_key(c)] = rtl::counter(st, c);
  r["latency_mean"] = rtl::value(st, rtl::UnitStat::LatencyMean);
  const auto put = [&r](const char* key, double db) {
    if (std::isinf(db)) {
      r[key] = "inf";
    } else {
      r[key] = db;
    }
  };
  put("psnr", psnr_db(res.image, truth.antialiased));
  r["ssim"] = ssim_luma(res.image, truth.antialiased);
  put("psnr_surface", psnr_db(res.image, truth.surface));
  put("psnr_interior", psnr_db(res.image, truth.surface, truth.interior));
  r["golden_equal"] = res.mismatch.empty();
  r["mismatch"] = res.mismatch;
  const rtl::CacheSramBits bits = rtl::texel_cache_sram_bits(p.config.cache);
  const auto units = static_cast<uint64_t>(p.units);
  r["sram_bits"] = units * bits.total();
  r["sram_bits_data"] = units * bits.data;
  r["sram_bits_tag"] = units * bits.tag;
  r["sram_bits_valid"] = units * bits.valid;
  r["sram_bits_lru"] = units * bits.lru;
  const rtl::FilterGates gates = rtl::filter_datapath_gates(frame.regs.samplers);
  r["filter_gates"] = static_cast<double>(p.units) * gates.ge;
  r["filter_blocks"] = gates.blocks;
  rtl::RunCounts run;
  run.cycles = res.cycles;
  run.pixels = res.requests;
  run.line_misses = rtl::counter(st, rtl::UnitStat::CacheLineMisses);
  run.line_lookups = rtl::counter(st, rtl::UnitStat::CacheLineHits) + run.line_misses;
  run.memory_bytes = rtl::counter(st, rtl::UnitStat::MemoryBytes);
  run.dram_bursts = rtl::counter(st, rtl::UnitStat::DramBursts);
  run.dram_activates = rtl::counter(st, rtl::UnitStat::DramActivates);
  const rtl::UnitCost cost = rtl::unit_cost(s.node, p.config, frame.regs.samplers, p.units, run);
  const auto optional = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(); };
  r["node"] = rtl::node_name(s.node);
  r["logic_um2"] = cost.logic_um2;
  r["sram_um2"] = optional(cost.sram_um2);
  r["area_mm2"] = optional(cost.area_mm2);
  r["fmax_mhz"] = cost.fmax_mhz;
  r["energy_pj_per_pixel"] = optional(cost.energy_pj_per_pixel);
  // Its breakdown per pixel: logic, SRAM, DRAM (null with the ideal memory).
  const auto per_pixel = [&res](const std::optional<double>& pj) {
    return pj && res.requests ? nlohmann::json(*pj / static_cast<double>(res.requests)) : nlohmann::json();
  };
  r["logic_pj_per_pixel"] = per_pixel(cost.logic_pj);
  r["sram_pj_per_pixel"] = per_pixel(cost.sram_pj);
  r["dram_pj_per_pixel"] = per_pixel(cost.dram_pj);
  r["datapath_um2"] = cost.datapath_um2;
  r["miss_fifo_um2"] = cost.miss_fifo_um2;
  r["logic_pj"] = cost.logic_pj;
  r["sram_pj"] = optional(cost.sram_pj);
  r["dram_pj"] = optional(cost.dram_pj);
  nlohmann::json inst = nlohmann::json::array();
  for (const auto& [block, count] : cost.instances) inst.push_back({{"block", block}, {"count", count}});
  r["datapath_instances"] = inst;
  return r;
}

}  // namespace

std::shared_ptr<const Scene> SceneCache::scene(const Spec& s, const Point& p) {
  return once<Scene>(mutex_, scenes_, scene_key(s, p), [&] {
    return std::make_shared<const Scene>(open_scene({p.scene_path, p.width, p.height, s.game_dir}));
  });
}

std::shared_ptr<const Truths> SceneCache::truth(const Spec& s, const Point& p) {
  const std::shared_ptr<const Scene> sc = scene(s, p);
  return once<Truths>(mutex_, truths_, truth_key(s, p), [&] {
    RenderResult r = render_scene(*sc, render_options(p, true));
    return std::make_shared<const Truths>(Truths{std::move(r.truth), std::move(r.surface_truth), std::move(r.interior)});
  });
}

void SceneCache::plan(const Spec& s, const std::vector<const Point*>& points) {
  const std::lock_guard lock(mutex_);
  for (const Point* p : points) ++render_uses_[render_key(s, *p)];
}

std::shared_ptr<const RenderResult> SceneCache::render(const Spec& s, const Point& p) {
  const std::shared_ptr<const Scene> sc = scene(s, p);
  return once<RenderResult>(mutex_, renders_, render_key(s, p),
                            [&] { return std::make_shared<const RenderResult>(render_scene(*sc, render_options(p, false))); });
}

void SceneCache::done_with_render(const Spec& s, const Point& p) {
  const std::lock_guard lock(mutex_);
  const std::string key = render_key(s, p);
  const auto it = render_uses_.find(key);
  if (it == render_uses_.end() || --it->second > 0) return;  // unplanned renders stay
  render_uses_.erase(it);
  renders_.erase(key);
}

std::string run_point(const Spec& s, const Point& p, SceneCache& cache, PointTiming* timing) {
  const auto t0 = std::chrono::steady_clock::now();
  nlohmann::json doc;
  doc["complete"] = true;
  doc["point"] = point_json(s, p);
  double sim_seconds = 0;
  try {
    const std::shared_ptr<const Scene> scene = cache.scene(s, p);
    const std::shared_ptr<const Truths> truth = cache.truth(s, p);
    const auto t1 = std::chrono::steady_clock::now();
    const std::shared_ptr<const RenderResult> shared = cache.render(s, p);
    const RenderResult& render = *shared;
    const rtl::SceneSimOptions so = scene_sim_options(p);
    const rtl::SceneSimResult res = rtl::simulate_scene(*scene, render, p.config, so);
    sim_seconds = seconds_since(t1);
    RunRecord rec = run_record(s, p, scene->width, scene->height);
    rec.textures = frame_texture_names(render.frame->frame);
    const nlohmann::json stats = nlohmann::json::parse(stats_document(res.stats, provenance_json(rec)));
    for (const auto& [k, v] : stats.items()) doc[k] = v;
    doc["result"] = result_json(s, p, res, *truth, render.frame->frame);
    cache.done_with_render(s, p);
  } catch (const InputError& e) {
    cache.done_with_render(s, p);
    doc["error"] = e.what();
    doc["provenance"] = provenance_json(run_record(s, p, p.width, p.height));
  } catch (const CheckFailed& e) {
    cache.done_with_render(s, p);
    std::string what = e.what();
    doc["error"] = what.substr(0, what.find('\n'));
    doc["provenance"] = provenance_json(run_record(s, p, p.width, p.height));
  }
  std::string text = json_dump(doc, 2) + "\n";
  if (timing) {
    timing->seconds = seconds_since(t0);
    timing->simulation_seconds = sim_seconds;
  }
  return text;
}

std::string point_path(const std::string& dir, const Point& p) { return (fs::path(dir) / "points" / (p.id + ".json")).string(); }

}  // namespace tfu::sweep
