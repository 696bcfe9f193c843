// Quake III BSP lumps and Bezier patches (cmodel/bsp.hpp, cmodel/bezier_patch.hpp): every lump the
// loader reads round-trips from a BSP built here; patch points against hand-computed Bernstein
// sums; every malformed file gives one InputError line naming the source and the lump.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "cmodel/bezier_patch.hpp"
#include "cmodel/bsp.hpp"
#include "cmodel/error.hpp"
#include "cmodel/pk3.hpp"
#include "cmodel/temp_paths.hpp"
#include "cmodel/trace.hpp"
#include "cmodel/q3_level.hpp"
#include "testbench/input_error.hpp"
#include "testbench/q3_test_data.hpp"

namespace tfu::q3 {
namespace {

using testdata::BspBuilder;
using testdata::Bytes;
using testdata::vtx;

// A small valid BSP: a quad polygon (lightmap 0), a mesh triangle (vertex-lit), a 3x3 patch
// (lightmap 1) and a billboard.
BspBuilder small_bsp() {
  BspBuilder b;
  b.entities = "{\n\"classname\" \"worldspawn\"\n}\n";
  b.textures = {{"textures/test/wall", 0, 1}, {"textures/test/curve", 0x20, 1}, {"flareShader", 0, 0}};
  b.vertices = {vtx({0, 0, 0}, {0, 1}, {0.25, 0.5}, {1, 2, 3, 4}, {0, -1, 0}), vtx({64, 0, 0}, {1, 1}),
                vtx({64, 0, 64}, {1, 0}), vtx({0, 0, 64}, {0, 0})};
  for (int i = 0; i < 3; ++i) b.vertices.push_back(vtx({100.0 + i, 0, 0}, {0.5 * i, 0}));
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) b.vertices.push_back(vtx({8.0 * i, 8.0 * j, 0}, {0.5 * i, 0.5 * j}, {0.5 * i, 0.5 * j}));
  b.vertices.push_back(vtx({0, 0, 128}, {0, 0}));
  b.meshverts = {0, 1, 2, 0, 2, 3, 2, 0, 1};
  b.faces = {{0, FaceType::Polygon, 0, 4, 0, 6, 0},
             {0, FaceType::Mesh, 4, 3, 6, 3, -1},
             {1, FaceType::Patch, 7, 9, 0, 0, 1, 3, 3},
             {2, FaceType::Billboard, 16, 1, 0, 0, -1}};
  Bytes lm0(size_t{128} * 128 * 3), lm1(size_t{128} * 128 * 3, 200);
  for (size_t i = 0; i < lm0.size(); ++i) lm0[i] = static_cast<uint8_t>(i % 251);
  b.lightmaps = {lm0, lm1};
  b.add_brush({-64, -64, -16}, {64, 64, 0}, 0);  // a floor, and a wedge cut by z <= y
  b.add_brush({0, 0, 0}, {32, 32, 32}, 1, {{{0, -0.6, 0.8}, 0.0}});
  b.models = {{{-64, -64, -16}, {64, 64, 32}, 0, 2}};
  return b;
}

// The InputError message of parsing `file`, or "" if it parses; also checks the one-line rule.
std::string parse_error(const Bytes& file) {
  try {
    parse_bsp(file, "test.pk3:maps/t.bsp");
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_LE(msg.size(), 300u) << msg;
    EXPECT_EQ(msg.rfind("test.pk3:maps/t.bsp: ", 0), 0u) << msg;
    return msg;
  }
  return "";
}

#define EXPECT_ERROR_HAS(file, text)                                         \
  do {                                                                      \
    const std::string msg_ = parse_error(file);                             \
    EXPECT_NE(msg_.find(text), std::string::npos) << "message: " << msg_;  \
  } while (0)

TEST(Bsp, EveryReadLumpRoundTrips) {
  const BspBuilder b = small_bsp();
  const Bsp bsp = parse_bsp(b.build(), "t.bsp");
  EXPECT_EQ(bsp.entities, b.entities);  // the trailing NUL is dropped
  ASSERT_EQ(bsp.textures.size(), 3u);
  EXPECT_EQ(bsp.textures[1].name, "textures/test/curve");
  EXPECT_EQ(bsp.textures[1].surface_flags, 0x20);
  EXPECT_EQ(bsp.textures[1].content_flags, 1);
  ASSERT_EQ(bsp.vertices.size(), b.vertices.size());
  const Vertex& v0 = bsp.vertices[0];
  EXPECT_EQ(v0.pos, glm::dvec3(0, 0, 0));
  EXPECT_EQ(v0.uv0, glm::dvec2(0, 1));
  EXPECT_EQ(v0.uv1, glm::dvec2(0.25, 0.5));
  EXPECT_EQ(v0.normal, glm::dvec3(0, -1, 0));
  EXPECT_EQ(v0.colour, (std::array<uint8_t, 4>{1, 2, 3, 4}));
  EXPECT_EQ(bsp.vertices[2].pos, glm::dvec3(64, 0, 64));
  EXPECT_EQ(bsp.meshverts, b.meshverts);
  ASSERT_EQ(bsp.faces.size(), 4u);
  EXPECT_EQ(bsp.faces[1].type, FaceType::Mesh);
  EXPECT_EQ(bsp.faces[1].first_meshvert, 6);
  EXPECT_EQ(bsp.faces[1].lightmap, -1);
  EXPECT_EQ(bsp.faces[2].patch_size, (std::array<int32_t, 2>{3, 3}));
  EXPECT_EQ(bsp.faces[2].first_vertex, 7);
  EXPECT_EQ(bsp.faces[2].lightmap, 1);
  ASSERT_EQ(bsp.lightmaps.size(), 2u);
  EXPECT_EQ(bsp.lightmaps[0], b.lightmaps[0]);
  EXPECT_EQ(bsp.lightmaps[1][3 * 128 * 128 - 1], 200);
  EXPECT_TRUE(bsp.nonfinite_lightmap_uv.empty());
}

TEST(Bsp, HeaderErrors) {
  const BspBuilder b = small_bsp();
  EXPECT_ERROR_HAS(b.build("IBSX"), "not a Quake III BSP (magic is not 'IBSP')");
  EXPECT_ERROR_HAS(b.build("IBSP", 47), "BSP version 47, expected 46");
  EXPECT_ERROR_HAS(Bytes(100, 0), "100 bytes, too short for a BSP header (144 bytes)");
  EXPECT_ERROR_HAS(Bytes{}, "0 bytes, too short");
}

TEST(Bsp, LumpsOutsideTheFile) {
  const Bytes good = small_bsp().build();
  const auto size = static_cast<int32_t>(good.size());
  Bytes f = good;
  const auto [off13, len13] = testdata::get_lump(f, kLumpFaces);
  testdata::set_lump(f, kLumpFaces, off13, size - off13 + 1);  // one byte past the end
  EXPECT_ERROR_HAS(f, "lump 13 (faces): bytes ");
  EXPECT_ERROR_HAS(f, "outside the " + std::to_string(size) + "-byte file");
  f = good;
  testdata::set_lump(f, 5, -4, 0);  // a lump the loader does not read is still checked
  EXPECT_ERROR_HAS(f, "lump 5 (leaf faces): bytes -4+0 outside");
  f = good;
  testdata::set_lump(f, kLumpVertices, 0, -44);
  EXPECT_ERROR_HAS(f, "lump 10 (vertices): bytes 0+-44 outside");
  f = good;
  testdata::set_lump(f, kLumpLightmaps, 2000000000, 2000000000);  // no int32 overflow
  EXPECT_ERROR_HAS(f, "lump 14 (lightmaps)");
  EXPECT_EQ(len13, 4 * 104);
}

TEST(Bsp, LumpsOfPartialRecords) {
  Bytes f = small_bsp().build();
  const auto [off, len] = testdata::get_lump(f, kLumpVertices);
  testdata::set_lump(f, kLumpVertices, off, len - 1);
  EXPECT_ERROR_HAS(f, "lump 10 (vertices): 747 bytes is not a whole number of 44-byte records");
  f = small_bsp().build();
  const auto [loff, llen] = testdata::get_lump(f, kLumpLightmaps);
  testdata::set_lump(f, kLumpLightmaps, loff, llen - 3);
  EXPECT_ERROR_HAS(f, "lump 14 (lightmaps)");
}

TEST(Bsp, FaceRangesAndIndices) {
  BspBuilder b = small_bsp();
  b.faces[0].vertex_count = 40;  // past the 17 vertices
  EXPECT_ERROR_HAS(b.build(), "lump 13 (faces): face 0: vertices 0+40 outside the 17 of lump 10");
  b = small_bsp();
  b.faces[1].first_vertex = -1;
  EXPECT_ERROR_HAS(b.build(), "face 1: vertices -1+3 outside");
  b = small_bsp();
  b.meshverts[4] = 9;  // face 0 has 4 vertices
  EXPECT_ERROR_HAS(b.build(), "lump 11 (meshverts): meshvert 4 (face 0) is 9, outside the face's 4 vertices");
  b = small_bsp();
  b.meshverts[7] = -1;
  EXPECT_ERROR_HAS(b.build(), "meshvert 7 (face 1) is -1");
  b = small_bsp();
  b.faces[1].first_meshvert = 8;  // 8 + 3 > 9 meshverts
  EXPECT_ERROR_HAS(b.build(), "face 1: meshverts 8+3 outside the 9 of lump 11");
  b = small_bsp();
  b.faces[0].meshvert_count = 4;
  EXPECT_ERROR_HAS(b.build(), "face 0: 4 meshverts is not a whole number of triangles");
  b = small_bsp();
  b.faces[3].texture = 3;
  EXPECT_ERROR_HAS(b.build(), "face 3: texture 3 outside the 3 of lump 1");
  b = small_bsp();
  b.faces[0].lightmap = 2;
  EXPECT_ERROR_HAS(b.build(), "face 0: lightmap 2 outside the 2 of lump 14");
  b = small_bsp();
  b.faces[3].type = static_cast<FaceType>(5);
  EXPECT_ERROR_HAS(b.build(), "face 3: unknown type 5 (1..4)");
  b = small_bsp();
  b.faces[3].type = static_cast<FaceType>(0);
  EXPECT_ERROR_HAS(b.build(), "face 3: unknown type 0");
}

TEST(Bsp, CollisionLumps) {
  const Bsp ok = parse_bsp(small_bsp().build(), "t.bsp");
  ASSERT_EQ(ok.brushes.size(), 2u);
  EXPECT_EQ(ok.brushes[1].side_count, 7);
  EXPECT_EQ(ok.brushes[1].texture, 1);
  ASSERT_EQ(ok.planes.size(), 13u);
  EXPECT_EQ(ok.planes[12].normal, glm::dvec3(0, static_cast<float>(-0.6), static_cast<float>(0.8)));
  EXPECT_EQ(ok.planes[4].dist, 16.0);  // the floor's -z side: dot((0, 0, -1), p) <= 16
  EXPECT_EQ(ok.brush_sides[7].plane, 7);
  ASSERT_EQ(ok.models.size(), 1u);
  EXPECT_EQ(ok.models[0].brush_count, 2);
  EXPECT_EQ(ok.models[0].maxs, glm::dvec3(64, 64, 32));
  BspBuilder b = small_bsp();
  b.planes[3].normal = {0, 0.5, 0};
  EXPECT_ERROR_HAS(b.build(), "lump 2 (planes): plane 3: normal of length 0.5, not a unit vector");
  b = small_bsp();
  b.planes[2].dist = std::numeric_limits<double>::infinity();
  EXPECT_ERROR_HAS(b.build(), "lump 2 (planes): record 2: inf is not a finite number");
  b = small_bsp();
  b.brush_sides[5].plane = 13;
  EXPECT_ERROR_HAS(b.build(), "lump 9 (brush sides): side 5: plane 13 outside the 13 of lump 2");
  b = small_bsp();
  b.brush_sides[0].texture = -1;
  EXPECT_ERROR_HAS(b.build(), "lump 9 (brush sides): side 0: texture -1 outside the 3 of lump 1");
  b = small_bsp();
  b.brushes[1].side_count = 8;
  EXPECT_ERROR_HAS(b.build(), "lump 8 (brushes): brush 1: sides 6+8 outside the 13 of lump 9");
  b = small_bsp();
  b.brushes[0].texture = 3;
  EXPECT_ERROR_HAS(b.build(), "lump 8 (brushes): brush 0: texture 3 outside the 3 of lump 1");
  b = small_bsp();
  b.models[0].brush_count = 3;
  EXPECT_ERROR_HAS(b.build(), "lump 7 (models): model 0: brushes 0+3 outside the 2 of lump 8");
  b = small_bsp();
  b.models[0].mins.x = std::nan("");
  EXPECT_ERROR_HAS(b.build(), "lump 7 (models): record 0: nan is not a finite number");
}

TEST(Bsp, PatchSizes) {
  BspBuilder b = small_bsp();
  b.faces[2].patch_w = 4;  // even
  b.faces[2].vertex_count = 12;
  b.vertices.resize(19, b.vertices.back());
  EXPECT_ERROR_HAS(b.build(), "face 2: patch of 4x3 control points (each side must be odd, 3..65)");
  b = small_bsp();
  b.faces[2].patch_h = 1;
  EXPECT_ERROR_HAS(b.build(), "patch of 3x1 control points");
  b = small_bsp();
  b.faces[2].patch_w = b.faces[2].patch_h = 67;
  EXPECT_ERROR_HAS(b.build(), "patch of 67x67");
  b = small_bsp();
  b.faces[2].vertex_count = 8;
  EXPECT_ERROR_HAS(b.build(), "face 2: patch of 3x3 control points but 8 vertices");
}

TEST(Bsp, NonFiniteVertexFields) {
  BspBuilder b = small_bsp();
  b.vertices[2].pos.y = std::numeric_limits<double>::infinity();
  EXPECT_ERROR_HAS(b.build(), "lump 10 (vertices): vertex 2: field 1 is not a finite number");
  b = small_bsp();
  b.vertices[3].uv0.x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_ERROR_HAS(b.build(), "vertex 3: field 3 is not a finite number");
  // A NaN lightmap uv on a vertex-lit face (q3map2 writes these): read as 0 and flagged.
  b = small_bsp();
  b.vertices[5].uv1.y = std::numeric_limits<double>::quiet_NaN();
  const Bsp bsp = parse_bsp(b.build(), "t.bsp");
  EXPECT_EQ(bsp.vertices[5].uv1, glm::dvec2(0, 0));
  ASSERT_EQ(bsp.nonfinite_lightmap_uv.size(), b.vertices.size());
  EXPECT_TRUE(bsp.nonfinite_lightmap_uv[5]);
  EXPECT_FALSE(bsp.nonfinite_lightmap_uv[4]);
  // ... but an error on a face with a lightmap.
  b = small_bsp();
  b.vertices[1].uv1.x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_ERROR_HAS(b.build(), "lump 10 (vertices): vertex 1 (face 0, lightmap 0): lightmap uv is not a finite number");
  // TFU-S E17: finite but beyond the scene format's bound (a uv of 1e15 overflowed the ground truth's
  // texel index): refused like a NaN, the bound named.
  b = small_bsp();
  b.vertices[3].uv0.x = 1e15;
  EXPECT_ERROR_HAS(b.build(), "vertex 3: field 3 is not a finite number within +-1e+06: 1e+15");
  b = small_bsp();
  b.vertices[2].pos.z = -2e6;
  EXPECT_ERROR_HAS(b.build(), "vertex 2: field 2 is not a finite number within +-1e+06: -2e+06");
  b = small_bsp();
  b.vertices[3].uv0.x = 1e6;  // the bound itself is allowed
  EXPECT_NO_THROW(parse_bsp(b.build(), "t.bsp"));
  b = small_bsp();
  b.vertices[1].uv1.x = 3e7;
  EXPECT_ERROR_HAS(b.build(), "vertex 1 (face 0, lightmap 0): lightmap uv is not a finite number within +-1e+06");
}

TEST(Bsp, Entities) {
  const std::string text =
      "{\n\"classname\" \"worldspawn\"\n\"message\" \"a { brace\"\n}\n"
      "// comment line\n{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"1 2 3\"\n\"angle\" \"90\"\n"
      "\"angle\" \"180\"\n}\n{ bare word }\n";
  const auto ents = parse_entities(text, "t.bsp");
  ASSERT_EQ(ents.size(), 3u);
  EXPECT_EQ(ents[0].value("message"), "a { brace");
  EXPECT_EQ(ents[1].value("origin"), "1 2 3");
  EXPECT_EQ(ents[1].value("angle"), "180");  // the last one wins
  EXPECT_EQ(ents[1].value("absent"), "");
  EXPECT_EQ(ents[2].value("bare"), "word");
  EXPECT_TRUE(parse_entities("", "t.bsp").empty());

  const auto error = [](const std::string& t) {
    try {
      parse_entities(t, "t.bsp");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error("{\n\"a\" \"b\n\"}"), "t.bsp: lump 0 (entities): line 2: line break inside a quoted string");
  EXPECT_EQ(error("{\n\"a\" \"b"), "t.bsp: lump 0 (entities): line 2: unterminated quoted string");
  EXPECT_EQ(error("\"a\" \"b\""), "t.bsp: lump 0 (entities): line 1: expected '{', found 'a'");
  EXPECT_EQ(error("{\n\"a\" \"b\"\n"), "t.bsp: lump 0 (entities): line 3: text ends inside an entity");
  EXPECT_EQ(error("{\n\"a\" }"), "t.bsp: lump 0 (entities): line 2: key 'a' has no value");
  EXPECT_EQ(error("{ { }"), "t.bsp: lump 0 (entities): line 1: '{' inside an entity");
}

// Random damage to the words of a valid file (header, directory, records; the lightmap texels at
// the end are left alone, any value is valid there): the loader either
// accepts the file and builds a level from it, or throws InputError; nothing else (the ASan build
// also checks every access).
TEST(Bsp, RandomWordDamageGivesInputErrorOrALevel) {
  const Bytes good = small_bsp().build();
  const GameArchives none(std::vector<std::string>{});
  TextureCache cache(none);
  std::mt19937 rng(20240611);
  const int32_t interesting[] = {0, 1, -1, 2, 3, 4, 5, 7, 9, 65, 67, 128, 1 << 20, INT32_MAX, INT32_MIN,
                                 static_cast<int32_t>(good.size())};
  const size_t damageable = static_cast<size_t>(testdata::get_lump(good, kLumpLightmaps).first);
  int accepted = 0, refused = 0;
  for (int iter = 0; iter < 3000; ++iter) {
    Bytes f = good;
    const int words = 1 + static_cast<int>(rng() % 3);
    for (int w = 0; w < words; ++w) {
      const size_t at = 4 * (rng() % (damageable / 4));
      const int32_t v = rng() % 2 ? interesting[rng() % std::size(interesting)] : static_cast<int32_t>(rng());
      std::memcpy(f.data() + at, &v, 4);
    }
    if (rng() % 8 == 0) f.resize(rng() % f.size());  // and sometimes truncated
    try {
      const Bsp bsp = parse_bsp(f, "fuzz.bsp");
      build_level(bsp, "fuzz", "fuzz.bsp", cache);
      ++accepted;
    } catch (const InputError& e) {
      ++refused;
      EXPECT_EQ(std::string(e.what()).rfind("fuzz.bsp: ", 0), 0u) << e.what();
    }
  }
  std::printf("random damage: %d files accepted, %d refused\n", accepted, refused);
  EXPECT_GT(accepted, 300);  // damage to floats, colours and names is harmless
  EXPECT_GT(refused, 1000);
}

// ---- Patches ----

TEST(BezierPatch, BernsteinWeights) {
  const auto w = quadratic_bernstein(0.25);
  EXPECT_DOUBLE_EQ(w[0], 0.5625);  // (3/4)^2
  EXPECT_DOUBLE_EQ(w[1], 0.375);   // 2 (1/4)(3/4)
  EXPECT_DOUBLE_EQ(w[2], 0.0625);  // (1/4)^2
}

// 3 x 3 control grid: x = 16 u^2 (controls 0, 0, 16 along u), y = 8 (2v - v^2) (0, 8, 8 along v),
// z = 32 B1(u) B1(v) (32 at the centre only); uv0 = (i/2, j/2) (reproduces (u, v)), uv1.x = i
// (gives 2u), red = 255 at the centre only, green 100 everywhere, normals +z.
std::vector<Vertex> test_grid_3x3() {
  std::vector<Vertex> c;
  const double xs[3] = {0, 0, 16}, ys[3] = {0, 8, 8};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const bool centre = i == 1 && j == 1;
      c.push_back(vtx({xs[i], ys[j], centre ? 32.0 : 0.0}, {0.5 * i, 0.5 * j}, {1.0 * i, 0},
                      {static_cast<uint8_t>(centre ? 255 : 0), 100, 0, 255}));
    }
  return c;
}

TEST(BezierPatch, HandComputedPointsAt8Subdivisions) {
  const auto control = test_grid_3x3();
  const PatchMesh m = tessellate_patch(control, 3, 3);
  ASSERT_EQ(kPatchSubdivision, 8);
  EXPECT_EQ(m.grid_width, 9);
  EXPECT_EQ(m.grid_height, 9);
  ASSERT_EQ(m.vertices.size(), 81u);
  ASSERT_EQ(m.triangles.size(), 128u);
  // Grid vertex (I, J) = (2, 6): u = 1/4, v = 3/4.
  const Vertex& p = m.vertices[6 * 9 + 2];
  EXPECT_DOUBLE_EQ(p.pos.x, 1.0);   // 16 (1/4)^2
  EXPECT_DOUBLE_EQ(p.pos.y, 7.5);   // 8 (3/2 - 9/16)
  EXPECT_DOUBLE_EQ(p.pos.z, 4.5);   // 32 (3/8)(3/8)
  EXPECT_DOUBLE_EQ(p.uv0.x, 0.25);
  EXPECT_DOUBLE_EQ(p.uv0.y, 0.75);
  EXPECT_DOUBLE_EQ(p.uv1.x, 0.5);   // 2u
  EXPECT_DOUBLE_EQ(p.uv1.y, 0.0);
  EXPECT_EQ(p.colour[0], 36);       // 255 (9/64) = 35.86 -> 36
  EXPECT_EQ(p.colour[1], 100);
  EXPECT_EQ(p.normal, glm::dvec3(0, 0, 1));
  // Centre (4, 4): u = v = 1/2: z = 32 / 4 = 8, x = 4, y = 6.
  EXPECT_DOUBLE_EQ(m.vertices[4 * 9 + 4].pos.z, 8.0);
  EXPECT_DOUBLE_EQ(m.vertices[4 * 9 + 4].pos.x, 4.0);
  EXPECT_DOUBLE_EQ(m.vertices[4 * 9 + 4].pos.y, 6.0);
  // The corners are the corner control points.
  EXPECT_EQ(m.vertices[0].pos, control[0].pos);
  EXPECT_EQ(m.vertices[8].pos, control[2].pos);
  EXPECT_EQ(m.vertices[80].pos, control[8].pos);
  // Triangle order: quad (0, 0) -> {g(0,0), g(1,0), g(1,1)}, {g(0,0), g(1,1), g(0,1)}.
  EXPECT_EQ(m.triangles[0], (std::array<uint32_t, 3>{0, 1, 10}));
  EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{0, 10, 9}));
  EXPECT_EQ(m.triangles[127], (std::array<uint32_t, 3>{70, 80, 79}));
}

