// tfu sweep --bench: the local runner's speed on a spec (docs/design-space.md, "Speed"):
//   single runs   every point alone, one after the other on one thread, as `tfu sim` runs it
//                 in-process (scene opened, golden render with trace, cycle model with golden
//                 compare): the sum of these is the work
//   sweep         the whole sweep on the local runner with the given workers into a scratch
//                 directory: its wall time, and per point the time beyond the simulation proper
//                 (scene and truth look-up, PSNR, cost, JSON, the file write)
#pragma once

#include <string>
#include <vector>

#include "sim/sweep/sweep_spec.hpp"

namespace tfu::sweep {

struct BenchFigures {
  size_t points = 0;
  int workers = 0;
  double single_sum = 0;      // seconds: the sum of the points' single-run times
  double wall = 0;            // seconds: the sweep's wall time
  double simulation_sum = 0;  // seconds: the points' simulation proper inside the sweep
  double point_sum = 0;       // seconds: the points' whole time inside the sweep (file write included)
  double single_cpu = 0;      // process CPU seconds of the single runs
  double sweep_cpu = 0;       // process CPU seconds of the sweep (all workers)
  double load_before = 0;     // the machine's 1-minute load average when the bench started
  double wall_ratio() const { return single_sum > 0 ? wall / single_sum : 0; }
  double overhead() const { return simulation_sum > 0 ? (point_sum - simulation_sum) / simulation_sum : 0; }
};

BenchFigures bench(const Spec& spec, const std::vector<Point>& points, int workers);
std::string bench_report(const BenchFigures& f);

}  // namespace tfu::sweep
