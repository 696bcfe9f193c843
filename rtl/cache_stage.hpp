// texel_cache stage: looks up one footprint per cycle in the texel cache's tags (rtl/texel_cache.hpp),
// resolves the cache-aware kernel shape by a tag probe, sends the missing lines to the memory model
// (rtl/memory_model.hpp) at once, and queues the footprint in an in-order miss FIFO (the prefetching
// texture cache of Igehy, Eldridge & Proudfoot 1998): several misses are outstanding, and hits
// behind a miss wait in order. The FIFO head leaves, with its texel words, when its lines have
// arrived. The banks serve one footprint per cycle; a bank conflict holds the tag port for the
// extra cycles. The texel words are read from the texel memory at their addresses (the descriptor's
// level address, pitch and layout) when the footprint leaves.
//
// The line buffer (the paper's reorder buffer): a missed line's data waits in one of
// `line_buffer_depth` slots from its request until the footprint that missed it leaves the FIFO
// head and writes it into the cache. The cache's data thus follows its tags in FIFO order, so a
// line is never overwritten while a queued footprint still needs it (the tags run ahead of the
// data by the FIFO). The tag stage does not know a footprint's misses before its lookup, so it
// accepts a footprint only while kMaxFootprintLines slots are free (after this cycle's exit); the
// footprint then holds one slot per missed line. The memory requests wait in order at the memory
// interface (the request queue: at most line_buffer_depth lines, each holding a slot).
//
// Latency tolerance (Little's law; docs/memory-system.md, "Latency tolerance"): a footprint stays
// in the miss FIFO about W = latency + ceil(line_bytes / bytes_per_cycle) + 2 cycles when the
// memory keeps up, so a unit that takes F footprints per cycle at zero latency keeps that rate only
// with miss_fifo_depth >= F W; a missed line holds its slot about as long, and misses come in
// bursts at the memory's rate, so the line buffer needs the lines the memory delivers in W cycles
// (W bytes_per_cycle / line_bytes) + kMaxFootprintLines slots. latency_tolerant_depths()
// (rtl/unit_config.hpp) computes both.
//
// Ports:
//   in  footprint  FootprintReq (texture, level, tap grid, shape, optional arms)   valid/ready
//   out filter     FilterReq of NEAREST / LINEAR / CUBIC footprints: up to 16 texel words [31:0]
//   out edge       FilterReq of EDGE_PRESERVING footprints: 12 texel words, shape[11:0]
//   mem            line read requests (MemoryModel::read), bytes counted there per texture
//   in  registers  texture descriptors (addresses, layout), sampler descriptors (border word)
// Border taps (clamp-to-border outside the texture) take the border word (zero for B-spline
// coefficients) and no cache access.
//
// Block-compressed textures (TextureDescriptor::compressed): the footprint comes with its grid in
// blocks and each tap's texel in its block (FootprintReq::blocks, formed by the address generator:
// rtl/address_gen_blocks.hpp); the stage divides nothing. The tags of compressed lines take the
// block grid, the decoders' jobs count its distinct (block column, block row) pairs, and the texel
// words are the decoder's, decode_block (cmodel/block_formats.hpp) of the blocks read from the
// texel memory at their descriptor addresses (TextureDescriptor::block_address of the block
// coordinates; each distinct block of a footprint decoded once), the texel in the block as the
// address generator gives it; never the golden model's decoded levels, so that the golden compare
// checks addressing and decoding. The decoders
// (DecoderConfig: `units` decoders of `texels_per_clock` texels per clock, `latency` clocks) sit
// where TexelCacheConfig::holds puts them:
//   compressed  after the cache: a footprint's texels (its used taps) are decoded once its lines
//               are in, ceil(taps / (texels_per_clock units)) busy clocks;
//   decoded     on fill: each missed line's tile of decoded texels (line_bytes / 4, clipped to the
//               level) is decoded once the blocks that cover it (fetched from memory, their bytes
//               exactly) are in, ceil(texels / (texels_per_clock units)) busy clocks; hits decode
//               nothing.
// The decoders serve one job at a time in acceptance order: a job whose input is in at `in` starts
// at max(in, the decoders' previous job's end), is busy `busy` clocks, and its texels are ready
// busy - 1 + latency clocks after it starts (latency 0: out in the last busy clock). The
// footprint's `ready` cycle (its lines in, as for every texture) is the latest of its jobs'.
// Statistics per texture: blocks decoded (a footprint's distinct blocks; a fill's covering
// blocks), decoder busy clocks, and decoder stall clocks (a job waiting for busy decoders).
#pragma once

