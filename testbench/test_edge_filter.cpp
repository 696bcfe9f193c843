// Lee & Jen edge-preserving interpolation: hand-derived edge cases, T/L kernels never read
// unavailable texels, cache-block shape selection, smooth light-maps stay close to bilinear.
#include <bit>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "cmodel/edge_filter.hpp"
#include "cmodel/sampler.hpp"

namespace tfu::lee_jen {
namespace {

std::array<Texel4, kTexels> vertical_edge() {
  // x <= 0 black, x >= 1 white: the edge runs between C4 and C5.
  std::array<Texel4, kTexels> c{};
  for (int n = 1; n <= kTexels; ++n) {
    const int v = texel_pos(n).x >= 1 ? 255 : 0;
    c[static_cast<size_t>(n - 1)] = {v, v, v, 255};
  }
  return c;
}

TEST(EdgeFilter, VerticalEdgeStaysSharp) {
  const auto c = vertical_edge();
  EdgeDecision d;
  // fu4 = 7 (x = 0.47): C4-C8 lies within its ROI, dP = 0 -> low part 0, high part 0.
  EXPECT_EQ(edge_preserving_interpolate(c, kAllTexels, 120, 64, TexelFormat::RGBA8, &d)[0], 0);
  EXPECT_EQ(directions()[static_cast<size_t>(d.direction)].name(), "C4-C8");
  EXPECT_EQ(d.cost, 0u);
  // fu4 = 8 (x = 0.53): C4-C8 is out of its ROI; C5-C9 wins -> 255. Bilinear would give 128..136.
  EXPECT_EQ(edge_preserving_interpolate(c, kAllTexels, 136, 64, TexelFormat::RGBA8, &d)[0], 255);
  EXPECT_EQ(directions()[static_cast<size_t>(d.direction)].name(), "C5-C9");
  // Alpha is carried (constant 255 here).
  EXPECT_EQ(edge_preserving_interpolate(c, kAllTexels, 136, 64, TexelFormat::RGBA8)[3], 255);
}

TEST(EdgeFilter, HighFrequencyPartRestoresAnIsolatedTexel) {
  // A single bright texel C4 in black: every median removes it (low part 0 everywhere), so the
  // result is the bilinear high part alone: H4 = 255 with weight (1 - fu)(1 - fv).
  std::array<Texel4, kTexels> c{};
  for (auto& t : c) t = {0, 0, 0, 255};
  c[3] = {255, 255, 255, 255};
  EXPECT_EQ(edge_preserving_interpolate(c, kAllTexels, 0, 0, TexelFormat::RGBA8)[0], 255);
  // fu = fv = 128: 255 / 4 = 63.75 -> 64 (round half up on the Q.16 sum)
  EXPECT_EQ(edge_preserving_interpolate(c, kAllTexels, 128, 128, TexelFormat::RGBA8)[0], 64);
}

TEST(EdgeFilter, ShapesNeverReadUnavailableTexels) {
  std::mt19937 rng(4);
  for (const KernelShape& shape : kernel_shapes()) {
    for (int i = 0; i < 2000; ++i) {
      std::array<Texel4, kTexels> a{}, b{};
      for (int n = 0; n < kTexels; ++n) {
        a[static_cast<size_t>(n)] = {static_cast<int32_t>(rng() % 256), static_cast<int32_t>(rng() % 256),
                                     static_cast<int32_t>(rng() % 256), static_cast<int32_t>(rng() % 256)};
        b[static_cast<size_t>(n)] = a[static_cast<size_t>(n)];
        if (!((shape.mask >> n) & 1u)) {  // poison the unavailable texels differently in a and b
          a[static_cast<size_t>(n)] = {255, 0, 255, 0};
          b[static_cast<size_t>(n)] = {0, 255, 0, 255};
        }
      }
      const uint32_t fu = rng() % 256, fv = rng() % 256;
      EdgeDecision da, db;
      const Texel4 ra = edge_preserving_interpolate(a, shape.mask, fu, fv, TexelFormat::RGBA8, &da);
      const Texel4 rb = edge_preserving_interpolate(b, shape.mask, fu, fv, TexelFormat::RGBA8, &db);
      ASSERT_EQ(ra, rb) << shape.name();
      ASSERT_EQ(da.direction, db.direction);
      ASSERT_EQ(da.read & ~shape.mask, 0) << shape.name();
      ASSERT_TRUE((usable_directions(shape.mask) >> da.direction) & 1u) << shape.name();
    }
  }
}

TEST(EdgeFilter, CacheBlockMaskPicksCrossTAndL) {
  // B = 4. Centre square inside a block -> cross.
  EXPECT_EQ(cache_block_mask(1, 2, 1, 2, 4), kAllTexels);
  // Top row of a block -> T without C1, C2 (Fig. 3a).
  EXPECT_EQ(std::popcount(static_cast<unsigned>(cache_block_mask(1, 2, 0, 1, 4))), 10);
  EXPECT_EQ(cache_block_mask(1, 2, 0, 1, 4) & 0x3, 0);
  // Top-left corner -> L (8 texels, 14 directions).
  const TexelMask l = cache_block_mask(0, 1, 0, 1, 4);
  EXPECT_EQ(std::popcount(static_cast<unsigned>(l)), 8);
  EXPECT_EQ(std::popcount(usable_directions(l)), 14);
  // Centre square straddling two blocks horizontally: both blocks are fetched, the cross is used
  // unless the rows leave them.
  EXPECT_EQ(cache_block_mask(3, 4, 1, 2, 4), kAllTexels);
  EXPECT_EQ(std::popcount(static_cast<unsigned>(cache_block_mask(3, 4, 0, 1, 4))), 10);
  // Every mask produced is one of the nine shapes.
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 8; ++y) {
      const TexelMask m = cache_block_mask(x, x + 1, y, y + 1, 4);
      bool found = false;
      for (const KernelShape& s : kernel_shapes()) found = found || s.mask == m;
      EXPECT_TRUE(found) << x << "," << y;
    }
}

// The rule of Sec. 3 written with C++'s / and % (truncating: a border coordinate -1 is in block 0
// with remainder -1), against cache_block_mask's shift form for power-of-two blocks, exhaustively
// over centre squares near and across block edges, wrapped seams and border columns.
TEST(EdgeFilter, CacheBlockMaskEqualsTheDivisionRule) {
  const auto rule = [](int x4, int x5, int y4, int y8, int b) {
    TexelMask m = kAllTexels;
    const bool same_x = x5 == x4 + 1 && x4 / b == x5 / b, same_y = y8 == y4 + 1 && y4 / b == y8 / b;
    if (same_y && y4 % b == 0) m = static_cast<TexelMask>(m & ~arm(Side::Top).mask);
    if (same_y && y8 % b == b - 1) m = static_cast<TexelMask>(m & ~arm(Side::Bottom).mask);
    if (same_x && x4 % b == 0) m = static_cast<TexelMask>(m & ~arm(Side::Left).mask);
    if (same_x && x5 % b == b - 1) m = static_cast<TexelMask>(m & ~arm(Side::Right).mask);
    return m;
  };
  int cases = 0;
  for (const int b : {1, 2, 3, 4, 8, 16, 64})
    for (int x4 = -1; x4 < 40; ++x4)
      for (const int x5 : {x4 + 1, 0, -1, x4})
        for (int y4 = -1; y4 < 40; y4 += 3)
          for (const int y8 : {y4 + 1, 0, -1}) {
            ASSERT_EQ(cache_block_mask(x4, x5, y4, y8, b), rule(x4, x5, y4, y8, b)) << b << ' ' << x4 << ' ' << x5 << ' ' << y4 << ' ' << y8;
            ++cases;
          }
  EXPECT_EQ(cases, 7 * 41 * 4 * 14 * 3);
}

TEST(EdgeFilter, SmoothLightMapStaysCloseToBilinear) {
  // Lee & Jen Sec. 2.3: on a light-map the result is almost identical to bilinear.
  Texture t;
  t.levels.emplace_back(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const double v = 0.5 + 0.35 * std::sin(x * 0.11) * std::cos(y * 0.07 + 0.3);
      const auto c = static_cast<uint8_t>(std::lround(255 * v));
      t.levels[0].at(x, y) = {c, static_cast<uint8_t>(c / 2 + 60), static_cast<uint8_t>(255 - c), 255};
    }
  SamplerDescriptor cb, ce;
  cb.mode = {BaseFilter::Linear, MipMode::None};
  ce.mode = {BaseFilter::EdgePreserving, MipMode::None};
  cb.wrap_s = cb.wrap_t = ce.wrap_s = ce.wrap_t = WrapMode::ClampToEdge;
  const Sampler bl(t, cb), ep(t, ce);
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);  // clamp-to-edge: no seam at the border
  int worst = 0;
  double sum = 0;
  constexpr int kN = 20000;
  for (int i = 0; i < kN; ++i) {
    const float s = u(rng), tt = u(rng);
    const Rgba8 a = bl.sample(s, tt, -256), b = ep.sample(s, tt, -256);
    worst = std::max({worst, std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
    sum += std::abs(a.r - b.r);
  }
  // The steepest gradient here is ~10 levels per texel; interpolating along a direction up to half
  // a texel away from the point can differ from bilinear by about half of that.
  EXPECT_LE(worst, 6);
  EXPECT_LE(sum / kN, 1.0);
}

}  // namespace
}  // namespace tfu::lee_jen
