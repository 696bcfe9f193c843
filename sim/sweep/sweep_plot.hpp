// Charts of a sweep (tfu plot, tfu sweep --plot): scripts/plot (matplotlib, run as /usr/bin/python3)
// on DIR/results.csv and DIR/columns.json.
#pragma once

#include <string>
#include <vector>

#include "sim/sweep/sweep_report.hpp"
#include "sim/sweep/sweep_spec.hpp"

namespace tfu::sweep {

struct PlotRequest {
  std::string dir;                  // the sweep directory (results.csv, columns.json)
  std::string x, y;                 // columns
  std::vector<std::string> series;  // columns whose distinct values make the lines
  std::vector<std::string> where;   // COLUMN=VALUE row filters
  std::string series_note;          // a column whose value each legend entry shows (e.g. filter_gates)
  bool log_x = false, log_y = false;
  std::string kind = "line";        // line | bar
  std::string title;
  std::string out;                  // FILE.png
  bool force = false;
};

// The plot script: $TFU_PLOT_SCRIPT, else scripts/plot of the source tree the binary was built from.
std::string plot_script();
// Draws one chart; InputError with the script's one-line message when it refuses.
void plot(const PlotRequest& r);

// The summary's charts, written as DIR/plot_*.png: for the first numeric grid key (log x when its
// values span 8x or more), bytes per pixel and pixels per clock, one line per filter (and scene and
// further grid keys when they vary); and area against benefit: texel cache SRAM bits against bytes
// per pixel, each filter's datapath gates in its legend entry. Overwrites earlier plots of DIR.
std::vector<Plot> default_plots(const Spec& spec, const std::vector<Point>& points, const std::string& dir);

}  // namespace tfu::sweep
