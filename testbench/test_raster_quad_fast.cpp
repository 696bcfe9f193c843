// The renderer's quad interpolation fast path (cmodel/raster_quad_fast.hpp) against its plain twin,
// bit for bit: barycentrics (RasterTriangle::barycentric), depth (b0 z0 + b1 z1 + b2 z2, raster.cpp's
// interpolate_z), and (s, t) as FP32 interface coordinates (interpolate_st, then the clamp to
// +-1e30 and the rounding to float of raster.cpp's to_float_coord), on random triangles of every
// shape and size and quads inside, on and beyond their edges (helper pixels extrapolate, some beyond
// the horizon where 1/w turns negative). And a render into a reused result equals a fresh one.
// The packed coverage and depth tests, the stepped edges and the batch's request gather and texel
// spread against their per-pixel plain twins (shade_triangle's loops with the fast paths off).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "cmodel/raster.hpp"
#include "cmodel/raster_quad_fast.hpp"
#include "cmodel/scene.hpp"
#include "testbench/iterations.hpp"
#include "testbench/quad_edges.hpp"

namespace tfu {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

float plain_coord(double v) { return static_cast<float>(std::clamp(v, -1e30, 1e30)); }

TEST(RasterQuadFast, InterpolationEqualsThePlainTwinBitForBit) {
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> pos(-40.0, 200.0), unit(0.0, 1.0), uv(-50.0, 50.0);
  const int triangles = test::iterations(3000);
  int64_t pixels = 0, beyond_horizon = 0, set_up = 0;
  for (int n = 0; n < triangles; ++n) {
    std::array<ScreenVertex, 3> v;
    // Shapes: small and large, thin (two vertices close), and wildly varying 1/w (steep perspective).
    const double scale = n % 3 == 0 ? 0.05 : 1.0;
    for (size_t i = 0; i < 3; ++i) {
      v[i].x = 80 + (pos(rng) - 80) * scale;
      v[i].y = 60 + (pos(rng) - 60) * scale;
      v[i].z = unit(rng);
      v[i].inv_w = n % 2 == 0 ? 0.5 + unit(rng) : std::pow(10.0, -4.0 + 5.0 * unit(rng));
      for (auto& set : v[i].uv_w) set = {uv(rng) * v[i].inv_w, uv(rng) * v[i].inv_w};
    }
    if (n % 5 == 0) v[2].x = v[1].x + 0.01, v[2].y = v[1].y + 3.0;  // a sliver
    const auto tri = setup_triangle(v, 160, 120);
    if (!tri) continue;
    ++set_up;
    // Quads across the bounding box and a margin of 6 pixels around it.
    for (int trial = 0; trial < 24; ++trial) {
      const int qx = (std::uniform_int_distribution<int>(tri->xmin - 6, tri->xmax + 6)(rng)) & ~1;
      const int qy = (std::uniform_int_distribution<int>(tri->ymin - 6, tri->ymax + 6)(rng)) & ~1;
      raster_fast::QuadEdges e;
      for (size_t k = 0; k < 4; ++k)
        for (int i = 0; i < 3; ++i)
          e.e[static_cast<size_t>(i)][k] = tri->edge(i, RasterTriangle::centre(qx + static_cast<int>(k & 1)),
                                                     RasterTriangle::centre(qy + static_cast<int>(k >> 1)));
      raster_fast::QuadLanes lanes;
      raster_fast::barycentrics(e, static_cast<double>(tri->area), *tri, lanes);
      const std::array<double, 4> z = raster_fast::depth(lanes, *tri);
      std::array<std::array<float, 4>, 2> s, t;
      for (int set = 0; set < 2; ++set)
        raster_fast::st(lanes, *tri, set, s[static_cast<size_t>(set)].data(), t[static_cast<size_t>(set)].data());
      for (size_t k = 0; k < 4; ++k) {
        const std::array<double, 3> b = tri->barycentric(RasterTriangle::centre(qx + static_cast<int>(k & 1)),
                                                         RasterTriangle::centre(qy + static_cast<int>(k >> 1)));
        for (size_t i = 0; i < 3; ++i) ASSERT_TRUE(same_bits(lanes.b[i][k], b[i])) << n << " " << k << " " << i;
        ASSERT_TRUE(same_bits(z[k], b[0] * tri->v[0].z + b[1] * tri->v[1].z + b[2] * tri->v[2].z)) << n << " " << k;
        double inv_w = 0;
        for (size_t i = 0; i < 3; ++i) inv_w += b[i] * tri->v[i].inv_w;
        beyond_horizon += !(inv_w > 0);
        for (int set = 0; set < 2; ++set) {
          const glm::dvec2 st = interpolate_st(*tri, b, set);
          ASSERT_TRUE(same_bits(s[static_cast<size_t>(set)][k], plain_coord(st.x))) << n << " " << k << " set " << set;
          ASSERT_TRUE(same_bits(t[static_cast<size_t>(set)][k], plain_coord(st.y))) << n << " " << k << " set " << set;
        }
        ++pixels;
      }
    }
  }
  // The sweep reached its cases: most triangles set up, and helper pixels beyond the horizon.
  EXPECT_GT(set_up, triangles / 2);
  EXPECT_GT(beyond_horizon, 0);
  EXPECT_GT(pixels, int64_t{4} * 24 * triangles / 2);
}

TEST(RasterQuadFast, ReusedResultEqualsAFreshRender) {
  Scene ground = load_scene("ground_plane");
  ground.width = 96, ground.height = 64;
  Scene tunnel = load_scene("tunnel");
  tunnel.width = 128, tunnel.height = 72;
  RenderOptions o;
  o.trace = true;
  o.threads = 1;
  const RenderResult fresh = render_scene(ground, o);
  RenderResult reused = render_scene(tunnel, o);  // a larger frame with other contents first
  render_scene(ground, o, reused);
  EXPECT_EQ(reused.image.width, 96);
  EXPECT_EQ(reused.image.height, 64);
  EXPECT_EQ(reused.image.texels, fresh.image.texels);
  EXPECT_EQ(reused.depth, fresh.depth);
  EXPECT_EQ(reused.stats.quads, fresh.stats.quads);
  EXPECT_EQ(reused.stats.pixels, fresh.stats.pixels);
  ASSERT_EQ(reused.trace.requests.size(), fresh.trace.requests.size());
  EXPECT_EQ(reused.quad_targets.size(), fresh.quad_targets.size());
  // The depth buffer holds +inf where nothing is drawn (the ground plane's sky) and each drawn
  // pixel's depth in [0, 1] elsewhere; drawn pixels are at most the sampled ones (overdraw).
  ASSERT_EQ(fresh.depth.size(), size_t{96} * 64);
  const auto drawn = std::count_if(fresh.depth.begin(), fresh.depth.end(), [](float d) { return d >= 0.0f && d <= 1.0f; });
  const auto empty = std::count(fresh.depth.begin(), fresh.depth.end(), std::numeric_limits<float>::infinity());
  EXPECT_GT(drawn, 0);
  EXPECT_GT(empty, 0);
  EXPECT_EQ(drawn + empty, 96 * 64);
  EXPECT_LE(drawn, fresh.stats.pixels);
}

// Each band's worker clears its own rows (clear_band): every pixel of a reused result's buffers is
// cleared, whatever the previous frame held, its size (smaller, larger) and the number of workers,
// also for a height that is not a multiple of the band's 16 rows.
TEST(RasterQuadFast, BandClearsEqualAFreshRender) {
  Scene ground = load_scene("ground_plane");
  ground.width = 96, ground.height = 64;
  Scene tunnel = load_scene("tunnel");
  tunnel.width = 130, tunnel.height = 75;  // its last band: rows 64..74
  Scene large = tunnel;
  large.width = 160, large.height = 90;
  for (const int threads : {1, 2}) {
    RenderOptions o;
    o.threads = threads;
    const RenderResult fresh_tunnel = render_scene(tunnel, o), fresh_ground = render_scene(ground, o);
    // A larger frame first: every element the tunnel's buffers keep held the large frame's colour
    // or depth (drawn depths in [0, 1], +inf elsewhere); a row left uncleared keeps it, and the
    // fresh render's zero-initialized buffers would not.
    RenderResult reused = render_scene(large, o);
    render_scene(tunnel, o, reused);
    EXPECT_EQ(reused.image.texels, fresh_tunnel.image.texels);
    EXPECT_EQ(reused.depth, fresh_tunnel.depth);
    render_scene(ground, o, reused);  // smaller
    EXPECT_EQ(reused.image.texels, fresh_ground.image.texels);
    EXPECT_EQ(reused.depth, fresh_ground.depth);
    render_scene(tunnel, o, reused);  // larger again: the buffers grow
    EXPECT_EQ(reused.image.texels, fresh_tunnel.image.texels);
    EXPECT_EQ(reused.depth, fresh_tunnel.depth);
  }
}

// Random triangles of every size, up to the screen-coordinate limit of setup (2^20 pixels: edge
// functions near 2^58), and thin slivers; quads in and around each bounding box. The packed
// coverage test equals the fill-rule test e_i + bias_i >= 0 per pixel and RasterTriangle::covers_pixel,
// and the edges stepped quad by quad equal RasterTriangle::edge at each quad.
using test::edges_at;

std::optional<RasterTriangle> random_triangle(std::mt19937_64& rng, int n) {
  const double span = n % 4 == 0 ? 1e6 : n % 4 == 1 ? 3.0 : n % 4 == 2 ? 300.0 : 40.0;
  std::uniform_real_distribution<double> pos(-span, span);
  std::array<ScreenVertex, 3> v;
  for (auto& sv : v) sv.x = 100 + pos(rng), sv.y = 80 + pos(rng);
  if (n % 5 == 0) v[2].x = v[1].x + 0.01, v[2].y = v[1].y + 0.5 * span;  // a sliver
  if (n % 7 == 0) v[2].y = v[1].y;                                       // a horizontal edge
  if (n % 11 == 0) v[2].x = v[0].x;                                      // a vertical edge
  if (n % 13 == 0)  // vertices on pixel centres: centres on the edges, the fill rule decides
    for (auto& sv : v) sv.x = std::floor(sv.x) + 0.5, sv.y = std::floor(sv.y) + 0.5;
  std::optional<RasterTriangle> tri = setup_triangle(v, 200, 160);
  // Off the screen inside the guard band (an empty bounding box): the renderer skips it
  // (setup_scene), and its bounds are no range to draw quads from.
  if (tri && (tri->xmin > tri->xmax || tri->ymin > tri->ymax)) return std::nullopt;
  return tri;
}

TEST(RasterQuadFast, CoverageEqualsThePerPixelTest) {
  std::mt19937_64 rng(20261208);
  const int triangles = test::iterations(20000);
  int64_t covered_pixels = 0, uncovered_pixels = 0;
  for (int n = 0; n < triangles; ++n) {
    const auto tri = random_triangle(rng, n);
    if (!tri) continue;
    for (int trial = 0; trial < 16; ++trial) {
      const int qx = std::uniform_int_distribution<int>(tri->xmin - 4, tri->xmax + 4)(rng) & ~1;
      const int qy = std::uniform_int_distribution<int>(tri->ymin - 4, tri->ymax + 4)(rng) & ~1;
      const raster_fast::QuadEdges q = edges_at(*tri, qx, qy);
      unsigned plain = 0;
      for (size_t k = 0; k < 4; ++k) {
        if (q.e[0][k] + tri->bias[0] >= 0 && q.e[1][k] + tri->bias[1] >= 0 && q.e[2][k] + tri->bias[2] >= 0) plain |= 1u << k;
        ASSERT_EQ((plain >> k & 1u) != 0, tri->covers_pixel(qx + static_cast<int>(k & 1), qy + static_cast<int>(k >> 1)));
      }
      ASSERT_EQ(raster_fast::coverage(q, tri->bias), plain) << n << " " << qx << " " << qy;
      for (size_t k = 0; k < 4; ++k) (plain >> k & 1u ? covered_pixels : uncovered_pixels) += 1;
    }
  }
  EXPECT_GT(covered_pixels, 1000);
  EXPECT_GT(uncovered_pixels, 1000);
}

TEST(RasterQuadFast, StepEqualsTheEdgeFunctions) {
  std::mt19937_64 rng(77);
  const int triangles = test::iterations(3000);
  for (int n = 0; n < triangles; ++n) {
    const auto tri = random_triangle(rng, n);
    if (!tri) continue;
    std::array<int64_t, 3> step{};
    for (size_t i = 0; i < 3; ++i) step[i] = -2 * (tri->Y[(i + 2) % 3] - tri->Y[(i + 1) % 3]) * 256;
    const int qy = std::uniform_int_distribution<int>(tri->ymin, tri->ymax)(rng) & ~1;
    const int qx0 = (tri->xmin & ~1) - 8;
    raster_fast::QuadEdges q = edges_at(*tri, qx0, qy);
    for (int qx = qx0 + 2; qx <= qx0 + 40; qx += 2) {
      raster_fast::step(q, step);
      const raster_fast::QuadEdges want = edges_at(*tri, qx, qy);
      ASSERT_EQ(q.e, want.e) << n << " " << qx;
    }
  }
}

TEST(RasterQuadFast, DepthTestEqualsThePerPixelTest) {
  // Depths at, just above and below the float stored, NaN and infinities on both sides; every
  // covered mask; quads at every position of a 5 x 3 buffer, each through both loads (the quad
  // inside the image: two 8-byte loads; else only covered pixels read).
  std::mt19937_64 rng(9);
  const float stored[] = {0.25f, 1.0f / 3.0f, 0.0f, -0.0f, 1.0f, std::numeric_limits<float>::infinity(),
                          std::numeric_limits<float>::quiet_NaN(), 1e-40f};
  const size_t w = 5, h = 3;
  int64_t passed = 0, failed = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    std::vector<float> depth(w * h);
    for (float& d : depth) d = stored[rng() % 8];
    const size_t qx = rng() % (w - 1), qy = rng() % (h - 1);
    std::array<double, 4> z;
    for (size_t k = 0; k < 4; ++k) {
      const double d = depth[(qy + (k >> 1)) * w + qx + (k & 1)];
      switch (rng() % 6) {
        case 0: z[k] = d; break;
        case 1: z[k] = std::nextafter(d, 2.0); break;
        case 2: z[k] = std::nextafter(d, -2.0); break;
        case 3: z[k] = std::numeric_limits<double>::quiet_NaN(); break;
        case 4: z[k] = rng() % 2 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity(); break;
        default: z[k] = std::uniform_real_distribution<double>(-0.5, 1.5)(rng); break;
      }
    }
    for (unsigned covered = 0; covered < 16; ++covered) {
      unsigned plain = 0;
      for (size_t k = 0; k < 4; ++k)
        if ((covered >> k & 1u) && z[k] < depth[(qy + (k >> 1)) * w + qx + (k & 1)]) plain |= 1u << k;
      ASSERT_EQ(raster_fast::depth_test(covered, z, depth.data(), qy * w + qx, w, false), plain) << trial << " " << covered;
      ASSERT_EQ(raster_fast::depth_test(covered, z, depth.data(), qy * w + qx, w, true), plain) << trial << " " << covered;
      for (size_t k = 0; k < 4; ++k)
        if (covered >> k & 1u) (plain >> k & 1u ? passed : failed) += 1;
    }
  }
  EXPECT_GT(passed, 1000);
  EXPECT_GT(failed, 1000);
}

