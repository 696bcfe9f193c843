// The sweep specification and its points (docs/design-space.md, "The spec"):
//
//   {"scenes": ["ground_plane", "my_scene.json", "oa:aggressor:2"],   required, non-empty
//    "filters": ["LINEAR_MIPMAP_LINEAR", "bilinear", "scene"],        optional; default ["scene"]
//    "width": 512, "height": 384,                                     optional; 0: each scene's own
//    "units": 1, "game_dir": "...",                                   optional
//    "raster": "scanline", "unit_tiles": "round-robin:32",            optional (cmodel/raster_order.hpp)
//    "texture_layout": "own",                                         optional: linear, tiled or own
//    "node": "osu018",                                                optional; the cost columns' node
//                                                                     (rtl/cost_model.hpp, osu035 or osu018)
//    "base": {"memory": {"latency": 200}, "sampler": {"max_aniso": 4}},  optional unit config + base-stage sampler keys
//    "grid": {"cache.capacity_bytes": [4096, 16384], "sampler.edge_shape": ["static", "cross"]},
//    "points": [{"cache.ways": 16, "scene": "ground_plane", "filter": "LINEAR"}]}   optional
//
// Grid keys are the dotted unit-configuration fields (rtl/unit_config.hpp), "sampler.KEY" for a
// sampler key of every mesh's base stage (cmodel/bindings.hpp), or a run key (kRunKeys), whose
// defaults are the spec's top-level keys of the same names ("spawn" has none: an oa: scene's own). The points are the cartesian product
// scenes x filters x grid (first grid key slowest), then every explicit point, which is crossed with
// the scenes and filters unless it names its own. A relative scene path is relative to the spec
// file's directory. Every problem is an InputError "SPEC: KEY: ..." naming the key.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "cmodel/bindings.hpp"
#include "cmodel/raster_order.hpp"
#include "rtl/cost_model.hpp"
#include "rtl/unit_config.hpp"

namespace tfu::sweep {

inline constexpr const char* kSceneFilter = "scene";  // the filter column of a point that keeps the scene's filters

// One key a sweep varies: a unit-configuration field, a sampler key of the base stages or a run key.
struct Key {
  std::string name;                       // "cache.ways", "sampler.max_aniso", "raster"
  const rtl::UnitField* field = nullptr;  // the unit field; nullptr for a sampler or run key
  std::string sampler_key;                // "max_aniso" (sampler keys only)
  bool run = false;                       // a run key (kRunKeys)
};

// The run keys, as they are named in a spec's top level and grid: the units, the render size, the
// raster order, the tiles' distribution over units, the layout of every texture ("linear", "tiled" or
// "own": each texture's), and the spawn point of oa: level scenes.
inline constexpr const char* kRunKeys[] = {"units", "width", "height", "raster", "unit_tiles", "texture_layout", "spawn"};

struct ExplicitPoint {
  std::vector<std::pair<size_t, std::string>> values;  // key index, value text
  std::string scene, filter;                           // empty: every spec scene / filter
};

struct Spec {
  std::string path, dir;                // the spec file as given; its directory (scene paths)
  std::vector<std::string> scenes;      // as given
  std::vector<std::string> filters;     // canonical names (filter_mode_name) or kSceneFilter
  int width = 0, height = 0, units = 1;  // the defaults of the run keys
  RasterOrder raster;
  UnitTiles unit_tiles;
  std::string texture_layout = "own";
  std::string game_dir;
  rtl::Node node = rtl::Node::Osu018;   // the standard-cell node of the cost columns
  rtl::UnitConfig base;
  Params base_sampler;
  std::vector<Key> keys;                // the grid's keys in spec order, then keys only explicit points set
  size_t grid_keys = 0;
  std::vector<std::vector<std::string>> grid_values;  // per grid key, value texts
  std::vector<ExplicitPoint> points;
  std::string text;                     // the spec file's text
};

// Parses a spec; `path` names it in errors and locates relative scene paths.
Spec parse_spec(const std::string& text, const std::string& path);
Spec load_spec(const std::string& path);  // InputError if unreadable

struct Point {
  size_t index = 0;
  std::string id;               // 16 hex digits: FNV-1a 64 of what the point runs (its result file's name)
  std::string scene;            // as in the spec
  std::string scene_path;       // built-in and oa: names as given; files resolved against Spec::dir
  std::string filter;           // canonical name or kSceneFilter
  rtl::UnitConfig config;
  Params sampler;               // base-stage sampler overrides (base, then the point's)
  int width = 0, height = 0, units = 1;  // the run keys (the spec's, then the point's)
  RasterOrder raster;
  UnitTiles unit_tiles;
  std::string texture_layout = "own";  // linear, tiled or own (each texture's)
  int spawn = -1;                      // -1: the scene as named; else the oa: level's spawn point
  std::vector<std::string> values;  // per Spec::keys: the value the point runs with ("" for an unset sampler key)
};

// Every point, each validated (its unit configuration, its sampler keys on a default sampler, its
// scene opened once per distinct scene), before any runs. `scene_id` hashes the scenes' sources
// into the ids (a changed scene file gives new ids). InputError names the point and the key.
std::vector<Point> expand(const Spec& spec);

// A point's keys as "key=value, ..." (progress lines, errors).
std::string describe(const Spec& spec, const Point& p);

}  // namespace tfu::sweep
