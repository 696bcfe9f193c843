#include "sim/sweep/sweep_spec.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <unordered_set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/descriptors.hpp"
#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/json_output.hpp"
#include "cmodel/run_files.hpp"
#include "cmodel/json_keys.hpp"
#include "cmodel/q3_scene.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/scene_source.hpp"
#include "sim/sweep/provenance.hpp"

namespace tfu::sweep {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

constexpr const char* kSamplerPrefix = "sampler.";
constexpr size_t kMaxPoints = 1000000;

// Errors name the spec file and the key.
struct Where {
  std::string spec;
  InputError operator()(const std::string& key, const std::string& why) const {
    return InputError(fmt::format("{}: {}: {}", quote_input(spec, 100), quote_input(key, 80), why));
  }
};

// A key name -> Key (unit field or sampler key); nullopt-like: throws naming `where_key`.
Key make_key(const std::string& name, const Where& where, const std::string& where_key) {
  Key k;
  k.name = name;
  if (std::find(std::begin(kRunKeys), std::end(kRunKeys), name) != std::end(kRunKeys)) {
    k.run = true;
    return k;
  }
  if (name.rfind(kSamplerPrefix, 0) == 0) {
    k.sampler_key = name.substr(std::string(kSamplerPrefix).size());
    if (k.sampler_key == "filter") throw where(where_key, "the filter is swept by \"filters\", not sampler.filter");
    bool known = false;
    for (const SamplerParam& p : sampler_params()) known = known || k.sampler_key == p.key;
    if (!known) throw where(where_key, fmt::format("unknown sampler key '{}'", quote_input(k.sampler_key, 40)));
    return k;
  }
  k.field = rtl::find_unit_field(name);
  if (!k.field)
    throw where(where_key, "unknown key (a unit configuration field of docs/cycle-model.md, sampler.KEY, units, width, height, raster, "
                           "unit_tiles, texture_layout or spawn)");
  return k;
}

// The text of one value of `key` from JSON, type-checked (names: strings; integer fields: integers;
// sampler keys: strings or numbers) and checked against the field's range.
int int_member(const Json& j, const std::string& key, int lo, int hi, const Where& where) {
  if (!j.is_number_integer()) throw where(key, "must be an integer");
  const int64_t v = j.is_number_unsigned() && j.get<uint64_t>() > static_cast<uint64_t>(INT64_MAX) ? INT64_MAX : j.get<int64_t>();
  if (v < lo || v > hi) throw where(key, fmt::format("{} is outside {}..{}", v, lo, hi));
  return static_cast<int>(v);
}

// A run key's value, canonical: units 1..256, width and height 0 (the scene's own) or 2..8192, a raster
// order (cmodel/raster_order.hpp), a unit distribution.
std::string run_value_text(const Key& key, const Json& v, const Where& where, const std::string& where_key) {
  if (key.name == "raster" || key.name == "unit_tiles") {
    if (!v.is_string()) throw where(where_key, "values must be strings");
    try {
      return key.name == "raster" ? raster_order_name(raster_order_from_name(v.get<std::string>()))
                                  : unit_tiles_name(unit_tiles_from_name(v.get<std::string>()));
    } catch (const InputError& e) {
      throw where(where_key, e.what());
    }
  }
  if (key.name == "texture_layout") {
    if (!v.is_string()) throw where(where_key, "values must be strings");
    const std::string l = v.get<std::string>();
    if (l == "own") return l;
    try {
      return memory_layout_name(memory_layout_from_name(l));
    } catch (const InputError& e) {
      throw where(where_key, fmt::format("{} (or own: each texture's)", e.what()));
    }
  }
  if (key.name == "spawn") return std::to_string(int_member(v, where_key, 0, 1 << 20, where));
  if (key.name == "units") return std::to_string(int_member(v, where_key, 1, 256, where));
  const int n = int_member(v, where_key, 0, kMaxRenderSize, where);
  if (n == 1) throw where(where_key, "must be 0 (the scene's own) or 2..8192");
  return std::to_string(n);
}

std::string value_text(const Key& key, const Json& v, const Where& where, const std::string& where_key) {
  if (key.run) return run_value_text(key, v, where, where_key);
  if (key.field) {
    std::string text;
    if (!key.field->names.empty()) {
      if (!v.is_string()) throw where(where_key, "values must be strings");
      text = v.get<std::string>();
    } else {
      if (!v.is_number_integer()) throw where(where_key, "values must be integers");
      if (v.is_number_unsigned() && v.get<uint64_t>() > static_cast<uint64_t>(INT64_MAX))
        throw where(where_key, fmt::format("{} is out of range", json_dump(v)));
      text = std::to_string(v.get<int64_t>());
    }
    rtl::UnitConfig probe;
    try {
      key.field->set_text(probe, text);
    } catch (const InputError& e) {
      throw where(where_key, e.what());
    }
    return text;
  }
  std::string text;
  if (v.is_string()) {
    text = v.get<std::string>();
  } else if (v.is_number() && !v.is_boolean()) {
    text = json_dump(v);
  } else {
    throw where(where_key, "values must be strings or numbers");
  }
  SamplerDescriptor probe;
  try {
    set_sampler_param(probe, key.sampler_key, text);
  } catch (const InputError& e) {
    throw where(where_key, e.what());
  }
  return text;
}

std::vector<std::string> string_list(const Json& j, const std::string& key, const Where& where) {
  if (!j.is_array() || j.empty()) throw where(key, "must be a non-empty list of strings");
  std::vector<std::string> out;
  std::unordered_set<std::string> seen;  // linear time: a list may hold 10^6 names (TFU-S E10)
  seen.reserve(j.size());
  out.reserve(j.size());
  for (const Json& v : j) {
    if (!v.is_string() || v.get<std::string>().empty()) throw where(key, "must be a non-empty list of strings");
    const std::string& s = v.get_ref<const std::string&>();
    if (!seen.insert(s).second) throw where(key, fmt::format("'{}' is listed twice", quote_input(s, 60)));
    out.push_back(s);
  }
  return out;
}

std::string canonical_filter(const std::string& name, const Where& where, const std::string& key) {
  if (name == kSceneFilter) return kSceneFilter;
  try {
    return filter_mode_name(filter_mode_from_name(name));
  } catch (const InputError&) {  // its list of every mode would make the line too long
    throw where(key, fmt::format("unknown filter '{}' (a mode of docs/sampler.md, e.g. LINEAR_MIPMAP_LINEAR, bilinear, "
                                 "trilinear, or \"scene\")", quote_input(name, 40)));
  }
}

// "base": a unit configuration object, optionally with a "sampler" object of base-stage keys.
void parse_base(const Json& j, Spec& s, const Where& where) {
  if (!j.is_object()) throw where("base", "must be an object (a unit configuration, optionally with \"sampler\")");
  Json unit = j;
  if (unit.contains("sampler")) {
    const Json& smp = unit["sampler"];
    if (!smp.is_object()) throw where("base.sampler", "must be an object of sampler keys");
    for (const auto& [k, v] : smp.items()) {
      const Key key = make_key(kSamplerPrefix + k, where, "base.sampler." + k);
      s.base_sampler[key.sampler_key] = value_text(key, v, where, "base.sampler." + k);
    }
    unit.erase("sampler");
  }
  try {
    s.base = rtl::unit_config_from_json(json_dump(unit), "base");
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", quote_input(s.path, 100), e.what()));
  }
}

size_t key_index(Spec& s, const std::string& name, const Where& where, const std::string& where_key) {
  for (size_t i = 0; i < s.keys.size(); ++i)
    if (s.keys[i].name == name) return i;
  s.keys.push_back(make_key(name, where, where_key));
  return s.keys.size() - 1;
}

void parse_grid(const Json& j, Spec& s, const Where& where) {
  if (!j.is_object()) throw where("grid", "must be an object of key: [values]");
  for (const auto& [name, values] : j.items()) {
    const std::string wk = "grid." + name;
    s.keys.push_back(make_key(name, where, wk));
    if (!values.is_array()) throw where(wk, "must be a list of values");
    if (values.empty()) throw where(wk, "is an empty list (a grid key needs at least one value)");
    std::vector<std::string> texts;
    texts.reserve(values.size());
    std::unordered_set<std::string> seen;  // linear time: a key may hold 10^6 values (TFU-S E10)
    seen.reserve(values.size());
    for (const Json& v : values) {
      std::string t = value_text(s.keys.back(), v, where, wk);
      if (!seen.insert(t).second) throw where(wk, fmt::format("value {} is listed twice", quote_input(t, 40)));
      texts.push_back(std::move(t));
    }
    s.grid_values.push_back(std::move(texts));
  }
  s.grid_keys = s.keys.size();
}

void parse_points(const Json& j, Spec& s, const Where& where) {
  if (!j.is_array()) throw where("points", "must be a list of objects");
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string wp = fmt::format("points[{}]", i);
    if (!j[i].is_object() || j[i].empty()) throw where(wp, "must be a non-empty object of key: value");
    ExplicitPoint p;
    for (const auto& [name, v] : j[i].items()) {
      const std::string wk = wp + "." + name;
      if (name == "scene") {
        if (!v.is_string() || v.get<std::string>().empty()) throw where(wk, "must be a scene name or path");
        p.scene = v.get<std::string>();
      } else if (name == "filter") {
        if (!v.is_string()) throw where(wk, "must be a filter name");
        p.filter = canonical_filter(v.get<std::string>(), where, wk);
      } else {
        const size_t k = key_index(s, name, where, wk);
        p.values.emplace_back(k, value_text(s.keys[k], v, where, wk));
      }
    }
    s.points.push_back(std::move(p));
  }
}

