// The wiring of one unit (the block diagram of rtl/tfu_unit.hpp): every block and channel,
// connected. Internal to the two ways of running it: clocked, every block evaluated every cycle
// (rtl/unit_clocked.cpp, the reference), and by timing recurrences (rtl/unit_recurrence.cpp).
#pragma once

#include <optional>
#include <vector>

#include "cmodel/frame.hpp"
#include "cmodel/trace.hpp"
#include "rtl/address_gen.hpp"
#include "rtl/cache_stage.hpp"
#include "rtl/edge_datapath.hpp"
#include "rtl/filter_unit.hpp"
#include "rtl/kernel_select.hpp"
#include "rtl/lod_unit.hpp"
#include "rtl/pipeline_registers.hpp"
#include "rtl/request_fifo.hpp"
#include "rtl/response.hpp"
#include "rtl/unit_config.hpp"
#include "rtl/unit_output.hpp"
#include "rtl/unit_watchdog.hpp"
#include "rtl/weight_rom_bank.hpp"

namespace tfu::rtl::detail {

// What the unit refuses before it starts (InputError): a configuration out of range, a frame tiled
// for another line size, a request naming an unbound descriptor, a sampler that needs B-spline
// coefficients on a texture that holds texels (or the reverse).
void check_inputs(const Frame& frame, const Trace& trace, const UnitConfig& u);

// The wiring: every block and channel of one unit, connected (the block diagram of tfu_unit.hpp).
// A datapath no sampler of the frame uses is left out of the simulation (software speed only: it
// would see no footprint).
struct Unit {
  // `shared`: the memory system the unit shares with others (none: its own memory).
  Unit(const Frame& frame, const Trace& trace, const UnitConfig& u, UnitOutput& out, MemoryBinding shared = {})
      : depth(static_cast<size_t>(u.channel_depth)),
        accept(trace.requests.size(), 0),
        // the watchdog, derived from the configuration (unit_watchdog.hpp)
        sim(no_progress_limit(u, shared.port != nullptr ? shared.port->units() : 1)),
        roms(frame.regs.samplers),
        cache(u.cache, frame.regs.textures),
        mem(u.memory, frame.regs.textures.size(), shared),
        request_fifo(sim, trace, c_quad, accept),
        lod_unit(sim, c_quad, c_pixel, trace.mode, frame.regs),
        address_gen(sim, c_pixel, c_addr, frame.regs, roms),
        kernel_select(sim, c_addr, c_shape, frame.regs),
        cache_stage(sim, c_shape, c_texels, c_edge_texels, frame.regs, frame.memory, cache, mem, u.miss_fifo_depth,
                    u.line_buffer_depth, u.decoder),
        // the clocks of each datapath beyond its blocks' (rtl/pipeline_registers.hpp)
        filter_pipe(sim, "filter_pipe", c_resp, uses(frame, false) ? u.filter.bilinear_stages - kFilterBlockDepth : 0,
                    depth),
        edge_pipe(sim, "edge_pipe", c_edge_resp, uses(frame, true) ? u.filter.edge_stages - kEdgeBlockClocks : 0,
                  depth),
        response(sim, filter_pipe.out(), edge_pipe.out(), out.pixels, out.response_cycle, accept) {
    if (cache_stage.records_shapes()) cache_stage.shapes.assign(trace.requests.size(), ProbeShapes{});  // one allocation, before the run
    const bool any_edge = uses(frame, true), any_filter = uses(frame, false);
    for (sim::ChannelBase* c : std::initializer_list<sim::ChannelBase*>{&c_quad, &c_pixel, &c_addr, &c_shape}) sim.add_clocked(c);
    if (any_filter) {
      filter.emplace(sim, c_texels, c_resp, frame.regs, roms, u.filter_lanes);
      for (sim::ChannelBase* c : std::initializer_list<sim::ChannelBase*>{&c_texels, &c_resp}) sim.add_clocked(c);
    }
    if (any_edge) {
      edge_median.emplace(sim, c_edge_texels, c_edge_median_out);
      edge_direction.emplace(sim, c_edge_median_out, c_edge_direction_out, frame.regs.textures.size());
      edge_merge.emplace(sim, c_edge_direction_out, c_edge_resp);
      for (sim::ChannelBase* c : std::initializer_list<sim::ChannelBase*>{&c_edge_texels, &c_edge_median_out, &c_edge_direction_out, &c_edge_resp}) sim.add_clocked(c);
    }
  }
  size_t depth;
  std::vector<uint64_t> accept;
  sim::Simulator sim;
  sim::Channel<QuadReq> c_quad{"quad", depth};
  sim::Channel<PixelReq> c_pixel{"pixel", depth};
  sim::Channel<FootprintReq> c_addr{"footprint", depth};
  sim::Channel<FootprintReq> c_shape{"shaped_footprint", depth};
  sim::Channel<FilterReq> c_texels{"texels", depth};
  sim::Channel<FilterReq> c_edge_texels{"edge_texels", depth};
  sim::Channel<EdgeMedianOut> c_edge_median_out{"edge_median_out", depth};
  sim::Channel<EdgeDirectionOut> c_edge_direction_out{"edge_direction_out", depth};
  sim::Channel<Response> c_resp{"response", depth};
  sim::Channel<Response> c_edge_resp{"edge_response", depth};
  WeightRomBank roms;
  TexelCache cache;
  MemoryModel mem;
  RequestFifo request_fifo;
  LodUnit lod_unit;
  AddressGen address_gen;
  KernelSelect kernel_select;
  CacheStage cache_stage;
  PipelineRegisters<Response> filter_pipe;  // after filter: filter.bilinear_stages - kFilterBlockDepth registers
  PipelineRegisters<Response> edge_pipe;    // after edge_merge: filter.edge_stages - kEdgeBlockClocks registers
  ResponseSink response;
  std::optional<FilterUnit> filter;
  std::optional<EdgeMedian> edge_median;
  std::optional<EdgeDirection> edge_direction;
  std::optional<EdgeMerge> edge_merge;
  // The static schedule (sim::Simulator::step_scheduled): every block once per cycle, called
  // directly, not through the simulator's module list. Software speed only: evaluate() reads only
  // committed channel state, so the order is free, and runs through the generic module list, in
  // either order, give the same results (run_unit_generic_schedule, tested).
  void evaluate_all() {
    request_fifo.evaluate();
    lod_unit.evaluate();
    address_gen.evaluate();
    kernel_select.evaluate();
    cache_stage.evaluate();
    if (filter) filter->evaluate();
    filter_pipe.evaluate();
    if (edge_median) {
      edge_median->evaluate();
      edge_direction->evaluate();
      edge_merge->evaluate();
    }
    edge_pipe.evaluate();
    response.evaluate();
  }
  // Whether a sampler of the frame uses the edge datapath (`edge`) or the filter (not `edge`).
  static bool uses(const Frame& frame, bool edge) {
    for (const SamplerDescriptor& s : frame.regs.samplers)
      if ((s.mode.base == BaseFilter::EdgePreserving) == edge) return true;
    return false;
  }
};

// The statistics of a finished run: the blocks' counters, the per-texture and per-stage traffic
// tables, and the derived rates.
void derive_stats(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, Unit& u, UnitOutput& out);

}  // namespace tfu::rtl::detail
