#include "sim/sweep/sweep_report.hpp"

#include <filesystem>
#include <map>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/json_output.hpp"
#include "rtl/cost_model.hpp"
#include "sim/sweep/sweep_point.hpp"

namespace tfu::sweep {
namespace {

constexpr size_t kSummaryRows = 500;  // summary.md lists at most this many rows (results.csv has all)

// Units of the unit-configuration fields, for axis labels (the field table has their meanings).
std::string field_unit(const std::string& key) {
  static const std::map<std::string, std::string> units = {
      {"cache.line_bytes", "bytes"},   {"cache.capacity_bytes", "bytes"}, {"cache.ways", "ways"},
      {"cache.banks", "banks"},        {"memory.latency", "cycles"},      {"memory.bytes_per_cycle", "bytes/cycle"},
      {"channel_depth", "entries"},    {"miss_fifo_depth", "footprints"}, {"filter_lanes", "lanes"}};
  const auto it = units.find(key);
  return it == units.end() ? "" : it->second;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// A result value as CSV/Markdown text: integers as they are, reals with fixed decimals.
std::string number_text(const nlohmann::json& v, int decimals) {
  if (v.is_null()) return "";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return json_dump(v);
  return fmt::format("{:.{}f}", v.get<double>(), decimals);
}

int decimals_of(const std::string& column) {
  if (column == "psnr" || column == "psnr_surface" || column == "psnr_interior" || column == "latency_mean") return 4;
  if (column == "filter_gates" || column == "logic_um2" || column == "sram_um2" || column == "fmax_mhz") return 1;
  if (column == "energy_pj_per_pixel" || column == "logic_pj_per_pixel" || column == "sram_pj_per_pixel" ||
      column == "dram_pj_per_pixel")
    return 2;
  return 6;
}

// The text of result column `c` of one point file.
std::string result_text(const nlohmann::json& file, const std::string& c) {
  if (c == "point") return file.at("point").at("id").get<std::string>();
  if (c == "error") return file.value("error", "");
  if (file.contains("error")) return c == "golden_equal" ? "false" : "";
  const nlohmann::json& r = file.at("result");
  return r.contains(c) ? number_text(r.at(c), decimals_of(c)) : "";
}

bool is_failed(const nlohmann::json& f) { return f.contains("error") || !f.at("result").at("golden_equal").get<bool>(); }

double result_number(const nlohmann::json& f, const char* c) {
  if (f.contains("error")) return 0;
  const nlohmann::json& v = f.at("result").at(c);
  return v.is_number() ? v.get<double>() : 0;
}

}  // namespace

const std::vector<Column>& result_columns() {
  static const std::vector<Column> cols = {
      {"cycles", "cycles", "clock cycles of the frame (the slowest unit's)", ResultType::Number},
      {"pixels", "requests", "requests simulated: every pixel of every shaded quad, helper pixels included, per material stage",
       ResultType::Number},
      {"pixels_per_clock", "pixels/clock", "requests per cycle", ResultType::Number},
      {"hit_rate", "fraction", "texel cache line lookups that hit", ResultType::Number},
      {"sector_hit_rate", "fraction",
       "texel cache 32-byte sector lookups that hit: each distinct sector of its lines a footprint reads, a hit when its line is "
       "(rtl/texel_cache.hpp)",
       ResultType::Number},
      {"bytes_per_pixel", "bytes/pixel", "memory bytes read per request", ResultType::Number},
      {"memory_bytes", "bytes", "memory bytes read", ResultType::Number},
      {"stall_cache_miss", "cycles", "cycles the miss-FIFO head waited for memory (summed over units)", ResultType::Number},
      {"stall_bank_conflict", "cycles", "cycles the tag port was held by a multi-cycle footprint (may overlap the other two)",
       ResultType::Number},
      {"stall_backpressure", "cycles", "cycles the cache stage's output was full", ResultType::Number},
      {"latency_mean", "cycles", "mean request latency, accept to response", ResultType::Number},
      {"psnr", "dB", "PSNR of the cycle model's image against the 8x8-supersampled ground truth (antialiased edges)",
       ResultType::NumberOrInf},
      {"ssim", "", "SSIM (luma, docs/metrics.md) of the cycle model's image against the same ground truth", ResultType::Number},
      {"psnr_surface", "dB",
       "PSNR against the surface truth: the render's own coverage, each surface integrated over its pixels (the filter's error alone)",
       ResultType::NumberOrInf},
      {"psnr_interior", "dB", "PSNR against the surface truth over the pixels whose quad lies inside one surface",
       ResultType::NumberOrInf},
      {"golden_equal", "", "every output of the cycle model equals the golden model's", ResultType::Bool},
      {"sram_bits", "bits", "texel cache SRAM: data, tags, valid and LRU bits, all units (rtl/cost_model.hpp)", ResultType::Number},
      {"filter_gates", "GE", "filter datapath gate equivalents the frame's filters need, all units (rtl/sv/filter_gates.json)",
       ResultType::Number},
      {"logic_um2", "um^2",
       "logic at the spec's node: the datapath blocks the frame's filters need, x filter_lanes, and the miss FIFO's flip-flops, all "
       "units (rtl/cost_model.hpp, rtl/sv/silicon_gates.json)",
       ResultType::Number},
      {"sram_um2", "um^2", "texel cache and line buffer SRAM at the node's SRAM model's area per bit (rtl::sram_macro), all units",
       ResultType::NumberOrNull},
      {"area_mm2", "mm^2", "logic_um2 + sram_um2", ResultType::NumberOrNull},
      {"fmax_mhz", "MHz", "the clock of the slowest block the frame needs at the node (the slowest part sets the clock)", ResultType::Number},
      {"energy_pj_per_pixel", "pJ/pixel",
       "logic_pj_per_pixel + sram_pj_per_pixel + dram_pj_per_pixel (DRAM 0 with the ideal memory; empty with a DRAM "
       "part that has no power sheet)", ResultType::NumberOrNull},
      {"logic_pj_per_pixel", "pJ/pixel", "logic: leakage + uniform-activity switching at fmax, per request", ResultType::NumberOrNull},
      {"sram_pj_per_pixel", "pJ/pixel", "texel cache and line buffer SRAM word reads and writes, per request", ResultType::NumberOrNull},
      {"dram_pj_per_pixel", "pJ/pixel",
       "DRAM bursts and activates at the part's TN-40-07 command energies (rtl::dram_command_energy), per request; empty with the "
       "ideal memory and with a part that has no power sheet (no cited IDD table: gddr3-1400-x32)",
       ResultType::NumberOrNull},
      {"point", "", "the point's id: its file DIR/points/ID.json"},
      {"error", "", "why the point could not run (empty when it ran)"},
  };
  return cols;
}

std::vector<Column> csv_columns(const Spec& spec) {
  std::vector<Column> cols;
  for (const Key& k : spec.keys)
    cols.push_back({k.name, k.field ? field_unit(k.name) : k.name == "width" || k.name == "height" ? "pixels" : "",
                    k.field ? k.field->meaning
                    : k.run ? "run key: the units, render size, raster order or unit tiles (docs/design-space.md)"
                            : "sampler key of every base stage"});
  cols.push_back({"scene", "", "the scene as the spec names it"});
  cols.push_back({"filter", "", "the filter of the base stages (\"scene\": the scene's own)"});
  for (const Column& c : result_columns()) cols.push_back(c);
  return cols;
}

std::optional<nlohmann::json> read_point_file(const std::string& dir, const Point& p) {
  const std::string path = point_path(dir, p);
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(path, ec))) return std::nullopt;
  const std::string label = fmt::format("point file {}", quoted_path(path));
  // Checked (TFU-S E5: never a FIFO or /dev/zero), but the sweep's own state: a point not done is written again.
  const std::string text = read_input_file(path, label, kMaxTextInputBytes, InputFile::Use::OwnState);
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("complete")) return std::nullopt;
  // Marked complete: every key read below is checked first (TFU-S E6: a mistyped one was exit 3).
  const auto bad = [&](const std::string& key, const std::string& why) {
    return InputError(fmt::format("{}: {}: {} (remove the file to run the point again)", label, key, why));
  };
  const nlohmann::json& complete = j["complete"];
  if (!complete.is_boolean()) throw bad("complete", "must be true or false");
  if (!complete.get<bool>()) return std::nullopt;
  if (!j.contains("point") || !j["point"].is_object()) throw bad("point", "missing or not an object");
  const nlohmann::json& point = j["point"];
  if (!point.contains("id") || !point["id"].is_string()) throw bad("point.id", "missing or not a string");
  if (point["id"].get<std::string>() != p.id)
    throw bad("point.id", fmt::format("'{}' is not this point's id ({})", quote_input(point["id"].get<std::string>(), 40), p.id));
  if (j.contains("error")) {
    const nlohmann::json& e = j["error"];
    if (!e.is_string() || e.get<std::string>().find_first_of("\n\r") != std::string::npos)
      throw bad("error", "must be a one-line string");
    return j;
  }
  if (!j.contains("result") || !j["result"].is_object()) throw bad("result", "missing or not an object (and no \"error\")");
  const nlohmann::json& r = j["result"];
  for (const Column& c : result_columns()) {
    if (c.type == ResultType::None) continue;
    const std::string key = "result." + c.name;
    if (!r.contains(c.name)) throw bad(key, "missing");
    const nlohmann::json& v = r[c.name];
    const bool number = v.is_number() && !v.is_boolean();
    switch (c.type) {
      case ResultType::Number:
        if (!number) throw bad(key, "must be a number");
        break;
      case ResultType::NumberOrInf:
        if (!number && v != "inf") throw bad(key, "must be a number or \"inf\"");
        break;
      case ResultType::Bool:
        if (!v.is_boolean()) throw bad(key, "must be true or false");
        break;
      case ResultType::NumberOrNull:
        if (!number && !v.is_null()) throw bad(key, "must be a number or null");
        break;
      case ResultType::None:
        break;
    }
  }
  return j;
}