std::string resolve_scene(const Spec& s, const std::string& scene) {
  const auto& names = builtin_scene_names();
  if (q3::is_level_scene(scene) || std::find(names.begin(), names.end(), scene) != names.end()) return scene;
  const fs::path p(scene);
  return p.is_relative() && !s.dir.empty() ? (fs::path(s.dir) / p).lexically_normal().string() : scene;
}

void apply(const Key& key, const std::string& text, Point& p) {
  if (key.run) {
    if (key.name == "raster") p.raster = raster_order_from_name(text);
    if (key.name == "unit_tiles") p.unit_tiles = unit_tiles_from_name(text);
    if (key.name == "units") p.units = std::stoi(text);
    if (key.name == "texture_layout") p.texture_layout = text;
    if (key.name == "spawn") p.spawn = std::stoi(text);
    if (key.name == "width") p.width = std::stoi(text);
    if (key.name == "height") p.height = std::stoi(text);
  } else if (key.field) {
    key.field->set_text(p.config, text);
  } else {
    p.sampler[key.sampler_key] = text;
  }
}

// The text of run key `name` at point p.
std::string run_value(const std::string& name, const Point& p) {
  if (name == "raster") return raster_order_name(p.raster);
  if (name == "unit_tiles") return unit_tiles_name(p.unit_tiles);
  if (name == "units") return std::to_string(p.units);
  if (name == "texture_layout") return p.texture_layout;
  if (name == "spawn") return p.spawn < 0 ? std::string() : std::to_string(p.spawn);
  return std::to_string(name == "width" ? p.width : p.height);
}

}  // namespace