TEST(BezierPatch, SubPatchesShareEdges) {
  // 5 x 3: two sub-patches along u. Row 0 x controls 0, 8, 16, 40, 48; rows 1, 2 shifted in y.
  std::vector<Vertex> c;
  const double xs[5] = {0, 8, 16, 40, 48};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 5; ++i) c.push_back(vtx({xs[i], 10.0 * j, 0}, {0.25 * i, 0.5 * j}));
  const PatchMesh m = tessellate_patch(c, 5, 3, 4);
  EXPECT_EQ(m.grid_width, 9);  // 2 sub-patches x 4 + 1
  EXPECT_EQ(m.grid_height, 5);
  EXPECT_EQ(m.triangles.size(), 2u * 8 * 4);
  // I = 4 ends sub-patch 0 (u = 1): control point 2; I = 6 is sub-patch 1 at u = 1/2:
  // (16 + 2 * 40 + 48) / 4 = 36.
  EXPECT_DOUBLE_EQ(m.vertices[4].pos.x, 16.0);
  EXPECT_DOUBLE_EQ(m.vertices[6].pos.x, 36.0);
  EXPECT_DOUBLE_EQ(m.vertices[8].pos.x, 48.0);
  EXPECT_DOUBLE_EQ(m.vertices[2 * 9 + 6].pos.y, 10.0);  // v = 1/2 of y = 0, 10, 20
  // Subdivision 1: only the control corners of each sub-patch.
  const PatchMesh coarse = tessellate_patch(c, 5, 3, 1);
  ASSERT_EQ(coarse.vertices.size(), 6u);
  EXPECT_EQ(coarse.vertices[1].pos, c[2].pos);
  EXPECT_EQ(coarse.vertices[5].pos, c[14].pos);
}

}  // namespace
}  // namespace tfu::q3

