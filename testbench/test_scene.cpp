// Scene files and procedural textures (cmodel/scene.hpp, cmodel/procedural.hpp): JSON errors with
// line and column, key and type checking, built-in scenes, mesh generators, analytic functions.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "cmodel/error.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/procedural_truth.hpp"
#include "cmodel/scene.hpp"

namespace tfu {
namespace {

// The InputError message of parsing `text`, or "" if it parses.
std::string parse_error(const std::string& text) {
  try {
    parse_scene(text, "bad.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kMinimalMesh =
    R"({"primitive": "quad", "corners": [[-1,1,0],[1,1,0],[1,-1,0],[-1,-1,0]], "texture": {"procedural": "checkerboard", "size": 16}})";

std::string scene_with_mesh(const std::string& mesh) {
  return R"({"width": 32, "height": 32, "meshes": [)" + mesh + "]}";
}

TEST(Scene, MalformedJsonReportsLineAndColumn) {
  // Missing colon after "height": nlohmann stops after the number token "64", whose last
  // character is line 3, column 13 (the position is that of the last character read).
  EXPECT_EQ(parse_error("{\n  \"width\": 64,\n  \"height\" 64\n}").rfind("bad.json: line 3, column 13: ", 0), 0u)
      << parse_error("{\n  \"width\": 64,\n  \"height\" 64\n}");
  // Truncated input: the error is one past the end of line 2 (14 characters).
  const std::string trunc = parse_error("{\n  \"width\": 64,");
  EXPECT_EQ(trunc.rfind("bad.json: line 2, column 15: ", 0), 0u) << trunc;
  // A single line, no newline in the message.
  EXPECT_EQ(parse_error("[1, 2,, 3]").rfind("bad.json: line 1, column 7: ", 0), 0u) << parse_error("[1, 2,, 3]");
  EXPECT_EQ(parse_error("{\n\n  \"a\": tru\n}").find('\n'), std::string::npos);
}

TEST(Scene, UnknownKeysAreRejectedByName) {
  EXPECT_NE(parse_error(R"({"widht": 64, "meshes": []})").find("bad.json: unknown key 'widht'"), std::string::npos);
  EXPECT_NE(parse_error(R"({"camera": {"fov": 40}, "meshes": []})").find("camera: unknown key 'fov'"),
            std::string::npos);
  std::string mesh = kMinimalMesh;
  mesh.insert(mesh.size() - 1, R"(, "sampler": {"filtr": "linear"})");
  EXPECT_NE(parse_error(scene_with_mesh(mesh)).find("meshes[0].sampler: unknown key 'filtr'"), std::string::npos)
      << parse_error(scene_with_mesh(mesh));
  // A key of another primitive is unknown for this one.
  mesh = kMinimalMesh;
  mesh.insert(mesh.size() - 1, R"(, "segments": [8, 4])");
  EXPECT_NE(parse_error(scene_with_mesh(mesh)).find("meshes[0]: unknown key 'segments'"), std::string::npos);
}

TEST(Scene, WrongTypesAndValuesAreRejectedByName) {
  EXPECT_NE(parse_error(R"({"width": "64", "meshes": []})").find("width: expected an integer, got string"),
            std::string::npos);
  EXPECT_NE(parse_error(R"({"width": 0, "meshes": []})").find("width: 0 outside 1..8192"), std::string::npos);
  EXPECT_NE(parse_error(R"({"camera": {"position": [0, 1]}, "meshes": []})").find("camera.position: expected an array of 3"),
            std::string::npos);
  EXPECT_NE(parse_error(R"({"width": 8})").find("missing key 'meshes'"), std::string::npos);
  std::string mesh = kMinimalMesh;
  mesh.insert(mesh.size() - 1, R"(, "sampler": {"filter": "bogus"})");
  EXPECT_NE(parse_error(scene_with_mesh(mesh)).find("meshes[0].sampler.filter: unknown filter 'bogus'"),
            std::string::npos);
  EXPECT_NE(parse_error(scene_with_mesh(R"({"primitive": "torus", "texture": {"procedural": "noise"}})"))
                .find("meshes[0].primitive: unknown primitive 'torus'"),
            std::string::npos);
  EXPECT_NE(parse_error(scene_with_mesh(R"({"primitive": "cube", "texture": {"procedural": "marble"}})"))
                .find("unknown procedural texture 'marble'"),
            std::string::npos);
  EXPECT_NE(parse_error(scene_with_mesh(R"({"primitive": "cube", "texture": {"file": "/nonexistent/t.png"}})"))
                .find("/nonexistent/t.png"),
            std::string::npos);
}

TEST(Scene, EveryBuiltinSceneParsesAndRendersNonTrivially) {
  const std::set<std::string> want{"magnified", "ground_plane", "text_quad", "object", "text_patch", "lightmapped", "grazing", "tunnel"};
  EXPECT_EQ(std::set<std::string>(builtin_scene_names().begin(), builtin_scene_names().end()), want);
  for (const std::string& name : builtin_scene_names()) {
    Scene scene = load_scene(name);
    EXPECT_EQ(scene.name, name);
    EXPECT_FALSE(scene.description.empty()) << name;
    EXPECT_GE(scene.width, 256) << name;
    EXPECT_LE(scene.width * scene.height, 512 * 384) << name;
    scene.width = 64;
    scene.height = 48;
    RenderOptions o;
    o.ground_truth = true;
    const RenderResult r = render_scene(scene, o);
    EXPECT_GT(r.stats.pixels, 64 * 48 / 4) << name;
    std::set<uint32_t> colours;
    for (const Rgba8& c : r.image.texels) colours.insert(uint32_t{c.r} << 16 | uint32_t{c.g} << 8 | c.b);
    EXPECT_GT(colours.size(), 8u) << name;
    // The filtered image is close to the ground truth on average (mean |difference| per channel);
    // the tunnel's mip_colours texture has no truth beyond level 0's colour (procedural.hpp).
    if (name == "tunnel") continue;
    double diff = 0;
    for (size_t i = 0; i < r.image.texels.size(); ++i)
      diff += std::abs(r.image.texels[i].r - r.truth.texels[i].r) + std::abs(r.image.texels[i].g - r.truth.texels[i].g);
    EXPECT_LT(diff / (2.0 * static_cast<double>(r.image.texels.size())), 40.0) << name;
  }
}

TEST(Scene, LoadSceneFromNameOrPath) {
  EXPECT_THROW(load_scene("no_such_scene"), InputError);
  EXPECT_THROW(builtin_scene_json("no_such_scene"), InputError);
  const auto dir = std::filesystem::temp_directory_path() / "tfu_test_scene";
  std::filesystem::create_directories(dir);
  const auto path = (dir / "mine.json").string();
  {
    std::ofstream(path) << builtin_scene_json("magnified");
  }
  const Scene s = load_scene(path);
  EXPECT_EQ(s.name, "mine");
  EXPECT_EQ(s.width, 256);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].stages[0].texture->width(), 64);
  EXPECT_EQ(s.meshes[0].stages[0].texture->levels.size(), 7u);  // a complete MIP chain 64 .. 1
  EXPECT_EQ(s.meshes[0].stages[0].sampler.mode, (FilterMode{BaseFilter::Cubic, MipMode::None}));
  std::filesystem::remove_all(dir);
}

TEST(Scene, SamplerSettingsMapOntoSamplerDescriptor) {
  std::string mesh = kMinimalMesh;
  mesh.insert(mesh.size() - 1,
              R"(, "sampler": {"filter": "nearest_mipmap_nearest", "kernel": "bspline", "wrap_s": "mirrored-repeat",
                   "wrap_t": "clamp-to-edge", "lod_bias": -0.5})");
  const Scene s = parse_scene(scene_with_mesh(mesh), "s.json");
  const SamplerDescriptor& c = s.meshes.at(0).stages.at(0).sampler;
  EXPECT_EQ(c.mode, (FilterMode{BaseFilter::Nearest, MipMode::Nearest}));
  EXPECT_EQ(c.kernel, "bspline");
  EXPECT_EQ(c.wrap_s, WrapMode::MirroredRepeat);
  EXPECT_EQ(c.wrap_t, WrapMode::ClampToEdge);
  EXPECT_EQ(c.lod.bias_q8, -128);
}

TEST(Scene, MeshGenerators) {
  const Mesh cube = make_cube_mesh();
  EXPECT_EQ(cube.triangles.size(), 12u);
  for (const Vertex& v : cube.vertices)
    EXPECT_DOUBLE_EQ(std::max({std::fabs(v.pos.x), std::fabs(v.pos.y), std::fabs(v.pos.z)}), 0.5);
  const Mesh sphere = make_sphere_mesh(8, 4);
  EXPECT_EQ(sphere.triangles.size(), 64u);
  for (const Vertex& v : sphere.vertices) EXPECT_NEAR(glm::length(v.pos), 0.5, 1e-12);
  std::array<glm::dvec3, 16> control;
  for (size_t i = 0; i < 16; ++i) control[i] = {static_cast<double>(i % 4), std::sin(static_cast<double>(i)), static_cast<double>(i / 4)};
  const Mesh patch = make_bezier_patch_mesh(control, 4, {2, 3});
  EXPECT_EQ(patch.vertices.size(), 25u);
  EXPECT_EQ(patch.triangles.size(), 32u);
  EXPECT_EQ(patch.vertices.front().pos, control[0]);  // a Bezier patch interpolates its corners
  EXPECT_EQ(patch.vertices[4].pos, control[3]);
  EXPECT_EQ(patch.vertices.back().pos, control[15]);
  EXPECT_EQ(patch.vertices.back().uv, glm::dvec2(2, 3));
}

TEST(Procedural, TexelsArePointSamplesOfTheAnalyticFunction) {
  for (const std::string& name : procedural_names()) {
    if (name == "mip_colours") continue;  // a whole chain: Procedural.MipColoursIsOneFlatColourPerLevel
    const Procedural p = make_procedural(name, 32);
    ASSERT_EQ(p.texture.levels.size(), 1u);
    EXPECT_EQ(p.texture.width(), 32);
    for (double s : {0.1, 0.37, 0.8})
      for (double t : {0.05, 0.5, 0.93}) {
        const auto a = p.eval(s, t), b = p.eval(s + 1, t - 2);  // period 1
        for (size_t c = 0; c < 4; ++c) {
          EXPECT_NEAR(a[c], b[c], 1e-9) << name;
          EXPECT_GE(a[c], 0.0);
          EXPECT_LE(a[c], 1.0);
        }
      }
    if (name == "text") continue;  // text texels are 4x4 box averages (procedural.hpp)
    for (int j = 0; j < 32; j += 5)
      for (int i = 0; i < 32; i += 3) {
        const auto c = p.eval((i + 0.5) / 32, (j + 0.5) / 32);
        EXPECT_EQ(p.texture.levels[0].at(i, j).g, static_cast<uint8_t>(std::lround(c[1] * 255))) << name;
      }
  }
  EXPECT_THROW(make_procedural("marble", 64), InputError);
  EXPECT_THROW(make_procedural("noise", 0), InputError);
}

TEST(Procedural, MipColoursIsOneFlatColourPerLevel) {
  const Procedural p = make_procedural("mip_colours", 32);
  ASSERT_EQ(p.texture.levels.size(), 6u);  // 32, 16, 8, 4, 2, 1
  for (size_t l = 0; l < p.texture.levels.size(); ++l) {
    EXPECT_EQ(p.texture.levels[l].width, 32 >> l);
    for (const Rgba8& t : p.texture.levels[l].texels) ASSERT_EQ(t, mip_level_colour(static_cast<int>(l))) << l;
  }
  EXPECT_EQ(mip_level_colour(0), (Rgba8{255, 0, 0, 255}));
  EXPECT_EQ(mip_level_colour(12), mip_level_colour(0));  // 12 colours, repeating
  for (int l = 0; l < 12; ++l)  // all 12 distinct
    for (int k = l + 1; k < 12; ++k) EXPECT_NE(mip_level_colour(l), mip_level_colour(k)) << l << " " << k;
  const auto c = p.eval(0.3, 0.7);
  EXPECT_DOUBLE_EQ(c[0], 1.0);
  EXPECT_DOUBLE_EQ(c[1], 0.0);
  EXPECT_THROW(make_procedural("mip_colours", 48), InputError);  // not a power of two
  // The scene loader keeps the chain (mipmaps auto generates one only for a single level).
  const Scene tunnel = load_scene("tunnel");
  ASSERT_EQ(tunnel.meshes.size(), 1u);
  const Texture& tex = *tunnel.meshes[0].stages[0].texture;
  ASSERT_EQ(tex.levels.size(), 9u);  // 256 .. 1
  EXPECT_EQ(tex.levels[3].texels.front(), mip_level_colour(3));
  // tfu report flags the scene: its truth is level 0's colour, not a filtered image
  EXPECT_TRUE(procedural_truth_is_level0_only(tunnel.meshes[0].stages[0].spec.source)) << tunnel.meshes[0].stages[0].spec.source;
  EXPECT_TRUE(procedural_truth_is_level0_only("proc:mip_colours"));
  EXPECT_FALSE(procedural_truth_is_level0_only("proc:mip_colours_x:64"));
  EXPECT_FALSE(procedural_truth_is_level0_only("proc:checkerboard:64"));
  EXPECT_FALSE(procedural_truth_is_level0_only("mip_colours.png"));
}

TEST(Scene, CylinderMesh) {
  const Mesh c = make_cylinder_mesh(8, 2, {4, 10});
  EXPECT_EQ(c.vertices.size(), 27u);
  EXPECT_EQ(c.triangles.size(), 32u);
  for (const Vertex& v : c.vertices) {
    EXPECT_NEAR(std::hypot(v.pos.x, v.pos.y), 0.5, 1e-12);
    EXPECT_GE(v.pos.z, -1.0);
    EXPECT_LE(v.pos.z, 0.0);
    EXPECT_NEAR(v.uv.y, -v.pos.z * 10, 1e-12);
  }
  EXPECT_EQ(c.vertices[2].uv, glm::dvec2(1, 0));      // a quarter of the way round: s = 4 / 4
  EXPECT_NEAR(c.vertices[2].pos.y, 0.5, 1e-12);       // angle 90 degrees: +y
  EXPECT_EQ(c.vertices.back().uv, glm::dvec2(4, 10));  // the seam closes at s = repeat, far end t = repeat
}

TEST(Procedural, TextHasInkAndPaper) {
  const Procedural p = make_procedural("text", 128);
  int ink = 0, paper = 0;
  for (const Rgba8& c : p.texture.levels[0].texels) {
    if (c.r < 64) ++ink;
    if (c.r > 192) ++paper;
  }
  EXPECT_GT(ink, 128 * 128 / 50);
  EXPECT_GT(paper, 128 * 128 / 2);
}

}  // namespace
}  // namespace tfu
