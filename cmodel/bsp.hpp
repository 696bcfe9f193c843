// Quake III BSP files (IBSP version 46, as written by q3map / q3map2): the lumps the level loader
// reads, parsed and checked. docs/real-frames.md lists every field and how it is used.
//
// File layout (little-endian): magic "IBSP", int32 version 46, then 17 directory entries
// {int32 offset, int32 length}; lump k is the byte range [offset, offset + length) of the file.
// Lumps read here (record size in bytes):
//   0  entities    text: { "key" "value" ... } blocks (parsed by parse_entities)
//   1  textures    72: char name[64] (NUL-terminated), int32 surface flags, int32 content flags
//   2  planes      16: float normal[3], float dist (points p with dot(normal, p) = dist)
//   7  models      40: float mins[3], maxs[3]; int32 first_face, face_count, first_brush, brush_count
//                      (model 0 is the world; the others are brush entities: doors, platforms)
//   8  brushes     12: int32 first_side, side_count, texture (its content flags are the brush's)
//   9  brush sides 8:  int32 plane, texture
//   10 vertices    44: float position[3], float uv[2] (base), float lightmap_uv[2], float normal[3],
//                      uint8 colour[4] (RGBA)
//   11 meshverts   4:  int32, an offset added to the face's first vertex
//   13 faces       104: int32 texture, effect, type, first_vertex, vertex_count, first_meshvert,
//                      meshvert_count, lightmap, lightmap_start[2], lightmap_size[2]; float
//                      lightmap_origin[3], lightmap_vecs[2][3], normal[3]; int32 patch_size[2]
//   14 lightmaps   49152: 128 x 128 RGB8, row-major, row 0 first
// Planes, models, brushes and brush sides are the collision world (q3_collision.hpp: where a
// player spawned at a spot comes to rest). The other lumps (nodes, leaves, effects, light volumes,
// visibility) are only bounds-checked.
//
// Checks (each failure is an InputError "SOURCE: lump N (name): what", one line): the magic and
// version; every lump inside the file; each read lump a whole number of records; every count
// below kMaxBspRecords; finite vertex floats (except the lightmap uv, which q3map2 leaves NaN on
// some vertices of vertex-lit faces: set to 0 and flagged, an error only on a face with a
// lightmap); per face: texture index inside lump 1, type 1..4,
// vertex range inside lump 10, meshvert range inside lump 11, meshvert_count a multiple of 3,
// every meshvert inside the face's own vertex range, lightmap index < the lightmap count (negative:
// vertex-lit), patch control size odd and 3..kMaxPatchControlSize with width x height vertices;
// plane floats finite within +-kMaxSceneMagnitude and the normal of unit length (+-1e-3); per
// brush: side range inside lump 9, texture inside lump 1; per side: plane inside lump 2, texture
// inside lump 1 (Quake III's CMod_LoadBrushSides refuses the same); per model: brush range inside
// lump 8 (its face range is not used).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace tfu::q3 {

inline constexpr int kBspVersion = 46;
inline constexpr int kLumpCount = 17;
inline constexpr int kLightmapSize = 128;  // lightmaps are 128 x 128 RGB8
inline constexpr int64_t kMaxBspRecords = int64_t{1} << 24;  // per lump; q3map2's own limits are far lower
inline constexpr int kMaxPatchControlSize = 65;              // control points per patch side (Quake III MAX_GRID_SIZE)

enum Lump : int {
  kLumpEntities = 0,
  kLumpTextures = 1,
  kLumpPlanes = 2,
  kLumpModels = 7,
  kLumpBrushes = 8,
  kLumpBrushSides = 9,
  kLumpVertices = 10,
  kLumpMeshverts = 11,
  kLumpFaces = 13,
  kLumpLightmaps = 14,
};
const char* lump_name(int lump);  // "entities", "textures", ... for every lump 0..16