namespace tfu::q3 {
namespace {

// Names from archives and files never reach an output format with a control character in them
// (docs/inputs-outputs.md, "Names"): a BSP texture name, a pk3 entry name and a trace binding that
// hold a newline are refused with one line (a newline in a texture name once wrote a binding line
// "# tfu-texture 1 /etc/hostname" of its own into a trace).
TEST(Names, ControlCharactersAreRefusedBeforeAnyOutput) {
  BspBuilder b = small_bsp();
  b.textures[1].name = "textures/x\n# tfu-texture 1 /etc/hostname";
  EXPECT_ERROR_HAS(b.build(), "lump 1 (textures): texture 1 is named 'textures/x?# tfu-texture 1 /etc/hostname', with a "
                              "control character");
  b.textures[1].name = std::string("textures/del") + char{0x7f};
  EXPECT_ERROR_HAS(b.build(), "texture 1 is named 'textures/del?'");
  // A pk3 entry.
  const TempDir scratch("tfu-names");
  const std::filesystem::path dir = scratch.path();
  testdata::write_zip(dir / "a.pk3", {{"maps/ok.bsp", Bytes{1}}, {"maps/x\ny.bsp", Bytes{2}}});
  try {
    Pk3Archive a((dir / "a.pk3").string());
    ADD_FAILURE() << "opened";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a.pk3: entry 1 is named 'maps/x?y.bsp', with a control character"),
              std::string::npos)
        << e.what();
  }
  testdata::write_zip(dir / "b.pk3", {{"maps/ok.bsp", Bytes{1}}});
  EXPECT_EQ(Pk3Archive((dir / "b.pk3").string()).entry_names(), std::vector<std::string>{"maps/ok.bsp"});
  // A trace binding, refused before a line is written.
  Trace t;
  t.mode = TraceMode::Lod;
  t.textures.push_back({1, "proc:text\n# tfu-texture 2 /etc/hostname", {}, ""});
  t.requests.push_back({});
  std::ostringstream out;
  try {
    write_trace(out, t);
    ADD_FAILURE() << "written";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "trace binding tfu-texture 1 ('proc:text?# tfu-texture 2 /etc/hostname'): a control character cannot be "
              "written into a trace line");
  }
  EXPECT_EQ(out.str(), "");
  t.textures[0].spec = "proc:text";
  t.textures[0].params = {{"format", "l8\r"}};
  EXPECT_THROW(write_trace(out, t), InputError);
  // ... nor read from one: so what the reader accepts, the writer writes back.
  std::istringstream in("# tfu-texture 0 proc:te\x01xt\n0.5,0.5,0\n");
  try {
    parse_trace(in, "n.txt");
    ADD_FAILURE() << "parsed";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "n.txt:1: a control character in a binding line");
  }
}

