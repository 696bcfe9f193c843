// What the blocks' timing rules share. Each block states its timing twice, side by side in its own
// header: in evaluate() (the clocked engine, rtl/unit_clocked.cpp) and in its `Timing` (the
// recurrence engine, rtl/unit_recurrence.cpp), which computes, item by item, the cycle at which
// evaluate() would move that item. The two change together; TfuUnit.InterleavedTexturesFormats-
// LayoutsAndSamplers and the differential fuzz target hold them equal, and `tfu sim
// --compare-engines` names the first block and item at which they differ (rtl/engine_compare.hpp).
//
// The recurrences rest on one property of the channels (rtl/kernel/kernel.hpp): a valid/ready
// channel's ready is registered, so in cycle t its consumer sees item j iff j was pushed before t
// and item j - 1 popped before t, and its producer may push item j iff item j - depth was popped
// before t. A channel is therefore described, for the recurrences, by the cycles at which its
// items left it: ChannelTimes. (The derivation: rtl/unit_recurrence.cpp.)
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace tfu::rtl {

// The cycles at which the items of one channel of `depth` entries left it (were popped), by item
// number: the last ones, in a ring.
// Item i < 0 (before the first) left at cycle -1. The ring has a power-of-two size of at least
// 2 depth + 1, so item i < 0 reads -1 without a test: every index read is at least count - depth,
// so while i < 0 fewer than depth items exist, in slots below depth, and the slot of i is
// size + i >= size - depth > depth. (The mask is 32 bits wide so that the compiler need not reload
// it after a store of a 64-bit cycle.)
class ChannelTimes {
 public:
  explicit ChannelTimes(size_t depth)
      : ring_(std::make_unique<int64_t[]>(std::bit_ceil(2 * depth + 1))),
        v_(ring_.get()),
        mask_(static_cast<uint32_t>(std::bit_ceil(2 * depth + 1) - 1)),
        depth_(static_cast<int64_t>(depth)) {
    std::fill(v_, v_ + mask_ + 1, int64_t{-1});
  }
  // The first cycle in which the next item may be pushed: the cycle after item count - depth left
  // (ready is registered).
  int64_t room() const { return at(count_ - depth_) + 1; }
  // The cycle in which item count - depth left: for a block's own FIFO, whose pop (its output side)
  // comes before its push (its input side) in the same cycle, the first cycle the next item may enter.
  int64_t freed() const { return at(count_ - depth_); }
  // The next item leaves at `cycle`.
  [[gnu::always_inline]] void pop(int64_t cycle) { v_[static_cast<size_t>(count_++) & mask_] = cycle; }
  // A copy of the channel that shares its ring, for timing a batch of items with the count in a
  // local variable (a register: the ring's stores cannot alias it) instead of in the channel, whose
  // other fields the compiler must otherwise reload after every store of a cycle; settle() hands
  // the count back. Software speed only: the same cycles, read and written in the same ring. No
  // item may move through the channel itself between lend() and settle().
  ChannelTimes lend() const { return ChannelTimes(v_, mask_, depth_, count_); }
  void settle(const ChannelTimes& lent) { count_ = lent.count_; }
  ChannelTimes(ChannelTimes&&) = default;
  ChannelTimes& operator=(ChannelTimes&&) = default;

 private:
  std::unique_ptr<int64_t[]> ring_;  // null in a lent copy
  int64_t* v_;
  uint32_t mask_;
  int64_t depth_;
  int64_t count_ = 0;  // items that left so far
  ChannelTimes(int64_t* v, uint32_t mask, int64_t depth, int64_t count)
      : v_(v), mask_(mask), depth_(depth), count_(count) {}
  int64_t at(int64_t i) const { return v_[static_cast<size_t>(i) & mask_]; }
};

// The rule of a block that takes one item per cycle, in order, from `in` and pushes its result into
// `out` in the cycle it takes it (kernel_select, edge_median, edge_direction; with `hold` the filter,
// and without an output the response sink). Item j leaves `in` in the first cycle in which it is
// visible (pushed + 1), the block has finished the previous item (its cycle + 1), plus the `hold`
// cycles the item keeps the block before it may leave, and `out` has room; `out` nullptr: the item
// pushes nothing (a probe or level0 footprint that completes no pixel).
struct InOrderTiming {
  int64_t last = -1;  // the previous item's cycle (-1: none)
  [[gnu::always_inline]] int64_t move(int64_t pushed, ChannelTimes& in, const ChannelTimes* out, int hold = 0) {
    int64_t t = std::max(pushed + 1, last + 1) + hold;
    if (out != nullptr) t = std::max(t, out->room());
    in.pop(t);
    last = t;
    return t;
  }
};

// The rule of a block that takes one item and pushes its outputs one per cycle, the first in the
// cycle it takes the item, and takes the next item after pushing the last (lod_unit: a quad and its
// pixels; address_gen: a pixel and its level footprints). take(): the cycle item j leaves `in`
// (visible, and the block free since the cycle after its last push); push(): the cycle the block
// pushes an output (the item's first in its take cycle, the next one cycle after the previous),
// when `out` has room.
struct SequencerTiming {
  int64_t last_push = -1;  // the previous output's push cycle (-1: none)
  [[gnu::always_inline]] int64_t take(int64_t pushed, ChannelTimes& in) {
    const int64_t t = std::max(pushed + 1, last_push + 1);
    in.pop(t);
    return t;
  }
  [[gnu::always_inline]] int64_t push(bool first_output, int64_t taken, const ChannelTimes& out) {
    last_push = std::max(first_output ? taken : last_push + 1, out.room());
    return last_push;
  }
};

// Cycles from `from` to `to` (0 when `to` is not later): the stall counters' span.
inline uint64_t cycles_between(int64_t from, int64_t to) {
  return static_cast<uint64_t>(std::max<int64_t>(0, to - from));
}

}  // namespace tfu::rtl
