#include "rtl/request_stream.hpp"

#include <algorithm>
#include <chrono>

#include "cmodel/parallel.hpp"

namespace tfu::rtl {

double RoomSignal::wait_past(uint64_t seen) {
  std::unique_lock lock(mutex_);
  if (generation_ != seen) return 0;
  const auto t0 = std::chrono::steady_clock::now();
  changed_.wait(lock, [&] { return generation_ != seen; });
  return seconds_since(t0);
}

void RequestStream::append(std::unique_lock<std::mutex>& lock, const TraceRequest* r, size_t k) {
  const size_t at = produced_.load(std::memory_order_relaxed);
  // Slots [at, at + k) are free: the unit reads only below `produced_` and has released the ids
  // a window earlier, so the copy runs outside the lock.
  lock.unlock();
  for (size_t j = 0; j < k; ++j) ring_[(at + j) & mask_] = r[j];
  lock.lock();
  produced_.store(at + k, std::memory_order_release);
  changed_.notify_all();
}

size_t RequestStream::offer(const TraceRequest* r, size_t n) {
  std::unique_lock lock(mutex_);
  if (abandoned_) return n;
  const size_t k = std::min(n, capacity_ - (produced_.load(std::memory_order_relaxed) - released_));
  if (k > 0) append(lock, r, k);
  return k;
}

double push_each(RoomSignal& room, std::vector<StreamPart> parts) {
  double waited = 0;
  for (;;) {
    // The generation before the offers: room freed after an offer found none bumps it, so the
    // wait below cannot miss it.
    const uint64_t seen = room.generation();
    bool left = false, took = false;
    for (StreamPart& p : parts) {
      if (p.n == 0) continue;
      const size_t k = p.stream->offer(p.requests, p.n);
      p.requests += k;
      p.n -= k;
      took = took || k > 0;
      left = left || p.n > 0;
    }
    if (!left) return waited;
    if (!took) waited += room.wait_past(seen);
  }
}

bool RequestStream::push(const TraceRequest* r, size_t n) {
  std::unique_lock lock(mutex_);
  size_t done = 0;
  const auto room = [&] { return abandoned_ || produced_.load(std::memory_order_relaxed) - released_ < capacity_; };
  while (done < n) {
    if (!room()) {
      const auto t0 = std::chrono::steady_clock::now();
      changed_.wait(lock, room);
      producer_wait_ += seconds_since(t0);
    }
    if (abandoned_) return false;
    const size_t k = std::min(n - done, capacity_ - (produced_.load(std::memory_order_relaxed) - released_));
    append(lock, r + done, k);
    done += k;
  }
  return true;
}

void RequestStream::close() {
  const std::lock_guard lock(mutex_);
  closed_ = true;
  changed_.notify_all();
}

bool RequestStream::wait_for(size_t i) {
  std::unique_lock lock(mutex_);
  const auto ready = [&] { return closed_ || produced_.load(std::memory_order_relaxed) > i; };
  if (!ready()) {
    const auto t0 = std::chrono::steady_clock::now();
    changed_.wait(lock, ready);
    unit_wait_ += seconds_since(t0);
  }
  known_ = produced_.load(std::memory_order_relaxed);
  return i < known_;
}

void RequestStream::release(size_t drained) {
  if (whole_) return;
  {
    const std::lock_guard lock(mutex_);
    released_ = std::max(released_, drained);
    changed_.notify_all();
  }
  if (room_ != nullptr) room_->bump();
}

void RequestStream::abandon() {
  if (whole_) return;
  {
    const std::lock_guard lock(mutex_);
    abandoned_ = true;
    changed_.notify_all();
  }
  if (room_ != nullptr) room_->bump();
}

}  // namespace tfu::rtl
