// Worker threads, in one place: the renderer's bands, the kernel-error sweep, the scene simulation's
// units and the exhaustive format checks all run their workers through run_workers().
//
// Thread counts the user gives are range-checked (checked_thread_count). If the system refuses to
// start a thread (std::thread throws), the work runs on the workers started so far: every caller
// hands out its work through a shared counter and the calling thread is always worker 0, so the
// work completes with the same results (they never depend on the number of threads), only slower.
#pragma once

#include <chrono>
#include <functional>
#include <string>

namespace tfu {

inline constexpr int kMaxThreads = 256;

// A user's thread count: 1..kMaxThreads, or 0 ("all hardware threads") where `zero_means_all`.
// Throws InputError naming `option` otherwise.
int checked_thread_count(const std::string& option, long long n, bool zero_means_all);

// The number of hardware threads, clamped to 1..kMaxThreads.
int hardware_threads();

// CPU seconds used so far by the calling thread (CLOCK_THREAD_CPUTIME_ID): speed figures only.
double thread_cpu_seconds();

// Wall-clock seconds elapsed since `t0` (steady clock): speed figures only.
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Runs body(0) on the calling thread and body(1) .. body(workers - 1) on new threads (workers is
// clamped to 1..kMaxThreads), then joins them. Returns how many workers ran (fewer than asked only
// when the system refused a thread). The first exception a worker throws is rethrown after the join.
int run_workers(int workers, const std::function<void(int worker)>& body);

namespace detail {
// Test hook: the next run_workers() calls fail to start any thread beyond `n` (-1: no limit), as if
// the system refused it.
void set_thread_start_limit(int n);
}  // namespace detail

}  // namespace tfu