#include <algorithm>
#include <array>
#include <deque>
#include <memory>
#include <vector>

#include "cmodel/descriptors.hpp"
#include "cmodel/texture_memory.hpp"
#include "rtl/address_gen_blocks.hpp"
#include "rtl/memory_model.hpp"
#include "rtl/texel_cache.hpp"
#include "rtl/request_stream.hpp"
#include "rtl/timing.hpp"
#include "rtl/unit_ports.hpp"
#include "rtl/kernel/kernel.hpp"

namespace tfu::rtl {

// Texel read-out of an n x n grid whose taps are all inside the texture, row-major.
template <int n>
[[gnu::always_inline]] inline void read_square_taps(const TapGrid& g, const LevelReadout& level, Rgba8* out) {
  size_t col[n];
  for (size_t i = 0; i < n; ++i) col[i] = level.column(g.x[i]);
  for (size_t j = 0; j < n; ++j) {
    const size_t row = level.row(g.y[j]);
    for (size_t i = 0; i < n; ++i) out[n * j + i] = level.at(col[i] + row);
  }
}

class CacheStage : public sim::Module {
 public:
  CacheStage(sim::Simulator& s, sim::Channel<FootprintReq>& i, sim::Channel<FilterReq>& filter,
             sim::Channel<FilterReq>& edge, const Registers& regs, const TextureMemory& memory, TexelCache& c,
             MemoryModel& m, int miss_fifo_depth, int line_buffer_depth, const DecoderConfig& decoder = {});
  void evaluate() override;
  std::string state() const override;
  void publish(sim::Stats& st) const;
  // The counters of one statistics slot (stat_slot()), lines and memory reads included.
  void publish_slot(sim::Stats& st, size_t slot) const;
  uint64_t wake_cycle(uint64_t now) const override;
  void skip_cycles(uint64_t n) override;
  bool busy() const { return !fifo_.empty(); }
  uint32_t current_id() const { return fifo_.empty() ? 0 : fifo_.front().f.tag.id; }
  // Waveform probes (no effect on timing), recorded only while probes(true) (a waveform is being
  // written; 0 before): the request id of the footprint last accepted, the line address (byte
  // address / line bytes, 40 - log2(line) bits) of its first in-texture tap, of the last line sent
  // to memory, and how many lines that footprint missed.
  void probes(bool on) { probes_ = on; }
  uint32_t accepted_id() const { return accepted_id_; }
  uint64_t accepted_line() const { return accepted_line_; }
  uint64_t last_miss_line() const { return last_miss_line_; }
  int last_misses() const { return last_misses_; }
  // The footprint last accepted, tap by tap in FilterReq order (grid row-major, the cross in C
  // order): the byte address of tap k (0..15) in the texel memory, 0 where the tap reads no texel
  // (k >= its tap count, a border tap, a cross texel outside the edge shape; 0 is never a texel
  // address).
  uint64_t accepted_tap_address(int k) const;
  int accepted_taps() const { return probes_ ? accepted_.ntaps() : 0; }
  const FootprintReq& accepted() const { return accepted_; }  // its texture, stage and level
  // Kernel shape chosen per pixel, probe and level, for the golden compare of cache-aware shapes:
  // recorded when some sampler is EDGE_PRESERVING with the cache-aware policy (records_shapes();
  // the other policies' shapes follow from the descriptors), into `shapes` sized by the caller to
  // one entry per request (or a window of them, zeroed for reuse: rtl/request_stream.hpp) before
  // the run.
  bool records_shapes() const { return record_shapes_; }
  RequestRing<ProbeShapes> shapes;
  // The block's counters per statistics slot (a texture descriptor and material stage,
  // stat_slot()): line hits and misses per level, memory reads, stalls (counted for the footprint
  // that waits: the one at the input for the bank port, the miss-FIFO head for lines and room),
  // kernel shapes and the decoders' work. The totals are their sums (the lines' also counted by
  // the cache's tag unit).
  struct SlotCounters {
    std::array<uint64_t, kMaxLevels> level_hits{}, level_misses{};
    uint64_t sector_hits = 0, sector_lookups = 0;  // 32-byte sectors (rtl/texel_cache.hpp)
    uint64_t memory_bytes = 0, memory_requests = 0;
    uint64_t footprints = 0;  // looked up (accepted into the miss FIFO)
    uint64_t stall_miss = 0, stall_bank = 0, stall_back = 0, stall_line_buffer = 0;
    std::array<uint64_t, 3> shapes{};  // cross, T, L
    uint64_t decoded_blocks = 0, decoder_busy = 0, decoder_stall = 0;
  };
  const std::vector<SlotCounters>& slot_counters() const { return slots_; }
  SlotCounters& counters(size_t slot) { return slots_[slot]; }
  // The stall counters Timing keeps for a batch of footprints of one slot (register copies, as the
  // batch's timing: rtl/unit_recurrence.cpp), and their sum into the slot's.
  struct StallCounts {
    uint64_t footprints = 0, stall_miss = 0, stall_bank = 0, stall_back = 0, stall_line_buffer = 0;
  };
  void add_stalls(size_t slot, const StallCounts& s) {
    SlotCounters& c = slots_[slot];
    c.footprints += s.footprints;
    c.stall_miss += s.stall_miss;
    c.stall_bank += s.stall_bank;
    c.stall_back += s.stall_back;
    c.stall_line_buffer += s.stall_line_buffer;
  }
  // The line buffer held some footprint at the tag stage (stall_line_buffer is published then only).
  bool stalled_on_line_buffer() const {
    return std::any_of(slots_.begin(), slots_.end(), [](const SlotCounters& c) { return c.stall_line_buffer != 0; });
  }
  // The block without its miss FIFO and handshakes (the timing recurrences of
  // rtl/unit_recurrence.cpp drive these; evaluate() uses the same code): admit_footprint looks a
  // footprint up at cycle `now` (cache-aware arms, tags, memory reads, statistics) and returns the
  // cycle its lines are all in, with the cycles it holds the tag/bank port; read_out_footprint
  // forms its texel words.
  uint64_t admit_footprint(FootprintReq& f, uint64_t now, int& bank_cycles);
  void read_out_footprint(const FootprintReq& f, FilterReq& out) const;
  // admit_footprint's tail, once the taps to look up are known (`lookup`: the grid, its used cells
  // narrowed by an edge shape): the tags (hits, misses, LRU, bank cycles in `r`), the memory reads
  // of the missing lines, the per-stage counters; returns the cycle the lines are all in. Also
  // called by the recurrences' LINEAR quad path (rtl/unit_recurrence_linear_quads.cpp).
  [[gnu::always_inline]] uint64_t admit_lines(int texture, int stage, int level, const TapGrid& lookup, uint64_t now,
                                              int& bank_cycles, FootprintResult& r) {
    r = cache_.access(texture, level, lookup);
    return lines_in(texture, stage, level, r, now, bank_cycles);
  }
  // admit_lines of a 2 x 2 footprint whose four taps are all used (the recurrences' LINEAR quad
  // path): the tags through TexelCache::access_square, inline.
  [[gnu::always_inline]] uint64_t admit_square(int texture, int stage, int level, const TapGrid& lookup, uint64_t now,
                                               int& bank_cycles) {
    const FootprintResult r = cache_.access_square(texture, level, lookup);
    return lines_in(texture, stage, level, r, now, bank_cycles);
  }
  // admit_lines of a full 4 x 4 grid (the recurrences' CUBIC quad path,
  // rtl/unit_recurrence_cubic_quads.cpp): the tags through TexelCache::access_square4.
  [[gnu::always_inline]] uint64_t admit_square4(int texture, int stage, int level, const TapGrid& lookup, uint64_t now,
                                                int& bank_cycles) {
    return lines_in(texture, stage, level, cache_.access_square4(texture, level, lookup), now, bank_cycles);
  }
  // admit_lines after the tags: the counters of the lookup `r`, the bank cycles, the memory reads
  // of its missing lines; the cycle the lines are all in.
  [[gnu::always_inline]] uint64_t lines_in(int texture, int stage, int level, const FootprintResult& r, uint64_t now,
                                           int& bank_cycles) {
    count_lines(stat_slot(texture, stage), level, r);
    return lines_ready(texture, r.cycles, r.misses, r.missed_lines.data(), now, bank_cycles);
  }
  // lines_in's two parts: the counters of the lookup `r` in statistics slot `slot` (sums, which the
  // probe quad path adds a quad's lookups at a time); and, at cycle `now`, the bank cycles of a
  // lookup of `cycles` (at least 1), the memory reads of its `misses` missing lines and the
  // line-buffer slots they take; the cycle its lines are all in.
  template <class Counts>  // FootprintResult, LineCounts
  [[gnu::always_inline]] void count_lines(size_t slot, int level, const Counts& r) {
    SlotCounters& c = slots_[slot];
    c.level_hits[static_cast<size_t>(level)] += static_cast<uint64_t>(r.hits);
    c.level_misses[static_cast<size_t>(level)] += static_cast<uint64_t>(r.misses);
    c.sector_hits += static_cast<uint64_t>(r.sector_hits);
    c.sector_lookups += static_cast<uint64_t>(r.sector_lookups);
    c.memory_requests += static_cast<uint64_t>(r.misses);
    c.memory_bytes += static_cast<uint64_t>(r.misses) * static_cast<uint64_t>(cache_.config().line_bytes);
  }
  [[gnu::always_inline]] uint64_t lines_ready(int texture, int cycles, int misses, const uint64_t* missed_lines,
                                              uint64_t now, int& bank_cycles) {
    admitted_lines_ = misses;  // the line buffer's slots this footprint takes (accept)
    bank_cycles = cycles > 1 ? cycles : 1;
    uint64_t ready = now + static_cast<uint64_t>(bank_cycles) - 1;
    for (int m = 0; m < misses; ++m) {
      const int line_bytes = cache_.config().line_bytes;
      const uint64_t in = mem_.read(now, line_bytes, texture, missed_lines[m] * static_cast<uint64_t>(line_bytes));
      ready = in > ready ? in : ready;
    }
    return ready;
  }
  // The texel cache's tags (the recurrences' quad paths: rtl/unit_recurrence_probes.hpp).
  TexelCache& tags() { return cache_; }
  // The recurrences' LINEAR quad path on a block-compressed texture (software speed only,
  // rtl/cache_stage_block_squares.cpp, which names the plain twins and the equality test): a 2 x 2
  // footprint whose taps are all inside the level, its grid in texels (`texels`) and in blocks
  // (`s`, formed by the address generator's block_grid, rtl/address_gen_blocks.hpp, as for every
  // footprint). admit_footprint of such a footprint: admit_blocks with its taps known to be the
  // four. Blocks in the cache: the tags of its blocks' lines, then one decoder job of its four taps
  // and of its distinct blocks, the product of its distinct block columns and rows (admit_blocks
  // counts the distinct (column, row) pairs of its taps). Decoded on fill: admit_blocks itself (its
  // tags take the texel grid, and only its misses do more). Inline, as admit_lines: once per
  // footprint.
  [[gnu::always_inline]] uint64_t admit_block_square(int texture, int stage, int level, const TapGrid& texels,
                                                     const TapBlocks& s, uint64_t now, int& bank_cycles) {
    FootprintResult r;
    if (cache_.config().holds == CacheHolds::Decoded) [[unlikely]]
      return admit_blocks(texture, stage, level, texels, now, bank_cycles, r);
    r = cache_.access(texture, level, s.blocks);
    const uint64_t in = lines_in(texture, stage, level, r, now, bank_cycles);
    const int blocks = (s.blocks.x[0] != s.blocks.x[1] ? 2 : 1) * (s.blocks.y[0] != s.blocks.y[1] ? 2 : 1);
    return decode(in, 4, blocks, stat_slot(texture, stage));
  }
  // read_out_footprint of four such footprints on one level (a quad's pixels): taps[k] the four
  // texels of footprint k in read_out's order.
  void read_block_squares(int texture, int level, const std::array<TapBlocks, 4>& s,
                          std::array<std::array<Rgba8, 4>, 4>& taps) const;
  // Some texture is compressed (the decoders' counters; zero elsewhere).
  bool any_compressed() const { return any_compressed_; }
  // The read-out registers of a texture's level (its address, pitch, layout and format).
  const LevelReadout& level_readout(int texture, int level) const {
    return readout_[first_readout_[static_cast<size_t>(texture)] + static_cast<size_t>(level)];
  }

