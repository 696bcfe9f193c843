// OpenArena levels (cmodel/q3_*.hpp, cmodel/pk3.hpp): a tiny game directory written by the test
// (two .pk3 archives built with libzip, a BSP with every face type, TGA and JPEG textures) checks
// archive search order, texture resolution and decoding, the invisible / sky / fallback rules,
// level assembly and counts, spawn cameras and the preview scene; bad archives and images give one
// InputError line; and the real level maps/aggressor.bsp (when the game packages are installed)
// has the counts checked by hand.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include <fmt/format.h>

#include "cmodel/bindings.hpp"
#include "cmodel/error.hpp"
#include "cmodel/metrics.hpp"
#include "cmodel/pk3.hpp"
#include "cmodel/q3_archives.hpp"
#include "cmodel/q3_camera.hpp"
#include "cmodel/q3_level.hpp"
#include "cmodel/q3_scene.hpp"
#include "cmodel/q3_textures.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene_source.hpp"
#include "cmodel/upload_compression.hpp"
#include "rtl/scene_sim.hpp"
#include "sim/sweep/provenance.hpp"
#include "testbench/q3_test_data.hpp"

namespace tfu::q3 {
namespace {

namespace fs = std::filesystem;
using testdata::BspBuilder;
using testdata::Bytes;
using testdata::vtx;

constexpr Rgba8 kRed{255, 0, 0, 255}, kGreen{0, 255, 0, 255}, kBlue{0, 0, 255, 255}, kWhiteHalf{255, 255, 255, 128};

// Faces of the tiny level, in BSP order:
//   0 polygon quad   "textures/test/wall" (wall.tga)          lightmap 0
//   1 mesh triangle  "textures/test/jpgwall" (jpgwall.jpg)    vertex-lit
//   2 patch 3x3      "textures/test/missing" (no image)       lightmap 1
//   3 billboard      "flareShader"
//   4 polygon        "textures/common/caulk" (SURF_NODRAW)
//   5 patch 5x3      "textures/test/wall"                      lightmap 0
//   6 polygon        "textures/test/sky" (SURF_SKY)
//   7 polygon        "textures/test/hint_marker" (name token "hint", no flags)
// and a texture entry no face uses ("textures/test/both").
BspBuilder tiny_level() {
  BspBuilder b;
  b.entities =
      "{\n\"classname\" \"worldspawn\"\n\"message\" \"tiny\"\n}\n"
      "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"16 -32 24\"\n\"angle\" \"90\"\n}\n"
      "// a light\n{\n\"classname\" \"light\"\n\"origin\" \"0 0 0\"\n}\n"
      "{\n\"classname\" \"info_player_start\"\n\"origin\" \"0 0 0\"\n}\n"
      "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"-8 8 40\"\n\"angles\" \"0 180 0\"\n}\n";
  b.textures = {{"textures/test/wall", 0, 1},       {"textures/test/jpgwall", 0, 1}, {"textures/test/missing", 0, 1},
                {"flareShader", 0, 0},              {"textures/common/caulk", kSurfNodraw, 1},
                {"textures/test/sky", kSurfSky, 1}, {"textures/test/hint_marker", 0, 0},
                {"textures/test/both", 0, 1}};  // used by no face
  // 0..3 quad, 4..6 mesh, 7..15 patch 3x3, 16..30 patch 5x3, 31 billboard, 32..34 caulk,
  // 35..37 sky, 38..40 hint.
  b.vertices = {vtx({0, 0, 0}, {0, 1}, {0, 0.5}, {10, 20, 30, 40}, {0, -1, 0}), vtx({64, 0, 0}, {1, 1}, {0.5, 0.5}),
                vtx({64, 0, 64}, {1, 0}, {0.5, 0}), vtx({0, 0, 64}, {0, 0}, {0, 0})};
  for (int i = 0; i < 3; ++i) b.vertices.push_back(vtx({0, 10.0 * i, 0}, {0.5 * i, 0}));
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) b.vertices.push_back(vtx({8.0 * i, 100, 8.0 * j}, {0.5 * i, 0.5 * j}));
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 5; ++i) b.vertices.push_back(vtx({8.0 * i, 200, 8.0 * j}, {0.25 * i, 0.5 * j}));
  b.vertices.push_back(vtx({0, 0, 500}, {0, 0}));
  for (int k = 0; k < 9; ++k) b.vertices.push_back(vtx({1.0 * k, -50, 1.0 * (k % 3)}, {0, 0}));
  b.meshverts = {0, 1, 2, 0, 2, 3, 2, 0, 1, 0, 1, 2};
  b.faces = {{0, FaceType::Polygon, 0, 4, 0, 6, 0},   {1, FaceType::Mesh, 4, 3, 6, 3, -1},
             {2, FaceType::Patch, 7, 9, 0, 0, 1, 3, 3}, {3, FaceType::Billboard, 31, 1, 0, 0, -1},
             {4, FaceType::Polygon, 32, 3, 9, 3, 0},  {0, FaceType::Patch, 16, 15, 0, 0, 0, 5, 3},
             {5, FaceType::Polygon, 35, 3, 9, 3, 0},  {6, FaceType::Polygon, 38, 3, 9, 3, 0}};
  Bytes lm0(size_t{128} * 128 * 3), lm1(size_t{128} * 128 * 3, 77);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      const size_t i = 3 * (static_cast<size_t>(y) * 128 + static_cast<size_t>(x));
      lm0[i] = static_cast<uint8_t>(x);
      lm0[i + 1] = static_cast<uint8_t>(y);
      lm0[i + 2] = 7;
    }
  b.lightmaps = {lm0, lm1};
  // The collision world: a solid floor slab (top at z = 0) under both spawn points.
  b.add_brush({-100, -100, -16}, {100, 100, 0}, 0);
  b.models = {{{-100, -100, -16}, {100, 100, 0}, 0, 1}};
  return b;
}

// A scratch game directory: pak0.pk3 (the level and most textures) and pak9.pk3 (overrides).
class TinyGame : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / fmt::format("tfu_q3_{}_{}", ::getpid(),
                                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    const Bytes wall = testdata::make_tga({{kRed, kGreen}, {kBlue, kWhiteHalf}});
    const Bytes jpg = testdata::make_jpeg(dir_ / "scratch.jpg", 16, 8, {200, 100, 50, 255});
    fs::remove(dir_ / "scratch.jpg");
    testdata::write_zip(dir_ / "pak0.pk3", {{"maps/tiny.bsp", tiny_level().build()},
                                            {"textures/test/wall.tga", wall},
                                            {"textures/test/jpgwall.jpg", jpg},
                                            {"textures/test/both.jpg", jpg},
                                            {"textures/test/both.tga", wall},
                                            {"textures/test/shadowed.tga", wall},
                                            {"textures/test/corrupt.tga", Bytes(40, 0xAB)}});
    testdata::write_zip(dir_ / "pak9.pk3", {{"Textures/Test/Shadowed.TGA", testdata::make_tga({{kGreen}})},
                                            {"maps/other.bsp", tiny_level().build()}});
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string dir() const { return dir_.string(); }
  fs::path dir_;
};

