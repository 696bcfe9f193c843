// The renderer's quad interpolation fast path (cmodel/raster_quad_fast.hpp) against its plain twin,
// bit for bit: barycentrics (RasterTriangle::barycentric), depth (b0 z0 + b1 z1 + b2 z2, raster.cpp's
// interpolate_z), and (s, t) as FP32 interface coordinates (interpolate_st, then the clamp to
// +-1e30 and the rounding to float of raster.cpp's to_float_coord), on random triangles of every
// shape and size and quads inside, on and beyond their edges (helper pixels extrapolate, some beyond
// the horizon where 1/w turns negative). And a render into a reused result equals a fresh one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "cmodel/raster.hpp"
#include "cmodel/raster_quad_fast.hpp"
#include "cmodel/scene.hpp"
#include "testbench/iterations.hpp"

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
      std::array<std::array<int64_t, 3>, 4> e;
      for (size_t k = 0; k < 4; ++k)
        for (int i = 0; i < 3; ++i)
          e[k][static_cast<size_t>(i)] = tri->edge(i, RasterTriangle::centre(qx + static_cast<int>(k & 1)),
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
