// Rasterizer conventions (cmodel/raster.hpp, docs/renderer.md): top-left fill rule, degenerate
// triangles, perspective-correct interpolation, thread-count independence, trace and ideal path.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "cmodel/mipmap.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "testbench/iterations.hpp"

namespace tfu {
namespace {

ScreenVertex sv(double x, double y) {
  ScreenVertex v;
  v.x = x;
  v.y = y;
  return v;
}

// How often each pixel of a w x h grid is covered by the given triangles.
std::vector<int> coverage(const std::vector<std::array<ScreenVertex, 3>>& tris, int w, int h) {
  std::vector<int> count(static_cast<size_t>(w * h), 0);
  for (const auto& t : tris) {
    const auto rt = setup_triangle(t, w, h);
    if (!rt) continue;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (rt->covers_pixel(x, y)) ++count[static_cast<size_t>(y * w + x)];
  }
  return count;
}

// A square [a, b)^2 split along a diagonal: every pixel centre inside the half-open square is
// covered exactly once, every other pixel never (GL / D3D top-left rule).
void expect_square_covered_once(double a, double b, bool other_diagonal, bool flip_winding) {
  constexpr int n = 16;
  const ScreenVertex p00 = sv(a, a), p10 = sv(b, a), p11 = sv(b, b), p01 = sv(a, b);
  std::vector<std::array<ScreenVertex, 3>> tris =
      other_diagonal ? std::vector<std::array<ScreenVertex, 3>>{{p10, p11, p01}, {p10, p01, p00}}
                     : std::vector<std::array<ScreenVertex, 3>>{{p00, p10, p11}, {p00, p11, p01}};
  if (flip_winding)
    for (auto& t : tris) std::swap(t[1], t[2]);
  const auto count = coverage(tris, n, n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double cx = x + 0.5, cy = y + 0.5;
      const int want = (cx >= a && cx < b && cy >= a && cy < b) ? 1 : 0;
      EXPECT_EQ(count[static_cast<size_t>(y * n + x)], want) << "pixel " << x << "," << y << " square " << a << ".." << b;
    }
}

TEST(Raster, FillRuleSharedDiagonalCoversEachPixelOnce) {
  for (bool diag : {false, true})
    for (bool flip : {false, true}) {
      expect_square_covered_once(2.0, 10.0, diag, flip);   // diagonal through pixel centres
      expect_square_covered_once(1.5, 9.5, diag, flip);    // every edge through pixel centres
      expect_square_covered_once(1.3, 11.7, diag, flip);   // no centre on an edge
    }
}

TEST(Raster, FillRuleFanAroundCentreCoversEachPixelOnce) {
  // Four triangles around the centre of [1.5, 9.5]^2: horizontal, vertical and diagonal shared edges.
  const ScreenVertex c = sv(5.5, 5.5), a = sv(1.5, 1.5), b = sv(9.5, 1.5), d = sv(9.5, 9.5), e = sv(1.5, 9.5);
  const auto count = coverage({{c, a, b}, {c, b, d}, {c, d, e}, {c, e, a}}, 12, 12);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x) {
      const bool inside = x + 0.5 >= 1.5 && x + 0.5 < 9.5 && y + 0.5 >= 1.5 && y + 0.5 < 9.5;
      EXPECT_EQ(count[static_cast<size_t>(y * 12 + x)], inside ? 1 : 0) << x << "," << y;
    }
}

TEST(Raster, FillRuleTopAndLeftEdgesOnly) {
  // A single triangle with a horizontal top edge and a vertical left edge through pixel centres.
  const auto rt = setup_triangle({sv(2.5, 2.5), sv(8.5, 2.5), sv(2.5, 8.5)}, 16, 16);
  ASSERT_TRUE(rt);
  EXPECT_TRUE(rt->covers_pixel(2, 2));   // top-left corner: on the top and the left edge
  EXPECT_TRUE(rt->covers_pixel(5, 2));   // on the top edge
  EXPECT_TRUE(rt->covers_pixel(2, 5));   // on the left edge
  EXPECT_FALSE(rt->covers_pixel(5, 5));  // on the hypotenuse (a right edge)
  EXPECT_TRUE(rt->covers_pixel(4, 5));
  // The same triangle mirrored (flat bottom, vertical right edge) excludes those edges.
  const auto mirrored = setup_triangle({sv(8.5, 8.5), sv(2.5, 8.5), sv(8.5, 2.5)}, 16, 16);
  ASSERT_TRUE(mirrored);
  EXPECT_FALSE(mirrored->covers_pixel(5, 8));  // bottom edge
  EXPECT_FALSE(mirrored->covers_pixel(8, 5));  // right edge
  EXPECT_TRUE(mirrored->covers_pixel(5, 5));   // the hypotenuse is its left edge
}

// The renderer visits only the quads of each row's covered interval (covered_interval, solved on
// the integer edge functions): it must be exactly the pixels covers_pixel accepts, on random
// triangles of every shape (large, partly off screen, thin slivers, vertices on pixel centres and
// edges on the sample grid, where the fill rule decides) and on every row of their bounding boxes.
TEST(Raster, CoveredIntervalEqualsPerPixelCoverage) {
  constexpr int w = 64, h = 48;
  std::mt19937 rng(20261206);
  std::uniform_real_distribution<double> wide(-40.0, 104.0), pos(0.0, 64.0), small(-1.5, 1.5);
  std::uniform_int_distribution<int> grid(-16, 80), kind(0, 3);
  int rows = 0, covered = 0;
  for (int n = 0; n < test::iterations(4000); ++n) {
    std::array<ScreenVertex, 3> v;
    const int k = kind(rng);
    for (size_t i = 0; i < 3; ++i) {
      if (k == 0)
        v[i] = sv(wide(rng), wide(rng));  // large, off screen too
      else if (k == 1)
        v[i] = sv(pos(rng), pos(rng));  // on screen
      else if (k == 2)
        v[i] = sv(grid(rng) + 0.5, grid(rng) * 0.5);  // centres and half rows
      else
        v[i] = i == 0 ? sv(pos(rng), pos(rng)) : sv(v[0].x + 30 * small(rng), v[0].y + small(rng));  // slivers
    }
    const auto t = setup_triangle(v, w, h);
    if (!t) continue;
    for (int y = t->ymin; y <= t->ymax; ++y) {
      const auto [first, last] = t->covered_interval(y);
      ++rows;
      for (int x = t->xmin; x <= t->xmax; ++x) {
        const bool in = x >= first && x <= last;
        covered += in;
        ASSERT_EQ(in, t->covers_pixel(x, y)) << "triangle " << n << " (kind " << k << ") pixel " << x << "," << y
                                             << " interval " << first << ".." << last;
      }
    }
  }
  EXPECT_GT(rows, test::iterations(4000));  // the loop checked something
  EXPECT_GT(covered, 0);
}

TEST(Raster, DegenerateTriangleAfterSnappingIsSkipped) {
  EXPECT_FALSE(setup_triangle({sv(1, 1), sv(5, 5), sv(9, 9)}, 16, 16));          // collinear
  EXPECT_FALSE(setup_triangle({sv(1, 1), sv(1.0005, 1), sv(1, 1.001)}, 16, 16));  // snaps to one point
  EXPECT_TRUE(setup_triangle({sv(1, 1), sv(1 + 1.0 / 256, 1), sv(1, 1 + 1.0 / 256)}, 16, 16));
}

Scene plane_scene(int w, int h) {
  Scene s;
  s.width = w;
  s.height = h;
  s.camera.position = {0, 1, 0};
  s.camera.look_at = {0, 1, -1};
  s.camera.fov_y_deg = 90;
  s.camera.near_plane = 0.1;
  s.camera.far_plane = 100;
  // Ground quad x in [-1, 1], z in [-2, -6]; s = (x + 1) / 2, t = (-2 - z) / 4.
  Mesh m = make_quad_mesh({glm::dvec3{-1, 0, -2}, {1, 0, -2}, {1, 0, -6}, {-1, 0, -6}},
                          {glm::dvec2{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  Procedural p = make_procedural("checkerboard", 64);
  TextureStage st;
  st.spec = {"proc:checkerboard:64", {{"mipmaps", "none"}}};
  st.texture = std::make_shared<const Texture>(std::move(p.texture));
  st.truth = p.eval;
  st.sampler.mode = FilterMode{BaseFilter::Linear, MipMode::None};
  m.stages.push_back(std::move(st));
  s.meshes.push_back(std::move(m));
  return s;
}

TEST(Raster, PerspectiveCorrectInterpolationMatchesRayPlaneIntersection) {
  const Scene scene = plane_scene(128, 96);
  RenderOptions o;
  o.keep_coords = true;
  o.threads = 2;
  const RenderResult r = render_scene(scene, o);
  const double tan_half = std::tan(scene.camera.fov_y_deg * std::numbers::pi / 360.0), aspect = 128.0 / 96.0;
  int checked = 0;
  double max_err = 0, max_affine_gap = 0;
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) {
      const auto st = r.coords[static_cast<size_t>(y * scene.width + x)];
      if (std::isnan(st[0])) continue;
      // Ray through the pixel centre from (0, 1, 0), looking down -z.
      const double nx = (x + 0.5) / scene.width * 2 - 1, ny = 1 - (y + 0.5) / scene.height * 2;
      const glm::dvec3 dir{nx * tan_half * aspect, ny * tan_half, -1};
      const double k = -1.0 / dir.y;
      const glm::dvec3 hit = glm::dvec3{0, 1, 0} + k * dir;
      const double s = (hit.x + 1) / 2, t = (-2 - hit.z) / 4;
      max_err = std::max({max_err, std::fabs(st[0] - s), std::fabs(st[1] - t)});
      // Screen-space (affine) t would be linear in y: compare with the linear map through the ends.
      max_affine_gap = std::max(max_affine_gap, std::fabs(t - (ny - (-0.5)) / (-1.0 / 6 - (-0.5))));
      ++checked;
    }
  EXPECT_GT(checked, 400);
  EXPECT_LT(max_err, 2e-3);  // vertices snap to 1/256 pixel
  EXPECT_GT(max_affine_gap, 0.1);  // the test would catch affine interpolation
}

bool same_image(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.texels == b.texels;
}

bool same_trace(const Trace& a, const Trace& b) {
  if (a.requests.size() != b.requests.size()) return false;
  for (size_t i = 0; i < a.requests.size(); ++i)
    if (a.requests[i].s != b.requests[i].s || a.requests[i].t != b.requests[i].t) return false;
  return true;
}

TEST(Raster, OutputIndependentOfThreadCount) {
  for (const char* name : {"object", "ground_plane"}) {
    Scene scene = load_scene(name);
    scene.width = 160;
    scene.height = 100;
    RenderOptions o;
    o.trace = true;
    o.ground_truth = true;
    o.threads = 1;
    const RenderResult one = render_scene(scene, o);
    for (int threads : {2, 3, 7}) {
      o.threads = threads;
      const RenderResult many = render_scene(scene, o);
      EXPECT_TRUE(same_image(one.image, many.image)) << name << " threads " << threads;
      EXPECT_TRUE(same_image(one.truth, many.truth)) << name << " threads " << threads;
      EXPECT_TRUE(same_trace(one.trace, many.trace)) << name << " threads " << threads;
      EXPECT_EQ(one.stats.quads, many.stats.quads);
    }
  }
}

TEST(Raster, TraceHasFourLinesPerShadedQuad) {
  const Scene scene = plane_scene(64, 48);
  RenderOptions o;
  o.trace = true;
  const RenderResult r = render_scene(scene, o);
  EXPECT_EQ(r.trace.mode, TraceMode::Quad);
  EXPECT_GT(r.stats.quads, 0);
  EXPECT_EQ(static_cast<int64_t>(r.trace.requests.size()), 4 * r.stats.quads);
  EXPECT_LE(r.stats.pixels, 4 * r.stats.quads);
  // Pixel order (0,0), (1,0), (0,1), (1,1): s grows to the right; the lower pixels are nearer the
  // camera, where the ground quad's t is smaller (t = 0 at z = -2, the bottom of the screen).
  for (size_t q = 0; q < r.trace.requests.size(); q += 4) {
    EXPECT_GT(r.trace.requests[q + 1].s, r.trace.requests[q].s);
    EXPECT_LT(r.trace.requests[q + 2].t, r.trace.requests[q].t);
  }
}

TEST(Raster, DegenerateTrianglesInASceneAreSkipped) {
  Scene scene = plane_scene(32, 32);
  // A quad whose corners are collinear in world space: both triangles have zero area.
  Mesh flat = make_quad_mesh({glm::dvec3{-1, 0.5, -3}, {0, 0.5, -3}, {1, 0.5, -3}, {2, 0.5, -3}},
                             {glm::dvec2{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  flat.stages = scene.meshes[0].stages;
  scene.meshes = {flat};
  const RenderResult r = render_scene(scene, RenderOptions{});
  EXPECT_EQ(r.stats.triangles, 2);
  EXPECT_EQ(r.stats.degenerate, 2);
  EXPECT_EQ(r.stats.pixels, 0);
  for (const Rgba8& c : r.image.texels) EXPECT_EQ(c, (Rgba8{0, 0, 0, 255}));
}

TEST(Raster, NearPlaneClippingKeepsGeometryBehindTheCamera) {
  // The ground plane extends behind the camera: it must be clipped, not wrapped around.
  Scene scene = load_scene("ground_plane");
  scene.width = 96;
  scene.height = 72;
  const RenderResult r = render_scene(scene, RenderOptions{});
  // The sky (top row) stays background, the bottom row is ground.
  const Rgba8 sky{static_cast<uint8_t>(std::lround(scene.background[0] * 255)),
                  static_cast<uint8_t>(std::lround(scene.background[1] * 255)),
                  static_cast<uint8_t>(std::lround(scene.background[2] * 255)), 255};
  for (int x = 0; x < scene.width; ++x) {
    EXPECT_EQ(r.image.at(x, 0), sky);
    EXPECT_NE(r.image.at(x, scene.height - 1), sky);
  }
}

TEST(Raster, IdealPathCloseToFixedPoint) {
  Scene scene = load_scene("ground_plane");
  scene.width = 128;
  scene.height = 96;
  RenderOptions o;
  const RenderResult fixed = render_scene(scene, o);
  o.ideal = true;
  const RenderResult ideal = render_scene(scene, o);
  double sum = 0;
  for (size_t i = 0; i < fixed.image.texels.size(); ++i)
    sum += std::abs(fixed.image.texels[i].g - ideal.image.texels[i].g);
  EXPECT_LT(sum / static_cast<double>(fixed.image.texels.size()), 2.0);  // mean |difference| in 8-bit steps
}

TEST(Raster, TruthBackgroundRoundsLikeTheRender) {
  // ground_plane's sky (0.55, 0.7, 0.9): 0.7 * 255 = 178.5 and 0.9 * 255 = 229.5 round up in both images
  // (summing float samples gave 178 and 229). The top-left pixel is background alone.
  Scene s = load_scene("ground_plane");
  s.width = 32;
  s.height = 24;
  RenderOptions o;
  o.ground_truth = true;
  const RenderResult r = render_scene(s, o);
  const Rgba8 sky = r.image.at(0, 0);
  EXPECT_EQ(sky.r, 140);
  EXPECT_EQ(sky.g, 179);
  EXPECT_EQ(sky.b, 230);
  const Rgba8 t = r.truth.at(0, 0);
  EXPECT_EQ(t.r, sky.r);
  EXPECT_EQ(t.g, sky.g);
  EXPECT_EQ(t.b, sky.b);
  EXPECT_EQ(t.a, sky.a);
}

// TFU-S E17: the truth of a file texture cast floor(s * width - 0.5) to int, which overflowed for a repeating uv
// of 1e6 (inside the scene bound) on a texture wider than 2,147 texels (UBSan float-cast-overflow; in Release
// garbage truth pixels, exit 0). A whole-number uv offset is the same image under repeat, so the truth of a quad
// whose uv start at 1e6 must equal that of the same quad at 0, up to the rounding of 1e6 + u in double.
TEST(Raster, TruthOfARepeatingUvFarOutsideAWideTexture) {
  constexpr int kWide = 4096;  // > 2^31 / 1e6 texels
  auto tex = std::make_shared<Texture>();
  Image base(kWide, 4);
  for (int y = 0; y < base.height; ++y)
    for (int x = 0; x < kWide; ++x)
      base.at(x, y) = Rgba8{static_cast<uint8_t>(x * 37), static_cast<uint8_t>(x >> 4), static_cast<uint8_t>(y * 60), 255};
  tex->levels.push_back(base);
  generate_mipmaps(*tex, MipMethod::Box);
  auto truth_at_offset = [&](double offset) {
    Scene s;
    s.width = 32;
    s.height = 24;
    s.camera.position = {0, 0, 1.5};
    Mesh m = make_quad_mesh({glm::dvec3{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}},
                            {glm::dvec2{offset, offset}, {offset + 0.01, offset}, {offset + 0.01, offset + 1},
                             {offset, offset + 1}});
    TextureStage st;
    st.spec.source = "wide.png";
    st.texture = tex;
    st.sampler.wrap_s = st.sampler.wrap_t = WrapMode::Repeat;
    m.stages.push_back(st);
    s.meshes.push_back(m);
    RenderOptions o;
    o.ground_truth = true;
    return render_scene(s, o).truth;
  };
  const Image near = truth_at_offset(0.0), far = truth_at_offset(1e6);
  ASSERT_EQ(near.texels.size(), far.texels.size());
  int worst = 0, textured = 0;
  for (size_t i = 0; i < near.texels.size(); ++i) {
    const Rgba8 a = near.texels[i], b = far.texels[i];
    if (a.b != 0 || a.g != 0 || a.r != 0) ++textured;
    worst = std::max({worst, std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b), std::abs(a.a - b.a)});
  }
  EXPECT_GT(textured, 200);  // the quad covers most of the frame
  EXPECT_LE(worst, 2) << "truth at uv 1e6 differs from the truth at uv 0";
}

// A constant texture has no filtering error: the surface truth (the render's coverage, the material
// integrated over each pixel) must equal the render pixel for pixel, while the antialiased truth
// blends the silhouette with the background. The interior mask is the pixels whose whole quad the
// render drew (one mesh here).
TEST(SurfaceTruth, ConstantTextureEqualsTheRenderWhileTheAntialiasedTruthBlendsItsEdges) {
  auto tex = std::make_shared<Texture>();
  tex->levels.push_back(Image(4, 4, Rgba8{200, 120, 40, 255}));
  generate_mipmaps(*tex, MipMethod::Box);
  Scene s;
  s.width = 48;
  s.height = 40;
  s.background = {0, 0, 0, 1};
  s.camera.position = {0, 0, 3};
  // A tilted quad: slanted edges cross pixels at every fraction.
  Mesh m = make_quad_mesh({glm::dvec3{-1, -0.8, 0}, {0.9, -1, -0.5}, {1, 0.7, 0}, {-0.8, 1, 0.4}},
                          {glm::dvec2{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  TextureStage st;
  st.spec.source = "constant.png";
  st.texture = tex;
  m.stages.push_back(st);
  s.meshes.push_back(m);
  RenderOptions o;
  o.ground_truth = true;
  o.filter = FilterMode{BaseFilter::Linear, MipMode::Linear};
  const RenderResult r = render_scene(s, o);
  ASSERT_EQ(r.surface_truth.texels.size(), r.image.texels.size());
  ASSERT_EQ(r.interior.size(), r.image.texels.size());
  const Rgba8 bg{0, 0, 0, 255};
  int drawn = 0, blended = 0, interior = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      EXPECT_EQ(r.surface_truth.at(x, y), r.image.at(x, y)) << x << "," << y;
      const Rgba8 t = r.truth.at(x, y);
      if (t != bg && t != Rgba8{200, 120, 40, 255}) ++blended;
      if (r.image.at(x, y) != bg) ++drawn;
      const int qx = x & ~1, qy = y & ~1;
      bool whole = true;
      for (int k = 0; k < 4; ++k) {
        const int px = qx + (k & 1), py = qy + (k >> 1);
        whole = whole && px < s.width && py < s.height && r.image.at(px, py) != bg;
      }
      EXPECT_EQ(r.interior[static_cast<size_t>(y * s.width + x)], whole ? 1 : 0) << x << "," << y;
      interior += whole;
    }
  EXPECT_GT(drawn, 500);
  EXPECT_GT(blended, 40) << "the antialiased truth blends the slanted edges";
  EXPECT_GT(interior, 400);
  EXPECT_LT(interior, drawn);
}

// Beyond its edges the surface truth extends the drawn triangle's texture (helper-pixel style)
// instead of taking the neighbour's: two meshes side by side with different constant colours meet on
// a slanted line, and every pixel of the surface truth is exactly the colour the render drew there.
TEST(SurfaceTruth, PixelsOnASeamTakeTheirOwnSurfaceOnly) {
  auto solid = [](Rgba8 c) {
    auto t = std::make_shared<Texture>();
    t->levels.push_back(Image(2, 2, c));
    generate_mipmaps(*t, MipMethod::Box);
    return t;
  };
  Scene s;
  s.width = 40;
  s.height = 32;
  s.camera.position = {0, 0, 2.5};
  const Rgba8 red{250, 10, 10, 255}, blue{10, 10, 250, 255};
  Mesh left = make_quad_mesh({glm::dvec3{-2, -2, 0}, {0.3, -2, 0}, {-0.3, 2, 0}, {-2, 2, 0}},
                             {glm::dvec2{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  Mesh right = make_quad_mesh({glm::dvec3{0.3, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-0.3, 2, 0}},
                              {glm::dvec2{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  for (auto [mesh, c] : {std::pair{&left, red}, std::pair{&right, blue}}) {
    TextureStage st;
    st.spec.source = "solid.png";
    st.texture = solid(c);
    mesh->stages.push_back(st);
    s.meshes.push_back(*mesh);
  }
  RenderOptions o;
  o.ground_truth = true;
  const RenderResult r = render_scene(s, o);
  int mixed = 0, seam_quads = 0;
  for (size_t i = 0; i < r.image.texels.size(); ++i) {
    EXPECT_EQ(r.surface_truth.texels[i], r.image.texels[i]) << i;
    const Rgba8 t = r.truth.texels[i];
    if (t != red && t != blue) ++mixed;
    if (!r.interior[i]) ++seam_quads;
  }
  EXPECT_GT(mixed, 20) << "the antialiased truth mixes the two colours along the seam";
  EXPECT_GT(seam_quads, 20);
}

}  // namespace
}  // namespace tfu