// The InputError message of f(), checked to be one line of at most 300 characters.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_LE(msg.size(), 300u) << msg;
    return msg;
  }
  return "";
}

TEST_F(TinyGame, ArchivesInSearchOrder) {
  const GameArchives a(dir());
  ASSERT_EQ(a.archives().size(), 2u);
  EXPECT_EQ(fs::path(a.archives()[0].path()).filename(), "pak0.pk3");
  EXPECT_EQ(a.level_names(), (std::vector<std::string>{"other", "tiny"}));
  // The later archive wins, names match in any case, the stored spelling is reported.
  const auto ref = a.locate("textures/test/shadowed.tga");
  ASSERT_TRUE(ref);
  EXPECT_EQ(ref->archive, 1u);
  EXPECT_EQ(a.describe(*ref), "pak9.pk3:Textures/Test/Shadowed.TGA");
  EXPECT_EQ(a.describe(*a.locate("TEXTURES/TEST/WALL.TGA")), "pak0.pk3:textures/test/wall.tga");
  EXPECT_FALSE(a.locate("textures/test/nothing.tga"));
  EXPECT_EQ(a.archives()[0].read("maps/tiny.bsp"), tiny_level().build());
  EXPECT_EQ(a.describe(a.locate_level("tiny")), "pak0.pk3:maps/tiny.bsp");
  // Directory entries are not files.
  EXPECT_EQ(a.archives()[1].entry_names().size(), 2u);
}

TEST_F(TinyGame, TextureResolutionAndDecoding) {
  const GameArchives a(dir());
  TextureCache cache(a);
  const ResolvedTexture& wall = cache.get("textures/test/wall");
  EXPECT_FALSE(wall.fallback);
  EXPECT_EQ(wall.source, "pak0.pk3:textures/test/wall.tga");
  const Texture& t = *wall.texture;
  EXPECT_EQ(t.format, TexelFormat::RGBA8);
  ASSERT_EQ(t.levels.size(), 2u);  // 2x2 + box level 1x1
  // The TGA is stored bottom-up; row 0 of the texture is the top of the image.
  EXPECT_EQ(t.levels[0].at(0, 0), kRed);
  EXPECT_EQ(t.levels[0].at(1, 0), kGreen);
  EXPECT_EQ(t.levels[0].at(0, 1), kBlue);
  EXPECT_EQ(t.levels[0].at(1, 1), kWhiteHalf);  // alpha kept unassociated
  // Box level (Lee & Jen Eq. 8): (sum + 2) >> 2 = (510 + 2) >> 2 = 128; alpha (3 255 + 128 + 2) >> 2 = 223.
  EXPECT_EQ(t.levels[1].at(0, 0), (Rgba8{128, 128, 128, 223}));
  // .tga before .jpg; a given extension is tried first; the override archive wins.
  EXPECT_EQ(cache.get("textures/test/both").source, "pak0.pk3:textures/test/both.tga");
  EXPECT_EQ(cache.get("textures/test/both.jpg").source, "pak0.pk3:textures/test/both.jpg");
  EXPECT_EQ(cache.get("textures/test/shadowed").texture->levels[0].at(0, 0), kGreen);
  // JPEG through the memory proxy: 16 x 8, a flat colour (JPEG is lossy: within 3).
  const Texture& j = *cache.get("textures/test/jpgwall").texture;
  EXPECT_EQ(j.width(), 16);
  EXPECT_EQ(j.height(), 8);
  EXPECT_EQ(j.levels.size(), 5u);
  EXPECT_NEAR(j.levels[0].at(5, 3).r, 200, 3);
  EXPECT_NEAR(j.levels[0].at(5, 3).g, 100, 3);
  EXPECT_NEAR(j.levels[0].at(5, 3).b, 50, 3);
  EXPECT_EQ(j.levels[0].at(5, 3).a, 255);
  // Misses get the shared fallback; every result is cached (the same object on the next call).
  const ResolvedTexture& miss = cache.get("textures/test/missing");
  EXPECT_TRUE(miss.fallback);
  EXPECT_EQ(miss.texture, cache.fallback());
  EXPECT_EQ(&cache.get("Textures/Test/Wall"), &wall);
  EXPECT_EQ(cache.decoded(), 5u);  // wall, both.tga, both.jpg, shadowed, jpgwall
  // A corrupt image names the archive and entry.
  EXPECT_NE(error_of([&] { cache.get("textures/test/corrupt"); }).find("pak0.pk3:textures/test/corrupt.tga: cannot decode image"),
            std::string::npos);
}

TEST(Q3Textures, FallbackAndClassification) {
  const Texture f = make_fallback_texture();
  ASSERT_EQ(f.width(), 64);
  EXPECT_EQ(f.levels.size(), 7u);
  EXPECT_EQ(f.levels[0].at(0, 0), (Rgba8{160, 160, 160, 255}));
  EXPECT_EQ(f.levels[0].at(7, 7), (Rgba8{160, 160, 160, 255}));
  EXPECT_EQ(f.levels[0].at(8, 0), (Rgba8{96, 96, 96, 255}));
  EXPECT_EQ(f.levels[0].at(8, 8), (Rgba8{160, 160, 160, 255}));
  EXPECT_EQ(f.levels[3].at(0, 0), (Rgba8{160, 160, 160, 255}));  // 8x8: one texel per square
  EXPECT_EQ(f.levels[4].at(0, 0), (Rgba8{128, 128, 128, 255}));  // (160 2 + 96 2 + 2) >> 2

  EXPECT_EQ(classify_surface({"textures/common/caulk", 0, 0}), SurfaceClass::Invisible);
  EXPECT_EQ(classify_surface({"textures/Common/WeapClip", 0, 0}), SurfaceClass::Invisible);
  EXPECT_EQ(classify_surface({"textures/common/trigger", 0, 0}), SurfaceClass::Invisible);
  EXPECT_EQ(classify_surface({"textures/clown/pipe", kSurfNodraw | 0xc00, 1}), SurfaceClass::Invisible);
  EXPECT_EQ(classify_surface({"textures/x/y", kSurfSkip, 1}), SurfaceClass::Invisible);
  EXPECT_EQ(classify_surface({"textures/skies/hellsky", 0x414, 1}), SurfaceClass::Sky);
  EXPECT_EQ(classify_surface({"textures/common/caulk", kSurfSky | kSurfNodraw, 1}), SurfaceClass::Invisible);
  EXPECT_EQ(classify_surface({"textures/e7/e7walldesign01", 0, 1}), SurfaceClass::Drawn);
  EXPECT_EQ(classify_surface({"textures/sfx/clipboard_hint/metal", 0, 1}), SurfaceClass::Drawn);  // only the last component
  EXPECT_EQ(classify_surface({"flareShader", 0, 0}), SurfaceClass::Drawn);
}

