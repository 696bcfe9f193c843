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
#include "rtl/request_stream.hpp"
#include "rtl/response.hpp"
#include "rtl/unit_config.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_output.hpp"
#include "rtl/unit_stats.hpp"
#include "rtl/unit_watchdog.hpp"
#include "rtl/weight_rom_bank.hpp"

namespace tfu::rtl::detail {

// What the unit refuses before it starts (InputError): a configuration out of range, a frame tiled
// for another line size, a request naming an unbound descriptor, a sampler that needs B-spline
// coefficients on a texture that holds texels (or the reverse).
void check_inputs(const Frame& frame, const Trace& trace, const UnitConfig& u);
// The part of check_inputs that is the configuration and the frame (a stream's requests are
// checked as they are pushed: check_requests, rtl/tfu_unit.hpp).
void check_config(const Frame& frame, const UnitConfig& u);

// The per-request statistics of a run, accumulated in request order as the requests are handed on
// (derive_stats reads them): per statistics slot the requests, the output cycles given to them
// and their latencies; per texture descriptor the requests.
struct RetireStats {
  RetireStats(size_t slots, size_t textures)
      : slot_requests(slots, 0), slot_cycles(slots, 0), slot_latency(slots), tex_requests(textures, 0) {}
  // Request r retired at `exit`, accepted at `accept`: pixels retire in request order, one per
  // cycle at most, so request i is given its retirement cycle minus request i - 1's (the first its
  // retirement cycle + 1), and one unit's slots add up to its cycles.
  void add(const TraceRequest& r, uint64_t exit, uint64_t accept) {
    const size_t k = stat_slot(r.texture, r.stage);
    ++slot_requests[k];
    slot_cycles[k] += exit + 1 - retired_by;
    retired_by = exit + 1;
    const uint64_t lat = exit - accept;
    std::vector<uint64_t>& h = slot_latency[k];
    if (h.size() <= lat) h.resize(lat + 1);
    ++h[lat];
    ++tex_requests[r.texture];
    ++requests;
  }
  // add() for requests [first, end) of `source`, with their `exit` and `accept` cycles: the same
  // sums, the rings' storage and the running sums in registers (software speed only).
  void add_range(const RequestStream& source, const RequestRing<uint64_t>& exit, const RequestRing<uint64_t>& accept,
                 size_t first, size_t end) {
    const TraceRequest* req = source.data();
    const uint64_t *ex = exit.data(), *ac = accept.data();
    const size_t req_mask = source.mask(), ex_mask = exit.mask(), ac_mask = accept.mask();
    uint64_t *sr = slot_requests.data(), *sc = slot_cycles.data(), *tr = tex_requests.data();
    std::vector<uint64_t>* sl = slot_latency.data();
    uint64_t by = retired_by;
    for (size_t i = first; i < end; ++i) {
      const TraceRequest& r = req[i & req_mask];
      const uint64_t e = ex[i & ex_mask];
      const size_t k = stat_slot(r.texture, r.stage);
      ++sr[k];
      sc[k] += e + 1 - by;
      by = e + 1;
      const uint64_t lat = e - ac[i & ac_mask];
      std::vector<uint64_t>& h = sl[k];
      if (h.size() <= lat) [[unlikely]]
        h.resize(lat + 1);
      ++h[lat];
      ++tr[r.texture];
    }
    retired_by = by;
    requests += end - first;
  }
  std::vector<uint64_t> slot_requests, slot_cycles;
  std::vector<std::vector<uint64_t>> slot_latency;
  std::vector<uint64_t> tex_requests;
  uint64_t retired_by = 0;  // the cycle after the previous request's retirement
  size_t requests = 0;
};

// The wiring: every block and channel of one unit, connected (the block diagram of tfu_unit.hpp).
// A datapath no sampler of the frame uses is left out of the simulation (software speed only: it
// would see no footprint).
struct Unit {
  // `trace`: the requests (a whole trace, or a stream: then every per-request record is a window,
  // rtl/request_stream.hpp). `shared`: the memory system the unit shares with others (none: its
  // own memory).
  Unit(const Frame& frame, RequestStream& trace, const UnitConfig& u, MemoryBinding shared = {})
      : depth(static_cast<size_t>(u.channel_depth)),
        source(trace),
        retire_stats(stat_slots(frame.regs.textures.size()), frame.regs.textures.size()),
        // the watchdog, derived from the configuration (unit_watchdog.hpp)
        sim(no_progress_limit(u, shared.port != nullptr ? shared.port->units() : 1)),
        roms(frame.regs.samplers),
        cache(u.cache, frame.regs.textures),
        mem(u.memory, frame.regs.textures.size(), shared),
        request_fifo(sim, trace, c_quad, accept),
        lod_unit(sim, c_quad, c_pixel, trace.mode(), frame.regs),
        address_gen(sim, c_pixel, c_addr, frame.regs, roms),
        kernel_select(sim, c_addr, c_shape, frame.regs),
        cache_stage(sim, c_shape, c_texels, c_edge_texels, frame.regs, frame.memory, cache, mem, u.miss_fifo_depth,
                    u.line_buffer_depth, u.decoder),
        // the clocks of each datapath beyond its blocks' (rtl/pipeline_registers.hpp)
        filter_pipe(sim, "filter_pipe", c_resp, uses(frame, false) ? u.filter.bilinear_stages - kFilterBlockDepth : 0,
                    depth),
        edge_pipe(sim, "edge_pipe", c_edge_resp, uses(frame, true) ? u.filter.edge_stages - kEdgeBlockClocks : 0,
                  depth),
        response(sim, filter_pipe.out(), edge_pipe.out(), pixels, exit_cycle, accept, trace) {
    // One allocation each, before the run.
    const auto size = [&trace](auto& ring) { trace.whole() ? ring.whole(trace.produced()) : ring.window(kStreamWindow); };
    size(accept);
    size(pixels);
    size(exit_cycle);
    if (cache_stage.records_shapes()) size(cache_stage.shapes);
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
  RequestStream& source;
  // Per request: its accept cycle (request_fifo), colour and exit cycle (response).
  RequestRing<uint64_t> accept;
  RequestRing<Rgba8> pixels;
  RequestRing<uint64_t> exit_cycle;
  RetireStats retire_stats;
  size_t drained = 0;  // requests handed on (drain_to)
  // drain_to's chunk, reused from chunk to chunk (software speed only: every field the sink reads is
  // written for each chunk; the vectors keep their memory, which resize would otherwise clear for
  // every chunk, and the process's fresh pages are expensive on this VM).
  UnitChunk chunk;
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
  // Hands on the retired requests before `end` (all retired, end a multiple of 4 or the last):
  // their statistics into retire_stats and, given a `sink`, the requests with their records as one
  // chunk (a window's slots are then free again).
  void drain_to(size_t end, const UnitChunkSink* sink);
  // The run's per-request results (a whole trace's rings, moved out).
  void take_outputs(UnitOutput& out) {
    out.pixels = pixels.take();
    out.response_cycle = exit_cycle.take();
    out.edge_shapes = cache_stage.shapes.take();
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
// `u.retire_stats` must hold every request (drain_to the end).
void derive_stats(const Frame& frame, const UnitConfig& ucfg, Unit& u, UnitOutput& out);

}  // namespace tfu::rtl::detail
