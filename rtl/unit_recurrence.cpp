// The unit run by timing recurrences (`tfu sim --engine recurrence`): the same blocks and
// datapaths as the clocked run of rtl/unit_clocked.cpp, the same results, cycles and statistics,
// computed request by request instead of cycle by cycle. A second statement of the unit's timing,
// checked against the clocked run, which stays the reference:
// TfuUnit.InterleavedTexturesFormatsLayoutsAndSamplers compares the two on every filter family,
// wrap mode, format, layout and trace mode and on random cache organisations, channel and FIFO
// depths, lane counts and memory timings, and the differential fuzz target on every input.
// (It is about 20 % faster on the filter path, no faster on the edge path: docs/speed-log.md.)
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
// queue, the filters' level and probe registers all see the same sequence).
//
// The blocks' rules are their `Timing` parts, each beside the block's evaluate() in its own header
// (rtl/timing.hpp: the rules they share; rtl/README.md: both change together):
//   request_fifo   RequestFifo::Timing   a quad in every cycle the quad channel has room (its
//                                        pixels' accept cycle)
//   lod_unit       SequencerTiming       a quad when it holds none, then its pixels one per cycle
//   address_gen    SequencerTiming       the same with a pixel and its level footprints
//   kernel_select  InOrderTiming         one footprint per cycle when its output has room
//   texel_cache    CacheStage::Timing    input side (visible, tag port free, miss-FIFO slot),
//                                        output side (lines in, output room); the stall counters
//   filter         FilterUnit::Timing    in order, holding the lanes ceil(taps / 4 lanes) - 1
//                                        cycles; the busy counter
//   edge_median, edge_direction, edge_merge   InOrderTiming
//   filter_pipe, edge_pipe   PipelineRegisters::Timing   the registers of a datapath deeper than
//                                        its blocks (filter.*_stages), an InOrderTiming each
//   response       ResponseSink::Timing  pixel ids in order, one per cycle, from either datapath
// Each channel of the unit (rtl/unit_wiring.hpp), and the texel cache's miss FIFO, is a
// ChannelTimes: the cycles at which its items left it. The run ends the cycle after the last
// retire. The blocks' functions are called per footprint (the plain path), or, for quads of
// isotropic LINEAR-family samplers on 8-bit textures, batched per quad by the LINEAR quad path
// (rtl/unit_recurrence_linear_quads.hpp, software speed only; a run of such quads on one lent
// copy of the blocks' timing, below: linear_run), for quads of anisotropic ones on
// uncompressed 8-bit textures by the probe quad path (rtl/unit_recurrence_probes.hpp, likewise),
// and for those of isotropic CUBIC-family samplers by the CUBIC quad path
// (rtl/unit_recurrence_cubic_quads.hpp, likewise), with the same timing functions.
// A unit sharing a memory system with other units (rtl/shared_memory.hpp) runs here too: its texel
// cache issues its misses at nondecreasing cycles, the same as the clocked run's, and each miss's
// answer (the cycle its data is in) is all the recurrences need from it, so the run pauses at each
// miss until the shared system's global order reaches it, exactly as the clocked run does.
#include <algorithm>
#include <functional>
#include <memory>
#include <type_traits>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/fast_paths.hpp"

#include "rtl/engine_compare.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/timing.hpp"
#include "rtl/unit_recurrence_cubic_quads.hpp"
#include "rtl/unit_recurrence_linear_quads.hpp"
#include "rtl/unit_recurrence_probes.hpp"
#include "rtl/unit_wiring.hpp"

namespace tfu::rtl {

UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, UnitEngine engine,
                    const VcdOptions& vcd) {
  return engine == UnitEngine::Recurrence && vcd.out == nullptr ? run_unit_recurrence(frame, trace, ucfg)
                                                                : run_unit(frame, trace, ucfg, vcd);
}

