#include "sim/sweep/sweep_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/json_output.hpp"
#include "rtl/kernel/kernel.hpp"
#include "sim/sweep/provenance.hpp"
#include "sim/sweep/sweep_report.hpp"

namespace tfu::sweep {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// The progress display: a bar redrawn in place on a terminal, otherwise one line per finished
// point (batch logs).
class Progress {
 public:
  Progress(size_t total, size_t already, bool on) : total_(total), done_(already), on_(on), tty_(::isatty(2) != 0) {}
  void point_done(const std::string& what) {
    const std::lock_guard lock(mutex_);
    ++done_;
    ++ran_;
    if (!on_) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - t0_).count();
    const size_t left = total_ - done_;
    const double eta = ran_ ? elapsed / static_cast<double>(ran_) * static_cast<double>(left) : 0;
    if (tty_) {
      constexpr int kWidth = 30;
      const int filled = total_ ? static_cast<int>(kWidth * done_ / total_) : kWidth;
      std::fprintf(stderr, "\rsweep: [%s%s] %zu/%zu points  %s elapsed  ETA %s   ", std::string(static_cast<size_t>(filled), '#').c_str(),
                   std::string(static_cast<size_t>(kWidth - filled), '.').c_str(), done_, total_, format_duration(elapsed).c_str(),
                   format_duration(eta).c_str());
      if (done_ == total_) std::fputc('\n', stderr);
    } else {
      std::fprintf(stderr, "sweep: %zu/%zu points, %s elapsed, ETA %s: %s\n", done_, total_, format_duration(elapsed).c_str(),
                   format_duration(eta).c_str(), what.substr(0, 160).c_str());
    }
    std::fflush(stderr);
  }

 private:
  std::mutex mutex_;
  size_t total_, done_, ran_ = 0;
  bool on_, tty_;
  Clock::time_point t0_ = Clock::now();
};

}  // namespace

std::string format_duration(double seconds) {
  const auto s = static_cast<long long>(std::max(0.0, seconds) + 0.5);
  if (s >= 3600) return fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60);
  return fmt::format("{}:{:02d}", s / 60, s % 60);
}

RunSummary run_points(const Spec& spec, const std::vector<Point>& points, const std::string& dir, const RunOptions& opt) {
  if (opt.tasks == 0 || opt.task >= opt.tasks) throw InputError(fmt::format("task {} of {}: out of range", opt.task, opt.tasks));
  RunSummary sum;
  std::vector<const Point*> todo;
  for (const Point& p : points) {
    if (p.index % opt.tasks != opt.task) continue;
    ++sum.points;
    if (point_done(dir, p)) {
      ++sum.skipped;
    } else {
      todo.push_back(&p);
    }
  }
  const int hw = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int workers = std::clamp(opt.workers > 0 ? opt.workers : hw, 1, std::max(1, static_cast<int>(todo.size())));
  if (opt.progress && sum.skipped > 0)
    std::fprintf(stderr, "sweep: %zu of %zu points already done in %s (skipped)\n", sum.skipped, sum.points, dir.c_str());
  sim::set_progress_bars(false);  // one progress display: the sweep's
  const auto t0 = Clock::now();
  Progress progress(sum.points, sum.skipped, opt.progress);
  SceneCache cache;
  cache.plan(spec, todo);
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::exception_ptr error;
  const auto worker = [&] {
    try {
      for (size_t i; !stop && (i = next++) < todo.size();) {
        const Point& p = *todo[i];
        PointTiming t;
        const auto w0 = Clock::now();
        const std::string text = run_point(spec, p, cache, &t);
        write_file_atomic(point_path(dir, p), text, "sweep point file");
        t.seconds = std::chrono::duration<double>(Clock::now() - w0).count();  // the file write included
        {
          const std::lock_guard lock(mutex);
          sum.timings.push_back(t);
          ++sum.ran;
        }
        progress.point_done(describe(spec, p));
      }
    } catch (...) {
      const std::lock_guard lock(mutex);
      if (!error) error = std::current_exception();
      stop = true;
    }
  };
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  sim::set_progress_bars(true);
  sum.wall_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  if (error) std::rethrow_exception(error);
  return sum;
}

void prepare_sweep_dir(const std::string& dir, const Spec& spec, bool force) {
  std::error_code ec;
  const fs::path d(dir), record = d / "sweep.json";
  if (fs::exists(d, ec) && !fs::is_directory(d, ec)) throw InputError(fmt::format("--out '{}' exists and is not a directory", dir));
  if (fs::exists(d, ec) && !fs::is_empty(d, ec) && !fs::exists(record, ec) && !force)
    throw InputError(fmt::format("--out '{}' is not empty and holds no sweep.json (use another directory, or --force)", dir));
  if (fs::exists(record, ec) && !force) {
    // Resuming is for the same spec: another spec's results.csv and summary.md are not replaced.
    std::string recorded;
    try {
      recorded = load_sweep_dir(dir).text;
    } catch (const InputError&) {
    }
    if (recorded != spec.text)
      throw InputError(fmt::format("--out '{}' holds a sweep of another spec (use another directory, or --force)", dir));
  }
  fs::create_directories(d / "points", ec);
  if (ec) throw InputError(fmt::format("--out '{}' cannot be created: {}", dir, ec.message()));
  const fs::path abs = fs::absolute(spec.path, ec).lexically_normal();
  const nlohmann::json j = {{"spec_path", abs.string()}, {"spec_text", spec.text}};
  write_file_atomic(record.string(), json_dump(j, 2) + "\n", "--out");
}

Spec load_sweep_dir(const std::string& dir) {
  const fs::path record = fs::path(dir) / "sweep.json";
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(record, ec)))
    throw InputError(fmt::format("'{}' holds no sweep.json (not a sweep directory)", dir));
  // A regular file (TFU-S E5: a FIFO or a link to /dev/zero is refused), bounded by the spec's bound
  // with the spec's text JSON-escaped (at most six bytes for one: \u001f) and two paths.
  const std::string text = read_input_file(record.string(), fmt::format("sweep record {}", quoted_path(record.string())),
                                           7 * kMaxTextInputBytes, InputFile::Use::OwnState);
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    return parse_spec(j.at("spec_text").get<std::string>(), j.at("spec_path").get<std::string>());
  } catch (const nlohmann::json::exception&) {
    throw InputError(fmt::format("'{}': malformed (expected spec_path and spec_text)", record.string()));
  }
}

}  // namespace tfu::sweep
