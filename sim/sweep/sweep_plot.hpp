// Charts of a sweep (tfu plot, tfu sweep --plot): scripts/plot (matplotlib, run as /usr/bin/python3)
// on DIR/results.csv and DIR/columns.json.
#pragma once

#include <string>
#include <vector>

#include "cmodel/output_files.hpp"
#include "sim/sweep/sweep_report.hpp"
#include "sim/sweep/sweep_spec.hpp"

namespace tfu::sweep {

struct PlotRequest {
  std::string dir;                  // the sweep directory (results.csv, columns.json)
  std::string csv, columns;         // the files read instead of DIR/results.csv and DIR/columns.json (empty: those)
  std::string x, y;                 // columns
  std::vector<std::string> series;  // columns whose distinct values make the lines
  std::vector<std::string> where;   // COLUMN=VALUE row filters
  std::string series_note;          // a column whose value each legend entry shows (e.g. filter_gates)
  bool log_x = false, log_y = false;
  std::string kind = "line";        // line | bar
  std::string title;
};

// The plot script: $TFU_PLOT_SCRIPT, else scripts/plot of the source tree the binary was built from.
std::string plot_script();
// plot_script(), or InputError when it does not exist (checked before a sweep with --plot runs).
std::string checked_plot_script();
// Reserves a chart's file in `outputs` under OPTION: a .png name; an existing file only with
// `force`, and never a directory, device or pipe (cmodel/output_files.hpp).
OutputFile& add_plot_output(OutputFiles& outputs, const std::string& option, const std::string& path, bool force);
// Draws one chart into `out`'s temporary (scripts/plot --write-to); the chart takes its name when
// the caller commits `out`'s OutputFiles. InputError with the script's one-line message when it refuses.
void plot(const PlotRequest& r, OutputFile& out);

// The summary's charts as outputs DIR/plot_*.png of `outputs` (replacing earlier plots of DIR when
// committed), drawn from the files `csv` and `columns`: for the first numeric grid key (log x when
// its values span 8x or more), bytes per pixel and pixels per clock, one line per filter (and scene
// and further grid keys when they vary); and area against benefit: texel cache SRAM bits against
// bytes per pixel, each filter's datapath gates in its legend entry.
std::vector<Plot> default_plots(const Spec& spec, const std::vector<Point>& points, const std::string& dir,
                                OutputFiles& outputs, const std::string& csv, const std::string& columns);

}  // namespace tfu::sweep