Spec parse_spec(const std::string& text, const std::string& path) {
  const Where where{path};
  Json j;
  try {
    j = Json::parse(text);
  } catch (const Json::parse_error& e) {
    throw InputError(fmt::format("{}: malformed JSON (byte {})", quote_input(path, 100), e.byte));
  } catch (const Json::exception& e) {
    throw InputError(fmt::format("{}: malformed JSON: {}", quote_input(path, 100), quote_input(e.what(), 100)));
  }
  if (!j.is_object()) throw InputError(fmt::format("{}: expected a JSON object", quote_input(path, 100)));
  Spec s;
  s.path = path;
  s.text = text;
  s.dir = fs::path(path).parent_path().string();
  static const std::set<std::string> kSpecKeys{"scenes", "filters", "width", "height", "units", "raster", "unit_tiles", "texture_layout",
                                               "game_dir", "node", "base", "grid", "points"};
  if (const auto k = first_unknown_key(j, kSpecKeys))
    throw where(*k, "unknown key (expected scenes, filters, width, height, units, raster, unit_tiles, texture_layout, game_dir, node, "
                    "base, grid, points)");
  if (!j.contains("scenes")) throw where("scenes", "missing (a list of scene names, files or oa: levels)");
  s.scenes = string_list(j["scenes"], "scenes", where);
  s.filters = {kSceneFilter};
  if (j.contains("filters")) {
    s.filters.clear();
    for (const std::string& f : string_list(j["filters"], "filters", where)) {
      std::string c = canonical_filter(f, where, "filters");
      for (const std::string& seen : s.filters)
        if (seen == c) throw where("filters", fmt::format("'{}' is listed twice (as {})", quote_input(f, 40), c));
      s.filters.push_back(std::move(c));
    }
  }
  if (j.contains("width")) s.width = int_member(j["width"], "width", 0, kMaxRenderSize, where);
  if (j.contains("height")) s.height = int_member(j["height"], "height", 0, kMaxRenderSize, where);
  if (s.width == 1 || s.height == 1) throw where(s.width == 1 ? "width" : "height", "must be 0 (the scene's own) or 2..8192");
  if (j.contains("units")) s.units = int_member(j["units"], "units", 1, 256, where);
  for (const char* key : {"raster", "unit_tiles", "texture_layout"}) {
    if (!j.contains(key)) continue;
    const std::string value = run_value_text(make_key(key, where, key), j[key], where, key);
    if (std::string(key) == "raster") s.raster = raster_order_from_name(value);
    else if (std::string(key) == "unit_tiles") s.unit_tiles = unit_tiles_from_name(value);
    else s.texture_layout = value;
  }
  if (j.contains("game_dir")) {
    if (!j["game_dir"].is_string()) throw where("game_dir", "must be a directory path");
    s.game_dir = j["game_dir"].get<std::string>();
  }
  if (j.contains("node")) {
    if (!j["node"].is_string()) throw where("node", fmt::format("must be a node name ({})", rtl::kNodeNames));
    try {
      s.node = rtl::node_from_name(j["node"].get<std::string>());
    } catch (const InputError& e) {
      throw where("node", e.what());
    }
  }
  if (j.contains("base")) parse_base(j["base"], s, where);
  if (j.contains("grid")) parse_grid(j["grid"], s, where);
  if (j.contains("points")) parse_points(j["points"], s, where);
  if (s.grid_keys == 0 && s.points.empty())
    throw where("grid", "empty: give at least one grid key with values, or explicit points");
  return s;
}