TEST(RasterQuadFast, GatherAndSpreadEqualThePerPixelLoops) {
  const float s[4] = {0.5f, -1.25f, 3.0f, 1e-3f}, t[4] = {7.0f, 0.125f, -2.0f, 1e9f};
  for (unsigned mask = 0; mask < 16; ++mask) {
    std::array<SampleRequest, 4> fast{}, plain{};
    size_t n_plain = 0;
    for (size_t k = 0; k < 4; ++k)
      if (mask >> k & 1u) plain[n_plain++] = {s[k], t[k], -77};
    const size_t n = raster_fast::gather_requests(mask, s, t, -77, fast.data());
    ASSERT_EQ(n, n_plain) << mask;
    for (size_t j = 0; j < n; ++j) {
      EXPECT_EQ(std::memcmp(&fast[j], &plain[j], sizeof(SampleRequest)), 0) << mask << " " << j;
    }
    // The batch's texels of the drawn pixels, in order, then spread back to their lanes.
    std::array<Rgba8, 4> texel_fast, texel_plain;
    for (size_t j = 0; j < 4; ++j) texel_fast[j] = texel_plain[j] = Rgba8{static_cast<uint8_t>(10 + j), 20, 30, static_cast<uint8_t>(40 + j)};
    size_t m = n_plain;
    for (size_t k = 4; k-- > 0;) texel_plain[k] = mask >> k & 1u ? texel_plain[--m] : Rgba8{};
    raster_fast::spread_texels(mask, texel_fast);
    EXPECT_EQ(std::memcmp(texel_fast.data(), texel_plain.data(), sizeof texel_fast), 0) << mask;
  }
}