  // The block's timing for the recurrence engine (rtl/timing.hpp), beside evaluate(), which it
  // restates item by item; the two change together. evaluate() runs its output side before its
  // input side in a cycle:
  //   input side   a footprint pushed into the shaped channel at `pushed` is accepted (looked up)
  //                in the first cycle in which it is visible (pushed + 1, and the previous one
  //                accepted a cycle earlier), the tag port is free (the previous footprint's
  //                accept cycle + its bank cycles), the miss FIFO has a slot (freed by this
  //                cycle's exit at the latest) and the line buffer kMaxFootprintLines free slots
  //                (the same); the cycles it waits for the port count as stall_bank_conflict, those
  //                it then waits for the line buffer (the FIFO having room) as stall_line_buffer;
  //   output side  the miss-FIFO head leaves, pushing its texel words, in the first cycle after its
  //                accept and the previous head's exit in which its lines are in (`ready`) and its
  //                output channel has room; it counts its cycles waiting for the lines as
  //                stall_cache_miss (for a compressed texture, `ready` includes its decoding:
  //                the decoder timing above, computed by admit_footprint for both engines), then
  //                those waiting for room as stall_backpressure.
  // Both count into the block's own stall counters (published by publish()).
  class Timing {
   public:
    explicit Timing(CacheStage& b) : b_(&b) {}
    // The cycle the footprint pushed at `pushed` leaves the shaped channel `in` into the miss FIFO;
    // its stalls count into `c`: its statistics slot's counters (counters(slot)), or a batch's
    // StallCounts, added to the slot's after the batch (sums).
    template <class Stalls>
    [[gnu::always_inline]] int64_t accept(int64_t pushed, ChannelTimes& in, const ChannelTimes& miss_fifo, Stalls& c) {
      const int64_t visible = std::max(pushed + 1, last_accept_ + 1);
      const int64_t port_free = last_accept_ + port_cycles_;
      const int64_t fifo_room = std::max({visible, port_free, miss_fifo.freed()});
      // The line buffer: the lines of the footprints still queued at `t` (they leave in order, and
      // free their slots in the cycle they leave). lines_in_flight_ may still count footprints that
      // have left (their slots are given back only when the count is short of room, as `t` never
      // decreases, the same result): when it leaves room, the exact count does too.
      int64_t t = fifo_room;
      if (lines_in_flight_ + kMaxFootprintLines > b_->line_buffer_depth_) [[unlikely]] {
        for (;;) {
          while (!b_->timing_in_flight_.empty() && b_->timing_in_flight_.front().exit <= t) {
            lines_in_flight_ -= b_->timing_in_flight_.front().lines;
            b_->timing_in_flight_.pop_front();
          }
          if (lines_in_flight_ + kMaxFootprintLines <= b_->line_buffer_depth_) break;
          t = b_->timing_in_flight_.front().exit;
        }
        c.stall_line_buffer += cycles_between(fifo_room, t);
      }
      ++c.footprints;
      c.stall_bank += cycles_between(visible, std::min(t, port_free));
      in.pop(t);
      last_accept_ = t;
      return t;
    }
    // The cycle the footprint accepted at `accepted`, holding the tag port `bank_cycles` cycles,
    // with its lines in at `ready`, leaves the miss FIFO into `out`; its stalls count into `c`, as
    // accept's.
    template <class Stalls>
    [[gnu::always_inline]] int64_t exit(int64_t accepted, int bank_cycles, int64_t ready, ChannelTimes& miss_fifo,
                                        const ChannelTimes& out, Stalls& c) {
      port_cycles_ = bank_cycles;
      const int64_t head = std::max(accepted + 1, last_exit_ + 1);
      const int64_t t = std::max({head, ready, out.room()});
      c.stall_miss += cycles_between(head, std::min(ready, t));
      c.stall_back += cycles_between(std::max(head, ready), t);
      miss_fifo.pop(t);
      last_exit_ = t;
      if (b_->admitted_lines_ > 0) {
        b_->timing_in_flight_.push_back({t, b_->admitted_lines_});
        lines_in_flight_ += b_->admitted_lines_;
      }
      return t;
    }

