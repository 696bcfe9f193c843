// Fuzz target (g): a sweep specification and its point files, as `tfu sweep SPEC` reads the spec
// and a resumed run or `tfu sweep --collect DIR` reads the points (docs/fuzzing.md). The input is
// the spec's JSON, then a line "=====", then a point file's bytes. The spec goes through parse_spec
// and expand; the point file is written for every point of the sweep into a private temporary
// directory (DIR/points/ID.json) -- when it is a JSON object with a "point" object, with that
// point's own id in it, so that it is taken for the point's result -- and the points are read as
// --collect reads them (point_done, read_point_files) and reported (results_csv, columns_json,
// summary_markdown, failed_points). Bad input must end in an InputError (or, for points without a
// complete result, the CheckFailed that --collect reports); anything else is a finding.
//
// Cost limits of the harness: scenes are built-in names only (no scene files, no game data), and a
// spec of more than 64 points (scenes x filters x grid values, before expand) is not expanded.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/temp_paths.hpp"
#include "sim/sweep/sweep_point.hpp"
#include "sim/sweep/sweep_report.hpp"
#include "sim/sweep/sweep_spec.hpp"
#include "testbench/fuzz/fuzz_input.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path& work_dir() {
  static const tfu::TempDir d("tfu-fuzz-sweep", fs::exists("/dev/shm") ? "/dev/shm" : "");
  return d.path();
}

// Built-in scenes only, and at most 64 points before expand.
bool within_limits(const std::string& spec_text) {
  const json j = json::parse(spec_text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return true;  // parse_spec reports it
  size_t points = 1;
  const auto count = [&](const json& v) {
    if (v.is_array()) points *= std::max<size_t>(v.size(), 1);
  };
  const auto& names = tfu::builtin_scene_names();
  const auto builtin = [&](const json& s) {
    return !s.is_string() || std::find(names.begin(), names.end(), s.get<std::string>()) != names.end();
  };
  for (const char* key : {"scenes", "filters"})
    if (j.contains(key)) {
      count(j[key]);
      if (j[key].is_array() && !std::all_of(j[key].begin(), j[key].end(), builtin) && std::string(key) == "scenes")
        return false;
      if (j[key].is_string() && std::string(key) == "scenes" && !builtin(j[key])) return false;
    }
  if (j.contains("grid") && j["grid"].is_object())
    for (const auto& [k, v] : j["grid"].items()) count(v);
  if (j.contains("points") && j["points"].is_array()) {
    points += j["points"].size();
    for (const json& p : j["points"])
      if (p.is_object() && p.contains("scene") && !builtin(p["scene"])) return false;
  }
  return points <= 64;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 16384) return 0;
  const std::string text = tfu::fuzz::as_text(data, size);
  const size_t cut = text.find("\n=====\n");
  const std::string spec_text = text.substr(0, cut);
  const std::string point_text = cut == std::string::npos ? std::string() : text.substr(cut + 7);
  if (!within_limits(spec_text)) return 0;
  try {
    const tfu::sweep::Spec spec = tfu::sweep::parse_spec(spec_text, (work_dir() / "spec.json").string());
    const std::vector<tfu::sweep::Point> points = tfu::sweep::expand(spec);
    if (points.size() > 64) return 0;
    const std::string dir = (work_dir() / "sweep").string();
    fs::remove_all(dir);
    fs::create_directories(fs::path(dir) / "points");
    json as_json = json::parse(point_text, nullptr, false);
    for (const tfu::sweep::Point& p : points) {
      std::string bytes = point_text;
      if (as_json.is_object() && as_json.contains("point") && as_json["point"].is_object()) {
        as_json["point"]["id"] = p.id;
        bytes = as_json.dump(-1, ' ', false, json::error_handler_t::replace);
      }
      std::ofstream(tfu::sweep::point_path(dir, p), std::ios::binary) << bytes;
    }
    try {
      const std::vector<json> files = tfu::sweep::read_point_files(dir, points);
      (void)tfu::sweep::results_csv(spec, points, files);
      (void)tfu::sweep::columns_json(spec);
      (void)tfu::sweep::summary_markdown(spec, points, files, {});
      (void)tfu::sweep::failed_points(files);
    } catch (const tfu::CheckFailed&) {
      // points without a complete result: --collect names them and exits
    }
  } catch (const tfu::InputError&) {
  }
  return 0;
}
