// The unit run by timing recurrences (`tfu sim --engine recurrence`): the same blocks and
// datapaths as the clocked run of rtl/unit_clocked.cpp, the same results, cycles and statistics,
// computed request by request instead of cycle by cycle. A second statement of the unit's timing,
// checked against the clocked run, which stays the reference:
// TfuUnit.InterleavedTexturesFormatsLayoutsAndSamplers compares the two on every filter family,
// wrap mode, format, layout and trace mode and on random cache organisations, channel and FIFO
// depths, lane counts and memory timings, and the differential fuzz target on every input.
// (It is about 20 % faster on the filter path, no faster on the edge path: docs/cycle-model.md.)
//
// Why this is exact. Every block takes its inputs in order, one per cycle at most, and talks to
// its neighbours only through valid/ready channels whose ready is registered: in cycle t a block
// sees item j of its input iff j was pushed before t and item j - 1 popped before t, and may push
// item j of its output iff item j - depth was popped before t (the occupancy it sees is the one
// committed at the edge). So the cycle at which each item moves through each block is the
// earliest one that meets these conditions and the block's own rules (below), and every condition
// names an earlier item, or the same item at an earlier block. Taking the requests in order and
// each through every block therefore computes the clocked run's cycles exactly, with the datapath
// functions called in the same order as there (the texel cache's tags and LRU, the memory model's
// queue, the filters' level and probe registers all see the same sequence). The blocks' rules:
//   request_fifo  pushes a quad every cycle it can (its pixels' accept cycle).
//   lod_unit      takes a quad when it holds none (the cycle after it pushed the previous quad's
//                 last pixel), pushes one pixel per cycle, the first in the cycle it took the quad.
//   address_gen   the same with pixels and their level footprints (AddressGen::begin / issue).
//   kernel_select moves a footprint when its input is valid and its output ready.
//   texel_cache   its output side (before its input side in the same cycle): the miss-FIFO head
//                 leaves when its lines are in (ready) and its output channel is ready; its input
//                 side: a footprint is taken when the tag port is free (the previous footprint's
//                 accept cycle + its bank cycles) and the FIFO has room after this cycle's exit.
//                 Stall counters: per head, the cycles waiting for lines (stall_cache_miss) and
//                 then for the output (stall_backpressure); per input, the cycles it waited for
//                 the port (stall_bank_conflict).
//   filter        the head keeps the lanes ceil(taps / 4 lanes) - 1 cycles, then leaves when the
//                 response channel is ready (if it completes a pixel).
//   edge_median, edge_direction  as kernel_select; edge_merge as the filter without lane cycles.
//   response      retires pixel ids in order, one per cycle, from either datapath (ResponseSink::Timing).
// The run ends the cycle after the last retire.
// The blocks' functions are called per footprint (the plain path), or, for quads of isotropic
// LINEAR-family samplers on 8-bit textures, batched per quad by the LINEAR quad path
// (rtl/unit_recurrence_linear_quads.hpp, software speed only), with the same timing functions.
#include <algorithm>
#include <functional>
#include <memory>
#include <type_traits>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/fast_paths.hpp"

#include "rtl/tfu_unit.hpp"
#include "rtl/timing.hpp"
#include "rtl/unit_recurrence_linear_quads.hpp"
#include "rtl/unit_wiring.hpp"

namespace tfu::rtl {

UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, UnitEngine engine, const VcdOptions& vcd) {
  return engine == UnitEngine::Recurrence && vcd.out == nullptr ? run_unit_recurrence(frame, trace, ucfg)
                                                                : run_unit(frame, trace, ucfg, vcd);
}