    // The probe quad path's lockstep footprint (software speed only; rtl/unit_recurrence.cpp,
    // probe_quad, derives it from accept and exit above, which it must equal): in_step(t) tells
    // that the previous footprint was accepted at t - 1 holding the port one cycle, that the line
    // buffer has room without a look at the queue and that the miss FIFO has room at t; step(t) is
    // accept and exit of a footprint pushed at t - 1 with one bank cycle and no misses, whose
    // output channel has room: accepted at t, out the cycle after it or after the previous
    // footprint's exit (the later), no stalls; returns its exit cycle.
    bool in_step(int64_t t, const ChannelTimes& miss_fifo) const {
      return last_accept_ == t - 1 && port_cycles_ == 1 &&
             lines_in_flight_ + kMaxFootprintLines <= b_->line_buffer_depth_ && miss_fifo.freed() <= t;
    }
    int64_t last_exit() const { return last_exit_; }
    // The LINEAR quad path's lockstep footprint (software speed only; rtl/unit_recurrence.cpp,
    // linear_run, derives it from accept and exit above, which it must equal): takes_at(t) tells
    // that a footprint visible at t is accepted at t without a stall (the previous one accepted
    // before t, the tag port free at t, the miss FIFO room at t, the line buffer room without a
    // look at the queue); hit(t) is accept and exit of such a footprint with one bank cycle and no
    // misses whose output channel has room at its head: step(t), the port held one cycle.
    bool takes_at(int64_t t, const ChannelTimes& miss_fifo) const {
      return last_accept_ < t && last_accept_ + port_cycles_ <= t &&
             lines_in_flight_ + kMaxFootprintLines <= b_->line_buffer_depth_ && miss_fifo.freed() <= t;
    }
    template <class Stalls>
    [[gnu::always_inline]] int64_t hit(int64_t t, ChannelTimes& in, ChannelTimes& miss_fifo, Stalls& c) {
      port_cycles_ = 1;
      return step(t, in, miss_fifo, c);
    }
    template <class Stalls>
    [[gnu::always_inline]] int64_t step(int64_t t, ChannelTimes& in, ChannelTimes& miss_fifo, Stalls& c) {
      ++c.footprints;
      in.pop(t);
      last_accept_ = t;
      b_->admitted_lines_ = 0;
      last_exit_ = std::max(t + 1, last_exit_ + 1);
      miss_fifo.pop(last_exit_);
      return last_exit_;
    }

