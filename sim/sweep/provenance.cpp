#include "sim/sweep/provenance.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/json_output.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/q3_archives.hpp"
#include "cmodel/q3_scene.hpp"
#include "cmodel/scene.hpp"
#include "sim/sweep/version.hpp"

namespace tfu {
namespace {

namespace fs = std::filesystem;

std::vector<std::string>& command_line_storage() {
  static std::vector<std::string> args;
  return args;
}

// The FNV-1a hash of an input file read in blocks, through the input checks (a regular file of at
// most `max_bytes`: a FIFO or /dev/zero named by a scene is refused, never hashed forever).
uint64_t file_hash(const std::string& path, const std::string& label, uint64_t max_bytes) {
  InputFile in(path, label, max_bytes);
  uint64_t h = fnv1a64({});
  std::string block(1 << 16, '\0');
  while (in.stream()) {
    in.stream().read(block.data(), static_cast<std::streamsize>(block.size()));
    h = fnv1a64_update(h, std::string_view(block.data(), static_cast<size_t>(in.stream().gcount())));
  }
  return h;
}

std::string absolute_text(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::absolute(path, ec);
  return ec ? path : p.lexically_normal().string();
}

// The .pk3 archives of a game directory: name, size and modification time (seconds since the epoch).
// Which archive entry the level and each texture it draws came from: {"level": "pak1-maps.pk3:maps/X.bsp",
// "textures": {NAME: "ARCHIVE:ENTRY", or "fallback" for a name with no image}}.
nlohmann::json level_sources(const SceneRequest& r) {
  const auto level = requested_level(r);
  nlohmann::json textures = nlohmann::json::object();
  for (const q3::LevelTexture& t : level->textures)
    if (t.faces_drawn > 0) textures[t.name] = t.fallback ? std::string("fallback") : t.source;
  return {{"level", level->source}, {"textures", textures}};
}

nlohmann::json archive_list(const std::string& dir) {
  nlohmann::json list = nlohmann::json::array();
  std::error_code ec;
  std::vector<fs::path> pk3;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && e.path().extension() == ".pk3") pk3.push_back(e.path());
  std::sort(pk3.begin(), pk3.end());
  for (const fs::path& p : pk3) {
    const auto mtime = fs::last_write_time(p, ec);
    const auto secs = std::chrono::duration_cast<std::chrono::seconds>(
        std::chrono::file_clock::to_sys(mtime).time_since_epoch()).count();
    list.push_back({{"file", p.filename().string()}, {"bytes", fs::file_size(p, ec)}, {"mtime", secs}});
  }
  return list;
}

// Texture sources of a scene file that are files (relative to the scene's directory).
nlohmann::json texture_files(const Scene& scene, const std::string& scene_path) {
  nlohmann::json list = nlohmann::json::array();
  std::vector<std::string> seen;
  const fs::path dir = fs::path(scene_path).parent_path();
  for (const Mesh& mesh : scene.meshes)
    for (const TextureStage& stage : mesh.stages) {
      const std::string& src = stage.spec.source;
      if (src.empty() || src.rfind("proc:", 0) == 0 || std::find(seen.begin(), seen.end(), src) != seen.end()) continue;
      seen.push_back(src);
      fs::path p(src);
      std::error_code ec;
      if (!fs::is_regular_file(p, ec) && p.is_relative()) p = dir / p;
      if (fs::is_regular_file(p, ec)) list.push_back({{"path", src}, {"fnv1a64", file_fnv1a64(p.string(), "texture", kMaxImageBytes)}});
    }
  return list;
}

}  // namespace

void set_command_line(int argc, const char* const* argv) {
  auto& args = command_line_storage();
  args.assign(argv, argv + argc);
}

const std::vector<std::string>& command_line() { return command_line_storage(); }

uint64_t fnv1a64_update(uint64_t h, std::string_view bytes) {
  for (const char c : bytes) h = (h ^ static_cast<uint8_t>(c)) * 1099511628211ull;
  return h;
}

uint64_t fnv1a64(std::string_view bytes) { return fnv1a64_update(14695981039346656037ull, bytes); }

std::string hex64(uint64_t v) { return fmt::format("{:016x}", v); }

std::string file_fnv1a64(const std::string& path, const std::string& what, uint64_t max_bytes) {
  return hex64(file_hash(path, fmt::format("{} {}", what, quoted_path(path)), max_bytes));
}

