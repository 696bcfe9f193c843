// Scene descriptions for the renderer (docs/renderer.md has the full JSON schema and an example).
//
// A scene is a JSON object: output size, camera, background colour and a list of meshes. Each mesh
// is generated from a primitive (quad, plane, cube, sphere, bezier_patch), placed by a transform
// (world = T R_z R_y R_x S p), and carries a material of 1 to 4 texture stages, each a texture
// (procedural or file), a sampler, a UV set (0, or the second set 1) and a texture environment
// (texenv.hpp) combining it with the stages before it.
// Every key is checked: an unknown key or a value of the wrong type throws InputError naming the
// key path ("scene.json: meshes[1].sampler: unknown key 'filtr'"). Malformed JSON throws
// InputError "FILE: line L, column C: message".
//
// The built-in scenes (cmodel/scenes/*.json) are compiled into the library at build time, so
// builtin_scene_names() / builtin_scene_json() work without the source tree.
#pragma once

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cmodel/bindings.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/procedural.hpp"
#include "cmodel/texenv.hpp"
#include "cmodel/texture.hpp"

namespace tfu {

inline constexpr int kMaxRenderSize = 8192;  // per side of the output image
// Largest magnitude of any number in a scene file (positions, UVs, camera, transform): far beyond
// any sensible scene, small enough that every product in the renderer stays finite and exact
// enough; a larger or non-finite value is an error naming the file and key.
inline constexpr double kMaxSceneMagnitude = 1e6;

struct Camera {
  glm::dvec3 position{0, 0, 3}, look_at{0, 0, 0}, up{0, 1, 0};
  double fov_y_deg = 45.0;
  double near_plane = 0.1, far_plane = 100.0;
};

struct Vertex {
  glm::dvec3 pos{};  // world space (after the mesh transform)
  glm::dvec2 uv{};   // texture coordinates (s, t), UV set 0
  glm::dvec2 uv1{};  // UV set 1 (e.g. a light map's own coordinates)
  Rgba8 colour{255, 255, 255, 255};  // the vertex's primary colour (glColor), read by Mesh::vertex_colour meshes
};

// Which triangles the renderer does not draw, by their winding as seen on the screen (GL
// GL_CULL_FACE: glFrontFace(GL_CCW) with glCullFace(GL_FRONT) culls the counter-clockwise ones).
enum class CullWinding { None, CounterClockwise, Clockwise };
inline constexpr EnumNames<CullWinding, 3> kCullWindingNames{
    "cull winding",
    {{{CullWinding::None, "none"}, {CullWinding::CounterClockwise, "ccw"}, {CullWinding::Clockwise, "cw"}}}};

// The display's gamma ramp as a left shift: each drawn colour channel becomes min(255, v << shift)
// (Quake III's R_SetColorMappings with r_gamma 1: the overbright bits of a hardware gamma ramp).
inline constexpr int kMaxDisplayShift = 2;

inline constexpr int kMaxStages = 4;

// One texture stage of a material.
struct TextureStage {
  TextureSpec spec;                        // "proc:text:1024" or a file path, with its keys
  std::shared_ptr<const Texture> texture;  // complete MIP chain (box, Lee & Jen Eq. 8) or the file's
  ColourFn truth;                          // analytic colour (procedural textures); empty for files
  SamplerDescriptor sampler;
  int uv_set = 0;                          // 0: Vertex::uv, 1: Vertex::uv1
  StageCombine combine{TexEnv::Replace, 1};
};

struct Mesh {
  std::string primitive;  // "quad", "plane", ...
  // Stage 0 combines with the interpolated vertex colour (perspective-correct, rounded to 8 bits
  // per channel) instead of white: the texture environment's primary colour.
  bool vertex_colour = false;
  std::vector<Vertex> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<TextureStage> stages;  // 1..kMaxStages, applied in order
};

struct Scene {
  std::string name;         // built-in name or file stem
  std::string description;  // free text (which paper figure the scene models)
  int width = 256, height = 256;
  Camera camera;
  std::array<double, 4> background{0, 0, 0, 1};
  std::vector<Mesh> meshes;
  CullWinding cull = CullWinding::None;  // triangles of this on-screen winding are not drawn
  int display_shift = 0;                 // 0..kMaxDisplayShift: the display's gamma ramp on drawn pixels
};

// The display's gamma ramp: rgb min(255, v << shift), alpha kept.
constexpr Rgba8 display_ramp(Rgba8 c, int shift) {
  const auto ramp = [shift](uint8_t v) { return static_cast<uint8_t>(std::min(255, int{v} << shift)); };
  return {ramp(c.r), ramp(c.g), ramp(c.b), c.a};
}

// Parses a scene. `source` names the input in error messages; relative texture file paths are
// resolved against `base_dir` (empty: the current directory).
Scene parse_scene(const std::string& json_text, const std::string& source, const std::string& base_dir = {});
// A built-in name (see builtin_scene_names()) or a path to a JSON file.
Scene load_scene(const std::string& name_or_path);

const std::vector<std::string>& builtin_scene_names();
// Throws InputError for an unknown name.
const std::string& builtin_scene_json(const std::string& name);
inline constexpr const char* kDefaultScene = "ground_plane";

// Mesh generators (object space, before the transform); exposed for tests.
Mesh make_quad_mesh(const std::array<glm::dvec3, 4>& corners, const std::array<glm::dvec2, 4>& uv);
Mesh make_plane_mesh(glm::dvec2 size, glm::dvec2 uv_repeat);           // y = 0 plane, centred
Mesh make_cube_mesh();                                                  // unit cube, centred
Mesh make_sphere_mesh(int segments_lon, int segments_lat);              // radius 0.5, lat/long uv
// Open cylinder of radius 0.5 around the z axis from z = 0 to z = -1 (a tunnel seen from inside):
// s = angle / 2 pi (angle from +x towards +y) times uv_repeat.x, t = -z times uv_repeat.y.
Mesh make_cylinder_mesh(int segments_around, int segments_along, glm::dvec2 uv_repeat);
Mesh make_bezier_patch_mesh(const std::array<glm::dvec3, 16>& control,  // row-major 4x4
                            int tessellation, glm::dvec2 uv_repeat);

}  // namespace tfu
