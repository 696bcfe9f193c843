// Where the engine puts the player and how it lights and culls (cmodel/q3_collision.hpp,
// cmodel/q3_scene.hpp, the renderer's vertex colour, culling and display ramp): box traces against
// hand-built brushes with hand-derived stops; the light-map shift of R_ColorShiftLightingBytes by
// hand; a culled and a vertex-coloured quad; and, with the game data, the eyes of spawn points
// against the figures ioquake3 printed for them (Debian's openarena-081-maps).
#include <gtest/gtest.h>

#include <cmath>

#include "cmodel/q3_archives.hpp"
#include "cmodel/q3_camera.hpp"
#include "cmodel/q3_collision.hpp"
#include "cmodel/q3_scene.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene_source.hpp"
#include "rtl/scene_sim.hpp"
#include "testbench/q3_test_data.hpp"

namespace tfu::q3 {
namespace {

using testdata::BspBuilder;

// A world of brushes: texture 0 solid, 1 water (no player contents), 2 player clip.
BspBuilder brush_world() {
  BspBuilder b;
  b.textures = {{"textures/test/solid", 0, kContentsSolid},
                {"textures/test/water", 0, 0x20},
                {"textures/test/clip", 0, kContentsPlayerClip}};
  return b;
}

Bsp built(BspBuilder& b) {
  b.models = {{{-1000, -1000, -1000}, {1000, 1000, 1000}, 0, static_cast<int32_t>(b.brushes.size())}};
  return parse_bsp(b.build(), "t.bsp");
}

TEST(Q3Collision, PlayerBoxStopsAnEighthAboveTheFloor) {
  BspBuilder b = brush_world();
  b.add_brush({-64, -64, -16}, {64, 64, 0}, 0);  // floor, top z = 0
  const Bsp bsp = built(b);
  const BrushWorld world(bsp);
  ASSERT_EQ(world.brush_count(), 1u);
  // Straight down from 33: the box's feet (origin - 24) stop kSurfaceClipEpsilon above z = 0.
  const BoxTrace t = world.trace({0, 0, 33}, {0, 0, -100}, kPlayerMins, kPlayerMaxs, kMaskPlayerSolid);
  EXPECT_EQ(t.brush, 0);
  EXPECT_FALSE(t.start_solid);
  EXPECT_NEAR(t.end_pos.z, 24.125, 1e-12);
  EXPECT_NEAR(t.fraction, (33 - 24.125) / 133.0, 1e-12);
  // The box overlaps the floor with its corner only (centre 79 units out in x: 79 - 15 = 64).
  EXPECT_EQ(world.trace({79, 0, 33}, {79, 0, -100}, kPlayerMins, kPlayerMaxs, kMaskPlayerSolid).brush, 0);
  // Just beyond (box edge at 64.5): it falls past.
  const BoxTrace miss = world.trace({79.5, 0, 33}, {79.5, 0, -100}, kPlayerMins, kPlayerMaxs, kMaskPlayerSolid);
  EXPECT_EQ(miss.fraction, 1.0);
  EXPECT_EQ(miss.end_pos, glm::dvec3(79.5, 0, -100));
  // Inside the floor: start solid, and all solid when the end is inside too.
  const BoxTrace in = world.trace({0, 0, 10}, {0, 0, 5}, kPlayerMins, kPlayerMaxs, kMaskPlayerSolid);
  EXPECT_TRUE(in.start_solid);
  EXPECT_TRUE(in.all_solid);
  EXPECT_EQ(in.fraction, 0.0);
  // A spawn spot 24 above the floor: the engine's eye is 26 above the resting origin, 0.125 higher
  // than spot + 26.
  const SpawnRest r = spawn_rest(world, {10, 20, 24}, -200);
  EXPECT_TRUE(r.landed);
  EXPECT_NEAR(r.origin.z, 24.125, 1e-12);
  // A spot 40 above the floor falls 16 units further.
  EXPECT_NEAR(spawn_rest(world, {10, 20, 40}, -200).origin.z, 24.125, 1e-12);
}

TEST(Q3Collision, ContentsAndSlopes) {
  BspBuilder b = brush_world();
  b.add_brush({-64, -64, 80}, {64, 64, 100}, 1);  // water above: not player solid
  b.add_brush({-64, -64, 40}, {64, 64, 50}, 2);   // player clip: stops the player
  // A wedge: the box x, y in -64..64, z -64..100, cut by z <= y (normal (0, -1, 1) / sqrt 2).
  const double a = 1.0 / std::sqrt(2.0);
  b.add_brush({-64, -64, -64}, {64, 64, 100}, 0, {{{0, -a, a}, 0.0}});
  const Bsp bsp = built(b);
  const BrushWorld world(bsp);
  // From 200 the water is passed, the clip brush stops the box: feet 0.125 above z = 50.
  EXPECT_NEAR(world.trace({0, 0, 200}, {0, 0, -50}, kPlayerMins, kPlayerMaxs, kMaskPlayerSolid).end_pos.z, 74.125,
              1e-12);
  EXPECT_EQ(world.trace({0, 0, 200}, {0, 0, -50}, kPlayerMins, kPlayerMaxs, kMaskPlayerSolid).brush, 1);
  // Only solid (a mask without player clip): the slope. The plane is pushed out by the box corner
  // nearest it, (0, +15, -28) about the centre (origin + 4): dist' = 0 + 15 a + 28 a = 43 a. Along x
  // = y = 0 the centre stops where z a - 43 a = 0.125: z = 43 + 0.125 sqrt 2, the origin 4 lower.
  const BoxTrace slope = world.trace({0, 0, 200}, {0, 0, -50}, kPlayerMins, kPlayerMaxs, kContentsSolid);
  EXPECT_EQ(slope.brush, 2);
  EXPECT_NEAR(slope.end_pos.z, 43 + 0.125 * std::sqrt(2.0) - 4, 1e-6);  // the plane's normal is stored as float
}

TEST(Q3Lighting, ColorShiftKeepsTheHue) {
  // R_ColorShiftLightingBytes by hand.
  EXPECT_EQ(shift_lighting({100, 50, 25, 7}, 1), (Rgba8{200, 100, 50, 7}));
  EXPECT_EQ(shift_lighting({127, 127, 127, 255}, 1), (Rgba8{254, 254, 254, 255}));
  // (400, 200, 100): max 400, each x 255 / 400 with integer division: 255, 127 (127.5), 63 (63.75).
  EXPECT_EQ(shift_lighting({200, 100, 50, 255}, 1), (Rgba8{255, 127, 63, 255}));
  EXPECT_EQ(shift_lighting({100, 50, 25, 255}, 2), (Rgba8{255, 127, 63, 255}));
  // A saturated grey stays grey (white), a saturated red stays red.
  EXPECT_EQ(shift_lighting({200, 200, 200, 1}, 1), (Rgba8{255, 255, 255, 1}));
  EXPECT_EQ(shift_lighting({200, 0, 0, 1}, 2), (Rgba8{255, 0, 0, 1}));
  EXPECT_EQ(shift_lighting({9, 8, 7, 6}, 0), (Rgba8{9, 8, 7, 6}));
  // Every input against the rule restated in floating point (floor of the exact quotient).
  for (int shift = 0; shift <= kMaxLightingShift; ++shift)
    for (int v = 0; v < 256; v += 3) {
      const Rgba8 in{static_cast<uint8_t>(v), static_cast<uint8_t>(255 - v), static_cast<uint8_t>(v / 2), 9};
      const double r = v * std::pow(2, shift), g = (255 - v) * std::pow(2, shift), bb = (v / 2) * std::pow(2, shift);
      const double m = std::max({r, g, bb}), k = m > 255 ? 255 / m : 1.0;
      const Rgba8 out = shift_lighting(in, shift);
      ASSERT_EQ(out.r, static_cast<uint8_t>(std::floor(r * k + 1e-9))) << shift << " " << v;
      ASSERT_EQ(out.g, static_cast<uint8_t>(std::floor(g * k + 1e-9))) << shift << " " << v;
      ASSERT_EQ(out.b, static_cast<uint8_t>(std::floor(bb * k + 1e-9))) << shift << " " << v;
    }
  // The defaults: r_mapOverBrightBits 2, r_overBrightBits 1 with a hardware gamma ramp.
  LevelSceneOptions o;
  EXPECT_EQ(display_overbright_bits(o), 1);
  EXPECT_EQ(lighting_shift(o), 1);
  o.hardware_gamma = false;  // a window, or no gamma ramp
  EXPECT_EQ(display_overbright_bits(o), 0);
  EXPECT_EQ(lighting_shift(o), 2);
  o.hardware_gamma = true;
  o.overbright_bits = 2;
  EXPECT_EQ(lighting_shift(o), 0);
  o.map_overbright_bits = 0;
  EXPECT_EQ(lighting_shift(o), 0);  // never negative
}

// One square of two triangles facing the camera (clockwise on screen, as Quake III's visible faces
// are) and one behind it facing away, over a 1 x 1 texture.
Scene cull_scene(Rgba8 texel, Rgba8 vertex_colour) {
  Scene s;
  s.width = 8;
  s.height = 8;
  s.camera.position = {0, 0, 3};
  s.camera.look_at = {0, 0, 0};
  s.camera.up = {0, 1, 0};
  s.camera.fov_y_deg = 90;
  Mesh m;
  m.primitive = "test";
  m.vertex_colour = true;
  const auto v = [&](double x, double y, double z) {
    return tfu::Vertex{{x, y, z}, {0.5, 0.5}, {0.5, 0.5}, vertex_colour};
  };
  // Front square at z = 0 covering the view; clockwise as seen from +z: (-9, 9), (9, 9), (9, -9).
  m.vertices = {v(-9, 9, 0), v(9, 9, 0), v(9, -9, 0), v(-9, -9, 0)};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  TextureStage st;
  auto tex = std::make_shared<Texture>();
  tex->levels.emplace_back(1, 1, texel);
  st.texture = tex;
  st.spec = {"test", {}};
  st.sampler.mode = FilterMode{BaseFilter::Nearest, MipMode::None};
  st.combine = {TexEnv::Modulate, 1};
  m.stages = {st};
  s.meshes.push_back(m);
  // A second square in front (z = 1), counter-clockwise on screen: a back face.
  Mesh back = m;
  for (tfu::Vertex& vx : back.vertices) vx.pos.z = 1;
  back.triangles = {{0, 2, 1}, {0, 3, 2}};
  back.vertex_colour = false;
  s.meshes.push_back(back);
  return s;
}

TEST(Q3Lighting, CullVertexColourAndDisplayRamp) {
  RenderOptions ro;
  ro.threads = 1;
  ro.trace = true;
  Scene s = cull_scene({200, 100, 50, 255}, {100, 150, 60, 255});
  // No culling: the nearer (back-facing) square covers the frame: the texel alone.
  const RenderResult all = render_scene(s, ro);
  EXPECT_EQ(all.stats.culled, 0);
  EXPECT_EQ(all.image.at(3, 4), (Rgba8{200, 100, 50, 255}));
  // Culling counter-clockwise triangles leaves the front square: texel x vertex colour, rounded
  // (200 x 100 / 255 = 78.4, 100 x 150 / 255 = 58.8, 50 x 60 / 255 = 11.8), then the display
  // ramp doubles it.
  s.cull = CullWinding::CounterClockwise;
  const RenderResult front = render_scene(s, ro);
  EXPECT_EQ(front.stats.culled, 2);
  EXPECT_EQ(front.image.at(3, 4), (Rgba8{78, 59, 12, 255}));
  s.display_shift = 1;
  const RenderResult ramp = render_scene(s, ro);
  EXPECT_EQ(ramp.image.at(3, 4), (Rgba8{156, 118, 24, 255}));
  // The composed image (from the requests' outputs, as the cycle model's run is) is the same.
  const rtl::SceneSimResult sim = rtl::simulate_scene(s, ramp, rtl::UnitConfig{}, {});
  EXPECT_TRUE(sim.mismatch.empty()) << sim.mismatch;
  EXPECT_EQ(sim.image.texels, ramp.image.texels);
  // Culling clockwise ones leaves the back square.
  s.cull = CullWinding::Clockwise;
  EXPECT_EQ(render_scene(s, ro).image.at(3, 4), (Rgba8{255, 200, 100, 255}));
}

// ---- The real game data: the eyes the engine printed ----

using testdata::checked_game_data;

// Debian's openarena-081-maps (pak1-maps.pk3), spawned in ioquake3 1.36 one spot at a time: the eye
// height it printed (integer part) for three spawn points, and the earlier rule's spot + 26.
TEST(OpenArena, SpawnEyesAsTheEnginePrinted) {
  if (!checked_game_data().present()) GTEST_SKIP() << checked_game_data().missing();
  struct Case {
    const char* level;
    int spawn;
    int engine_eye_z, spot_eye_z;
  };
  for (const Case& c : {Case{"oa_dm5", 2, 242, 274}, Case{"wrackdm17", 0, 306, 322}, Case{"ps37ctf", 0, -109, -102}}) {
    const auto level = cached_level(checked_game_data().dir(), c.level);
    const SpawnPoint& s = level->spawns.at(static_cast<size_t>(c.spawn));
    EXPECT_TRUE(s.landed) << c.level;
    const double eye = spawn_eye(s).z;
    EXPECT_EQ(static_cast<int>(eye), c.engine_eye_z) << c.level << ":" << c.spawn << " eye " << eye;  // C truncation
    EXPECT_NEAR(eye - std::floor(eye), 0.125, 1e-6) << c.level;  // a flat floor: F + 24.125 + 26
    EXPECT_EQ(spawn_eye(s, EyeRule::Spot).z, c.spot_eye_z) << c.level;
  }
}

// Over all 50 levels (BSPs only, no textures): how many eyes the drop moves by more than one unit
// from spot + 26 (docs/real-frames.md states the figures), and none starts in solid.
TEST(OpenArena, SpawnDropOverEveryLevel) {
  if (!checked_game_data().present()) GTEST_SKIP() << checked_game_data().missing();
  const GameArchives a(checked_game_data().dir());
  int64_t spawns = 0, moved = 0, solid = 0, fell = 0, patch = 0;
  for (const std::string& name : a.level_names()) {
    const EntryRef ref = a.locate_level(name);
    const Bsp bsp = parse_bsp(a.read(ref), a.describe(ref));
    for (const SpawnPoint& s : level_spawn_points(bsp, a.describe(ref))) {
      ++spawns;
      moved += std::fabs(spawn_eye(s).z - spawn_eye(s, EyeRule::Spot).z) > 1.0;
      solid += s.start_solid;
      fell += !s.landed;
      patch += s.patch_in_drop;
    }
  }
  EXPECT_EQ(spawns, 527);
  EXPECT_EQ(moved, 244);
  EXPECT_EQ(solid, 0);
  EXPECT_EQ(fell, 0);
  EXPECT_EQ(patch, 9);  // a colliding patch in the drop column: there the engine may stop higher
}

}  // namespace
}  // namespace tfu::q3
