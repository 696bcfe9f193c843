// One sweep point, run in-process: its scene rendered by the golden model with the request trace
// (textures tiled for the point's line size), the trace through the cycle model with the golden
// compare (rtl/scene_sim.hpp), PSNR and SSIM of the cycle model's image against the scene's
// supersampled ground truth, and the cost model's figures (rtl/cost_model.hpp). The result is the point's file:
//
//   {"complete": true, "point": {"id", "index", "scene", "filter", "keys": {KEY: value}},
//    "result": {"cycles", "pixels", "pixels_per_clock", "hit_rate", "sector_hit_rate", "bytes_per_pixel", "memory_bytes",
//               "stall_cache_miss", "stall_bank_conflict", "stall_backpressure", "latency_mean",
//               "psnr", "ssim", "psnr_surface", "psnr_interior" (dB, or "inf"; SSIM beside the first; against the antialiased truth, the
//               surface truth, the surface truth over the interior), "golden_equal", "mismatch", "sram_bits", "sram_bits_data",
//               "sram_bits_tag", "sram_bits_valid", "sram_bits_lru", "filter_gates", "filter_blocks", "node", "logic_um2",
//               "sram_um2", "area_mm2", "fmax_mhz", "energy_pj_per_pixel" and its parts "logic_pj_per_pixel",
//               "sram_pj_per_pixel", "dram_pj_per_pixel" (null with the ideal memory), "datapath_um2", "miss_fifo_um2",
//               "logic_pj", "sram_pj", "dram_pj", "datapath_instances" (rtl/cost_model.hpp)},
//    "provenance", "definitions", "counters", "values", "histograms", "tables"}
// or, when the point cannot run (an input the point's configuration refuses, a deadlock):
//   {"complete": true, "point": {...}, "error": "one line", "provenance": {...}}
// Nothing in it depends on timing or on how many points run at once.
#pragma once

#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include <vector>

#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/scene_sim.hpp"
#include "sim/sweep/sweep_spec.hpp"

namespace tfu::sweep {

// The two ground truths of a scene (cmodel/raster.hpp): the antialiased one, and the surface truth
// with the render's coverage and its interior mask.
struct Truths {
  Image antialiased, surface;
  std::vector<uint8_t> interior;
};

// Scenes, ground truths and golden renders shared by the points of one process, each made once
// (thread-safe; a second thread asking for one being made waits for it).
class SceneCache {
 public:
  std::shared_ptr<const Scene> scene(const Spec& s, const Point& p);
  // The ground truth depends on the scene, its size and the base-stage sampler keys (wrap modes,
  // border), not on the filter or the unit.
  std::shared_ptr<const Truths> truth(const Spec& s, const Point& p);
  // The golden render with its request trace depends on those, the filter and the cache line (the
  // textures are tiled for it), not on the rest of the unit: the points of a cache or memory grid
  // share it. plan() counts the points that will ask for each render; a render is dropped when the
  // last of them has called done_with_render (so memory holds the renders of points in flight).
  void plan(const Spec& s, const std::vector<const Point*>& points);
  std::shared_ptr<const RenderResult> render(const Spec& s, const Point& p);
  void done_with_render(const Spec& s, const Point& p);

 private:
  std::mutex mutex_;
  std::map<std::string, std::shared_future<std::shared_ptr<const Scene>>> scenes_;
  std::map<std::string, std::shared_future<std::shared_ptr<const Truths>>> truths_;
  std::map<std::string, std::shared_future<std::shared_ptr<const RenderResult>>> renders_;
  std::map<std::string, size_t> render_uses_;  // points still to use each render (plan())
};

// Wall seconds of run_point, and of the part that is the simulation proper (the golden render
// with its trace, when this point made it or waited for it, plus the cycle model with the golden
// compare): the rest is the sweep's overhead.
struct PointTiming {
  double seconds = 0, simulation_seconds = 0;
};

std::string run_point(const Spec& s, const Point& p, SceneCache& cache, PointTiming* timing = nullptr);

// How a sweep simulates a point's scene: the point's units and unit tiles, by the timing recurrences
// (the clocked run's results, tested; the sweep writes no waveforms).
inline rtl::SceneSimOptions scene_sim_options(const Point& p) {
  rtl::SceneSimOptions so;
  so.units = p.units;
  so.tiles = p.unit_tiles;
  so.engine = rtl::UnitEngine::Recurrence;
  return so;
}

// DIR/points/ID.json (read back by read_point_file, sim/sweep/sweep_report.hpp)
std::string point_path(const std::string& dir, const Point& p);

}  // namespace tfu::sweep