Spec load_spec(const std::string& path) {
  const std::string label = fmt::format("sweep spec '{}'", quote_input(path, 200));
  std::string text = read_input_file(path, label, kMaxTextInputBytes);  // a regular file, bounded (TFU-S E5)
  note_run_input(path, label);  // never an output of the run
  return parse_spec(text, path);
}

std::vector<Point> expand(const Spec& s) {
  const Where where{s.path};
  // Every distinct scene opened once (errors name it) and fingerprinted for the point ids.
  std::map<std::string, std::string> fingerprint;
  const auto scene_fp = [&](const std::string& path, int width, int height, const std::string& where_key) {
    const std::string fp_key = fmt::format("{}\n{}x{}", path, width, height);
    auto it = fingerprint.find(fp_key);
    if (it != fingerprint.end()) return it->second;
    try {
      (void)open_scene({path, width, height, s.game_dir});
      return fingerprint[fp_key] = json_dump(scene_fingerprint({path, width, height, s.game_dir}));
    } catch (const InputError& e) {
      throw where(where_key, e.what());
    }
  };
  struct Proto {
    std::string scene, filter;
    std::vector<std::pair<size_t, std::string>> values;
    std::string where_key;
  };
  std::vector<Proto> protos;
  size_t grid_size = 1;
  for (const auto& v : s.grid_values) {
    grid_size *= v.size();
    if (grid_size > kMaxPoints) throw where("grid", fmt::format("more than {} points", kMaxPoints));
  }
  if (s.grid_keys == 0) grid_size = 0;
  if (grid_size * s.scenes.size() * s.filters.size() + s.points.size() * s.scenes.size() * s.filters.size() > kMaxPoints)
    throw where("grid", fmt::format("more than {} points", kMaxPoints));
  for (const std::string& scene : s.scenes)
    for (const std::string& filter : s.filters)
      for (size_t g = 0; g < grid_size; ++g) {
        Proto p{scene, filter, {}, "grid"};
        size_t rest = g;
        for (size_t k = s.grid_keys; k-- > 0;) {  // the last key varies fastest
          const size_t n = s.grid_values[k].size();
          p.values.emplace_back(k, s.grid_values[k][rest % n]);
          rest /= n;
        }
        std::reverse(p.values.begin(), p.values.end());
        protos.push_back(std::move(p));
      }
  for (size_t i = 0; i < s.points.size(); ++i) {
    const ExplicitPoint& e = s.points[i];
    for (const std::string& scene : e.scene.empty() ? s.scenes : std::vector<std::string>{e.scene})
      for (const std::string& filter : e.filter.empty() ? s.filters : std::vector<std::string>{e.filter})
        protos.push_back({scene, filter, e.values, fmt::format("points[{}]", i)});
  }
  std::vector<Point> points;
  std::map<std::string, size_t> seen_ids;
  for (const Proto& pr : protos) {
    Point p;
    p.index = points.size();
    p.scene = pr.scene;
    p.scene_path = resolve_scene(s, pr.scene);
    p.filter = pr.filter;
    p.config = s.base;
    p.sampler = s.base_sampler;
    p.width = s.width;
    p.height = s.height;
    p.units = s.units;
    p.raster = s.raster;
    p.unit_tiles = s.unit_tiles;
    p.texture_layout = s.texture_layout;
    for (const auto& [k, text] : pr.values) apply(s.keys[k], text, p);
    if (p.spawn >= 0) {  // the level scene at this spawn point: oa:MAP:SPAWN
      if (!q3::is_level_scene(p.scene_path))
        throw where(pr.where_key, fmt::format("point {}: spawn applies to oa: level scenes, not to '{}'", p.index, quote_input(p.scene, 60)));
      const q3::LevelSceneSpec level = q3::parse_level_scene(p.scene_path, "scene");
      p.scene_path = fmt::format("{}{}:{}", q3::kLevelScenePrefix, level.level, p.spawn);
    }
    for (const Key& k : s.keys)
      p.values.push_back(k.run     ? run_value(k.name, p)
                         : k.field ? k.field->value_text(p.config)
                                   : (p.sampler.contains(k.sampler_key) ? p.sampler.at(k.sampler_key) : ""));
    for (std::string& v : p.values)
      if (v.size() >= 2 && v.front() == '"') v = v.substr(1, v.size() - 2);  // names: without JSON quotes
    try {
      p.config.validate();
    } catch (const InputError& e) {
      throw where(pr.where_key, fmt::format("point {} ({}): {}", p.index, describe(s, p), e.what()));
    }
    nlohmann::json id = {{"scene", p.scene_path},
                         {"scene_source", scene_fp(p.scene_path, p.width, p.height, pr.where_key == "grid" ? "scenes" : pr.where_key + ".scene")},
                         {"filter", p.filter},
                         {"width", p.width},
                         {"height", p.height},
                         {"units", p.units},
                         {"unit_config", nlohmann::json::parse(rtl::unit_config_to_json(p.config))},
                         {"sampler", p.sampler}};
    // The raster order and the unit tiles enter the id only when they are not the defaults, so that
    // every point of a spec that sets neither keeps the id (and result file) it always had.
    if (!(p.raster == RasterOrder{})) id["raster"] = raster_order_name(p.raster);
    if (!(p.unit_tiles == UnitTiles{})) id["unit_tiles"] = unit_tiles_name(p.unit_tiles);
    if (p.texture_layout != "own") id["texture_layout"] = p.texture_layout;
    if (s.node != Spec{}.node) id["node"] = rtl::node_name(s.node);  // the cost columns differ; default-node ids unchanged
    p.id = hex64(fnv1a64(json_dump(id)));
    if (const auto [it, fresh] = seen_ids.emplace(p.id, p.index); !fresh)
      throw where(pr.where_key, fmt::format("point {} ({}) repeats point {}", p.index, describe(s, p), it->second));
    points.push_back(std::move(p));
  }
  return points;
}

std::string describe(const Spec& s, const Point& p) {
  std::string d = fmt::format("{} {}", p.scene, p.filter);
  for (size_t k = 0; k < s.keys.size() && k < p.values.size(); ++k)
    if (!p.values[k].empty()) d += fmt::format(", {}={}", s.keys[k].name, p.values[k]);
  return d;
}

}  // namespace tfu::sweep
