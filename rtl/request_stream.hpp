// request_stream: where a unit takes its requests from and keeps what it records per request, so
// that a unit can run on a stream of requests (a scene's render, band by band) in a bounded
// working set instead of on a whole frame's trace (docs/cycle-model.md, "Streaming").
//
//   RequestRing<T>   one entry per request id: the whole trace (index = id), or a window of 2^k
//                    entries (index = id mod 2^k) that the ids in flight and not yet drained share
//   RequestStream    the requests a unit takes, in order: a view of a whole trace, or a bounded
//                    queue filled by a producer thread (the renderer) and emptied by the unit's
//                    thread; the producer waits while the window is full, the unit while it is empty
//   push_each        one producer feeding several units' streams (a band dealt to the units): it
//                    waits only while every stream it still has requests for is full (RoomSignal)
//
// A unit on a stream retires its pixels in request order (rtl/response.hpp), so it hands them on
// in chunks of kStreamChunk requests (rtl/tfu_unit.hpp, run_unit_stream): a chunk's requests,
// pixels, exit cycles and edge shapes; the window then frees them. The window holds the requests
// in flight in the unit (at most 4 with the timing recurrences: one quad), the retired ones not yet
// handed on (< kStreamChunk) and the ones queued ahead; so a window larger than kStreamChunk plus
// a quad can never leave the producer waiting on a unit that waits on it.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <utility>
#include <vector>

#include "cmodel/trace.hpp"

namespace tfu::rtl {

// Requests handed on per chunk by a streaming unit (a multiple of 4: whole quads).
inline constexpr size_t kStreamChunk = size_t{1} << 14;
// A streaming unit's window: requests queued, in flight and retired but not yet handed on.
inline constexpr size_t kStreamWindow = size_t{1} << 16;
static_assert(kStreamWindow >= 2 * kStreamChunk && (kStreamWindow & (kStreamWindow - 1)) == 0);

// Entries [first, first + n) of storage `v` indexed by id & mask (mask ~0: the whole trace; else a
// power-of-two window, n at most its size) to out[0, n), in at most two runs.
template <typename T>
void copy_runs(const T* v, size_t mask, size_t first, size_t n, T* out) {
  if (n == 0) return;
  const size_t at = first & mask;
  const size_t head = std::min(n - 1, mask - at) + 1;  // to the storage's end (mask ~0: n, no wrap)
  std::copy(v + at, v + at + head, out);
  std::copy(v, v + (n - head), out + head);
}

// Per-request storage: every id of a trace, or a power-of-two window of ids.
template <typename T>
class RequestRing {
 public:
  void whole(size_t n) {  // index = id
    v_.assign(n, T{});
    mask_ = ~size_t{0};
  }
  void window(size_t capacity) {  // index = id mod capacity (a power of two)
    v_.assign(capacity, T{});
    mask_ = capacity - 1;
  }
  T& operator[](size_t id) { return v_[id & mask_]; }
  const T& operator[](size_t id) const { return v_[id & mask_]; }
  bool empty() const { return v_.empty(); }
  // Entries of ids [first, first + n) to out[0, n): at most two runs of the storage (a window wraps
  // once at most: n <= its capacity).
  void copy_out(size_t first, size_t n, T* out) const { copy_runs(v_.data(), mask_, first, n, out); }
  // The storage and its mask (entry id at data()[id & mask()]): for a loop over many ids with the two in
  // registers (software speed only: a store of a T could otherwise alias them).
  const T* data() const { return v_.data(); }
  size_t mask() const { return mask_; }
  // The storage of a whole-trace ring (one entry per request), moved out after the run.
  std::vector<T> take() { return std::move(v_); }

