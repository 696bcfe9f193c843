// A Quake III / OpenArena level assembled for drawing: textures, lightmaps, one vertex array,
// triangles in BSP face order with each face's base texture and lightmap, spawn points and counts.
// docs/real-frames.md describes the rules; the parts live in pk3.hpp (archives), bsp.hpp (lumps),
// bezier_patch.hpp (type-2 faces), q3_textures.hpp (names -> images), q3_archives.hpp (game data).
//
// Faces (BSP lump 13), in file order:
//   type 1 polygon, 3 mesh  triangles from the face's meshverts: vertex first_vertex + meshvert[k]
//                           (winding as stored: Quake III's front faces are clockwise on screen)
//   type 2 patch            tessellated (bezier_patch.hpp, kPatchSubdivision quads per sub-patch side)
//   type 4 billboard        skipped (flares, sprites drawn by the engine), counted
// A face whose texture is Invisible or Sky (q3_textures.hpp) is skipped and counted; a Drawn one
// whose name has no image gets the fallback texture (counted per face and per texture name).
//
// Lightmaps: lump 14's 128 x 128 RGB8 images as RGBA8 textures (A = 255), one level each (Quake III
// does not MIP-map lightmaps), bytes as stored: Quake III's overbright shift is not applied here.
// One more lightmap follows them, index `white_lightmap`: a 1 x 1 texel (255, 255, 255, 255) for
// vertex-lit faces (lightmap index < 0: Quake III lights those by vertex colour, which the texture
// unit has no stage for; the vertex colours are kept in Vertex::colour). Their uv1 stays as stored:
// every coordinate of a 1 x 1 texture addresses its one texel, whatever the wrap mode.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cmodel/bsp.hpp"
#include "cmodel/q3_archives.hpp"
#include "cmodel/q3_textures.hpp"
#include "cmodel/texture.hpp"

