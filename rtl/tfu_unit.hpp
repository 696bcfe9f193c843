// tfu_unit: the texture filter unit as a pipeline of clocked blocks (TFU-C). First slice: the
// NEAREST and LINEAR families (plain, _MIPMAP_NEAREST, _MIPMAP_LINEAR) for 8-bit formats, through
// the texel cache and the memory model. Every block calls the golden model's arithmetic
// (cmodel/datapath.hpp, lod.hpp, Sampler::lod_info), never a copy of it.
//
//   request_fifo --QuadReq--> lod_unit --PixelReq--> address_gen --FootprintReq--> texel_cache
//        --FilterReq--> filter --Response--> (collected in order)
//
// Ports and widths (per channel word):
//   QuadReq      id[31:0], s[4] t[4] (FP32)                      one 2x2 quad
//   PixelReq     id[31:0], s t (FP32), lambda[15:0] (Q.8)        one pixel per cycle
//   FootprintReq id, level[3:0], taps 4 x {x[13:0], y[13:0], border[0]}, fu[7:0] fv[7:0],
//                blend[8:0], second[0] (1: the level1 footprint of a MIPMAP_LINEAR pixel)
//   FilterReq    id, 4 texel words [31:0], fu, fv, blend, second
//   Response     id[31:0], rgba[31:0]
// Rates: one pixel per cycle for NEAREST/LINEAR on cache hits; MIPMAP_LINEAR takes two footprints
// (one per cycle), so one pixel per two cycles. Misses stall the cache stage until the memory model
// delivers every missing line of the footprint.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "cmodel/sampler.hpp"
#include "cmodel/trace.hpp"
#include "rtl/memory_model.hpp"
#include "rtl/texel_cache.hpp"
#include "sim/kernel/kernel.hpp"

namespace tfu::rtl {

struct UnitConfig {
  TexelCacheConfig cache{};
  MemoryConfig memory{};
  int channel_depth = 2;  // skid buffers between blocks
};

struct UnitOutput {
  std::vector<Rgba8> pixels;  // in request order
  uint64_t cycles = 0;
  sim::Stats stats;
};

// Runs a quad-mode trace through the unit (clocked by the simulation kernel). Throws InputError for
// a mode or format this slice does not support yet, CheckFailed on deadlock.
UnitOutput run_unit(const Texture& tex, const SamplerConfig& cfg, const Trace& trace, const UnitConfig& ucfg);

}  // namespace tfu::rtl