 private:
  std::vector<T> v_;
  size_t mask_ = ~size_t{0};
};

// Tells a producer that feeds several streams (push_each) that one of them has freed room or
// given up: the streams bump its generation, the producer waits for a generation it has not seen.
class RoomSignal {
 public:
  uint64_t generation() {
    const std::lock_guard lock(mutex_);
    return generation_;
  }
  void bump() {
    {
      const std::lock_guard lock(mutex_);
      ++generation_;
    }
    changed_.notify_all();
  }
  // Waits until the generation differs from `seen`; returns the wall seconds waited.
  double wait_past(uint64_t seen);

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  uint64_t generation_ = 0;
};

class RequestStream {
 public:
  // A whole trace: every request available, nothing queued (the trace must outlive the stream).
  explicit RequestStream(const Trace& trace)
      : mode_(trace.mode),
        data_(trace.requests.data()),
        mask_(~size_t{0}),
        known_(trace.requests.size()),
        produced_(trace.requests.size()),
        closed_(true),
        whole_(true) {}
  // A bounded queue of `capacity` requests (a power of two) in `mode`, filled by push() (or by
  // push_each, with `room` the signal it waits on).
  RequestStream(TraceMode mode, size_t capacity, RoomSignal* room = nullptr)
      : mode_(mode), ring_(capacity), data_(ring_.data()), mask_(capacity - 1), capacity_(capacity), room_(room) {}
  RequestStream(const RequestStream&) = delete;
  RequestStream& operator=(const RequestStream&) = delete;

  TraceMode mode() const { return mode_; }
  bool whole() const { return whole_; }  // a view of a whole trace
  const TraceRequest& operator[](size_t i) const { return data_[i & mask_]; }
  // Requests [first, first + n) to out[0, n) (available ones: has(first + n - 1)).
  void copy_out(size_t first, size_t n, TraceRequest* out) const { copy_runs(data_, mask_, first, n, out); }
  const TraceRequest* data() const { return data_; }  // request i at data()[i & mask()], as RequestRing's
  size_t mask() const { return mask_; }

  // Producer: appends requests in order, waiting while the window is full. Returns false (and
  // drops them) once the unit has given up (abandon()).
  bool push(const TraceRequest* r, size_t n);
  // Producer: appends as many of the n requests as the window has room for now, without waiting.
  // Returns how many it took: pushed, or all n (dropped) once the unit has given up.
  size_t offer(const TraceRequest* r, size_t n);
  // Producer: no more requests (also after a failure: the unit then ends with what it has).
  void close();

  // The unit: whether request i exists, waiting for the producer until it is pushed or the stream
  // is closed. Requests [0, i] may be read once it returns true.
  bool has(size_t i) {
    if (i < known_) return true;
    return !whole_ && wait_for(i);
  }
  // The unit: requests before `drained` are handed on, their slots free.
  void release(size_t drained);
  // The unit: gives up (it threw); the producer's further pushes return at once.
  void abandon();
  // Requests pushed so far (the total once closed).
  size_t produced() const { return produced_.load(std::memory_order_acquire); }
  // Wall seconds the producer stood in push() waiting for room in the window, and the unit in
  // has() waiting for requests (steady clock, measured only when a wait happens): where a streamed
  // run's threads stand still. Speed figures only (no result depends on them); read them after the
  // producer and the unit are done.
  double producer_wait_seconds() const { return producer_wait_; }
  double unit_wait_seconds() const { return unit_wait_; }

 private:
  bool wait_for(size_t i);
  // Copies r[0, k) to ids [at, at + k) (free slots) outside the lock and publishes them.
  void append(std::unique_lock<std::mutex>& lock, const TraceRequest* r, size_t k);
  TraceMode mode_;
  std::vector<TraceRequest> ring_;
  const TraceRequest* data_;
  size_t mask_;
  size_t capacity_ = 0;
  RoomSignal* room_ = nullptr;
  size_t known_ = 0;  // the unit's thread: requests it has seen available
  std::atomic<size_t> produced_{0};
  size_t released_ = 0;  // guarded by mutex_
  bool closed_ = false, abandoned_ = false, whole_ = false;
  double producer_wait_ = 0;  // the producer's, guarded by mutex_
  double unit_wait_ = 0;      // the unit's thread's
  std::mutex mutex_;
  std::condition_variable changed_;
};

// One producer, several streams: appends parts[k].n requests from parts[k].requests to
// parts[k].stream, each stream's in order, giving every stream what its window has room for and
// waiting (on `room`, the signal all of them were built with) only while every stream it still has
// requests for is full. So within one call (a band) one unit's full window does not hold back the
// others' shares (push() stream after stream would: a unit waits for its share of the band while
// the producer waits on another unit's window); the next call starts once this one is done, so a
// unit far behind the others still holds them back by up to its window. What each stream receives,
// and so every result, is the same as with push(). Returns the wall seconds waited.
struct StreamPart {
  RequestStream* stream = nullptr;
  const TraceRequest* requests = nullptr;
  size_t n = 0;
};
double push_each(RoomSignal& room, std::vector<StreamPart> parts);

}  // namespace tfu::rtl
