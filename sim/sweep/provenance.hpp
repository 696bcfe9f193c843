// Provenance of a result: what produced a statistics file, recorded in the file itself, so that a
// number can be traced to its tool version, unit configuration, scene, filter, resolution and
// command line, and the run repeated (docs/design-space.md, "Provenance").
//
// Every statistics JSON of `tfu sim --stats`, `tfu report` (results.json) and `tfu sweep` (one file
// per point) is {"provenance": {...}, "definitions": {...}, "counters": ..., "values": ...,
// "histograms": ..., "tables": ...}; provenance_json() documents the keys.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "cmodel/bindings.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/scene_source.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_config.hpp"
#include "rtl/kernel/kernel.hpp"

namespace tfu {

// The command line of this process, as main() received it (recorded in every statistics file).
void set_command_line(int argc, const char* const* argv);
const std::vector<std::string>& command_line();

// FNV-1a 64 (offset basis 14695981039346656037, prime 1099511628211) of a byte string, and its
// 16-digit lower-case hex form: the content hash of scene files and sweep points.
uint64_t fnv1a64(std::string_view bytes);
// The hash `h` continued over more bytes: fnv1a64(a + b) == fnv1a64_update(fnv1a64(a), b).
uint64_t fnv1a64_update(uint64_t h, std::string_view bytes);
std::string hex64(uint64_t v);
// The FNV-1a 64 of a file's bytes as hex, read through the input checks (cmodel/input_file.hpp: a
// regular file of at most `max_bytes`); InputError naming `what` and the path otherwise.
std::string file_fnv1a64(const std::string& path, const std::string& what, uint64_t max_bytes);

// What identifies a scene's source, by kind:
//   built-in  {"kind": "builtin", "name", "fnv1a64" (of the embedded JSON text)}
//   file      {"kind": "file", "path" (as given), "absolute", "bytes", "fnv1a64",
//              "texture_files": [{"path", "fnv1a64"}] for the textures that are files}
//   level     {"kind": "level", "name" (oa:MAP[:SPAWN][:KEY=VALUE...]), "map", "spawn", "game_dir",
//              "archives": [{"file", "bytes", "mtime"}] of every .pk3 in game_dir,
//              "sources": {"level": "ARCHIVE:maps/MAP.bsp", "textures": {NAME: "ARCHIVE:ENTRY" or
//              "fallback"} for every texture a drawn face uses}}
// Levels are fingerprinted by their archives' sizes and modification times, not by hashing
// ~140 MB of game data. Throws InputError for an unreadable file.
nlohmann::json scene_fingerprint(const SceneRequest& request);

// One run, as the statistics file records it.
struct RunRecord {
  std::string command;             // "sim", "report", "sweep"
  SceneRequest scene;              // as requested (width/height 0: the scene's own)
  bool has_scene = true;           // false: a request trace (`trace` names it)
  std::string trace;               // request-trace path (tfu sim --requests)
  std::string trace_fnv1a64;       // a trace that is no file (the Python module's arrays): its text's hash
  int width = 0, height = 0;       // the rendered resolution
  std::string filter = "scene";    // canonical filter name of the base stages, or "scene" (their own)
  Params sampler_overrides;        // further sampler keys of the base stages
  int units = 1;
  std::string raster = "scanline", unit_tiles = "round-robin:32";  // cmodel/raster_order.hpp
  std::string texture_layout = "own";  // every texture's layout override (own: none)
  const rtl::UnitConfig* config = nullptr;  // the whole effective configuration (nullptr: golden only)
  rtl::UnitEngine engine = rtl::UnitEngine::Recurrence;  // the cycle model's engine (with `config`)
  std::vector<std::string> textures;        // the frame's textures, "INDEX NAME"
};

// {"tool": "tfu", "version", "command", "command_line": [...]}: what every provenance starts with.
nlohmann::json tool_provenance(const std::string& command);

// {"tool": "tfu", "version", "command", "command_line": [...], "scene": scene_fingerprint or
//  {"kind": "trace", "path", "fnv1a64"}, "width", "height", "filter", "sampler_overrides", "units",
//  "raster", "unit_tiles" and "texture_layout" (each only when not scanline, round-robin:32, own), "textures", "unit_config": every field, defaults included (unit_config_to_json), "engine":
//  "recurrence" or "clocked"}; the last two only where a cycle model ran (`config`)
nlohmann::json provenance_json(const RunRecord& run);

// The textures of a frame as "INDEX NAME" (the statistics' table labels).
std::vector<std::string> frame_texture_names(const Frame& frame);
// The distinct texture sources of a scene's stages ("proc:checker:256", file paths, level textures).
std::vector<std::string> scene_texture_names(const Scene& scene);

// A scene name as a file-name part: built-in names as they are; a scene file's stem; other
// characters outside [A-Za-z0-9._-] (the ':' of oa:MAP:SPAWN) as '_'.
std::string scene_label(const std::string& scene);

// What the counters mean where a name alone could mislead ("pixels", the stall counters); written
// into every statistics file beside the counters.
nlohmann::json stats_definitions();

// The unit configuration JSON text of `text`: a statistics file's recorded
// provenance.unit_config, or `text` itself (a unit configuration, or malformed: the configuration
// reader reports it).
std::string unit_config_text(const std::string& text);

// A statistics file: {"provenance", "definitions"} and the statistics' own keys.
std::string stats_document(const sim::Stats& stats, const nlohmann::json& provenance);

// Writes `text` to `path` through OutputFiles with --force (cmodel/output_files.hpp: a temporary
// in the same directory, then rename, so a reader sees the old file, no file, or the whole new
// one; missing parent directories created; every write checked). For the files a sweep owns in its
// directory, which a resumed or collected sweep replaces. InputError naming `what` and the path.
void write_file_atomic(const std::string& path, const std::string& text, const std::string& what);

}  // namespace tfu