TEST_F(TinyGame, LevelAssemblyAndCounts) {
  const GameArchives a(dir());
  TextureCache cache(a);
  const Level l = load_level(a, "tiny", cache);
  EXPECT_EQ(l.name, "tiny");
  EXPECT_EQ(l.source, "pak0.pk3:maps/tiny.bsp");
  const LevelCounts& c = l.counts;
  EXPECT_EQ(c.faces_by_type, (std::array<int64_t, 5>{0, 4, 2, 1, 1}));
  EXPECT_EQ(c.faces_drawn, 4);        // quad, mesh, both patches
  EXPECT_EQ(c.skipped_invisible, 2);  // caulk (flag), hint_marker (name)
  EXPECT_EQ(c.skipped_sky, 1);
  EXPECT_EQ(c.billboards, 1);
  EXPECT_EQ(c.fallback_faces, 1);
  EXPECT_EQ(c.fallback_textures, 1);
  EXPECT_EQ(c.resolved_textures, 2);
  EXPECT_EQ(c.patches, 2);
  EXPECT_EQ(c.vertex_lit_faces, 1);
  EXPECT_EQ(c.triangles, 2 + 1 + 128 + 256);          // 3x3 patch: 8 x 8 quads; 5x3: 16 x 8
  EXPECT_EQ(c.vertices, 41 + 81 + 17 * 9);            // BSP vertices + both patch grids
  ASSERT_EQ(l.triangles.size(), 387u);
  // The same counts as the statistics of `tfu sim` name them.
  const auto fields = level_count_fields(l);
  const std::map<std::string, int64_t> stat(fields.begin(), fields.end());
  EXPECT_EQ(stat.size(), fields.size());  // no name twice
  EXPECT_EQ(stat.at("faces_polygon"), 4);
  EXPECT_EQ(stat.at("faces_billboard"), 1);
  EXPECT_EQ(stat.at("faces_drawn"), 4);
  EXPECT_EQ(stat.at("skipped_invisible"), 2);
  EXPECT_EQ(stat.at("skipped_sky"), 1);
  EXPECT_EQ(stat.at("fallback_faces"), 1);
  EXPECT_EQ(stat.at("triangles"), 387);
  EXPECT_EQ(stat.at("lightmaps"), static_cast<int64_t>(l.lightmaps.size()) - 1);
  EXPECT_EQ(stat.at("spawn_points"), static_cast<int64_t>(l.spawns.size()));
  // Textures: one per BSP entry, classified.
  ASSERT_EQ(l.textures.size(), 8u);
  EXPECT_EQ(l.textures[0].source, "pak0.pk3:textures/test/wall.tga");
  EXPECT_EQ(l.textures[0].faces_drawn, 2);
  EXPECT_TRUE(l.textures[2].fallback);
  EXPECT_EQ(l.textures[2].texture, cache.fallback());
  EXPECT_EQ(l.textures[4].surface, SurfaceClass::Invisible);
  EXPECT_EQ(l.textures[4].texture, nullptr);
  EXPECT_EQ(l.textures[5].surface, SurfaceClass::Sky);
  EXPECT_EQ(l.textures[6].surface, SurfaceClass::Invisible);
  EXPECT_EQ(l.textures[7].surface, SurfaceClass::Drawn);
  EXPECT_EQ(l.textures[7].texture, nullptr);  // no drawn face: not decoded
  EXPECT_EQ(cache.decoded(), 2u);             // wall.tga, jpgwall.jpg
  // Faces: drawn ones in BSP order with their triangle ranges.
  ASSERT_EQ(l.faces.size(), 4u);
  EXPECT_EQ(l.faces[0].bsp_face, 0);
  EXPECT_EQ(l.faces[1].bsp_face, 1);
  EXPECT_EQ(l.faces[2].bsp_face, 2);
  EXPECT_EQ(l.faces[3].bsp_face, 5);
  EXPECT_EQ(l.faces[2].type, FaceType::Patch);
  EXPECT_EQ(l.faces[3].first_triangle, 131u);
  EXPECT_EQ(l.faces[3].triangle_count, 256u);
  EXPECT_EQ(l.faces[3].texture, 0);
  // Triangles from meshverts: first_vertex + meshvert.
  EXPECT_EQ(l.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(l.triangles[1], (std::array<uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(l.triangles[2], (std::array<uint32_t, 3>{6, 4, 5}));
  // The 3x3 patch grid starts after the 41 BSP vertices: its first triangle is {41, 42, 51}.
  EXPECT_EQ(l.triangles[3], (std::array<uint32_t, 3>{41, 42, 51}));
  EXPECT_EQ(l.vertices[41].pos, glm::dvec3(0, 100, 0));
  EXPECT_EQ(l.vertices[41 + 80].pos, glm::dvec3(16, 100, 16));
  EXPECT_EQ(l.vertices[41 + 4 * 9 + 4].pos, glm::dvec3(8, 100, 8));  // a flat grid stays flat
  // BSP vertices are kept with every attribute.
  EXPECT_EQ(l.vertices[0].uv1, glm::dvec2(0, 0.5));
  EXPECT_EQ(l.vertices[0].colour, (std::array<uint8_t, 4>{10, 20, 30, 40}));
  EXPECT_EQ(l.vertices[0].normal, glm::dvec3(0, -1, 0));
  // Lightmaps: RGB -> RGBA, row 0 first, plus the white 1 x 1 for the vertex-lit mesh face.
  ASSERT_EQ(l.lightmaps.size(), 3u);
  EXPECT_EQ(l.white_lightmap, 2);
  EXPECT_EQ(l.lightmaps[0]->levels.size(), 1u);
  EXPECT_EQ(l.lightmaps[0]->levels[0].at(5, 9), (Rgba8{5, 9, 7, 255}));
  EXPECT_EQ(l.lightmaps[1]->levels[0].at(127, 127), (Rgba8{77, 77, 77, 255}));
  EXPECT_EQ(l.lightmaps[2]->width(), 1);
  EXPECT_EQ(l.lightmaps[2]->levels[0].at(0, 0), (Rgba8{255, 255, 255, 255}));
  EXPECT_EQ(l.faces[0].lightmap, 0);
  EXPECT_EQ(l.faces[1].lightmap, 2);
  EXPECT_EQ(l.faces[2].lightmap, 1);
  // Bounds of the drawn triangles (the skipped faces at y = -50 and z = 500 do not count).
  EXPECT_EQ(l.bounds_min, glm::dvec3(0, 0, 0));
  EXPECT_EQ(l.bounds_max, glm::dvec3(64, 200, 64));
  // Spawn points: the info_player_deathmatch entities, "angle" or the yaw of "angles".
  EXPECT_EQ(l.spawn_class, "info_player_deathmatch");
  ASSERT_EQ(l.spawns.size(), 2u);
  EXPECT_EQ(l.spawns[0].origin, glm::dvec3(16, -32, 24));
  EXPECT_EQ(l.spawns[0].yaw_deg, 90.0);
  EXPECT_EQ(l.spawns[1].origin, glm::dvec3(-8, 8, 40));
  EXPECT_EQ(l.spawns[1].yaw_deg, 180.0);
  // Textures are decoded once per cache, across levels.
  const size_t decoded = cache.decoded();
  load_level(a, "other", cache);
  EXPECT_EQ(cache.decoded(), decoded);
}

TEST(Q3Level, SpawnClassesAndErrors) {
  const auto ents = parse_entities(
      "{\n\"classname\" \"info_player_start\"\n\"origin\" \"1 2 3\"\n}\n"
      "{\n\"classname\" \"team_CTF_redspawn\"\n\"origin\" \"4 5 6\"\n\"angle\" \"-45.5\"\n}\n"
      "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"1 2\"\n}\n"
      "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"1 2 3\"\n\"angle\" \"east\"\n}\n",
      "t.bsp");
  const auto red = spawn_points(ents, "team_CTF_redspawn", "t.bsp");
  ASSERT_EQ(red.size(), 1u);
  EXPECT_EQ(red[0].yaw_deg, -45.5);
  EXPECT_EQ(spawn_points(ents, "info_player_start", "t.bsp")[0].yaw_deg, 0.0);
  EXPECT_EQ(error_of([&] { spawn_points(ents, "info_player_deathmatch", "t.bsp"); }),
            "t.bsp: lump 0 (entities): entity 2 (info_player_deathmatch): \"origin\" \"1 2\" is not 3 numbers");
}

TEST_F(TinyGame, SpawnCamera) {
  const GameArchives a(dir());
  TextureCache cache(a);
  const Level l = load_level(a, "tiny", cache);
  // Dropped from 24 + 9 onto the floor slab (top z = 0): the box's feet rest 0.125 above it, the
  // origin at 24.125, the eye 26 higher.
  EXPECT_TRUE(l.spawns[0].landed);
  EXPECT_EQ(l.spawns[0].rest, glm::dvec3(16, -32, 24.125));
  EXPECT_EQ(l.spawns[1].rest, glm::dvec3(-8, 8, 24.125));  // from 40 + 9
  EXPECT_EQ(l.counts.world_brushes, 1);
  const Camera cam = spawn_camera(l, 0, 1280, 720);
  EXPECT_EQ(cam.position, glm::dvec3(16, -32, 50.125));
  EXPECT_EQ(spawn_camera(l, 0, 1280, 720, EyeRule::Spot).position, glm::dvec3(16, -32, 50));  // origin + 26
  EXPECT_NEAR(cam.look_at.x, 16.0, 1e-12);                                                    // yaw 90: +y
  EXPECT_NEAR(cam.look_at.y, -31.0, 1e-12);
  EXPECT_EQ(cam.look_at.z, 50.125);
  EXPECT_EQ(cam.up, glm::dvec3(0, 0, 1));
  EXPECT_NEAR(cam.fov_y_deg, 58.7155, 1e-4);  // 2 atan(720 / 1280) for 90 degrees across
  EXPECT_NEAR(vertical_fov_deg(90, 1.0), 90.0, 1e-12);
  EXPECT_NEAR(vertical_fov_deg(90, 4.0 / 3.0), 73.7398, 1e-4);  // 2 atan(3/4)
  EXPECT_EQ(cam.near_plane, 4.0);
  // Far: per axis the larger distance from the eye (16, -32, 50.125) to the bounds (0..64, 0..200,
  // 0..64): (48, 232, 50.125).
  EXPECT_NEAR(cam.far_plane, 1.01 * std::sqrt(48.0 * 48 + 232.0 * 232 + 50.125 * 50.125) + 16, 1e-9);
  const Camera back = spawn_camera(l, 1, 1280, 720);
  EXPECT_NEAR(back.look_at.x - back.position.x, -1.0, 1e-12);  // yaw 180: -x
  EXPECT_EQ(error_of([&] { spawn_camera(l, 2, 64, 64); }),
            "level 'tiny' has 2 spawn points (info_player_deathmatch), no spawn point 2");
}

TEST_F(TinyGame, LevelSceneBaseTimesLightmap) {
  const GameArchives a(dir());
  TextureCache cache(a);
  const Level l = load_level(a, "tiny", cache);
  const Scene s = level_scene(l, 1, 96, 54);
  EXPECT_EQ(s.name, "oa-tiny-1");
  EXPECT_EQ(s.width, 96);
  EXPECT_EQ(s.height, 54);
  EXPECT_EQ(s.description, level_summary(l));
  // The game's light: light maps shifted by r_mapOverBrightBits 2 - r_overBrightBits 1 at load, the
  // display ramp doubling; back faces culled.
  EXPECT_EQ(s.display_shift, 1);
  EXPECT_EQ(s.cull, CullWinding::CounterClockwise);
  // One mesh per (texture, light map), in order of first use: wall with light map 0 (faces 0, 5),
  // jpgwall vertex-lit (one stage, base x vertex colour), missing with light map 1.
  ASSERT_EQ(s.meshes.size(), 3u);
  EXPECT_EQ(s.meshes[0].stages[0].texture, l.textures[0].texture);
  EXPECT_EQ(s.meshes[0].stages[0].spec.source, "oa:tiny:texture:textures/test/wall");
  EXPECT_EQ(s.meshes[0].stages[1].spec.source, "oa:tiny:lightmap-shift1:0");
  // Light map 0 holds (x, y, 7), x, y < 128: shifted by one bit, (2x, 2y, 14).
  const Image& lm0 = s.meshes[0].stages[1].texture->levels[0];
  EXPECT_EQ(lm0.at(5, 9), (Rgba8{10, 18, 14, 255}));
  EXPECT_EQ(lm0.at(127, 100), (Rgba8{254, 200, 14, 255}));
  EXPECT_EQ(lm0.at(127, 127), (Rgba8{254, 254, 14, 255}));
  EXPECT_EQ(s.meshes[0].triangles.size(), 2u + 256u);
  EXPECT_EQ(s.meshes[0].vertices.size(), 4u + 17u * 9u);
  EXPECT_FALSE(s.meshes[0].vertex_colour);
  ASSERT_EQ(s.meshes[1].stages.size(), 1u);
  EXPECT_TRUE(s.meshes[1].vertex_colour);
  EXPECT_EQ(s.meshes[1].stages[0].combine, (StageCombine{TexEnv::Modulate, 1}));
  EXPECT_EQ(s.meshes[1].triangles.size(), 1u);
  EXPECT_EQ(s.meshes[2].stages[0].texture, cache.fallback());
  EXPECT_EQ(s.meshes[2].stages[1].texture->levels[0].at(0, 0), (Rgba8{154, 154, 154, 255}));  // 77 << 1
  for (size_t i : {0u, 2u}) {
    const Mesh& m = s.meshes[i];
    ASSERT_EQ(m.stages.size(), 2u);
    EXPECT_EQ(m.stages[0].sampler.mode, (FilterMode{BaseFilter::Linear, MipMode::Linear}));
    EXPECT_EQ(m.stages[0].sampler.wrap_s, WrapMode::Repeat);
    EXPECT_EQ(m.stages[0].combine, (StageCombine{TexEnv::Replace, 1}));
    EXPECT_EQ(m.stages[1].sampler.mode, (FilterMode{BaseFilter::Linear, MipMode::None}));
    EXPECT_EQ(m.stages[1].sampler.wrap_t, WrapMode::ClampToEdge);
    EXPECT_EQ(m.stages[1].uv_set, 1);
    EXPECT_EQ(m.stages[1].combine, (StageCombine{TexEnv::Modulate, 1}));
  }
  // The mesh triangle (level vertices 6, 4, 5) keeps position, base uv and the colour, shifted.
  const auto& tri = s.meshes[1].triangles[0];
  EXPECT_EQ(s.meshes[1].vertices[tri[0]].pos, l.vertices[6].pos);
  EXPECT_EQ(s.meshes[1].vertices[tri[1]].uv, l.vertices[4].uv0);
  EXPECT_EQ(s.meshes[1].vertices[tri[1]].uv1, l.vertices[4].uv1);
  EXPECT_EQ(s.meshes[0].vertices[0].colour, (Rgba8{20, 40, 60, 255}));  // (10, 20, 30) << 1, opaque

  // The earlier rules: light map as stored x 2 (rgb_scale), vertex-lit faces with the white light
  // map, no culling, no display ramp.
  LevelSceneOptions old;
  old.light = LightRule::Double;
  old.vertex = VertexLight::White;
  old.cull = FaceCull::None;
  const Scene o = level_scene(l, 1, 96, 54, old);
  EXPECT_EQ(o.display_shift, 0);
  EXPECT_EQ(o.cull, CullWinding::None);
  ASSERT_EQ(o.meshes.size(), 3u);
  EXPECT_EQ(o.meshes[0].stages[1].texture, l.lightmaps[0]);
  EXPECT_EQ(o.meshes[0].stages[1].spec.source, "oa:tiny:lightmap:0");
  EXPECT_EQ(o.meshes[1].stages[1].texture, l.lightmaps[static_cast<size_t>(l.white_lightmap)]);
  EXPECT_FALSE(o.meshes[1].vertex_colour);
  for (const Mesh& m : o.meshes) EXPECT_EQ(m.stages[1].combine, (StageCombine{TexEnv::Modulate, 2}));
  // Windowed (no hardware gamma): no display ramp, the light map shifted by both bits.
  LevelSceneOptions window;
  window.hardware_gamma = false;
  const Scene w = level_scene(l, 1, 96, 54, window);
  EXPECT_EQ(w.display_shift, 0);
  EXPECT_EQ(w.meshes[0].stages[1].spec.source, "oa:tiny:lightmap-shift2:0");
  const Image& lw = w.meshes[0].stages[1].texture->levels[0];
  EXPECT_EQ(lw.at(5, 9), (Rgba8{20, 36, 28, 255}));
  // (508, 400, 28) exceeds 255: each x 255 / 508 (integer division), the hue kept.
  EXPECT_EQ(lw.at(127, 100), (Rgba8{255, 200, 14, 255}));
  EXPECT_EQ(lw.at(127, 127), (Rgba8{255, 255, 14, 255}));
}

// Base textures declared sRGB (scene key srgb=true): each becomes exactly the texture a scene file's
// srgba8 texture of the same image gives (texture key srgb: level 0 as stored, the MIP chain averaged
// in linear light); light maps stay as they were; the frame goes through the cycle model bit for
// bit; a trace's binding of a level texture with srgb loads the same texture again, and a light map
// with srgb is refused.
TEST_F(TinyGame, BaseTexturesDeclaredSrgbAreTheSceneFilesSrgba8Textures) {
  EXPECT_TRUE(parse_level_scene("oa:tiny:1:srgb=true").options.srgb_textures);
  EXPECT_FALSE(parse_level_scene("oa:tiny:1:srgb=false").options.srgb_textures);
  EXPECT_FALSE(parse_level_scene("oa:tiny:1").options.srgb_textures);
  EXPECT_NE(error_of([] { parse_level_scene("oa:tiny:1:srgb=yes"); }).find("unknown option 'srgb=yes'"),
            std::string::npos);
  // The longest message (a 48-character level name, a long unknown key) stays within one 300-character line.
  EXPECT_NE(error_of([] {
              parse_level_scene("oa:" + std::string(48, 'm') + ":1:" + std::string(200, 'k') + "=true");
            }).find("srgb=false|true)"),
            std::string::npos);
  const GameArchives a(dir());
  TextureCache cache(a);
  const Level l = load_level(a, "tiny", cache);
  LevelSceneOptions declared;
  declared.srgb_textures = true;
  const Scene plain = level_scene(l, 1, 96, 54), s = level_scene(l, 1, 96, 54, declared);
  ASSERT_EQ(s.meshes.size(), 3u);  // wall, jpgwall (vertex-lit), the fallback
  for (size_t i = 0; i < s.meshes.size(); ++i) {
    const TextureStage& base = s.meshes[i].stages.at(0);
    EXPECT_EQ(base.texture->format, TexelFormat::SRGBA8) << i;
    EXPECT_EQ(base.spec.params, (Params{{"srgb", "true"}})) << i;
    Texture stored = *plain.meshes[i].stages.at(0).texture;
    EXPECT_EQ(stored.format, TexelFormat::RGBA8) << i;
    stored.levels.resize(1);
    const Texture expected = texture_with_params(stored, {{"srgb", "true"}}, "scene texture");
    ASSERT_EQ(base.texture->levels.size(), expected.levels.size()) << i;
    for (size_t k = 0; k < expected.levels.size(); ++k)
      EXPECT_EQ(base.texture->levels[k].texels, expected.levels[k].texels) << i << " level " << k;
    if (s.meshes[i].stages.size() == 2) {  // the light map as it was
      EXPECT_EQ(s.meshes[i].stages[1].texture->format, TexelFormat::RGBA8) << i;
      EXPECT_EQ(s.meshes[i].stages[1].texture->levels.at(0).texels,
                plain.meshes[i].stages[1].texture->levels.at(0).texels)
          << i;
      EXPECT_TRUE(s.meshes[i].stages[1].spec.params.empty()) << i;
    }
  }
  // The wall's level 1 averages red, green, blue and white (alpha 128): its red channel as codes is
  // (255 + 0 + 0 + 255 + 2) / 4 = 128; in linear light 2048 of 4095, which sRGB encodes as
  // 255 (1.055 x 0.5001^(1/2.4) - 0.055) = 187.5, so 187 or 188 (the box filter's rounding).
  EXPECT_EQ(plain.meshes[0].stages[0].texture->levels.at(1).at(0, 0).r, 128);
  EXPECT_NEAR(s.meshes[0].stages[0].texture->levels.at(1).at(0, 0).r, 187.5, 0.5);

  // Spawn 0 looks at the wall quad and the patches (both windings drawn): the frame differs from
  // the stored-code frame, and the cycle model equals the golden model on every request.
  LevelSceneOptions both = declared;
  both.cull = FaceCull::None;
  const Scene view = level_scene(l, 0, 96, 54, both);
  both.srgb_textures = false;
  const Scene view_plain = level_scene(l, 0, 96, 54, both);
  RenderOptions ro;
  ro.trace = true;
  const RenderResult r = render_scene(view, ro), rp = render_scene(view_plain, ro);
  int64_t differ = 0;
  for (size_t i = 0; i < r.image.texels.size(); ++i) differ += !(r.image.texels[i] == rp.image.texels[i]);
  EXPECT_GT(differ, 100) << differ;
  const rtl::SceneSimResult sim = rtl::simulate_scene(view, r, rtl::UnitConfig{}, {});
  EXPECT_TRUE(sim.mismatch.empty()) << sim.mismatch;
  EXPECT_EQ(sim.image.texels, r.image.texels);

  // With upload compression: declared first, then encoded with the format's sRGB variant (jpgwall
  // is opaque, so s3tc makes it BC1).
  const Scene c = level_scene(l, 1, 96, 54, declared, upload_compression_from_name("s3tc"));
  const TextureStage& jpg = c.meshes[1].stages.at(0);
  ASSERT_TRUE(jpg.texture->compressed);
  EXPECT_TRUE(jpg.texture->compressed->image.srgb);
  EXPECT_EQ(jpg.texture->format, TexelFormat::SRGBA8);
  EXPECT_EQ(jpg.spec.params, (Params{{"compress", "s3tc"}, {"srgb", "true"}}));

  // Trace bindings.
  const LoadedTexture again = load_texture_spec(s.meshes[0].stages[0].spec, "trace line 2", {}, dir());
  EXPECT_EQ(again.texture->format, TexelFormat::SRGBA8);
  ASSERT_EQ(again.texture->levels.size(), s.meshes[0].stages[0].texture->levels.size());
  for (size_t k = 0; k < again.texture->levels.size(); ++k)
    EXPECT_EQ(again.texture->levels[k].texels, s.meshes[0].stages[0].texture->levels[k].texels) << k;
  TextureSpec bad = s.meshes[0].stages[0].spec;
  bad.params["srgb"] = "maybe";
  EXPECT_NE(error_of([&] { load_texture_spec(bad, "trace line 2", {}, dir()); }).find("trace line 2: key 'srgb': "),
            std::string::npos);
  TextureSpec light = s.meshes[0].stages.at(1).spec;
  light.params = {{"srgb", "true"}};
  EXPECT_EQ(error_of([&] { load_texture_spec(light, "trace line 2", {}, dir()); }),
            "trace line 2: key 'srgb': a level's light maps hold linear light and cannot be declared sRGB");
  light.params = {{"srgb", "false"}};
  EXPECT_EQ(load_texture_spec(light, "trace line 2", {}, dir()).texture->levels.at(0).texels,
            s.meshes[0].stages[1].texture->levels.at(0).texels);
}

// The provenance of a level scene names the archive entry of the level and of every texture a drawn
// face uses (the fallback as such), whichever archive of the directory holds it.
TEST_F(TinyGame, ProvenanceNamesTheArchives) {
  const nlohmann::json j = scene_fingerprint({"oa:other:1", 0, 0, dir()});
  EXPECT_EQ(j["kind"], "level");
  EXPECT_EQ(j["sources"]["level"], "pak9.pk3:maps/other.bsp");
  const nlohmann::json& t = j["sources"]["textures"];
  EXPECT_EQ(t.size(), 3u);  // wall, jpgwall, missing: the drawn faces' textures
  EXPECT_EQ(t.at("textures/test/wall"), "pak0.pk3:textures/test/wall.tga");
  EXPECT_EQ(t.at("textures/test/jpgwall"), "pak0.pk3:textures/test/jpgwall.jpg");
  EXPECT_EQ(t.at("textures/test/missing"), "fallback");
  EXPECT_EQ(j["archives"].size(), 2u);
}

TEST(Q3Preview, SceneNames) {
  EXPECT_TRUE(is_level_scene("oa:aggressor"));
  EXPECT_FALSE(is_level_scene("ground_plane"));
  EXPECT_EQ(parse_level_scene("oa:aggressor").level, "aggressor");
  EXPECT_EQ(parse_level_scene("oa:aggressor").spawn, 0);
  EXPECT_EQ(parse_level_scene("oa:oa_dm5:3").spawn, 3);
  EXPECT_EQ(error_of([] { parse_level_scene("oa:"); }),
            "--scene 'oa:': no level name (expected oa:MAP[:SPAWN][:KEY=VALUE...])");
  EXPECT_EQ(error_of([] { parse_level_scene("oa:x:-1"); }),
            "--scene 'oa:x:-1': spawn point '-1' is not a number >= 0 (expected oa:MAP[:SPAWN][:KEY=VALUE...])");
  // Options after the spawn point (or instead of it: spawn 0).
  EXPECT_EQ(parse_level_scene("oa:x").options, LevelSceneOptions{});
  const LevelSceneSpec o = parse_level_scene(
      "oa:x:2:cull=none:light=double:vertex=white:eye=spot:gamma=none:overbright=2:"
      "mapoverbright=3");
  EXPECT_EQ(o.spawn, 2);
  EXPECT_EQ(o.options.cull, FaceCull::None);
  EXPECT_EQ(o.options.light, LightRule::Double);
  EXPECT_EQ(o.options.vertex, VertexLight::White);
  EXPECT_EQ(o.options.eye, EyeRule::Spot);
  EXPECT_FALSE(o.options.hardware_gamma);
  EXPECT_EQ(o.options.overbright_bits, 2);
  EXPECT_EQ(o.options.map_overbright_bits, 3);
  EXPECT_EQ(parse_level_scene("oa:x:cull=none").spawn, 0);
  EXPECT_NE(error_of([] { parse_level_scene("oa:x:1:cull=front"); }).find("unknown option 'cull=front'"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_level_scene("oa:x:1:overbright=3"); }).find("unknown option 'overbright=3'"),
            std::string::npos);
  EXPECT_NE(error_of([] { parse_level_scene("oa:x:1:2"); }).find("unknown option '2'"), std::string::npos);
  EXPECT_NE(error_of([] { parse_level_scene("oa:x:1z"); }).find("spawn point '1z'"), std::string::npos);
  EXPECT_NE(error_of([] { parse_level_scene("oa:x:"); }).find("spawn point ''"), std::string::npos);
  EXPECT_NE(error_of([] { parse_level_scene("oa:../x"); }).find("path separator"), std::string::npos);
  EXPECT_NE(error_of([] { parse_level_scene("oa:" + std::string(49, 'a')); }).find("level name longer than 48 characters"),
            std::string::npos);
}

// ---- Bad archives ----

TEST_F(TinyGame, BadArchives) {
  EXPECT_EQ(error_of([&] { const GameArchives g(std::vector<std::string>{dir() + "/none.pk3"}); }), dir() + "/none.pk3: no such archive");
  testdata::write_file(dir_ / "garbage.pk3", Bytes(1000, 0x55));
  EXPECT_NE(error_of([&] { const GameArchives g(dir()); }).find(dir() + "/garbage.pk3: not a readable zip archive ("), std::string::npos);
  fs::remove(dir_ / "garbage.pk3");
  // A truncated archive (the central directory is at the end).
  Bytes pak = testdata::read_file(dir_ / "pak0.pk3");
  pak.resize(pak.size() / 2);
  testdata::write_file(dir_ / "cut.pk3", pak);
  EXPECT_NE(error_of([&] { const Pk3Archive p(dir() + "/cut.pk3"); }).find("cut.pk3: not a readable zip archive"), std::string::npos);
  fs::remove(dir_ / "cut.pk3");
  // Damaged entry data: stored entry, one byte flipped inside its data -> CRC error on read.
  const Bytes payload(500, 0x11);
  testdata::write_zip(dir_ / "crc.pk3", {{"maps/x.bsp", payload}}, true);
  Bytes z = testdata::read_file(dir_ / "crc.pk3");
  const size_t data_start = 30 + z[26] + 256u * z[27] + z[28] + 256u * z[29];  // local header, name, extra field
  z[data_start + 100] ^= 0xFF;
  testdata::write_file(dir_ / "crc.pk3", z);
  const Pk3Archive crc(dir() + "/crc.pk3");
  EXPECT_NE(error_of([&] { crc.read("maps/x.bsp"); }).find(dir() + "/crc.pk3:maps/x.bsp: read failed ("), std::string::npos)
      << error_of([&] { crc.read("maps/x.bsp"); });
  EXPECT_NE(error_of([&] { crc.read("maps/y.bsp"); }).find("crc.pk3: no entry 'maps/y.bsp'"), std::string::npos);
  fs::remove(dir_ / "crc.pk3");
  // Directories.
  EXPECT_NE(error_of([&] { const GameArchives g(dir() + "/nowhere"); }).find("/nowhere: no such game directory"), std::string::npos);
  fs::create_directories(dir_ / "empty");
  EXPECT_EQ(error_of([&] { const GameArchives g(dir() + "/empty"); }), dir() + "/empty: no .pk3 archives in the game directory");
  const GameArchives a(dir());
  EXPECT_NE(error_of([&] { a.locate_level("nope"); }).find("no level 'nope' (maps/nope.bsp) in the 2 archives of "), std::string::npos);
}

TEST_F(TinyGame, BadLevelNamesArchiveAndLump) {
  BspBuilder b = tiny_level();
  b.meshverts[10] = 5;  // the caulk face has 3 vertices
  Bytes bad_version = tiny_level().build("IBSP", 47);
  testdata::write_zip(dir_ / "pak5.pk3", {{"maps/bad.bsp", b.build()}, {"maps/old.bsp", bad_version}});
  const GameArchives a(dir());
  TextureCache cache(a);
  EXPECT_EQ(error_of([&] { load_level(a, "bad", cache); }),
            "pak5.pk3:maps/bad.bsp: lump 11 (meshverts): meshvert 10 (face 4) is 5, outside the face's 3 vertices");
  EXPECT_EQ(error_of([&] { load_level(a, "old", cache); }), "pak5.pk3:maps/old.bsp: BSP version 47, expected 46 (Quake III)");
}

TEST(Q3Level, TriangleBudget) {
  // 33 patch faces sharing one 65 x 65 control grid: 33 x 32 x 32 x 128 triangles > 2^22. Refused
  // before anything is tessellated.
  BspBuilder b;
  b.textures = {{"textures/test/wall", 0, 1}};
  for (int j = 0; j < 65; ++j)
    for (int i = 0; i < 65; ++i) b.vertices.push_back(vtx({1.0 * i, 1.0 * j, 0}, {0, 0}));
  for (int k = 0; k < 33; ++k) b.faces.push_back({0, FaceType::Patch, 0, 65 * 65, 0, 0, -1, 65, 65});
  const Bsp bsp = parse_bsp(b.build(), "t.bsp");
  const GameArchives none(std::vector<std::string>{});
  TextureCache cache(none);
  EXPECT_EQ(error_of([&] { build_level(bsp, "t", "t.bsp", cache); }),
            "t.bsp: lump 13 (faces): face 32: the level exceeds 4194304 triangles");
  b.faces.resize(1);  // one such patch is fine: 32 x 32 sub-patches of 8 x 8 quads
  EXPECT_EQ(build_level(parse_bsp(b.build(), "t.bsp"), "t", "t.bsp", cache).counts.triangles, 131072);
}

// ---- The real game data (Debian openarena-081-maps / -textures; scripts/bootstrap installs them) ----

using testdata::checked_game_data;

// The private game directory holds exactly the checked archives of the installed one, whatever else
// is installed beside them: a full game's archive that overrides a level and adds one is not read.
TEST(OpenArena, TestsReadExactlyTheCheckedArchives) {
  const TempDir installed("tfu-installed-game");
  const fs::path dir = installed.path();
  const Bytes bsp = BspBuilder{}.build();
  testdata::write_zip(dir / "pak1-maps.pk3", {{"maps/arena.bsp", bsp}});
  testdata::write_zip(dir / "pak4-textures.pk3", {{"textures/base/wall.tga", testdata::make_tga({{Rgba8{1, 2, 3, 255}}})}});
  testdata::write_zip(dir / "pak6-patch088.pk3", {{"maps/arena.bsp", bsp}, {"maps/extra.bsp", bsp}});
  const GameArchives everything(dir.string());
  EXPECT_EQ(everything.level_names(), (std::vector<std::string>{"arena", "extra"}));
  EXPECT_EQ(everything.describe(everything.locate_level("arena")), "pak6-patch088.pk3:maps/arena.bsp");

  const testdata::CheckedGameData checked(dir.string());
  ASSERT_TRUE(checked.present());
  const GameArchives exactly(checked.dir());
  EXPECT_EQ(exactly.archives().size(), 2u);
  EXPECT_EQ(exactly.level_names(), (std::vector<std::string>{"arena"}));
  EXPECT_EQ(exactly.describe(exactly.locate_level("arena")), "pak1-maps.pk3:maps/arena.bsp");

  fs::remove(dir / "pak4-textures.pk3");
  EXPECT_FALSE(testdata::CheckedGameData(dir.string()).present());
}

TEST(OpenArena, AggressorCountsCheckedByHand) {
  if (!checked_game_data().present()) GTEST_SKIP() << checked_game_data().missing();
  const GameArchives a(checked_game_data().dir());
  EXPECT_EQ(a.level_names().size(), 50u);
  TextureCache cache(a);
  const Level l = load_level(a, "aggressor", cache);
  // Counted with a separate script over the raw lumps (docs/real-frames.md lists the figures).
  EXPECT_EQ(l.source, "pak1-maps.pk3:maps/aggressor.bsp");
  EXPECT_EQ(l.textures.size(), 31u);
  EXPECT_EQ(l.lightmaps.size(), 4u + 1u);
  ASSERT_EQ(l.spawns.size(), 7u);
  EXPECT_EQ(l.spawns[0].origin, glm::dvec3(-616, 448, 152));
  EXPECT_EQ(l.spawns[0].yaw_deg, 0.0);
  EXPECT_EQ(l.counts.faces_by_type, (std::array<int64_t, 5>{0, 1209, 0, 0, 74}));
  EXPECT_EQ(l.counts.faces_drawn, 1206);
  EXPECT_EQ(l.counts.skipped_sky, 3);  // textures/skies/hellsky
  EXPECT_EQ(l.counts.skipped_invisible, 0);
  EXPECT_EQ(l.counts.fallback_textures, 2);  // textures/evil8_lights/evil8_rlight, textures/liquids/tele
  EXPECT_EQ(l.counts.fallback_faces, 62);    // 54 + 8
  EXPECT_EQ(l.counts.resolved_textures, 21);
  EXPECT_EQ(l.counts.triangles, 3300);
  const auto it = std::find_if(l.textures.begin(), l.textures.end(),
                               [](const LevelTexture& t) { return t.name == "textures/e7/e7walldesign01"; });
  ASSERT_NE(it, l.textures.end());
  EXPECT_EQ(it->source, "pak4-textures.pk3:textures/e7/e7walldesign01.jpg");
  EXPECT_EQ(it->texture->width(), 256);
  EXPECT_EQ(it->texture->height(), 640);

  // A reduced preview from spawn 0 (a corridor, no sky in view): the level covers every pixel.
  const Scene s = level_scene(l, 0, 160, 90);
  RenderOptions ro;
  ro.threads = 1;
  const RenderResult r = render_scene(s, ro);
  const Rgba8 bg{static_cast<uint8_t>(std::lround(kLevelSceneBackground[0] * 255)),
                 static_cast<uint8_t>(std::lround(kLevelSceneBackground[1] * 255)),
                 static_cast<uint8_t>(std::lround(kLevelSceneBackground[2] * 255)), 255};
  int64_t background = 0;
  for (const Rgba8& p : r.image.texels) background += p == bg;
  EXPECT_EQ(background, 0);
  EXPECT_EQ(r.stats.triangles, 3300);
}

// A real frame through both models (game levels as workloads): aggressor from spawn 0 at 320x180, base
// texture x light map, as the game shows it. The cycle model equals the golden model on every request of
// both stages in trilinear and edge-preserving modes; statistics that fail on garbage (a wrong UV set, a
// light map on the wrong faces, an upside-down texture) hold: the frame is covered, its brightness and
// contrast are those of the checked render (mean luma 46.8, standard deviation 34.4 on 0..255; 25.3 and
// 22.2 under the earlier light rule, light=double: the game's light is 1.85 times as bright), and it is
// close to the supersampled truth. Culling back faces as the engine does removes requests, not pixels.
TEST(OpenArena, RealFrameThroughBothModels) {
  if (!checked_game_data().present()) GTEST_SKIP() << checked_game_data().missing();
  const Scene s = open_scene({"oa:aggressor:0", 320, 180, checked_game_data().dir()});
  ASSERT_EQ(s.meshes.front().stages.size(), 2u);
  RenderOptions ro;
  ro.trace = true;
  ro.ground_truth = true;
  const RenderResult r = render_scene(s, ro);
  double sum = 0, sum2 = 0;
  for (const Rgba8& p : r.image.texels) {
    const double y = (5.0 * p.r + 9.0 * p.g + 2.0 * p.b) / 16.0;
    sum += y;
    sum2 += y * y;
  }
  const double n = static_cast<double>(r.image.texels.size()), mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 46.8, 1.5);
  EXPECT_NEAR(sd, 34.4, 1.5);
  const Rgba8 bg{static_cast<uint8_t>(std::lround(kLevelSceneBackground[0] * 255)),
                 static_cast<uint8_t>(std::lround(kLevelSceneBackground[1] * 255)),
                 static_cast<uint8_t>(std::lround(kLevelSceneBackground[2] * 255)), 255};
  EXPECT_EQ(std::count(r.image.texels.begin(), r.image.texels.end(), bg), 0);  // the level covers the frame
  EXPECT_GT(psnr_db(r.truth, r.image), 31.0);  // measured 32.1: the display ramp doubles every error
  // Without culling: more requests, the same picture but for a few pixels (rounding of edges that
  // back faces share with front ones).
  const Scene both = open_scene({"oa:aggressor:0:cull=none", 320, 180, checked_game_data().dir()});
  const RenderResult rb = render_scene(both, ro);
  EXPECT_GT(r.stats.culled, 0);
  EXPECT_EQ(rb.stats.culled, 0);
  EXPECT_GT(rb.trace.requests.size(), r.trace.requests.size());
  int64_t differ = 0;
  for (size_t i = 0; i < r.image.texels.size(); ++i) differ += !(r.image.texels[i] == rb.image.texels[i]);
  EXPECT_LT(differ, static_cast<int64_t>(r.image.texels.size() / 100)) << differ;
  for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_LINEAR"}) {
    ro.filter = filter_mode_from_name(mode);
    ro.ground_truth = false;
    const RenderResult rm = render_scene(s, ro);
    const rtl::SceneSimResult sim = rtl::simulate_scene(s, rm, rtl::UnitConfig{}, {});
    EXPECT_TRUE(sim.mismatch.empty()) << mode << ": " << sim.mismatch;
    EXPECT_EQ(sim.image.texels, rm.image.texels) << mode;
    EXPECT_EQ(sim.stats.table("stages")->rows.size(), 2u);
    EXPECT_GE(sim.stats.table("textures")->rows.size(), 10u) << mode;
  }
}