nlohmann::json scene_fingerprint(const SceneRequest& r) {
  if (q3::is_level_scene(r.name)) {
    const q3::LevelSceneSpec spec = q3::parse_level_scene(r.name);
    const std::string dir = q3::openarena_dir(r.game_dir);
    return {{"kind", "level"},
            {"name", r.name},
            {"map", spec.level},
            {"spawn", spec.spawn},
            {"game_dir", dir},
            {"archives", archive_list(dir)},
            {"sources", level_sources(r)}};
  }
  const auto& names = builtin_scene_names();
  if (std::find(names.begin(), names.end(), r.name) != names.end())
    return {{"kind", "builtin"}, {"name", r.name}, {"fnv1a64", hex64(fnv1a64(builtin_scene_json(r.name)))}};
  const std::string bytes = read_input_file(r.name, fmt::format("scene {}", quoted_path(r.name)), kMaxTextInputBytes);
  nlohmann::json j = {{"kind", "file"},
                      {"path", r.name},
                      {"absolute", absolute_text(r.name)},
                      {"bytes", bytes.size()},
                      {"fnv1a64", hex64(fnv1a64(bytes))}};
  j["texture_files"] = texture_files(load_scene(r.name), r.name);
  return j;
}

nlohmann::json tool_provenance(const std::string& command) {
  return {{"tool", "tfu"}, {"version", tool_version()}, {"command", command}, {"command_line", command_line()}};
}

nlohmann::json provenance_json(const RunRecord& run) {
  nlohmann::json j = tool_provenance(run.command);
  if (run.has_scene) {
    j["scene"] = scene_fingerprint(run.scene);
  } else {
    const std::string hash =
        run.trace_fnv1a64.empty() ? file_fnv1a64(run.trace, "--requests", kMaxTraceBytes) : run.trace_fnv1a64;
    j["scene"] = {{"kind", "trace"}, {"path", run.trace}, {"fnv1a64", hash}};
  }
  j["width"] = run.width;
  j["height"] = run.height;
  j["filter"] = run.filter;
  j["sampler_overrides"] = nlohmann::json::object();
  for (const auto& [k, v] : run.sampler_overrides) j["sampler_overrides"][k] = v;
  j["units"] = run.units;
  if (run.raster != "scanline") j["raster"] = run.raster;
  if (run.unit_tiles != "round-robin:32") j["unit_tiles"] = run.unit_tiles;
  if (run.texture_layout != "own") j["texture_layout"] = run.texture_layout;
  j["textures"] = run.textures;
  if (run.config) {
    j["unit_config"] = nlohmann::json::parse(rtl::unit_config_to_json(*run.config));
    j["engine"] = rtl::unit_engine_name(run.engine);
  }
  return j;
}

std::vector<std::string> frame_texture_names(const Frame& frame) {
  std::vector<std::string> names;
  for (size_t t = 0; t < frame.textures.size(); ++t) names.push_back(fmt::format("{} {}", t, frame.textures[t].name));
  return names;
}

std::vector<std::string> scene_texture_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const Mesh& mesh : scene.meshes)
    for (const TextureStage& stage : mesh.stages)
      if (std::find(names.begin(), names.end(), stage.spec.source) == names.end()) names.push_back(stage.spec.source);
  return names;
}

std::string scene_label(const std::string& scene) {
  const auto& builtin = builtin_scene_names();
  std::string s = scene;
  if (std::find(builtin.begin(), builtin.end(), scene) == builtin.end() && !q3::is_level_scene(scene))
    s = fs::path(scene).stem().string();
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
  return s.empty() ? std::string("scene") : s;
}

nlohmann::json stats_definitions() {
  return {
      {"pixels", "requests: every pixel of every shaded 2x2 quad, helper pixels outside the triangle included, "
                 "once per material stage"},
      {"stalls", "per unit and cycle, at the texel cache stage; stall_cache_miss (miss-FIFO head waits for memory) and "
                 "stall_backpressure (next block full) exclude each other; stall_bank_conflict (tag port held by a "
                 "multi-cycle footprint) is counted on the input side and may fall in the same cycle as either: the three "
                 "overlap and do not add up to the stalled cycles"},
      {"cycles", "the slowest unit's; every other counter is summed over units"},
  };
}

std::string unit_config_text(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_object() && j.contains("provenance") && j["provenance"].is_object() && j["provenance"].contains("unit_config"))
    return json_dump(j["provenance"]["unit_config"]);
  return text;
}

std::string stats_document(const sim::Stats& stats, const nlohmann::json& provenance) {
  nlohmann::json j = nlohmann::json::parse(stats.json_text());
  j["provenance"] = provenance;
  j["definitions"] = stats_definitions();
  return json_dump(j, 2) + "\n";
}

void write_file_atomic(const std::string& path, const std::string& text, const std::string& what) {
  OutputFiles out(/*force=*/true);  // the sweep's own files in its own directory: replaced
  out.add(what, path).stream() << text;
  out.commit();
}

}  // namespace tfu
