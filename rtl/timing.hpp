// What the blocks' timing rules share (the timing-recurrence engine, rtl/unit_recurrence.cpp): the
// ring of the last items' cycles and the per-item event cycles of the two datapaths.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tfu::rtl {

// The cycles of the last items of one kind (at least `keep` of them), by item number: a ring of a
// power-of-two size, at least 2 keep + 1, filled with `before` (the value of an item that does not
// exist). Item i < 0 therefore reads `before` without a test: every index read is at least
// count - keep, so while i < 0 fewer than keep items exist, in slots below keep, and the slot of
// i is size + i >= size - keep > keep. (The mask is 32 bits wide so that the compiler need not
// reload it after a store of a 64-bit cycle.)
template <typename T>
class Ring {
 public:
  Ring(size_t keep, T before)
      : v_(std::bit_ceil(2 * keep + 1), before), mask_(static_cast<uint32_t>(v_.size() - 1)) {}
  T& operator[](int64_t i) { return v_[static_cast<size_t>(i) & mask_]; }

 private:
  std::vector<T> v_;
  uint32_t mask_;
};

// Per footprint: the cycle kernel_select took it (it left the footprint channel), the cycle the
// texel cache accepted it (it left the shaped channel), the cycle it left the miss FIFO.
struct FootprintTimes {
  int64_t shaped_push, accept, exit;
};
// Per edge footprint: the cycles it left the edge texel channel and the two stage channels.
struct EdgeTimes {
  int64_t t1, t2, t3;
};

}  // namespace tfu::rtl
