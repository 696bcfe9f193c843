// A Quake III level as a tfu::Scene: every drawn face with the material the game gives it, base
// texture x light map, as the game draws it.
//
//   meshes     one per (base texture, light map) pair, in the order of its first drawn face; each
//              holds the triangles of its faces in BSP face order (vertices copied: uv = uv0,
//              uv1 = the light-map coordinates)
//   stage 0    the base texture: LINEAR_MIPMAP_LINEAR, repeat in s and t, its box MIP chain, replace
//   stage 1    the light map on UV set 1: LINEAR (no MIP chain: light maps are magnified), clamp to
//              edge, modulate, rgb_scale 2: Quake III's overbright factor (r_mapOverBrightBits 2
//              with the usual gamma ramp shifts light-map texels left by one bit, i.e. x 2 clamped)
//   camera     spawn_camera (q3_camera.hpp)
//   size       kLevelSceneWidth x kLevelSceneHeight unless given
//   background kLevelSceneBackground, seen where the sky (skipped) would be
// Texture names in trace headers: "oa:MAP:texture:NAME" and "oa:MAP:lightmap:N".
//
// Scene names on the command line: "oa:MAP[:SPAWN]" (SPAWN defaults to 0), e.g. oa:aggressor:3.
#pragma once

#include <array>
#include <string>

#include "cmodel/q3_level.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/upload_compression.hpp"

namespace tfu::q3 {

inline constexpr const char* kLevelScenePrefix = "oa:";
inline constexpr size_t kMaxLevelNameLength = 48;  // "maps/NAME.bsp" within Quake III's 64-character paths
inline constexpr int kLevelSceneWidth = 1280, kLevelSceneHeight = 720;
inline constexpr std::array<double, 4> kLevelSceneBackground{0.35, 0.45, 0.6, 1.0};

struct LevelSceneSpec {
  std::string level;
  int spawn = 0;
};

bool is_level_scene(const std::string& scene);  // starts with "oa:"
// Parses "oa:MAP[:SPAWN]"; throws InputError naming `option` and the text.
LevelSceneSpec parse_level_scene(const std::string& scene, const std::string& option = "--scene");

inline constexpr int kLightmapOverbright = 2;  // rgb_scale of the light-map stage
// `compress`: the base textures as the game uploads them (cmodel/upload_compression.hpp; the base
// stages' texture specs carry the key compress = its name); light maps stay uncompressed, as ioquake3
// uploads them (IMGFLAG_NO_COMPRESSION). The description then ends with the textures per format.
Scene level_scene(const Level& level, int spawn, int width = kLevelSceneWidth, int height = kLevelSceneHeight,
                  const UploadCompression& compress = {});

}  // namespace tfu::q3
