// tfu_unit: the texture filter unit as a pipeline of clocked blocks (TFU-C), one C++ module per
// block (files named after the blocks), every block calling the golden model's arithmetic
// (cmodel/), never a copy of it:
//
//   request_fifo --QuadReq--> lod_unit --PixelReq--> address_gen --FootprintReq--> kernel_select
//     --FootprintReq--> texel_cache (+ memory_model) --FilterReq--> filter --Response--> response
//                                                               \-> edge_median --EdgeS1-->
//                                     edge_direction --EdgeS2--> edge_merge --Response--> response
//
// Port payloads and widths: rtl/unit_ports.hpp and each block's header. Rates (cache hits):
// NEAREST, LINEAR and EDGE_PRESERVING 1 pixel/clock; a blending *_MIPMAP_LINEAR pixel 2 clocks (one
// level footprint per clock); CUBIC ceil(T*T / (4 lanes)) clocks per level footprint. Latency per
// mode: docs/cycle-model.md (measured by the tests).
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "cmodel/sampler.hpp"
#include "cmodel/trace.hpp"
#include "rtl/kernel_select.hpp"
#include "rtl/memory_model.hpp"
#include "rtl/texel_cache.hpp"
#include "sim/kernel/kernel.hpp"

namespace tfu::rtl {

// Every architectural parameter (the JSON config of `tfu sim --config`, docs/cycle-model.md).
struct UnitConfig {
  TexelCacheConfig cache{};
  MemoryConfig memory{};
  int channel_depth = 2;  // skid buffers between blocks
  int miss_fifo_depth = 128;  // footprints queued in the texel cache behind outstanding misses
  int filter_lanes = 1;   // bilinear-equivalent multiplier lanes of the filter (1, 2 or 4)
  ShapePolicy shape_policy = ShapePolicy::Static;
  // Simulation option, not architecture (not in the JSON): jump over cycles in which no block can
  // act (sim::Simulator::set_idle_skip). Results and statistics are the same either way.
  bool idle_skip = true;
  void validate() const;  // throws InputError naming the field
};
// Parses a config JSON object; unknown keys and bad values are InputErrors naming them.
UnitConfig unit_config_from_json(const std::string& text, const std::string& name);
std::string unit_config_to_json(const UnitConfig& c);

struct UnitOutput {
  std::vector<Rgba8> pixels;              // in request order
  std::vector<uint64_t> response_cycle;   // cycle each pixel left the unit
  std::vector<std::array<lee_jen::TexelMask, 2>> edge_shapes;  // per pixel, level0/level1 (edge modes)
  uint64_t cycles = 0;
  sim::Stats stats;
};

// The sampler configuration the golden model must use to see what the unit computes: the edge
// shape policy follows the unit's (static -> cache blocks of B, full-cross -> cross; cache-aware
// needs the per-pixel shapes of UnitOutput, see golden_pixel).
SamplerConfig golden_sampler_config(const SamplerConfig& cfg, const UnitConfig& u);

// Runs a trace through the unit (clocked by the simulation kernel). `vcd`, if given, receives a
// value-change dump of every channel's valid/ready/occupancy and the stages' busy flags. Throws
// InputError for an invalid configuration, DeadlockError on deadlock (with every block's state).
UnitOutput run_unit(const Texture& tex, const SamplerConfig& cfg, const Trace& trace, const UnitConfig& ucfg,
                    std::ostream* vcd = nullptr);

// The golden model's value for pixel i of a run (uses the run's kernel shapes for cache-aware).
Rgba8 golden_pixel(const Sampler& golden, const UnitConfig& u, const UnitOutput& out, const TraceRequest& r,
                   int32_t lambda, size_t i);

}  // namespace tfu::rtl
