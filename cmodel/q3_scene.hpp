// A Quake III level as a tfu::Scene: every drawn face with the material the game gives it (its
// default shaders; shader scripts are not read), lit and culled as the game shows it.
// docs/real-frames.md, "The level as a scene", has the rules and the engine code they follow.
//
//   meshes     one per (base texture, light map) pair, in the order of its first drawn face; each
//              holds the triangles of its faces in BSP face order (vertices copied: uv = uv0,
//              uv1 = the light-map coordinates, colour = the vertex colour, shifted as below, alpha
//              255: the default shaders draw opaque)
//   light-mapped faces (LevelSceneOptions::light = Game, the default)
//     stage 0  the base texture: LINEAR_MIPMAP_LINEAR, repeat in s and t, its box MIP chain, replace
//     stage 1  the light map on UV set 1, shifted at load (shift_lighting: Quake III's
//              R_ColorShiftLightingBytes), LINEAR (no MIP chain), clamp to edge, modulate
//     display  Scene::display_shift = the overbright bits the gamma ramp takes (R_SetColorMappings)
//   vertex-lit faces (light-map index < 0; vertex = Colour, the default): one stage, the base
//              texture modulating the interpolated vertex colour (shifted like light maps): the
//              shader's rgbGen exactVertex; the display ramp as above
//   cull       CullWinding::CounterClockwise (cull = Back, the default): Quake III's default
//              shaders are "cull front" in its own terms (CT_FRONT_SIDED), which GL_Cull turns
//              into glCullFace(GL_FRONT) under glFrontFace(GL_CCW); its visible faces turn
//              clockwise on screen
//   camera     spawn_camera (q3_camera.hpp) with LevelSceneOptions::eye
//   size       kLevelSceneWidth x kLevelSceneHeight unless given
//   background kLevelSceneBackground, seen where the sky (skipped) would be (no display ramp)
// The earlier rules stay available: light = Double (the light map as stored, modulate with
// rgb_scale 2, no display ramp; vertex-lit faces with the white 1 x 1 light map), vertex = White,
// cull = None, eye = Spot.
//
// Texture names in trace headers: "oa:MAP:texture:NAME", "oa:MAP:lightmap:N" (as stored) and
// "oa:MAP:lightmap-shiftK:N" (shifted by K bits at load, K = 1..kMaxLightingShift).
//
// Scene names on the command line: "oa:MAP[:SPAWN][:KEY=VALUE...]" (SPAWN defaults to 0), e.g.
// oa:aggressor:3 or oa:aggressor:3:cull=none:light=double. Keys (defaults first): eye=rest|spot,
// light=game|double, vertex=colour|white, cull=back|none, mapoverbright=2 (r_mapOverBrightBits,
// 0..kMaxLightingShift), overbright=1 (r_overBrightBits, 0..2), gamma=hardware|none (none: no
// hardware gamma ramp, or a window: Quake III then takes no overbright bits, tr.overbrightBits 0),
// srgb=false|true (true: the base textures declared sRGB, below).
#pragma once

#include <array>
#include <string>

#include "cmodel/q3_camera.hpp"
#include "cmodel/q3_level.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/upload_compression.hpp"

namespace tfu::q3 {

inline constexpr const char* kLevelScenePrefix = "oa:";
inline constexpr size_t kMaxLevelNameLength = 48;  // "maps/NAME.bsp" within Quake III's 64-character paths
inline constexpr int kLevelSceneWidth = 1280, kLevelSceneHeight = 720;
inline constexpr std::array<double, 4> kLevelSceneBackground{0.35, 0.45, 0.6, 1.0};
inline constexpr int kMaxLightingShift = 4;

enum class LightRule { Game, Double };
enum class VertexLight { Colour, White };
enum class FaceCull { Back, None };

struct LevelSceneOptions {
  EyeRule eye = EyeRule::Rest;
  LightRule light = LightRule::Game;
  VertexLight vertex = VertexLight::Colour;
  FaceCull cull = FaceCull::Back;
  int map_overbright_bits = 2;  // r_mapOverBrightBits (ioquake3 default)
  int overbright_bits = 1;      // r_overBrightBits (ioquake3 default)
  bool hardware_gamma = true;   // fullscreen with a gamma ramp (glConfig.deviceSupportsGamma && isFullscreen)
  // The base textures declared sRGB (srgba8, docs/srgb.md): decoded to linear before filtering,
  // their MIP levels averaged in linear light. Light maps and vertex colours stay linear: they hold
  // light computed by the light compiler, which the load shift scales by powers of two and the
  // modulate stage multiplies with the surface colour; both are products of light, meaningful only
  // on linear values. False is the game's GL 1 renderer: every texture filtered as stored.
  bool srgb_textures = false;
  friend bool operator==(const LevelSceneOptions&, const LevelSceneOptions&) = default;
};

// tr.overbrightBits of R_SetColorMappings: r_overBrightBits with hardware gamma, clamped to 0..2
// (24-bit colour), else 0. The display ramp's shift.
int display_overbright_bits(const LevelSceneOptions& o);
// The load-time shift of light maps and vertex colours: r_mapOverBrightBits - tr.overbrightBits,
// at least 0 (the engine would shift by a negative count, undefined in C; the defaults never do).
int lighting_shift(const LevelSceneOptions& o);

// R_ColorShiftLightingBytes: r, g, b each shifted left by `shift`; if any exceeds 255, all three
// are scaled by 255 / max with integer division (the hue kept instead of saturating to white);
// alpha kept.
Rgba8 shift_lighting(Rgba8 c, int shift);
// Every texel of a light map through shift_lighting.
std::shared_ptr<const Texture> shifted_lightmap(const std::shared_ptr<const Texture>& lightmap, int shift);

struct LevelSceneSpec {
  std::string level;
  int spawn = 0;
  LevelSceneOptions options;
};

bool is_level_scene(const std::string& scene);  // starts with "oa:"
// Parses "oa:MAP[:SPAWN][:KEY=VALUE...]"; throws InputError naming `option` and the text.
LevelSceneSpec parse_level_scene(const std::string& scene, const std::string& option = "--scene");

inline constexpr int kLightmapOverbright = 2;  // rgb_scale of the light-map stage under LightRule::Double
// A level texture declared sRGB: level 0's codes as stored, format srgba8, the box MIP chain made
// again in linear light (generate_mipmaps on srgba8), as texture_with_params does for the texture key
// srgb. The one definition for level scenes (LevelSceneOptions::srgb_textures) and for traces that
// name a level texture with the key srgb.
std::shared_ptr<const Texture> srgb_declared(const std::shared_ptr<const Texture>& texture);

// `compress`: the base textures as the game uploads them (cmodel/upload_compression.hpp; the base
// stages' texture specs carry the key compress = its name); light maps stay uncompressed, as ioquake3
// uploads them (IMGFLAG_NO_COMPRESSION). The description then ends with the textures per format.
// With options.srgb_textures the base textures are declared sRGB first (srgb_declared; the base
// stages' texture specs carry the key srgb = true), then compressed with the format's sRGB variant.
Scene level_scene(const Level& level, int spawn, int width = kLevelSceneWidth, int height = kLevelSceneHeight,
                  const LevelSceneOptions& options = {}, const UploadCompression& compress = {});

}  // namespace tfu::q3