// Surface flags (q3map's surfaceflags.h) the loader looks at.
inline constexpr int32_t kSurfSky = 0x4;       // drawn by the sky box, not as a textured face
inline constexpr int32_t kSurfNodraw = 0x80;   // no draw surface at all
inline constexpr int32_t kSurfSkip = 0x200;    // ignored by the compiler and the renderer

// Content flags (q3map's surfaceflags.h) of the texture entries: what a brush or patch is made of.
inline constexpr int32_t kContentsSolid = 0x1;
inline constexpr int32_t kContentsPlayerClip = 0x10000;
inline constexpr int32_t kContentsBody = 0x2000000;
// What a player's movement collides with (bg_public.h MASK_PLAYERSOLID).
inline constexpr int32_t kMaskPlayerSolid = kContentsSolid | kContentsPlayerClip | kContentsBody;

enum class FaceType : int32_t { Polygon = 1, Patch = 2, Mesh = 3, Billboard = 4 };

struct BspTexture {
  std::string name;  // shader name, e.g. "textures/e7/e7walldesign01" (no extension)
  int32_t surface_flags = 0, content_flags = 0;
};

// A vertex as the level uses it (floats of the file converted exactly to double).
struct Vertex {
  glm::dvec3 pos{0.0};       // world units, Quake axes (z up)
  glm::dvec2 uv0{0.0};       // base texture (s, t); t grows down the image
  glm::dvec2 uv1{0.0};       // lightmap (s, t) inside the face's lightmap
  glm::dvec3 normal{0.0};
  std::array<uint8_t, 4> colour{};  // vertex colour RGBA (vertex lighting)
};

struct BspFace {
  int32_t texture = 0, effect = -1;
  FaceType type = FaceType::Polygon;
  int32_t first_vertex = 0, vertex_count = 0;
  int32_t first_meshvert = 0, meshvert_count = 0;
  int32_t lightmap = -1;  // < 0: vertex-lit (no lightmap)
  std::array<int32_t, 2> patch_size{};  // control points along s (width) and t (height): patches only
};

struct BspPlane {
  glm::dvec3 normal{0.0};
  double dist = 0.0;
};

struct BspBrush {
  int32_t first_side = 0, side_count = 0;
  int32_t texture = 0;  // its content flags are the brush's contents
};

struct BspBrushSide {
  int32_t plane = 0, texture = 0;
};

struct BspModel {
  glm::dvec3 mins{0.0}, maxs{0.0};
  int32_t first_brush = 0, brush_count = 0;
};

struct Bsp {
  std::string entities;  // lump 0 text (up to its first NUL)
  std::vector<BspTexture> textures;
  std::vector<BspPlane> planes;
  std::vector<BspModel> models;  // model 0: the world
  std::vector<BspBrush> brushes;
  std::vector<BspBrushSide> brush_sides;
  std::vector<Vertex> vertices;
  std::vector<bool> nonfinite_lightmap_uv;  // per vertex, true where the file's lightmap uv was not finite (empty: none)
  std::vector<int32_t> meshverts;
  std::vector<BspFace> faces;
  std::vector<std::vector<uint8_t>> lightmaps;  // each kLightmapSize^2 x RGB8, row 0 first
};

// Parses and checks a whole BSP file; `source` names it in errors (e.g. "pak1-maps.pk3:maps/x.bsp").
Bsp parse_bsp(std::span<const uint8_t> file, const std::string& source);

// Entities of lump 0: { "key" "value" ... } blocks, in file order (keys in block order).
struct Entity {
  std::vector<std::pair<std::string, std::string>> keys;
  // The value of `key`, or empty if it is absent (the last one wins, as in Quake III).
  std::string value(const std::string& key) const;
};
// Throws InputError "SOURCE: lump 0 (entities): line L: what" on malformed text.
std::vector<Entity> parse_entities(const std::string& text, const std::string& source);

}  // namespace tfu::q3