bool point_done(const std::string& dir, const Point& p) { return read_point_file(dir, p).has_value(); }

std::vector<nlohmann::json> read_point_files(const std::string& dir, const std::vector<Point>& points) {
  std::vector<nlohmann::json> files;
  std::vector<std::string> missing;
  for (const Point& p : points) {
    std::optional<nlohmann::json> j = read_point_file(dir, p);
    if (!j) missing.push_back(fmt::format("{} ({})", p.index, p.id));
    files.push_back(j ? std::move(*j) : nlohmann::json());
  }
  if (!missing.empty()) {
    std::string list;
    for (size_t i = 0; i < missing.size() && i < 3; ++i) list += (i ? ", " : "") + missing[i];
    throw CheckFailed(fmt::format("{} of {} points have no complete result in {}/points (e.g. point {}{})", missing.size(),
                                  points.size(), dir.substr(0, 100), list, missing.size() > 3 ? ", ..." : ""));
  }
  return files;
}

std::string results_csv(const Spec& spec, const std::vector<Point>& points, const std::vector<nlohmann::json>& files) {
  std::string out;
  const std::vector<Column> cols = csv_columns(spec);
  std::vector<std::string> fields;
  for (const Column& c : cols) fields.push_back(csv_field(c.name));
  out += fmt::format("{}\n", fmt::join(fields, ","));
  for (size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    fields.clear();
    for (const std::string& v : p.values) fields.push_back(csv_field(v));
    fields.push_back(csv_field(p.scene));
    fields.push_back(csv_field(p.filter));
    for (const Column& c : result_columns()) fields.push_back(csv_field(result_text(files[i], c.name)));
    out += fmt::format("{}\n", fmt::join(fields, ","));
  }
  return out;
}