// A file name with a space, a '%' or what looks like a parameter ("a.png mipmaps=none") is one word
// of a binding line: the writer encodes ' ', '%' and a key's '=' as %20, %25, %3D and the reader
// decodes them (docs/traces.md). Before, "# tfu-texture 0 a b.png" was written, and read as the
// spec "a" with a parameter "b.png" (refused), or "c.png mipmaps=none" as c.png without MIP levels.
TEST(Names, SpacesPercentAndEqualsInNamesRoundTripThroughTraces) {
  Trace t;
  t.mode = TraceMode::Lod;
  t.textures.push_back({0, "my textures/a b.png", {{"layout", "linear"}}, ""});
  t.textures.push_back({1, "c.png mipmaps=none", {}, ""});
  t.textures.push_back({2, "100%25 real%.png", {{"odd=key", "v=1 2"}}, ""});
  t.samplers.push_back({0, "", {{"filter", "LINEAR"}}, ""});
  t.requests.push_back({});
  std::ostringstream out;
  write_trace(out, t);
  EXPECT_NE(out.str().find("# tfu-texture 0 my%20textures/a%20b.png layout=linear\n"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("# tfu-texture 1 c.png%20mipmaps=none\n"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("# tfu-texture 2 100%2525%20real%25.png odd%3Dkey=v=1%202\n"), std::string::npos) << out.str();
  std::istringstream in(out.str());
  const Trace back = parse_trace(in, "w.txt");
  ASSERT_EQ(back.textures.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(back.textures[k].spec, t.textures[k].spec);
    EXPECT_EQ(back.textures[k].params, t.textures[k].params);
  }
  // A '%' that starts no %XX is refused with the word.
  std::istringstream bad("# tfu-texture 0 50%.png\n0.5,0.5,0\n");
  EXPECT_EQ(input_error([&] { parse_trace(bad, "b.txt"); }), "b.txt:1: '50%.png': a '%' starts %XX, two hex digits (a '%' itself is %25)");
  // What the reader could not take back is refused before a line is written.
  t.textures = {{0, "", {}, ""}};
  std::ostringstream none;
  EXPECT_EQ(input_error([&] { write_trace(none, t); }), "trace binding tfu-texture 0: a texture binding needs a spec");
  EXPECT_EQ(none.str(), "");
}

}  // namespace
}  // namespace tfu::q3
