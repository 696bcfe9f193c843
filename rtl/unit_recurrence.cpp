// The unit run by timing recurrences (`tfu sim --engine recurrence`): the same blocks and
// datapaths as the clocked run of rtl/tfu_unit.cpp, the same results, cycles and statistics,
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
//   response      retires pixel ids in order, one per cycle, from either datapath.
// The run ends the cycle after the last retire.
#include <algorithm>
#include <bit>
#include <memory>

#include <fmt/format.h>

#include "cmodel/error.hpp"

#include "rtl/tfu_unit.hpp"
#include "rtl/unit_wiring.hpp"

namespace tfu::rtl {
namespace {

// Pop cycles of the items of one channel (or any per-item time), kept for the last `keep`
// items: at(i) for i < 0 is -1, so that "after item i - depth left" (at(i - depth) + 1) is cycle 0
// when no such item exists.
class Times {
 public:
  explicit Times(size_t keep) : v_(std::bit_ceil(keep + 1), -1), mask_(v_.size() - 1) {}
  int64_t at(int64_t i) const { return i < 0 ? -1 : v_[static_cast<size_t>(i) & mask_]; }
  void set(int64_t i, int64_t t) { v_[static_cast<size_t>(i) & mask_] = t; }

 private:
  std::vector<int64_t> v_;
  size_t mask_;
};

// One channel between two blocks: its items so far and their pop cycles.
struct Link {
  explicit Link(size_t keep) : pop(keep) {}
  int64_t count = 0;
  Times pop;
  // The earliest cycle item `count` may be pushed: item count - depth has left.
  int64_t room(int64_t depth) const { return pop.at(count - depth) + 1; }
  // The cycle the previous item left (-1: none).
  int64_t last_pop() const { return pop.at(count - 1); }
};

}  // namespace

const char* unit_engine_name(UnitEngine e) { return e == UnitEngine::Clocked ? "clocked" : "recurrence"; }

UnitEngine unit_engine_from_name(const std::string& name) {
  if (name == "recurrence") return UnitEngine::Recurrence;
  if (name == "clocked") return UnitEngine::Clocked;
  throw InputError(fmt::format("'{}' is not an engine: recurrence or clocked", name.size() > 40 ? name.substr(0, 40) + "..." : name));
}

UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, UnitEngine engine, const VcdOptions& vcd) {
  return engine == UnitEngine::Recurrence && vcd.out == nullptr ? run_unit_recurrence(frame, trace, ucfg)
                                                                : run_unit(frame, trace, ucfg, vcd);
}