std::string columns_json(const Spec& spec) {
  nlohmann::json j = nlohmann::json::array();
  for (const Column& c : csv_columns(spec)) j.push_back({{"name", c.name}, {"unit", c.unit}, {"meaning", c.meaning}});
  return json_dump(j, 2) + "\n";
}

size_t failed_points(const std::vector<nlohmann::json>& files) {
  size_t n = 0;
  for (const nlohmann::json& f : files) n += is_failed(f) ? 1 : 0;
  return n;
}

std::string summary_markdown(const Spec& spec, const std::vector<Point>& points, const std::vector<nlohmann::json>& files,
                             const std::vector<Plot>& plots) {
  std::ostringstream md;
  md << fmt::format("# Sweep `{}`\n\nGenerated by `tfu sweep` (docs/design-space.md). {} points: {} scene(s) x {} filter(s)",
                    std::filesystem::path(spec.path).filename().string(), points.size(), spec.scenes.size(), spec.filters.size());
  size_t grid = spec.grid_keys ? 1 : 0;
  for (const auto& v : spec.grid_values) grid *= v.size();
  if (grid) md << fmt::format(" x {} grid point(s)", grid);
  if (!spec.points.empty()) md << fmt::format(", {} explicit point(s)", spec.points.size());
  md << fmt::format(", at {}, {} unit(s).\n\n", spec.width ? fmt::format("{}x{}", spec.width, spec.height) : "each scene's own size",
                    spec.units);
  const size_t failed = failed_points(files);
  md << (failed == 0 ? fmt::format("**Golden compare: every output of all {} points equals the golden model's.**\n\n", points.size())
                     : fmt::format("**{} point(s) failed** (golden mismatch or error; see the `golden_equal` and `error` columns).\n\n",
                                   failed));
  md << "| key | values |\n|---|---|\n";
  md << fmt::format("| scenes | {} |\n| filters | {} |\n", fmt::join(spec.scenes, ", "), fmt::join(spec.filters, ", "));
  for (size_t k = 0; k < spec.grid_keys; ++k) md << fmt::format("| {} | {} |\n", spec.keys[k].name, fmt::join(spec.grid_values[k], ", "));
  md << fmt::format("\nBase configuration (every point starts from it): `{}`", json_dump(nlohmann::json::parse(rtl::unit_config_to_json(spec.base))));
  if (!spec.base_sampler.empty()) md << fmt::format("; base-stage sampler keys: `{}`", json_dump(nlohmann::json(spec.base_sampler)));
  md << ".\n\nCost columns: `sram_bits` is the texel cache's data, tag, valid and LRU bits (formula in rtl/cost_model.hpp); "
        "`filter_gates` the Yosys gate equivalents of the filter datapaths the frame's filters need ("
     << rtl::filter_gate_source() << "); `logic_um2`, `sram_um2`, `area_mm2`, `fmax_mhz` and `energy_pj_per_pixel` the whole unit at "
     << rtl::node_name(spec.node) << " (docs/design-space.md, \"The whole unit at a node\").\n";
  if (!plots.empty()) {
    md << "\n## Plots\n\n";
    for (const Plot& pl : plots) md << fmt::format("![{}]({})\n\n*{}*\n\n", pl.caption, pl.file, pl.caption);
  }
  // Best points per scene and filter.
  md << "\n## Best points per scene and filter\n\n| scene | filter | most pixels/clock | at | fewest bytes/pixel | at |\n"
        "|---|---|---:|---|---:|---|\n";
  std::map<std::pair<std::string, std::string>, std::pair<size_t, size_t>> best;
  for (size_t i = 0; i < points.size(); ++i) {
    if (files[i].contains("error")) continue;
    const auto key = std::make_pair(points[i].scene, points[i].filter);
    auto it = best.find(key);
    if (it == best.end()) {
      best.emplace(key, std::make_pair(i, i));
      continue;
    }
    if (result_number(files[i], "pixels_per_clock") > result_number(files[it->second.first], "pixels_per_clock")) it->second.first = i;
    if (result_number(files[i], "bytes_per_pixel") < result_number(files[it->second.second], "bytes_per_pixel")) it->second.second = i;
  }
  const auto keys_of = [&](size_t i) {
    std::string s;
    for (size_t k = 0; k < spec.keys.size(); ++k)
      if (!points[i].values[k].empty()) s += fmt::format("{}{}={}", s.empty() ? "" : " ", spec.keys[k].name, points[i].values[k]);
    return s;
  };
  for (const auto& [key, b] : best)
    md << fmt::format("| {} | {} | {} | {} | {} | {} |\n", key.first, key.second, result_text(files[b.first], "pixels_per_clock"),
                      keys_of(b.first), result_text(files[b.second], "bytes_per_pixel"), keys_of(b.second));
  // Every row (the first kSummaryRows).
  const std::vector<Column> cols = csv_columns(spec);
  md << "\n## Every point\n\n|";
  for (const Column& c : cols)
    if (c.name != "point" && c.name != "error") md << ' ' << c.name << (c.unit.empty() ? "" : " (" + c.unit + ")") << " |";
  md << "\n|";
  for (const Column& c : cols)
    if (c.name != "point" && c.name != "error") md << "---|";
  md << '\n';
  for (size_t i = 0; i < points.size() && i < kSummaryRows; ++i) {
    md << '|';
    for (const std::string& v : points[i].values) md << ' ' << v << " |";
    md << ' ' << points[i].scene << " | " << points[i].filter << " |";
    for (const Column& c : result_columns())
      if (c.name != "point" && c.name != "error") md << ' ' << result_text(files[i], c.name) << " |";
    md << '\n';
  }
  if (points.size() > kSummaryRows) md << fmt::format("\n({} more rows in results.csv.)\n", points.size() - kSummaryRows);
  for (size_t i = 0; i < points.size(); ++i)
    if (files[i].contains("error")) md << fmt::format("\nPoint {} ({}): {}\n", i, describe(spec, points[i]), result_text(files[i], "error"));
  return md.str();
}

}  // namespace tfu::sweep
