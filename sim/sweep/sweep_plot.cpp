#include "sim/sweep/sweep_plot.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"
#include "rtl/cost_model.hpp"
#include "sim/sweep/process.hpp"

namespace tfu::sweep {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPython = "/usr/bin/python3";  // Debian's, with python3-matplotlib (scripts/bootstrap)

size_t distinct(const std::vector<Point>& points, size_t key) {
  std::set<std::string> v;
  for (const Point& p : points) v.insert(p.values[key]);
  return v.size();
}

// A key whose every point value is a number (a numeric config field, or a sampler key such as
// max_aniso or lod_bias): its charts have a numeric x axis.
bool numeric_values(const std::vector<Point>& points, size_t key) {
  for (const Point& p : points) {
    const std::string& v = p.values[key];
    char* end = nullptr;
    if (v.empty() || (std::strtod(v.c_str(), &end), end != v.c_str() + v.size())) return false;
  }
  return true;
}

}  // namespace

std::string plot_script() {
  if (const char* env = std::getenv("TFU_PLOT_SCRIPT"); env && *env) return env;
  return std::string(TFU_SOURCE_DIR) + "/scripts/plot";
}

OutputFile& add_plot_output(OutputFiles& outputs, const std::string& option, const std::string& path, bool force) {
  // The script's own checks first, with its messages: the file type, then an existing file.
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower.size() < 4 || lower.compare(lower.size() - 4, 4, ".png") != 0)
    throw InputError(fmt::format("{} {}: must be a .png file", option, quoted_path(path)));
  struct stat st {};
  if (!force && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode))
    throw InputError(fmt::format("{} {} exists (use --force to overwrite)", option, quoted_path(path)));
  return outputs.add(option, path);
}

std::string checked_plot_script() {
  const std::string script = plot_script();
  if (!fs::exists(script)) throw InputError(fmt::format("plot script '{}' not found (set TFU_PLOT_SCRIPT)", script));
  return script;
}

void plot(const PlotRequest& r, OutputFile& out) {
  const std::string script = checked_plot_script();
  const std::string csv = r.csv.empty() ? (fs::path(r.dir) / "results.csv").string() : r.csv;
  if (!fs::exists(csv)) throw InputError(fmt::format("'{}' has no results.csv (run tfu sweep, or tfu sweep --collect)", r.dir));
  // --out names the chart in the script's messages; the PNG goes into the temporary (--write-to).
  std::vector<std::string> argv = {kPython, script, "--csv", csv, "--x", r.x, "--y", r.y, "--kind", r.kind};
  argv.insert(argv.end(), {"--out", out.path(), "--write-to", out.temp_path()});
  if (!r.columns.empty()) argv.insert(argv.end(), {"--columns", r.columns});
  if (!r.series.empty()) {
    std::string s;
    for (const std::string& c : r.series) s += (s.empty() ? "" : ",") + c;
    argv.insert(argv.end(), {"--series", s});
  }
  for (const std::string& w : r.where) argv.insert(argv.end(), {"--where", w});
  if (!r.series_note.empty()) argv.insert(argv.end(), {"--series-note", r.series_note});
  if (!r.title.empty()) argv.insert(argv.end(), {"--title", r.title});
  if (r.log_x) argv.push_back("--log-x");
  if (r.log_y) argv.push_back("--log-y");
  const ProcessResult res = run_process(argv);
  if (res.status == -1) throw InputError(fmt::format("cannot run {} (scripts/bootstrap installs python3-matplotlib)", kPython));
  if (res.status != 0) {
    std::string line = failure_line(res.err, 260);
    if (line.rfind("plot: error: ", 0) == 0) line = line.substr(13);
    throw InputError(fmt::format("plot: {}", line.empty() ? fmt::format("{} exited with status {}", script, res.status) : line));
  }
  out.mark_written();
}

std::vector<Plot> default_plots(const Spec& spec, const std::vector<Point>& points, const std::string& dir,
                                OutputFiles& outputs, const std::string& csv, const std::string& columns) {
  std::vector<Plot> plots;
  // The x axis: the first grid key that varies and is numeric, else the first that varies (a
  // categorical axis, drawn as bars): every grid key, config or sampler, gets the charts per metric.
  size_t xk = spec.keys.size();
  for (size_t k = 0; k < spec.grid_keys && xk == spec.keys.size(); ++k)
    if (distinct(points, k) > 1 && numeric_values(points, k)) xk = k;
  for (size_t k = 0; k < spec.grid_keys && xk == spec.keys.size(); ++k)
    if (distinct(points, k) > 1) xk = k;
  std::vector<std::string> series;
  if (spec.filters.size() > 1) series.push_back("filter");
  if (spec.scenes.size() > 1) series.push_back("scene");
  for (size_t k = 0; k < spec.keys.size(); ++k)
    if (k != xk && distinct(points, k) > 1) series.push_back(spec.keys[k].name);
  if (series.empty()) series.push_back("filter");
  const auto make = [&](PlotRequest r, const std::string& file, const std::string& caption) {
    r.dir = dir;
    r.csv = csv;
    r.columns = columns;
    r.series = series;
    plot(r, add_plot_output(outputs, "--plot", (fs::path(dir) / file).string(), /*force=*/true));
    plots.push_back({file, caption});
  };
  if (xk < spec.keys.size()) {
    const std::string& x = spec.keys[xk].name;
    PlotRequest r;
    r.x = x;
    if (numeric_values(points, xk)) {
      double lo = 0, hi = 0;
      bool first = true;
      for (const Point& p : points) {
        const double v = std::strtod(p.values[xk].c_str(), nullptr);
        lo = first ? v : std::min(lo, v);
        hi = first ? v : std::max(hi, v);
        first = false;
      }
      r.log_x = lo > 0 && hi >= 8 * lo;
    } else {
      r.kind = "bar";
    }
    r.y = "bytes_per_pixel";
    make(r, "plot_bytes_per_pixel.png", fmt::format("Memory bytes per pixel against {}", x));
    r.y = "pixels_per_clock";
    make(r, "plot_pixels_per_clock.png", fmt::format("Pixels per clock against {}", x));
  }
  PlotRequest area;
  area.x = "sram_bits";
  area.y = "bytes_per_pixel";
  area.log_x = true;
  area.kind = "line";
  area.title = "Cost beside benefit: texel cache SRAM against memory traffic";
  if (std::find(series.begin(), series.end(), "filter") != series.end()) area.series_note = "filter_gates";
  make(area, "plot_area.png", "Area against benefit: texel cache SRAM bits against memory bytes per pixel "
                              "(legend: the filter datapath's gate equivalents)");
  if (rtl::sram_macro(spec.node)) {  // the whole unit's area and energy (docs/design-space.md, "The whole unit at a node")
    PlotRequest unit;
    unit.x = "bytes_per_pixel";
    unit.y = "area_mm2";
    unit.title = fmt::format("The whole unit at {}: area against memory traffic", rtl::node_name(spec.node));
    make(unit, "plot_unit_area.png",
         fmt::format("Unit area at {} (logic, miss FIFO, texel cache SRAM) against memory bytes per pixel", rtl::node_name(spec.node)));
    unit.x = "psnr_surface";
    unit.y = "energy_pj_per_pixel";
    unit.title = fmt::format("The whole unit at {}: energy against quality", rtl::node_name(spec.node));
    make(unit, "plot_energy_psnr.png",
         fmt::format("Energy per pixel at {} (logic and texel cache SRAM; DRAM not counted) against PSNR against the surface truth",
                     rtl::node_name(spec.node)));
  }
  return plots;
}

}  // namespace tfu::sweep