// Anisotropic filtering on a real level: 16 probes beat trilinear against the supersampled truth (measured at
// 320x180: 36.5 -> 41.8 dB, SSIM 0.938 -> 0.985), and the anisotropic frame, trilinear and
// edge-preserving probes, goes through the cycle model bit for bit.
TEST(OpenArena, AnisotropicRealFrame) {
  if (!checked_game_data().present()) GTEST_SKIP() << checked_game_data().missing();
  const Scene s = open_scene({"oa:aggressor:0", 320, 180, checked_game_data().dir()});
  RenderOptions ro;
  ro.trace = true;
  ro.ground_truth = true;
  const RenderResult tri = render_scene(s, ro);
  ro.ground_truth = false;
  ro.sampler_overrides["max_aniso"] = "16";
  const RenderResult aniso = render_scene(s, ro);
  EXPECT_GT(psnr_db(tri.truth, aniso.image), psnr_db(tri.truth, tri.image) + 3.0);
  EXPECT_GT(ssim_luma(tri.truth, aniso.image), ssim_luma(tri.truth, tri.image) + 0.02);
  for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_LINEAR"}) {
    ro.filter = filter_mode_from_name(mode);
    const RenderResult rm = render_scene(s, ro);
    const rtl::SceneSimResult sim = rtl::simulate_scene(s, rm, rtl::UnitConfig{}, {});
    EXPECT_TRUE(sim.mismatch.empty()) << mode << ": " << sim.mismatch;
    EXPECT_EQ(sim.image.texels, rm.image.texels) << mode;
    EXPECT_GT(sim.stats.counter("probes"), sim.requests + sim.requests / 4) << mode;  // measured: 1.87 probes per request
  }
}

}  // namespace
}  // namespace tfu::q3
