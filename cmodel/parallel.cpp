#include "cmodel/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include <time.h>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {
namespace {

std::atomic<int> g_thread_start_limit{-1};

}  // namespace

namespace detail {
void set_thread_start_limit(int n) { g_thread_start_limit = n; }
}  // namespace detail

int checked_thread_count(const std::string& option, long long n, bool zero_means_all) {
  const long long lo = zero_means_all ? 0 : 1;
  if (n < lo || n > kMaxThreads)
    throw InputError(fmt::format("{} must be in {}..{}{}, got {}", option, lo, kMaxThreads,
                                 zero_means_all ? " (0: all hardware threads)" : "", n));
  return static_cast<int>(n);
}

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

int hardware_threads() {
  return static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, static_cast<unsigned>(kMaxThreads)));
}

int run_workers(int workers, const std::function<void(int worker)>& body) {
  workers = std::clamp(workers, 1, kMaxThreads);
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto guarded = [&](int w) {
    try {
      body(w);
    } catch (...) {
      const std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<size_t>(workers));
  for (int w = 1; w < workers; ++w) {
    try {
      const int limit = g_thread_start_limit.load();
      if (limit >= 0 && w > limit) throw std::system_error(std::make_error_code(std::errc::resource_unavailable_try_again));
      pool.emplace_back(guarded, w);
    } catch (const std::system_error&) {
      break;  // the system refuses more threads: the workers started so far do the work
    }
  }
  guarded(0);
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
  return static_cast<int>(pool.size()) + 1;
}

}  // namespace tfu