namespace {

// The unit's channels for the recurrences (rtl/timing.hpp), as in rtl/unit_wiring.hpp, in
// data-flow order, with the texel cache's miss FIFO.
struct UnitChannelTimes {
  explicit UnitChannelTimes(const UnitConfig& c)
      : quad(depth(c)),
        pixel(depth(c)),
        footprint(depth(c)),
        shaped_footprint(depth(c)),
        miss_fifo(static_cast<size_t>(c.miss_fifo_depth)),
        texels(depth(c)),
        edge_texels(depth(c)),
        edge_median_out(depth(c)),
        edge_direction_out(depth(c)),
        response(depth(c)),
        edge_response(depth(c)) {}
  ChannelTimes quad, pixel, footprint, shaped_footprint, miss_fifo, texels, edge_texels, edge_median_out,
      edge_direction_out, response, edge_response;
  static size_t depth(const UnitConfig& c) { return static_cast<size_t>(c.channel_depth); }
};

// The events of the run (rtl/engine_compare.hpp), recorded when kRecord (a template constant, so
// that a run without the engine compare carries no test per event): at(e, t) records event e at
// cycle t and returns t. Every block's timing function returns the cycle its item leaves the
// block's input, which is the event.
template <bool kRecord>
struct EventLog {
  UnitEvents* events;
  [[gnu::always_inline]] int64_t at(UnitEvent e, int64_t t) const {
    if constexpr (kRecord) (*events)[static_cast<size_t>(e)].push_back(t);
    return t;
  }
};

// `trace`: a whole trace (its requests checked by the caller) or a stream, whose results go to
// `sink` chunk by chunk (rtl/request_stream.hpp).
template <bool kRecord>
UnitOutput recurrences(const Frame& frame, RequestStream& trace, const UnitConfig& ucfg, bool quad_paths,
                       EventLog<kRecord> log, MemoryBinding shared, const UnitChunkSink* sink = nullptr) {
  using enum UnitEvent;
  const size_t n = trace.whole() ? trace.produced() : 0;  // 0: not known (no progress bar)
  UnitOutput out;
  auto unit = std::make_unique<detail::Unit>(frame, trace, ucfg, shared);
  detail::Unit& u = *unit;
  detail::LinearQuadPath linear(frame.regs, u, quad_paths && fast_paths_enabled());
  detail::ProbeQuadPath probes(frame.regs, u, quad_paths && fast_paths_enabled());
  detail::CubicQuadPath cubic(frame.regs, u, quad_paths && fast_paths_enabled());
  UnitChannelTimes ch(ucfg);
  // The timing a footprint of the filter path moves through from address_gen to the response
  // (rtl/timing.hpp): the blocks' timing and the channels between them (the pixel channel's
  // consumer, address_gen, and the response sink included; the pipeline registers, which have
  // timing of their own, are passed as they are). `unit_path` refers to the unit's own; a batch of
  // footprints (the probe quad path) runs on register copies of them, lent() and settled() around
  // it, the same functions on the same cycles in the same order (software speed only: the copies
  // keep the blocks' last cycles and the channels' counts in registers, which the channels' ring
  // stores would otherwise force the compiler to reload; rtl/unit_recurrence_probes.hpp).
  struct PathTiming {
    SequencerTiming& address_gen;
    InOrderTiming& kernel_select;
    CacheStage::Timing& cache;
    FilterUnit::Timing* filter;  // null when no sampler of the frame uses the filter
    ResponseSink::Timing& response;
    ChannelTimes &footprint, &shaped_footprint, &miss_fifo, &texels, &response_in;
  };
  const PathTiming unit_path{u.address_gen.timing, u.kernel_select.timing, u.cache_stage.timing,
                             u.filter ? &u.filter->timing : nullptr, u.response.timing, ch.footprint,
                             ch.shaped_footprint, ch.miss_fifo, ch.texels, ch.response};
  struct LentTiming {
    SequencerTiming address_gen;
    InOrderTiming kernel_select;
    CacheStage::Timing cache;
    FilterUnit::Timing filter;
    ResponseSink::Timing response;
    ChannelTimes footprint, shaped_footprint, miss_fifo, texels, response_in;
  };
  const auto lend = [&]() __attribute__((always_inline)) {
    return LentTiming{unit_path.address_gen,
                      unit_path.kernel_select,
                      unit_path.cache,
                      *unit_path.filter,
                      unit_path.response,
                      unit_path.footprint.lend(),
                      unit_path.shaped_footprint.lend(),
                      unit_path.miss_fifo.lend(),
                      unit_path.texels.lend(),
                      unit_path.response_in.lend()};
  };
  const auto settle = [&](const LentTiming& l) __attribute__((always_inline)) {
    unit_path.address_gen = l.address_gen;
    unit_path.kernel_select = l.kernel_select;
    unit_path.cache = l.cache;
    *unit_path.filter = l.filter;
    unit_path.response = l.response;
    unit_path.footprint.settle(l.footprint);
    unit_path.shaped_footprint.settle(l.shaped_footprint);
    unit_path.miss_fifo.settle(l.miss_fifo);
    unit_path.texels.settle(l.texels);
    unit_path.response_in.settle(l.response_in);
  };
  // address_gen -> kernel_select -> texel_cache: a footprint of the pixel address_gen took at
  // `pixel_taken` (its first, or the next after the previous one), through the cache's input side,
  // where `admit(accepted, bank_cycles)` looks it up and returns the cycle its lines are in, and its
  // output side (`edge`: towards the edge datapath); the cycle it leaves the miss FIFO. `stalls`:
  // the counters of its statistics slot (stat_slot()), where its stalls count, or a batch's.
  const auto through_cache = [&](auto& p, bool first_footprint, int64_t pixel_taken, bool edge, auto& stalls,
                                 auto&& admit) __attribute__((always_inline)) {
    const int64_t pushed = p.address_gen.push(first_footprint, pixel_taken, p.footprint);
    const int64_t shaped =
        log.at(KernelSelectTakesFootprint, p.kernel_select.move(pushed, p.footprint, &p.shaped_footprint));
    const int64_t accepted =
        log.at(CacheAcceptsFootprint, p.cache.accept(shaped, p.shaped_footprint, p.miss_fifo, stalls));
    int bank_cycles = 1;
    const auto ready = static_cast<int64_t>(admit(static_cast<uint64_t>(accepted), bank_cycles));
    return log.at(CacheEmitsFootprint,
                  p.cache.exit(accepted, bank_cycles, ready, p.miss_fifo, edge ? ch.edge_texels : p.texels, stalls));
  };
  // The blocks' output registers, reused from item to item as the clocked run reuses its channel
  // slots (every field the datapath functions read is written first).
  QuadReq quad;
  FootprintReq f;
  FilterReq texel_words;
  EdgeMedianOut median_out;
  EdgeDirectionOut direction_out;
  std::array<int64_t, 4> quad_retire{};
  std::array<Rgba8, 4> quad_colour{};
  // pipeline registers -> response: the pixel pushed into `in` at `pushed` passes the datapath's
  // pipeline registers `pipe` (none at the default depths) and retires; the cycle it does.
  const auto retire_at = [&](ResponseSink::Timing& response, PipelineRegisters<Response>& pipe, ChannelTimes& in,
                             int64_t pushed, UnitEvent e) __attribute__((always_inline)) {
    const int64_t passed = pipe.timing.pass(pushed, in);
    return log.at(e, response.retire_at(pipe.timing.last(in), passed));
  };
  // The end of a quad on lent timing (probe_quad; linear_run, a run of quads): the timing back into the blocks,
  // the quad's stalls and busy cycles into its statistics slot.
  const auto settle_quad = [&](const LentTiming& p, size_t slot, const CacheStage::StallCounts& stalls, uint64_t busy)
                               __attribute__((always_inline)) {
    settle(p);
    u.cache_stage.add_stalls(slot, stalls);
    u.filter->busy_cycles(slot) += busy;
  };
  const auto retire = [&](const Response& r, PipelineRegisters<Response>& pipe, ChannelTimes& in, int64_t pushed,
                          UnitEvent e) {
    u.response.retire(r, static_cast<uint64_t>(retire_at(u.response.timing, pipe, in, pushed, e)));
  };
  // filter -> response: the texel words that left the cache at `exit`.
  const auto through_filter = [&](int64_t exit) {
    const bool emits = texel_words.tag.emits();
    const int64_t done =
        log.at(FilterFinishesFootprint, u.filter->timing.done(exit, texel_words.ntaps, emits, ch.texels, ch.response,
                                                              u.filter->busy_cycles(stat_slot(texel_words.tag.req))));
    Response r;
    if (u.filter->filter(texel_words, r)) retire(r, u.filter_pipe, ch.response, done, ResponseRetiresFilterPixel);
  };
  // edge_median -> edge_direction -> edge_merge -> response: the same for an edge footprint. The
  // stages' combinational parts in one call (edge_stages_fused, software speed only: the same
  // functions of the same inputs in the same order, which no timing reads) unless the fast paths
  // are off; then each stage's own, as the clocked blocks call them.
  const bool edge_fused = quad_paths && fast_paths_enabled();
  const auto through_edge_stages = [&](int64_t exit) {
    const bool emits = texel_words.tag.emits();
    Response r;
    bool retires = false;
    if (edge_fused) {
      retires = edge_stages_fused(texel_words, *u.edge_direction, *u.edge_merge, r);
    } else {
      EdgeMedian::stage(texel_words, median_out);
      u.edge_direction->stage(median_out, direction_out);
      retires = u.edge_merge->merge(direction_out, r);
    }
    const int64_t median =
        log.at(EdgeMedianTakesFootprint, u.edge_median->timing.move(exit, ch.edge_texels, &ch.edge_median_out));
    const int64_t direction = log.at(EdgeDirectionTakesFootprint,
                                     u.edge_direction->timing.move(median, ch.edge_median_out, &ch.edge_direction_out));
    const int64_t merged =
        log.at(EdgeMergeTakesFootprint,
               u.edge_merge->timing.move(direction, ch.edge_direction_out, emits ? &ch.edge_response : nullptr));
    if (retires) retire(r, u.edge_pipe, ch.edge_response, merged, ResponseRetiresEdgePixel);
  };
  // The CUBIC quad path (rtl/unit_recurrence_cubic_quads.hpp): one or two level footprints of 4 x 4
  // taps per pixel of `quad`, which lod_unit took at `quad_taken` (its levels from `lod`), timed
  // footprint by footprint as the LINEAR quad path's below (each pixel as pixel_taken_at takes it),
  // the functions batched per quad. Out of line, the quad's values passed by value: the loop's
  // other paths then compile as they would without it.
  const auto cubic_quad = [&](int64_t quad_taken, AnisoLod lod) __attribute__((noinline)) {
    const size_t slot = stat_slot(quad.req);
    const int levels = cubic.address(quad, lod);
    for (int k = 0; k < 4; ++k) {
      const int64_t pushed = u.lod_unit.timing.push(k == 0, quad_taken, ch.pixel);
      const int64_t pixel_taken = log.at(AddressGenTakesPixel, u.address_gen.timing.take(pushed, ch.pixel));
      for (int level = 0; level < levels; ++level) {  // level0, then level1 when blending
        const int64_t exit =
            through_cache(unit_path, level == 0, pixel_taken, false, u.cache_stage.counters(slot),
                          [&](uint64_t now, int& bank_cycles) { return cubic.admit(k, level, now, bank_cycles); });
        const bool emits = level + 1 == levels;
        const int64_t done =
            log.at(FilterFinishesFootprint,
                   u.filter->timing.done(exit, 16, emits, ch.texels, ch.response, u.filter->busy_cycles(slot)));
        if (emits)
          quad_retire[static_cast<size_t>(k)] =
              retire_at(u.response.timing, u.filter_pipe, ch.response, done, ResponseRetiresFilterPixel);
      }
    }
    cubic.filter(quad_colour);
    for (size_t k = 0; k < 4; ++k)
      u.response.retire({quad.id + static_cast<uint32_t>(k), quad_colour[k]}, static_cast<uint64_t>(quad_retire[k]));
  };
  // The probe quad path (rtl/unit_recurrence_probes.hpp): N probes per pixel of `quad`, one or two
  // level footprints each, timed footprint by footprint on register copies of the path's timing
  // (LentTiming), the functions batched per quad. Out of line, as cubic_quad.
  //
  // The lockstep footprint (software speed only; its plain twin is the through_cache and done
  // below, which it equals; TfuUnit.ProbeQuadPathEqualsThePlainBlocks). Footprint j > 0 of a
  // pixel, which completes no pixel, hits every line with one bank cycle and holds the filter no
  // cycle (4 taps on 4 lanes), whose predecessor j - 1 (the previous item of every channel below)
  // went through the input side in lockstep: pushed by address_gen at P - 1, taken by
  // kernel_select at P, accepted at P + 1 holding the port one cycle; and left the miss FIFO at
  // E' and the filter at E' + 1; whose line buffer has room at a glance (lines_in_flight_) and
  // whose miss FIFO has room at P + 2 (freed() <= P + 2). Then, with channels of depth D >= 2
  // (footprint, shaped, texels): each channel's pop cycles increase strictly (every rule takes
  // t >= its last + 1), so the item D back left at most D - 1 cycles before j - 1:
  //   address_gen   max(P - 1 + 1, footprint.room() <= P - (D - 1) + 1 <= P) = P
  //   kernel_select max(P + 1, P + 1, shaped.room() <= P + 1 - (D - 1) + 1 <= P + 1) = P + 1
  //   accept        visible max(P + 2, P + 2), port free P + 1 + 1, miss FIFO room: P + 2; no bank
  //                 stall (min(t, port free) = visible)
  //   lines         one bank cycle, no misses: in at P + 2 + 1 - 1 (no memory reads, no slots)
  //   exit          head e = max(P + 3, E' + 1), ready P + 2 < e, texels.room() <= E' + 1 - (D - 1)
  //                 + 1 <= e: e; no miss stall (min(ready, e) = ready < head), no back-pressure
  //   filter        max(e + 1, E' + 1 + 1) + 0 = e + 1, no output
  // so it goes through in lockstep too (the input side one cycle after its predecessor, the
  // output side at e and e + 1), no stall counted (the footprint counted), the same pops into the
  // same channels. (Behind a miss the output side lags the input side by the memory's latency:
  // the hits behind it leave the miss FIFO one a cycle, E' + 1.)
  //
  // A run of them (software speed only, the same plain twin and test): after a lockstep footprint
  // at P (last_push P, kernel_select's last P + 1, the cache's last accept P + 2 with the port held
  // one cycle as before, its line buffer unchanged, the filter's last its exit + 1), the next
  // footprint's t is P + 1, and kernel_select.last == t, the cache's last accept t + 1 with
  // port_cycles_ 1 and the line buffer's room, and the filter's in_step all hold already: of the
  // checks only the miss FIFO's room at t + 2 is left to ask, besides the footprint's own (not the
  // last, one bank cycle, no misses). The run goes on local copies of the four channels, the cache's
  // and the filter's timing (registers: the copy in `p` lives in memory across the quad), which go
  // back into `p` after it, with address_gen's last push and kernel_select's last, which nothing in
  // the run reads; its footprints count after it (a lockstep footprint stalls nowhere).
  const bool lockstep_depths = ucfg.channel_depth >= 2 && u.filter && u.filter->extra_clocks(4) == 0;
  const auto probe_quad = [&](int64_t quad_taken, AnisoLod lod) __attribute__((noinline)) {
    const int footprints = probes.address(quad, lod);
    const size_t slot = stat_slot(quad.req);
    LentTiming p = lend();           // its members named as PathTiming's
    CacheStage::StallCounts stalls;  // the quad's, in registers too
    uint64_t busy = 0;
    for (int k = 0; k < 4; ++k) {
      const int64_t pushed = u.lod_unit.timing.push(k == 0, quad_taken, ch.pixel);
      const int64_t pixel_taken = log.at(AddressGenTakesPixel, p.address_gen.take(pushed, ch.pixel));
      for (int j = 0; j < footprints; ++j) {
        const int64_t t = p.address_gen.last_push + 1;  // P, in lockstep
        if (lockstep_depths && j > 0 && j + 1 < footprints && probes.hits_in_one_cycle(k, j) &&
            p.kernel_select.last == t && p.cache.in_step(t + 2, p.miss_fifo) &&
            p.filter.in_step(p.cache.last_exit() + 2)) {
          ChannelTimes run_footprint = p.footprint.lend(), run_shaped = p.shaped_footprint.lend(),
                       run_miss_fifo = p.miss_fifo.lend(), run_texels = p.texels.lend();
          CacheStage::Timing run_cache = p.cache;
          FilterUnit::Timing run_filter = p.filter;
          CacheStage::StallCounts run_stalls;
          for (int64_t at = t;; ++at, ++j) {  // footprint j at P = at
            run_footprint.pop(log.at(KernelSelectTakesFootprint, at + 1));
            log.at(CacheAcceptsFootprint, at + 2);
            const int64_t e = log.at(CacheEmitsFootprint, run_cache.step(at + 2, run_shaped, run_miss_fifo, run_stalls));
            run_filter.step(log.at(FilterFinishesFootprint, e + 1), run_texels);
            if (!(j + 2 < footprints && probes.hits_in_one_cycle(k, j + 1) && run_miss_fifo.freed() <= at + 3)) {
              p.address_gen.last_push = at;
              p.kernel_select.last = at + 1;
              break;
            }
          }
          p.footprint.settle(run_footprint);
          p.shaped_footprint.settle(run_shaped);
          p.miss_fifo.settle(run_miss_fifo);
          p.texels.settle(run_texels);
          p.cache = run_cache;
          p.filter = run_filter;
          stalls.footprints += run_stalls.footprints;
          continue;
        }
        const int64_t exit = through_cache(p, j == 0, pixel_taken, false, stalls, [&](uint64_t now, int& bank_cycles) {
          return probes.admit(k, j, now, bank_cycles);
        });
        const bool emits = j + 1 == footprints;
        const int64_t done =
            log.at(FilterFinishesFootprint, p.filter.done(exit, 4, emits, p.texels, p.response_in, busy));
        if (emits)
          quad_retire[static_cast<size_t>(k)] =
              retire_at(p.response, u.filter_pipe, p.response_in, done, ResponseRetiresFilterPixel);
      }
    }
    settle_quad(p, slot, stalls, busy);
    for (size_t k = 0; k < 4; ++k)
      u.response.retire({quad.id + static_cast<uint32_t>(k), probes.colours()[k]},
                        static_cast<uint64_t>(quad_retire[k]));
  };
  // The LINEAR quad path (rtl/unit_recurrence_linear_quads.hpp): one or two level footprints per
  // pixel of `quad`, which lod_unit took at `quad_taken` (its levels from `lod`), timed footprint
  // by footprint on register copies of the path's timing (LentTiming) as probe_quad's, the
  // functions batched per quad. Out of line, as cubic_quad. (The level count is a template
  // constant, so that the loop over levels unrolls.)
  //
  // The lockstep footprint (software speed only; its plain twin is the through_cache, done and
  // retire_at below, which it equals; TfuUnit.LinearQuadPathEqualsThePlainBlocks). A level
  // footprint that hits every line with one bank cycle and holds the filter no cycle (4 taps on 4
  // lanes), with channels of depth D >= 2 and no filter pipeline registers. Let A be the earliest
  // cycle address_gen may push it (the pixel's first: the cycle address_gen took the pixel; the
  // level1 footprint: the level0 push + 1), E the cache's previous exit. Every channel's pop
  // cycles increase strictly (every rule takes t >= its last + 1), so a channel's room() is at
  // most its last pop - D + 2 <= its last pop. Then, when kernel_select's last cycle is at most A,
  // the cache takes a footprint at A + 2 without a stall (takes_at: the previous accepted before
  // A + 2, the port free by then, the miss FIFO and, at a glance, the line buffer room), the
  // filter's last cycle is at most E + 1 and, when the footprint completes its pixel, the
  // response's last retire at most E + 2:
  //   address_gen   max(A, footprint.room() <= kernel_select's last <= A) = A
  //   kernel_select max(A + 1, its last + 1 <= A + 1, shaped.room() <= last accept <= A + 1) = A + 1
  //   accept        visible max(A + 2, last accept + 1 <= A + 2), port free <= A + 2, miss FIFO
  //                 room <= A + 2, line buffer room: A + 2; no bank stall (min(t, port free) <=
  //                 visible)
  //   lines         one bank cycle, no misses: in at A + 2 (no memory reads, no slots)
  //   exit          head e = max(A + 3, E + 1), ready A + 2 < e, texels.room() <= filter's last
  //                 <= E + 1 <= e: e; no miss stall (min(ready, e) = ready < head), no
  //                 back-pressure
  //   filter        max(e + 1, its last + 1 <= E + 2 <= e + 1) + 0; completing the pixel also
  //                 max(e + 1, response.room() <= last retire <= E + 2 <= e + 1): e + 1
  //   response      (completing the pixel; no pipeline registers: passed at e + 1)
  //                 max(e + 2, last retire + 1 <= E + 3 <= e + 2) = e + 2
  // no stall counted (the footprint counted), no busy cycle, the same pops into the same
  // channels. (Unlike the probe path's lockstep it does not ask the previous footprint to have
  // moved in step: any earlier cycles leave these maxima unchanged.)
  const bool linear_lockstep = lockstep_depths && u.filter_pipe.timing.regs.empty();
  // The progress bar of a long run (as the clocked run's): requests retired, every 4096 quads.
  const std::function<uint64_t()> retired = [&u] { return static_cast<uint64_t>(u.response.retired()); };
  sim::ProgressBar bar(retired, n);
  const size_t last_pixel = trace.mode() == TraceMode::Quad ? 3 : 0;  // of a quad, after its first
  // The start of quad number `quads_in` at request `first`, every path's: the progress bar
  // (`last_retire`: the response's last retire cycle, of the unit's timing or of a lent copy), a
  // stream's complete chunk handed on (every request before `first` has retired), request_fifo ->
  // lod_unit (`lod_timing`: lod_unit's timing, or a lent copy); `first` moves past the quad. Returns
  // the cycle lod_unit takes it; its levels in `lod`.
  const auto begin_quad = [&](size_t& first, size_t quads_in, int64_t last_retire, AnisoLod& lod,
                              SequencerTiming& lod_timing) __attribute__((always_inline)) {
    if ((quads_in & 0xFFFu) == 0) bar.update(static_cast<uint64_t>(std::max<int64_t>(last_retire, 0)));
    if (sink != nullptr && first - u.drained >= kStreamChunk) u.drain_to(u.drained + kStreamChunk, sink);
    RequestFifo::form_quad(trace, first, quad);
    const int64_t quad_pushed = log.at(RequestFifoPushesQuad, u.request_fifo.timing.push(ch.quad));
    for (size_t k = 0; k < static_cast<size_t>(quad.npix); ++k)
      u.accept[first + k] = static_cast<uint64_t>(quad_pushed);
    first += static_cast<size_t>(quad.npix);
    const int64_t quad_taken = log.at(LodUnitTakesQuad, lod_timing.take(quad_pushed, ch.quad));
    lod = u.lod_unit.quad_lod(quad);
    return quad_taken;
  };
  // The LINEAR quad path's run (software speed only; its plain twin is the plain path at the end of
  // the loop below, each quad's footprints through the blocks' own timing, as TFU_PLAIN=1 runs
  // every quad; TfuUnit.LinearQuadPathEqualsThePlainBlocks compares the two on quads interleaved
  // with quads of the other paths and of other statistics slots, so on runs of every length):
  // `quad` (begun, lod_unit took it at `quad_taken`, its levels `lod`) and the LINEAR quads that
  // follow it, begun here (begin_quad) while they go this way, on one lent copy of the path's
  // timing (LentTiming) from the run's first quad to its last, where the probe quad path lends and
  // settles per quad. The same: between two quads only request_fifo, lod_unit, the chunk hand-over
  // (which reads the retired requests' records, no timing) and the progress bar run, and none of
  // them touches a lent block or channel; the bar reads the lent response's last retire. lod_unit's
  // timing and the pixel channel are lent too, lod_unit taking the run's quads on the copy
  // (begin_quad): nothing else reads them between its quads. The quads' stalls and busy cycles are
  // summed while their statistics slot stays the same (sums). Returns true when it stopped at a
  // quad it has begun that does not go this way (in `quad`, with `quad_taken` and `lod`), false at
  // the end of the requests. Out of line, as cubic_quad.
  const auto linear_run = [&](size_t& first, size_t& quads_in, int64_t& quad_taken, AnisoLod& lod)
                              __attribute__((noinline)) {
    LentTiming p = lend();           // its members named as PathTiming's
    CacheStage::StallCounts stalls;  // the slot's, in registers too
    uint64_t busy = 0;
    size_t slot = stat_slot(quad.req);
    // lod_unit's timing and the pixel channel lent too (begin_quad takes the quads with it).
    SequencerTiming lod_timing = u.lod_unit.timing;
    ChannelTimes pixel = ch.pixel.lend();
    const auto footprint_times = [&](auto level_count) __attribute__((always_inline)) {
      constexpr int kLevels = decltype(level_count)::value;
      for (int k = 0; k < 4; ++k) {
        const int64_t pushed = lod_timing.push(k == 0, quad_taken, pixel);
        const int64_t pixel_taken = log.at(AddressGenTakesPixel, p.address_gen.take(pushed, pixel));
        for (int level = 0; level < kLevels; ++level) {  // level0, then level1 when blending
          const bool emits = level + 1 == kLevels;
          const int64_t a = level == 0 ? pixel_taken : p.address_gen.last_push + 1;  // A
          if (linear_lockstep && linear.hits_in_one_cycle(k, level) && p.kernel_select.last <= a &&
              p.cache.takes_at(a + 2, p.miss_fifo) && p.filter.last() <= p.cache.last_exit() + 1 &&
              (!emits || p.response.last_retire() <= p.cache.last_exit() + 2)) {
            p.address_gen.last_push = a;
            p.footprint.pop(log.at(KernelSelectTakesFootprint, a + 1));
            p.kernel_select.last = a + 1;
            const int64_t e = log.at(
                CacheEmitsFootprint,
                p.cache.hit(log.at(CacheAcceptsFootprint, a + 2), p.shaped_footprint, p.miss_fifo, stalls));
            p.filter.step(log.at(FilterFinishesFootprint, e + 1), p.texels);
            if (emits) {
              p.response.step(log.at(ResponseRetiresFilterPixel, e + 2), p.response_in);
              quad_retire[static_cast<size_t>(k)] = e + 2;
            }
            continue;
          }
          const int64_t exit = through_cache(p, level == 0, pixel_taken, false, stalls,
                                             [&](uint64_t now, int& bank_cycles) __attribute__((always_inline)) {
                                               return linear.admit(k, level, now, bank_cycles);
                                             });
          const int64_t done =
              log.at(FilterFinishesFootprint, p.filter.done(exit, 4, emits, p.texels, p.response_in, busy));
          if (emits)
            quad_retire[static_cast<size_t>(k)] =
                retire_at(p.response, u.filter_pipe, p.response_in, done, ResponseRetiresFilterPixel);
        }
      }
    };
    for (;;) {
      const size_t quad_slot = stat_slot(quad.req);
      if (quad_slot != slot) {
        u.cache_stage.add_stalls(slot, stalls);
        u.filter->busy_cycles(slot) += busy;
        stalls = {};
        busy = 0;
        slot = quad_slot;
      }
      if (linear.address(quad, lod) == 1) {
        footprint_times(std::integral_constant<int, 1>{});
      } else {
        footprint_times(std::integral_constant<int, 2>{});
      }
      linear.filter(quad_colour);
      u.response.retire_quad(quad.id, quad_colour, quad_retire);
      // The next quad, begun as the recurrences' loop begins it (`quads_in`: the quads begun).
      const bool more = trace.has(first + last_pixel);
      if (more) quad_taken = begin_quad(first, quads_in++, p.response.last_retire(), lod, lod_timing);
      if (!more || !linear.takes(quad)) {
        settle_quad(p, slot, stalls, busy);
        u.lod_unit.timing = lod_timing;
        ch.pixel.settle(pixel);
        return more;
      }
    }
  };
  // The loop over the quads (`quads_in`: those begun). `begun`: the quad in `quad` was begun by the
  // LINEAR quad path's run.
  bool begun = false;
  int64_t quad_taken = 0;
  AnisoLod lod{};
  for (size_t first = 0, quads_in = 0; begun || trace.has(first + last_pixel);) {
    if (!begun) quad_taken = begin_quad(first, quads_in++, u.response.timing.last_retire(), lod, u.lod_unit.timing);
    begun = false;
    // lod_unit -> address_gen: the cycle address_gen takes pixel k.
    const auto pixel_taken_at = [&](int k) {
      const int64_t pushed = u.lod_unit.timing.push(k == 0, quad_taken, ch.pixel);
      return log.at(AddressGenTakesPixel, u.address_gen.timing.take(pushed, ch.pixel));
    };
    if (linear.takes(quad)) {
      begun = linear_run(first, quads_in, quad_taken, lod);
      continue;
    }
    if (probes.takes(quad)) {
      probe_quad(quad_taken, lod);
      continue;
    }
    if (cubic.takes(quad)) {
      cubic_quad(quad_taken, lod);
      continue;
    }
    for (int k = 0; k < quad.npix; ++k) {
      const int64_t pixel_taken = pixel_taken_at(k);
      u.address_gen.begin(LodUnit::pixel(quad, lod, k));
      for (bool first_footprint = true, last = false; !last; first_footprint = false) {
        last = u.address_gen.issue(f);
        u.kernel_select.shape(f);
        const bool edge = f.tag.base == BaseFilter::EdgePreserving;
        const int64_t exit = through_cache(
            unit_path, first_footprint, pixel_taken, edge, u.cache_stage.counters(stat_slot(f.tag.req)),
            [&](uint64_t now, int& bank_cycles) { return u.cache_stage.admit_footprint(f, now, bank_cycles); });
        u.cache_stage.read_out_footprint(f, texel_words);
        edge ? through_edge_stages(exit) : through_filter(exit);
      }
    }
  }
  out.cycles = static_cast<uint64_t>(u.response.timing.last_retire() + 1);
  bar.finish(out.cycles);
  u.drain_to(u.response.retired(), sink);
  if (sink == nullptr) u.take_outputs(out);
  detail::derive_stats(frame, ucfg, u, out);
  return out;
}

}  // namespace

