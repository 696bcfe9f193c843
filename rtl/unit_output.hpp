// What a run of the unit returns (either engine: rtl/tfu_unit.hpp), and the rates derived from
// its counters. Below the wiring (rtl/unit_wiring.hpp) and the engines, which fill it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "cmodel/frame.hpp"
#include "rtl/kernel/kernel.hpp"
#include "rtl/unit_ports.hpp"

namespace tfu::rtl {

struct UnitOutput {
  std::vector<Rgba8> pixels;             // in request order
  std::vector<uint64_t> response_cycle;  // cycle each pixel left the unit
  // Per pixel, probe and level0/level1: the edge kernel shape, when some sampler of the frame is
  // EDGE_PRESERVING with the cache-aware policy (the golden compare needs them); else empty.
  std::vector<ProbeShapes> edge_shapes;
  uint64_t cycles = 0;
  // Counters, values, histograms, the tables "textures" (per texture descriptor: requests, line
  // hits, line misses, memory bytes) and "stages" (the same per material stage), and the groups
  // "stage" and "texture": every statistic of the run per material stage and per texture
  // descriptor (rtl/unit_stats.hpp).
  sim::Stats stats;
};

// The rates derived from a run's counters (one unit's, or several units' summed with the cycles of
// the slowest): pixels_per_clock, memory_bytes_per_pixel, cache_hit_rate, probes_per_pixel and the
// latency mean, minimum and maximum from the latency histogram.
void derive_rates(sim::Stats& st, size_t requests, uint64_t cycles);
// derive_rates of every group of `st` (per stage, per texture: rtl/unit_stats.hpp), each from its
// own pixels and cycles.
void derive_group_rates(sim::Stats& st);

}  // namespace tfu::rtl
