#include "rtl/request_stream.hpp"

#include <algorithm>

namespace tfu::rtl {

bool RequestStream::push(const TraceRequest* r, size_t n) {
  std::unique_lock lock(mutex_);
  size_t done = 0;
  while (done < n) {
    changed_.wait(lock,
                  [&] { return abandoned_ || produced_.load(std::memory_order_relaxed) - released_ < capacity_; });
    if (abandoned_) return false;
    const size_t at = produced_.load(std::memory_order_relaxed);
    const size_t k = std::min(n - done, capacity_ - (at - released_));
    // Slots [at, at + k) are free: the unit reads only below `produced_` and has released the ids
    // a window earlier, so the copy runs outside the lock.
    lock.unlock();
    for (size_t j = 0; j < k; ++j) ring_[(at + j) & mask_] = r[done + j];
    lock.lock();
    produced_.store(at + k, std::memory_order_release);
    done += k;
    changed_.notify_all();
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
  changed_.wait(lock, [&] { return closed_ || produced_.load(std::memory_order_relaxed) > i; });
  known_ = produced_.load(std::memory_order_relaxed);
  return i < known_;
}

void RequestStream::release(size_t drained) {
  if (whole_) return;
  const std::lock_guard lock(mutex_);
  released_ = std::max(released_, drained);
  changed_.notify_all();
}

void RequestStream::abandon() {
  if (whole_) return;
  const std::lock_guard lock(mutex_);
  abandoned_ = true;
  changed_.notify_all();
}

}  // namespace tfu::rtl