UnitOutput run_unit_recurrence(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, bool quad_paths,
                               UnitEvents* events) {
  detail::check_inputs(frame, trace, ucfg);
  RequestStream whole(trace);
  if (events == nullptr) return recurrences(frame, whole, ucfg, quad_paths, EventLog<false>{nullptr}, MemoryBinding{});
  for (std::vector<int64_t>& row : *events) row.clear();
  return recurrences(frame, whole, ucfg, quad_paths, EventLog<true>{events}, MemoryBinding{});
}

UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, UnitEngine engine, const VcdOptions& vcd,
                    MemoryBinding shared) {
  if (engine == UnitEngine::Recurrence && vcd.out == nullptr) {
    detail::check_inputs(frame, trace, ucfg);
    RequestStream whole(trace);
    return recurrences(frame, whole, ucfg, true, EventLog<false>{nullptr}, shared);
  }
  return run_unit(frame, trace, ucfg, vcd, ClockedOptions{}, shared);
}

UnitOutput run_unit_stream(const Frame& frame, RequestStream& stream, const UnitConfig& ucfg, const UnitChunkSink& sink) {
  detail::check_config(frame, ucfg);
  if (stream.whole()) throw CheckFailed("run_unit_stream needs a queued stream (a whole trace: run_unit)");
  try {
    return recurrences(frame, stream, ucfg, true, EventLog<false>{nullptr}, MemoryBinding{}, &sink);
  } catch (...) {
    stream.abandon();  // the producer must not wait for a unit that has stopped
    throw;
  }
}

}  // namespace tfu::rtl