UnitOutput run_unit_recurrence(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, bool linear_quads) {
  detail::check_inputs(frame, trace, ucfg);
  const size_t n = trace.requests.size();
  UnitOutput out;
  out.pixels.resize(n);
  out.response_cycle.resize(n);
  auto unit = std::make_unique<detail::Unit>(frame, trace, ucfg, out);
  detail::Unit& u = *unit;
  detail::LinearQuadPath linear(frame.regs, u, linear_quads && fast_paths_enabled());
  const auto depth = static_cast<int64_t>(ucfg.channel_depth);
  const auto fifo_depth = static_cast<int64_t>(ucfg.miss_fifo_depth);
  const size_t keep = static_cast<size_t>(std::max(depth, fifo_depth)) + 1;
  // Pop cycles per item of each channel (-1: before the first item), and the items so far. A
  // channel of depth d has room for item i once item i - d has left it: ring[i - d] + 1. The
  // footprint channel, the shaped channel and the miss FIFO carry the same footprints (one row
  // each), as the three edge channels carry the same edge footprints.
  Ring<int64_t> quads(keep, -1), pixels(keep, -1), texels(keep, -1), responses(keep, -1), edge_responses(keep, -1);
  Ring<FootprintTimes> footprints(keep, {-1, -1, -1});
  Ring<EdgeTimes> edges(keep, {-1, -1, -1});
  int64_t n_quads = 0, n_pixels = 0, n_footprints = 0, n_texels = 0, n_edges = 0, n_responses = 0, n_edge_responses = 0;
  // The previous item's cycles (-1: none).
  int64_t quad_push = -1, last_pixel_push = -1, last_footprint_push = -1, last_shaped_push = -1;
  int64_t prev_accept = -1, prev_port_cycles = 0, last_exit = -1, last_done = -1;
  EdgeTimes last_edge{-1, -1, -1};
  uint64_t stall_miss = 0, stall_bank = 0, stall_back = 0, lane_busy = 0;
  const auto span = [](int64_t from, int64_t to) { return static_cast<uint64_t>(std::max<int64_t>(0, to - from)); };

  // The blocks' rules (the list above), one function per step; both the plain path and the LINEAR
  // quad path take their cycles from these.
  // lod_unit -> address_gen: pixel k of the quad taken at `quad_taken`; the cycle address_gen takes it.
  const auto pixel_taken_at = [&](int k, int64_t quad_taken) {
    last_pixel_push = std::max(k == 0 ? quad_taken : last_pixel_push + 1, pixels[n_pixels - depth] + 1);
    const int64_t pixel_taken = std::max(last_pixel_push + 1, last_footprint_push + 1);
    pixels[n_pixels++] = pixel_taken;
    return pixel_taken;
  };
  // address_gen -> kernel_select -> texel_cache: a footprint of the pixel taken at `pixel_taken`
  // (its first, or the next after the previous footprint), through the cache's input side, where
  // `admit(accept, bank_cycles)` looks it up and returns the cycle its lines are in, and its output
  // side (`edge`: towards the edge datapath); the cycle it leaves the miss FIFO.
  const auto cache_exit_at = [&](bool first_footprint, int64_t pixel_taken, bool edge, auto&& admit) {
    const FootprintTimes& earlier = footprints[n_footprints - depth];
    last_footprint_push = std::max(first_footprint ? pixel_taken : last_footprint_push + 1, earlier.shaped_push + 1);
    const int64_t shaped_push = std::max({last_footprint_push + 1, last_shaped_push + 1, earlier.accept + 1});
    last_shaped_push = shaped_push;
    // texel_cache: the input side
    const int64_t visible = std::max(shaped_push + 1, prev_accept + 1);
    const int64_t port_free = prev_accept + prev_port_cycles;
    const int64_t accept = std::max({visible, port_free, footprints[n_footprints - fifo_depth].exit});
    stall_bank += span(visible, std::min(accept, port_free));
    int bank_cycles = 1;
    const auto ready = static_cast<int64_t>(admit(static_cast<uint64_t>(accept), bank_cycles));
    prev_accept = accept;
    prev_port_cycles = bank_cycles;
    // texel_cache: the output side
    const int64_t words_room = (edge ? edges[n_edges - depth].t1 : texels[n_texels - depth]) + 1;
    const int64_t head = std::max(accept + 1, last_exit + 1);
    const int64_t exit = std::max({head, ready, words_room});
    stall_miss += span(head, std::min(ready, exit));
    stall_back += span(std::max(head, ready), exit);
    footprints[n_footprints++] = {shaped_push, accept, exit};
    last_exit = exit;
    return exit;
  };
  // filter: the cycle a footprint of `ntaps` taps that left the cache at `exit` leaves the lanes
  // (`emits`: it completes a pixel, whose response needs room).
  const auto filter_done_at = [&](int64_t exit, int ntaps, bool emits) {
    const int64_t filter_head = std::max(exit + 1, last_done + 1);
    const int lanes = u.filter->extra_clocks(ntaps);
    lane_busy += static_cast<uint64_t>(lanes);
    const int64_t done = std::max(filter_head + lanes, emits ? responses[n_responses - depth] + 1 : 0);
    texels[n_texels++] = done;
    last_done = done;
    return done;
  };
  // response: its rule is ResponseSink::Timing::retire_at (rtl/response.hpp).
  ResponseSink::Timing& response = u.sink.timing;
  // The blocks' output registers, reused from item to item as the clocked run reuses its channel
  // slots (every field the datapath functions read is written first).
  QuadReq quad;
  FootprintReq f;
  FilterReq texel_words;
  EdgeS1 median_out;
  EdgeS2 direction_out;
  std::array<uint64_t, 4> quad_retire{};
  std::array<Rgba8, 4> quad_colour{};
  // The progress bar of a long run (as the clocked run's): requests retired, every 4096 quads.
  const std::function<uint64_t()> retired = [&u] { return static_cast<uint64_t>(u.sink.retired()); };
  sim::ProgressBar bar(retired, n);
  for (size_t first = 0, quads_in = 0; first < n; ++quads_in) {
    if ((quads_in & 0xFFFu) == 0) bar.update(static_cast<uint64_t>(std::max<int64_t>(response.last_retire, 0)));
    // request_fifo -> lod_unit
    RequestFifo::form_quad(trace, first, quad);
    quad_push = std::max(quad_push + 1, quads[n_quads - depth] + 1);
    for (size_t k = 0; k < static_cast<size_t>(quad.npix); ++k) u.accept[first + k] = static_cast<uint64_t>(quad_push);
    const int64_t quad_taken = std::max(quad_push + 1, last_pixel_push + 1);
    quads[n_quads++] = quad_taken;
    first += static_cast<size_t>(quad.npix);
    const AnisoLod lod = u.lod.quad_lod(quad);
    if (linear.takes(quad)) {
      // The LINEAR quad path: one or two level footprints per pixel, the functions batched per quad.
      // (The level count is a template constant, so that the loop over levels unrolls.)
      const auto footprint_times = [&](auto level_count) __attribute__((always_inline)) {
        constexpr int kLevels = decltype(level_count)::value;
        for (int k = 0; k < 4; ++k) {
          const int64_t pixel_taken = pixel_taken_at(k, quad_taken);
          for (int n_level = 0; n_level < kLevels; ++n_level) {  // level0, then level1 when blending
            const int64_t exit = cache_exit_at(n_level == 0, pixel_taken, false, [&](uint64_t now, int& bank_cycles) {
              return linear.admit(k, n_level, now, bank_cycles);
            });
            const bool emits = n_level + 1 == kLevels;
            const int64_t done = filter_done_at(exit, 4, emits);
            if (emits) quad_retire[static_cast<size_t>(k)] = response.retire_at(responses, n_responses, done);
          }
        }
      };
      if (linear.address(quad, lod) == 1) {
        footprint_times(std::integral_constant<int, 1>{});
      } else {
        footprint_times(std::integral_constant<int, 2>{});
      }
      linear.filter(quad_colour);
      for (size_t k = 0; k < 4; ++k) u.sink.retire({quad.id + static_cast<uint32_t>(k), quad_colour[k]}, quad_retire[k]);
      continue;
    }
    for (int k = 0; k < quad.npix; ++k) {
      const int64_t pixel_taken = pixel_taken_at(k, quad_taken);
      u.addr.begin(LodUnit::pixel(quad, lod, k));
      for (bool first_footprint = true, last = false; !last; first_footprint = false) {
        last = u.addr.issue(f);
        u.shape.shape(f);
        const bool edge = f.tag.base == BaseFilter::EdgePreserving;
        const int64_t exit = cache_exit_at(first_footprint, pixel_taken, edge, [&](uint64_t now, int& bank_cycles) {
          return u.cst.admit_footprint(f, now, bank_cycles);
        });
        u.cst.read_out_footprint(f, texel_words);
        const bool emits = texel_words.tag.emits();
        Response r;
        if (!edge) {
          // filter -> response
          const int64_t done = filter_done_at(exit, texel_words.ntaps, emits);
          if (u.filter->filter(texel_words, r)) u.sink.retire(r, response.retire_at(responses, n_responses, done));
        } else {
          // edge_median -> edge_direction -> edge_merge -> response
          const EdgeTimes& earlier_edge = edges[n_edges - depth];
          EdgeTimes e;
          e.t1 = std::max({exit + 1, last_edge.t1 + 1, earlier_edge.t2 + 1});
          EdgeMedian::stage(texel_words, median_out);
          e.t2 = std::max({e.t1 + 1, last_edge.t2 + 1, earlier_edge.t3 + 1});
          u.e2->stage(median_out, direction_out);
          e.t3 = std::max({e.t2 + 1, last_edge.t3 + 1, emits ? edge_responses[n_edge_responses - depth] + 1 : 0});
          edges[n_edges++] = e;
          last_edge = e;
          if (u.e3->merge(direction_out, r))
            u.sink.retire(r, response.retire_at(edge_responses, n_edge_responses, e.t3));
        }
      }
    }
  }
  bar.finish(static_cast<uint64_t>(response.last_retire + 1));
  u.cst.add_stalls(stall_miss, stall_bank, stall_back);
  if (u.filter) u.filter->add_busy_cycles(lane_busy);
  out.cycles = static_cast<uint64_t>(response.last_retire + 1);
  out.edge_shapes = std::move(u.cst.shapes);
  detail::derive_stats(frame, trace, ucfg, u, out);
  return out;
}

}  // namespace tfu::rtl