namespace tfu::q3 {

// Entity classes that give spawn points, in priority order: the spawn points of a level are the
// entities of the first class it has (deathmatch levels: info_player_deathmatch; the CTF-only
// levels delta, oa_bases5 and oa_ctf4ish have none and use info_player_start).
inline constexpr std::array<const char*, 4> kSpawnClasses = {"info_player_deathmatch", "info_player_start",
                                                             "team_CTF_redspawn", "team_CTF_bluespawn"};

// At most this many triangles per level (InputError beyond): 40 times the largest OpenArena level
// (oa_dm5, 107,414), and a bound on memory, since faces may share vertex ranges.
inline constexpr int64_t kMaxLevelTriangles = int64_t{1} << 22;

// One entry of the BSP texture lump (index = the BSP's shader index).
struct LevelTexture {
  std::string name;  // as in the BSP
  int32_t surface_flags = 0;
  SurfaceClass surface = SurfaceClass::Drawn;
  // The image or the fallback, for textures of drawn faces (looked up and decoded when the first
  // such face is added); null for Invisible and Sky textures and those no drawn face uses.
  std::shared_ptr<const Texture> texture;
  bool fallback = false;                   // drawn with the fallback (no image found)
  std::string source;                      // "pak4-textures.pk3:textures/...jpg" when resolved
  int64_t faces_drawn = 0;                 // faces of this level drawn with it
};

// One drawn face: a contiguous range of Level::triangles.
struct LevelFace {
  int32_t bsp_face = 0;  // index in lump 13
  FaceType type = FaceType::Polygon;
  int32_t texture = 0;   // index into Level::textures (always a Drawn entry)
  int32_t lightmap = 0;  // index into Level::lightmaps (white_lightmap for vertex-lit faces)
  uint32_t first_triangle = 0, triangle_count = 0;
};

struct SpawnPoint {
  glm::dvec3 origin{0.0};  // world units, z up (the entity's "origin")
  double yaw_deg = 0.0;    // "angle" (degrees about +z, 0 = +x, 90 = +y)
  // Where the player spawned here comes to rest (q3_collision.hpp spawn_rest; build_level fills it).
  glm::dvec3 rest{0.0};
  bool landed = false;       // a world brush stopped the drop
  bool start_solid = false;  // the box at origin + 9 is inside a brush
  // A patch whose contents the player collides with overlaps the drop column above the resting
  // box's feet: the engine may stop the player on it, higher than the brush trace says.
  bool patch_in_drop = false;
};

struct LevelCounts {
  std::array<int64_t, 5> faces_by_type{};  // index = BSP face type 1..4 (0 unused)
  int64_t faces_drawn = 0;
  int64_t skipped_invisible = 0;  // faces of Invisible textures (billboards not included)
  int64_t skipped_sky = 0;        // faces of Sky textures (billboards not included)
  int64_t billboards = 0;         // type-4 faces (all skipped)
  int64_t fallback_faces = 0;     // drawn faces with the fallback texture
  int64_t fallback_textures = 0;  // distinct Drawn texture names without an image, used by a drawn face
  int64_t resolved_textures = 0;  // distinct texture names with an image, used by a drawn face
  int64_t patches = 0;            // drawn type-2 faces
  int64_t vertex_lit_faces = 0;   // drawn faces with lightmap index < 0
  int64_t world_brushes = 0;      // brushes of model 0 (the collision world)
  int64_t triangles = 0;
  int64_t vertices = 0;
};

struct Level {
  std::string name;    // "aggressor"
  std::string source;  // "pak1-maps.pk3:maps/aggressor.bsp"
  std::vector<LevelTexture> textures;
  std::vector<std::shared_ptr<const Texture>> lightmaps;  // BSP lightmaps, then the white 1 x 1
  int32_t white_lightmap = 0;
  std::vector<Vertex> vertices;  // all BSP vertices (lump 10 order), then the patch grids appended
  std::vector<std::array<uint32_t, 3>> triangles;  // indices into `vertices`, in face order
  std::vector<LevelFace> faces;                   // drawn faces in BSP order
  std::vector<SpawnPoint> spawns;                 // entities of the first of kSpawnClasses present, file order
  std::string spawn_class;                        // that class (empty: the level has none)
  glm::dvec3 bounds_min{0.0}, bounds_max{0.0};    // of the drawn triangles' vertices
  LevelCounts counts;
};

// Assembles a level from a parsed BSP; textures come from (and stay in) `cache`.
Level build_level(const Bsp& bsp, const std::string& name, const std::string& source, TextureCache& cache);
// Reads maps/NAME.bsp from the archives and builds it.
Level load_level(const GameArchives& archives, const std::string& name, TextureCache& cache);

// The entities of class `classname`: "origin" "x y z" (required), "angle" "deg" (default 0; an
// "angles" "pitch yaw roll" key gives the yaw when there is no "angle"). Malformed numbers throw
// InputError naming lump 0 and the entity.
std::vector<SpawnPoint> spawn_points(const std::vector<Entity>& entities, const std::string& classname,
                                     const std::string& source);

// Drops the player at every spawn point (q3_collision.hpp spawn_rest against the world's brushes,
// down to 64 units below the lowest vertex or world bound) and sets rest, landed, start_solid and
// patch_in_drop; `world_brushes` (if given) receives the world's brush count.
void place_spawns(const Bsp& bsp, std::vector<SpawnPoint>& spawns, int64_t* world_brushes = nullptr);
// The spawn points of a BSP: the entities of the first of kSpawnClasses it has (its name into
// `spawn_class`), placed (place_spawns). Needs no textures.
std::vector<SpawnPoint> level_spawn_points(const Bsp& bsp, const std::string& source,
                                           std::string* spawn_class = nullptr);

// One line for logs and the render summary: faces by type, skipped, fallbacks, triangles.
std::string level_summary(const Level& level);

// The counts as (name, value) pairs, for the statistics of `tfu sim` ("level_" + name):
// faces_polygon, faces_patch, faces_mesh, faces_billboard, faces_drawn, skipped_invisible,
// skipped_sky (billboards: faces_billboard, all skipped), fallback_faces, fallback_textures, resolved_textures, patches,
// vertex_lit_faces, triangles, vertices, lightmaps, spawn_points.
std::vector<std::pair<std::string, int64_t>> level_count_fields(const Level& level);

}  // namespace tfu::q3
