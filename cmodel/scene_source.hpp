// Every scene by name, as the command line gives it: a built-in scene, a scene JSON file, or an
// OpenArena level "oa:MAP[:SPAWN]" (cmodel/q3_scene.hpp). One entry point for `tfu render`,
// `tfu sim`, `tfu report` and the sweep, so that each accepts every kind.
//
// Size: a JSON scene keeps its own width and height unless the request gives them; a level is
// built at the given size, else 1280 x 720 (its camera's aspect ratio depends on it).
// Levels are loaded once per process (the game archives, each level and its decoded textures stay
// cached: several spawn points, modes or sweep points of one run load a level once).
#pragma once

#include <memory>
#include <string>

#include "cmodel/q3_level.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/upload_compression.hpp"

namespace tfu {

struct SceneRequest {
  std::string name;      // built-in name, JSON path, or oa:MAP[:SPAWN]
  int width = 0, height = 0;  // 0: the scene's own
  std::string game_dir;  // OpenArena data (empty: $TFU_OPENARENA_DIR or the Debian path)
};

// `compress`: a level's base textures compressed as the game uploads them (q3::level_scene;
// cmodel/upload_compression.hpp); InputError for any other scene unless it is none (a scene file's
// textures carry their own compress key).
Scene open_scene(const SceneRequest& request, const UploadCompression& compress = {});

// The level of an "oa:MAP[:SPAWN]" request (loaded once, cached), null for any other scene.
std::shared_ptr<const q3::Level> requested_level(const SceneRequest& request);

// The level MAP of the game data in `game_dir` (cached for the process; thread-safe).
std::shared_ptr<const q3::Level> cached_level(const std::string& game_dir, const std::string& map);

// A texture of a level as trace headers name it: "oa:MAP:texture:NAME" or "oa:MAP:lightmap:N".
// Throws InputError naming `where` when the level or the texture does not exist.
std::shared_ptr<const Texture> level_texture(const std::string& spec, const std::string& where,
                                             const std::string& game_dir = {});

}  // namespace tfu