TEST(RasterQuadFast, WriteQuadEqualsThePerPixelWrites) {
  // Every mask, quads at every position of a 5 x 4 image (odd width: rows not 8-byte aligned),
  // depths of every kind (rounding to FP32 up and down, ties, tiny, huge, infinite, NaN).
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<uint32_t> word;
  const double depths[] = {0.1, 1.0 / 3.0, 0.5 + 0x1p-25, 0.5 + 0x1p-24 + 0x1p-25, 1e-300, 1e300, -0.0,
                           std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()};
  const size_t w = 5, h = 4;
  for (int trial = 0; trial < 2000; ++trial)
    for (unsigned mask = 0; mask < 16; ++mask) {
      const size_t qx = static_cast<size_t>(trial) % (w - 1), qy = static_cast<size_t>(trial / 4) % (h - 1);
      std::array<Rgba8, 4> colour;
      std::array<double, 4> z;
      for (size_t k = 0; k < 4; ++k) {
        const uint32_t c = word(rng);
        colour[k] = {static_cast<uint8_t>(c), static_cast<uint8_t>(c >> 8), static_cast<uint8_t>(c >> 16), static_cast<uint8_t>(c >> 24)};
        z[k] = trial % 3 == 0 ? depths[word(rng) % 9] : std::uniform_real_distribution<double>(0.0, 1.0)(rng);
      }
      std::vector<Rgba8> image_fast(w * h, Rgba8{1, 2, 3, 4}), image_plain = image_fast;
      std::vector<float> depth_fast(w * h, 7.0f), depth_plain = depth_fast;
      raster_fast::write_quad(mask, colour, z, qy * w + qx, w, image_fast.data(), depth_fast.data());
      for (size_t k = 0; k < 4; ++k) {
        if (!(mask >> k & 1u)) continue;
        const size_t idx = (qy + (k >> 1)) * w + qx + (k & 1);
        image_plain[idx] = colour[k];
        depth_plain[idx] = static_cast<float>(z[k]);
      }
      ASSERT_EQ(std::memcmp(image_fast.data(), image_plain.data(), w * h * sizeof(Rgba8)), 0) << trial << " " << mask;
      ASSERT_EQ(std::memcmp(depth_fast.data(), depth_plain.data(), w * h * sizeof(float)), 0) << trial << " " << mask;
    }
}

}  // namespace
}  // namespace tfu