UnitOutput run_unit_recurrence(const Frame& frame, const Trace& trace, const UnitConfig& ucfg) {
  detail::check_inputs(frame, trace, ucfg);
  const size_t n = trace.requests.size();
  UnitOutput out;
  out.pixels.resize(n);
  out.response_cycle.resize(n);
  auto unit = std::make_unique<detail::Unit>(frame, trace, ucfg, out);
  detail::Unit& u = *unit;
  const auto depth = static_cast<int64_t>(ucfg.channel_depth);
  const auto fifo_depth = static_cast<int64_t>(ucfg.miss_fifo_depth);
  const size_t keep = static_cast<size_t>(std::max(depth, fifo_depth)) + 1;
  Link quads(keep), pixels(keep), footprints(keep), shaped(keep), texels(keep), edge_texels(keep), s1(keep), s2(keep),
      responses(keep), edge_responses(keep);
  Times cache_exit(keep);  // the cycle each footprint left the miss FIFO
  int64_t quad_push = -1, last_pixel_push = -1, last_footprint_push = -1;
  int64_t prev_accept = -1, prev_port_cycles = 0, last_exit = -1, last_retire = -1;
  uint64_t stall_miss = 0, stall_bank = 0, stall_back = 0, lane_busy = 0;
  const auto span = [](int64_t from, int64_t to) { return static_cast<uint64_t>(std::max<int64_t>(0, to - from)); };
  // The response of pixel r.id, pushed into `link` at `pushed`: retired in id order.
  const auto retire = [&](Link& link, const Response& r, int64_t pushed) {
    const int64_t t = std::max(pushed + 1, last_retire + 1);
    link.pop.set(link.count++, t);
    u.sink.retire(r, static_cast<uint64_t>(t));
    last_retire = t;
  };
  QuadReq quad;
  FootprintReq f;
  FilterReq texel_words;
  for (size_t first = 0; first < n;) {
    // request_fifo -> lod_unit
    RequestFifo::form_quad(trace, first, quad);
    quad_push = std::max(quad_push + 1, quads.room(depth));
    for (size_t k = 0; k < static_cast<size_t>(quad.npix); ++k) u.accept[first + k] = static_cast<uint64_t>(quad_push);
    const int64_t quad_taken = std::max(quad_push + 1, last_pixel_push + 1);
    quads.pop.set(quads.count++, quad_taken);
    const AnisoLod lod = u.lod.quad_lod(quad);
    for (int k = 0; k < quad.npix; ++k) {
      // lod_unit -> address_gen
      last_pixel_push = std::max(k == 0 ? quad_taken : last_pixel_push + 1, pixels.room(depth));
      const int64_t pixel_taken = std::max(last_pixel_push + 1, last_footprint_push + 1);
      pixels.pop.set(pixels.count++, pixel_taken);
      u.addr.begin(LodUnit::pixel(quad, lod, k));
      for (bool first_footprint = true, last = false; !last; first_footprint = false) {
        // address_gen -> kernel_select -> texel_cache
        last = u.addr.issue(f);
        last_footprint_push = std::max(first_footprint ? pixel_taken : last_footprint_push + 1, footprints.room(depth));
        const int64_t shaped_push = std::max({last_footprint_push + 1, footprints.last_pop() + 1, shaped.room(depth)});
        footprints.pop.set(footprints.count++, shaped_push);
        u.shape.shape(f);
        // texel_cache: the input side
        const int64_t visible = std::max(shaped_push + 1, shaped.last_pop() + 1);
        const int64_t port_free = prev_accept + prev_port_cycles;
        const int64_t accept = std::max({visible, port_free, cache_exit.at(shaped.count - fifo_depth)});
        stall_bank += span(visible, std::min(accept, port_free));
        int bank_cycles = 1;
        const auto ready = static_cast<int64_t>(u.cst.admit_footprint(f, static_cast<uint64_t>(accept), bank_cycles));
        prev_accept = accept;
        prev_port_cycles = bank_cycles;
        // texel_cache: the output side
        const bool edge = f.tag.base == BaseFilter::EdgePreserving;
        Link& words = edge ? edge_texels : texels;
        const int64_t head = std::max(accept + 1, last_exit + 1);
        const int64_t exit = std::max({head, ready, words.room(depth)});
        stall_miss += span(head, std::min(ready, exit));
        stall_back += span(std::max(head, ready), exit);
        cache_exit.set(shaped.count, exit);
        shaped.pop.set(shaped.count++, accept);
        last_exit = exit;
        u.cst.read_out_footprint(f, texel_words);
        const bool emits = texel_words.tag.emits();
        Response r;
        if (!edge) {
          // filter -> response
          const int64_t filter_head = std::max(exit + 1, texels.last_pop() + 1);
          const int lanes = u.filter->extra_clocks(texel_words.ntaps);
          lane_busy += static_cast<uint64_t>(lanes);
          const int64_t done = std::max(filter_head + lanes, emits ? responses.room(depth) : 0);
          texels.pop.set(texels.count++, done);
          if (u.filter->filter(texel_words, r)) retire(responses, r, done);
        } else {
          // edge_median -> edge_direction -> edge_merge -> response
          const int64_t t1 = std::max({exit + 1, edge_texels.last_pop() + 1, s1.room(depth)});
          edge_texels.pop.set(edge_texels.count++, t1);
          EdgeS1 a;
          EdgeMedian::stage(texel_words, a);
          const int64_t t2 = std::max({t1 + 1, s1.last_pop() + 1, s2.room(depth)});
          s1.pop.set(s1.count++, t2);
          EdgeS2 b;
          u.e2->stage(a, b);
          const int64_t t3 = std::max({t2 + 1, s2.last_pop() + 1, emits ? edge_responses.room(depth) : 0});
          s2.pop.set(s2.count++, t3);
          if (u.e3->merge(b, r)) retire(edge_responses, r, t3);
        }
      }
    }
    first += static_cast<size_t>(quad.npix);
  }
  u.cst.add_stalls(stall_miss, stall_bank, stall_back);
  if (u.filter) u.filter->add_busy_cycles(lane_busy);
  out.cycles = static_cast<uint64_t>(last_retire + 1);
  out.edge_shapes = std::move(u.cst.shapes);
  detail::derive_stats(frame, trace, ucfg, u, out);
  return out;
}

}  // namespace tfu::rtl