   private:
    // Pointers, and the queue of footprints in the block (CacheStage::timing_in_flight_): the
    // recurrences may copy the timing into registers for a batch of footprints.
    CacheStage* b_;
    int lines_in_flight_ = 0;  // the slots of timing_in_flight_'s footprints (with some that have left: accept)
    int64_t last_accept_ = -1, last_exit_ = -1;  // the previous footprint's cycles (-1: none)
    int port_cycles_ = 0;                        // the cycles it held the tag port
  } timing{*this};

 private:
  // Timing's queue: the footprints that missed lines, in order, with the cycle each leaves the miss
  // FIFO and the line-buffer slots it holds until then.
  struct QueuedLines {
    int64_t exit;
    int lines;
  };
  std::deque<QueuedLines> timing_in_flight_;
  sim::Channel<FootprintReq>& in_;
  sim::Channel<FilterReq>& filter_out_;
  sim::Channel<FilterReq>& edge_out_;
  const Registers& regs_;
  const TextureMemory& memory_;
  TexelCache& cache_;
  MemoryModel& mem_;
  struct Entry {
    FootprintReq f;
    uint64_t ready;  // cycle the footprint's lines are all in the cache
    int lines;       // line-buffer slots it holds (its missed lines)
  };
  sim::Fifo<Entry> fifo_;  // the miss FIFO
  int line_buffer_depth_;
  int lines_in_flight_ = 0;  // line-buffer slots held by the footprints in the miss FIFO
  int admitted_lines_ = 0;   // the lines the last footprint looked up missed
  // The input side may accept a footprint: the miss FIFO has an entry and the line buffer
  // kMaxFootprintLines slots.
  bool line_buffer_room() const { return lines_in_flight_ + kMaxFootprintLines <= line_buffer_depth_; }
  // The read-out registers of every level of every texture (decoded from the descriptors once):
  // texture t's level l is readout_[first_readout_[t] + l].
  std::vector<LevelReadout> readout_;
  std::vector<size_t> first_readout_;
  uint64_t port_free_ = 0;  // tag/bank port busy until this cycle (bank conflicts)
  // The decoders (compressed textures): configuration, free from this cycle on, counters per texture.
  DecoderConfig decoder_;
  uint64_t decoder_free_ = 0;
  bool any_compressed_ = false;
  std::vector<uint8_t> compressed_;  // per texture descriptor
  std::vector<uint8_t> block_tags_;  // per texture descriptor: compressed lines, tagged in blocks
  std::vector<SlotCounters> slots_;  // per statistics slot
  // One decoder job (the header's rule) of statistics slot `slot`: input in at `in`, `texels` to
  // decode; returns the cycle its texels are ready.
  [[gnu::always_inline]] uint64_t decode(uint64_t in, int texels, int blocks, size_t slot) {
    const uint64_t start = std::max(in, decoder_free_);
    const auto busy = static_cast<uint64_t>((texels + decoder_.texels_per_cycle() - 1) / decoder_.texels_per_cycle());
    decoder_free_ = start + busy;
    SlotCounters& c = slots_[slot];
    c.decoded_blocks += static_cast<uint64_t>(blocks);
    c.decoder_busy += busy;
    c.decoder_stall += start - in;
    return start + busy - 1 + static_cast<uint64_t>(decoder_.latency);
  }
  // admit_lines for a compressed texture: the tags, memory reads and the decoder jobs; `lookup` is
  // the grid the tags take (in blocks under CacheHolds::Compressed, in texels under Decoded).
  uint64_t admit_blocks(int texture, int stage, int level, const TapGrid& lookup, uint64_t now, int& bank_cycles,
                        FootprintResult& r);
  // read_out for a compressed texture: the taps' texels decoded from the blocks in memory, at the
  // address generator's block coordinates (cur.blocks).
  void read_out_blocks(const FootprintReq& cur, FilterReq& f, Rgba8 outside) const;
  // The stalls and shapes are counted in slots_ on the per-cycle path; published once, after the run.
  void publish_stalls_shapes_decoders(sim::Stats& st, const SlotCounters& c) const;
  // A memo of decoded blocks, for the model's speed only (no hardware counterpart; cycles,
  // statistics and outputs are the same without it): texel memory is written before a run and only
  // read during it, so the block at an address decodes to the same texels under the same format and
  // rules. Direct-mapped by block address, kDecodedMemoEntries entries, allocated when a texture is
  // compressed. decoded_block returns the texels of the block at `address`: the memo entry's, or
  // `scratch` when the entry holds another block of the same footprint (`held`, `n` of them).
  struct DecodedBlock {
    uint64_t address = UINT64_MAX;
    BlockFormat format{};
    BlockDecodeRules rules{};
    std::array<Rgba8, 144> texels;  // up to 12 x 12
  };
  struct HeldBlock {
    uint64_t address;
    const Rgba8* texels;
  };
  // 4096 entries (2.4 MB): the oa:aggressor frame's ASTC 6x6 textures touch about 6,000 distinct
  // blocks a run, and 1,024 entries decoded 11,000 (docs/compressed.md, "Cycle model on a
  // compressed real frame").
  static constexpr size_t kDecodedMemoEntries = 4096;
  mutable std::vector<DecodedBlock> decoded_memo_;
  // decoded_block's `scratch` for the blocks held at once (a footprint's): allocated with the memo,
  // not cleared per footprint.
  static constexpr size_t kHeldBlocks = 16;
  mutable std::vector<std::array<Rgba8, 144>> scratch_;
  const Rgba8* decoded_block(const TextureDescriptor& d, uint64_t address, const HeldBlock* held, size_t n,
                             Rgba8* scratch) const;
  // The same memo for read_block_squares, per texture level instead of per address: every block of
  // the level has its place (block-major: block (bx, by) of a level `blocks_across` blocks wide at
  // texel (by blocks_across + bx) block_w block_h, its texels row-major after it), decoded the
  // first time a footprint reads it, from the bytes at the descriptor's block address, and kept
  // for the run (no eviction: each block the run reads is decoded once). The storage is bytes,
  // allocated on the level's first read and written block by block (no clearing).
  struct DecodedLevel {
    std::unique_ptr<unsigned char[]> texels;  // 4 bytes a texel, an Rgba8 word
    std::vector<uint8_t> decoded;             // per block: 1 once its texels are in place
    int blocks_across = 0;
  };
  mutable std::vector<DecodedLevel> decoded_levels_;  // indexed like readout_
  DecodedLevel& decoded_level(int texture, int level) const;
  void decode_into_level(const TextureDescriptor& d, int level, DecodedLevel& dl, int bx, int by) const;
  bool any_edge_ = false;                  // some sampler is EDGE_PRESERVING (shape statistics)
  bool record_shapes_ = false;             // some EDGE_PRESERVING sampler is cache-aware (shapes)
  bool probes_ = false;                    // waveform probes recorded (probes())
  uint32_t accepted_id_ = 0;
  uint64_t accepted_line_ = 0;
  uint64_t last_miss_line_ = 0;
  int last_misses_ = 0;
  FootprintReq accepted_{};  // the footprint last accepted; no taps until the first one
  sim::Channel<FilterReq>& out_of(const FootprintReq& f) {
    return f.tag.base == BaseFilter::EdgePreserving ? edge_out_ : filter_out_;
  }
  // The input and output halves of evaluate() (inline: once per cycle each).
  inline void accept(uint64_t now);
  inline void emit();
  inline uint64_t admit(FootprintReq& cur, uint64_t now, int& bank_cycles);
  inline void read_out(const FootprintReq& cur, FilterReq& f) const;
};

}  // namespace tfu::rtl
