// The local runner of a sweep: its points in-process on long-lived worker threads (one process, so
// that OpenImageIO's libraries load once), each point's file written atomically into DIR/points/,
// points whose file is already complete skipped (resume), a progress bar with ETA on stderr.
// Results do not depend on the number of workers: every point is deterministic and independent,
// and results.csv is written from the point files in point order (sweep_report.hpp).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "sim/sweep/sweep_point.hpp"
#include "sim/sweep/sweep_spec.hpp"

namespace tfu::sweep {

struct RunOptions {
  int workers = 0;                  // 0: std::thread::hardware_concurrency()
  size_t task = 0, tasks = 1;       // this process runs the points with index % tasks == task (Slurm array tasks)
  bool progress = true;             // progress bar / lines on stderr
};

struct RunSummary {
  size_t points = 0;     // this task's share
  size_t skipped = 0;    // already complete in DIR
  size_t ran = 0;
  double wall_seconds = 0;
  std::vector<PointTiming> timings;  // of the points run (completion order)
};

// Runs the task's share of `points` into `dir`. Exceptions other than a point's own input or
// deadlock errors (recorded in its file) stop the workers and propagate.
RunSummary run_points(const Spec& spec, const std::vector<Point>& points, const std::string& dir, const RunOptions& opt);

// The sweep directory: DIR/sweep.json records the spec (its absolute path and text) so that array
// tasks and --collect expand the same points. A DIR that exists, is not empty and holds no
// sweep.json, or holds the sweep of a spec with other text, is refused unless `force` (InputError
// naming --out); the same spec resumes.
void prepare_sweep_dir(const std::string& dir, const Spec& spec, bool force);
Spec load_sweep_dir(const std::string& dir);  // the spec recorded in DIR/sweep.json

// "1:05:09", "3:07", "0:42"
std::string format_duration(double seconds);

}  // namespace tfu::sweep
