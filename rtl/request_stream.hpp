// request_stream: where a unit takes its requests from and keeps what it records per request, so
// that a unit can run on a stream of requests (a scene's render, band by band) in a bounded
// working set instead of on a whole frame's trace (docs/cycle-model.md, "Streaming").
//
//   RequestRing<T>   one entry per request id: the whole trace (index = id), or a window of 2^k
//                    entries (index = id mod 2^k) that the ids in flight and not yet drained share
//   RequestStream    the requests a unit takes, in order: a view of a whole trace, or a bounded
//                    queue filled by a producer thread (the renderer) and emptied by the unit's
//                    thread; the producer waits while the window is full, the unit while it is empty
//
// A unit on a stream retires its pixels in request order (rtl/response.hpp), so it hands them on
// in chunks of kStreamChunk requests (rtl/tfu_unit.hpp, run_unit_stream): a chunk's requests,
// pixels, exit cycles and edge shapes; the window then frees them. The window holds the requests
// in flight in the unit (at most 4 with the timing recurrences: one quad), the retired ones not yet
// handed on (< kStreamChunk) and the ones queued ahead; so a window larger than kStreamChunk plus
// a quad can never leave the producer waiting on a unit that waits on it.
#pragma once

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
  // The storage of a whole-trace ring (one entry per request), moved out after the run.
  std::vector<T> take() { return std::move(v_); }

 private:
  std::vector<T> v_;
  size_t mask_ = ~size_t{0};
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
  // A bounded queue of `capacity` requests (a power of two) in `mode`, filled by push().
  RequestStream(TraceMode mode, size_t capacity)
      : mode_(mode), ring_(capacity), data_(ring_.data()), mask_(capacity - 1), capacity_(capacity) {}
  RequestStream(const RequestStream&) = delete;
  RequestStream& operator=(const RequestStream&) = delete;

  TraceMode mode() const { return mode_; }
  bool whole() const { return whole_; }  // a view of a whole trace
  const TraceRequest& operator[](size_t i) const { return data_[i & mask_]; }

  // Producer: appends requests in order, waiting while the window is full. Returns false (and
  // drops them) once the unit has given up (abandon()).
  bool push(const TraceRequest* r, size_t n);
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

 private:
  bool wait_for(size_t i);
  TraceMode mode_;
  std::vector<TraceRequest> ring_;
  const TraceRequest* data_;
  size_t mask_;
  size_t capacity_ = 0;
  size_t known_ = 0;  // the unit's thread: requests it has seen available
  std::atomic<size_t> produced_{0};
  size_t released_ = 0;  // guarded by mutex_
  bool closed_ = false, abandoned_ = false, whole_ = false;
  std::mutex mutex_;
  std::condition_variable changed_;
};

}  // namespace tfu::rtl
