// Single-stage preview of a Quake III level as a tfu::Scene that render_scene draws: the base
// textures only (no lightmap), for checking the geometry and texture orientation by eye.
//
//   meshes   one per drawn texture, in the order of the texture's first drawn face; each holds the
//            triangles of that texture's faces in BSP face order (vertices copied, uv = uv0)
//   sampler  LINEAR_MIPMAP_LINEAR, repeat in s and t, the textures' box MIP chains
//   camera   spawn_camera (q3_camera.hpp)
//   size     kPreviewWidth x kPreviewHeight unless given
//   background  kPreviewBackground, seen where the sky (skipped) would be
//
// Scene names on the command line: "oa:MAP[:SPAWN]" (SPAWN defaults to 0), e.g. oa:aggressor:3.
#pragma once

#include <array>
#include <string>

#include "cmodel/q3_level.hpp"
#include "cmodel/scene.hpp"

namespace tfu::q3 {

inline constexpr const char* kLevelScenePrefix = "oa:";
inline constexpr size_t kMaxLevelNameLength = 48;  // "maps/NAME.bsp" within Quake III's 64-character paths
inline constexpr int kPreviewWidth = 1280, kPreviewHeight = 720;
inline constexpr std::array<double, 4> kPreviewBackground{0.35, 0.45, 0.6, 1.0};

struct LevelSceneSpec {
  std::string level;
  int spawn = 0;
};

bool is_level_scene(const std::string& scene);  // starts with "oa:"
// Parses "oa:MAP[:SPAWN]"; throws InputError naming `option` and the text.
LevelSceneSpec parse_level_scene(const std::string& scene, const std::string& option = "--scene");

Scene make_preview_scene(const Level& level, int spawn, int width = kPreviewWidth, int height = kPreviewHeight);

}  // namespace tfu::q3
