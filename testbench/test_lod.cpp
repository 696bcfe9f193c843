// LOD unit: fixed-point input conversion, log2 ROM accuracy, quad / gradient / explicit lambda,
// GL level selection.
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "cmodel/datapath.hpp"
#include "cmodel/fixed_coord.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/sampler.hpp"

namespace tfu {
namespace {

TEST(FixedCoord, HandValues) {
  EXPECT_EQ(float_to_fixed(0.5f, 4, 8), 512);
  EXPECT_EQ(float_to_fixed(-0.25f, 4, 8), -256);
  EXPECT_EQ(float_to_fixed(0.1f, 1, 8), 25);    // 25.6000004 -> 25
  EXPECT_EQ(float_to_fixed(-0.1f, 1, 8), -26);  // floor of -25.6
  EXPECT_EQ(float_to_fixed(0.0f, 100, 8), 0);
  EXPECT_EQ(float_to_fixed(-0.0f, 100, 8), 0);
  EXPECT_EQ(float_to_fixed(std::numeric_limits<float>::quiet_NaN(), 7, 8), 0);
  EXPECT_EQ(float_to_fixed(std::numeric_limits<float>::infinity(), 7, 8), kFixedLimit);
  EXPECT_EQ(float_to_fixed(-std::numeric_limits<float>::infinity(), 7, 8), -kFixedLimit);
  EXPECT_EQ(float_to_fixed(1e30f, 7, 8), kFixedLimit);
  EXPECT_EQ(float_to_fixed(std::numeric_limits<float>::denorm_min(), 16384, 24), 0);
  EXPECT_EQ(float_to_fixed(-std::numeric_limits<float>::denorm_min(), 16384, 24), -1);
  EXPECT_EQ(float_to_fixed_round(1.5f / 256.0f, 1, 8), 2);  // 1.5 -> 2 (ties up)
  EXPECT_EQ(float_to_fixed_round(-1.5f / 256.0f, 1, 8), -1);
}

// Property: equals floor(x * scale * 2^F) computed in long double (exact for these magnitudes).
TEST(FixedCoord, MatchesExactFloorOnRandomFloats) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<uint32_t> bits;
  std::uniform_int_distribution<uint32_t> scale(1, 16384);
  for (int i = 0; i < 1'000'000; ++i) {
    uint32_t b = bits(rng);
    // Keep exponents in a useful range (|x| < 2^20) most of the time; still covers tiny values.
    const uint32_t exp = ((b >> 23) & 0xFF) % 147;
    b = (b & 0x807FFFFFu) | (exp << 23);
    float x;
    std::memcpy(&x, &b, 4);
    const uint32_t sc = scale(rng);
    const int fb = static_cast<int>(i % 17);
    const long double exact = std::floor(static_cast<long double>(x) * sc * std::ldexp(1.0L, fb));
    if (std::fabs(exact) >= static_cast<long double>(kFixedLimit)) continue;
    ASSERT_EQ(float_to_fixed(x, sc, fb), static_cast<int64_t>(exact)) << x << " " << sc << " " << fb;
  }
}

// Property: the integer common case (float_to_fixed_fast, and dp::texel_coord built on it) equals
// float_to_fixed for every exponent, both signs, random and boundary mantissas, fraction widths
// 0..24 and power-of-two, odd and maximal scales.
TEST(FixedCoord, FastPathEqualsGeneral) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<uint32_t> mant(0, 0x7FFFFF);
  std::uniform_int_distribution<uint32_t> scale(1, 32768);
  for (uint32_t exp = 0; exp < 256; ++exp)
    for (uint32_t sign = 0; sign < 2; ++sign)
      for (int k = 0; k < 2000; ++k) {
        const uint32_t m = k == 0 ? 0 : k == 1 ? 0x7FFFFF : k == 2 ? 1 : mant(rng);
        const float x = std::bit_cast<float>((sign << 31) | (exp << 23) | m);
        const uint32_t w = k < 8 ? (1u << (k % 8) * 2) : k < 16 ? 32768u - static_cast<uint32_t>(k) : scale(rng);
        const int fb = k % 25;
        ASSERT_EQ(float_to_fixed_fast(x, w, fb), float_to_fixed(x, w, fb)) << x << " " << w << " " << fb;
        const int64_t u = float_to_fixed(x, w, 8) - 128;
        const dp::LevelCoord c = dp::texel_coord(x, static_cast<int>(w));
        ASSERT_EQ(c.i0, u >> 8) << x << " " << w;
        ASSERT_EQ(c.f, static_cast<uint32_t>(u & 255)) << x << " " << w;
      }
}

TEST(Log2Rom, ErrorBelowOne256thOfALevel) {
  double worst = 0;
  for (uint64_t x = 1; x < (uint64_t{1} << 22); ++x)
    worst = std::max(worst, std::abs(log2_q8(x) / 256.0 - std::log2(static_cast<double>(x))));
  std::mt19937_64 rng(3);
  for (int i = 0; i < 1'000'000; ++i) {
    const uint64_t x = rng() >> (rng() % 63);
    if (x == 0) continue;
    worst = std::max(worst, std::abs(log2_q8(x) / 256.0 - std::log2(static_cast<double>(x))));
  }
  for (int e = 0; e < 64; ++e) EXPECT_EQ(log2_q8(uint64_t{1} << e), e * 256);
  EXPECT_LE(worst, 1.0 / 256.0);
  EXPECT_EQ(log2_q8(0), kLodMinusInfinity);
}

TEST(Lod, QuadDerivatives) {
  // 256-wide texture, 4 texels per pixel in x, 1 in y -> lambda = log2(4) = 2 exactly (GL max of lengths).
  const float s[4] = {0.0f, 4.0f / 256, 0.0f, 4.0f / 256};
  const float t[4] = {0.0f, 0.0f, 1.0f / 256, 1.0f / 256};
  EXPECT_EQ(lambda_from_quad(s, t, 256, 256), 512);
  // Diagonal derivative (3, 4) texels: length 5, lambda = log2 5 = 2.3219 -> 594.4 in Q.8.
  const float s2[4] = {0.5f, 0.5f + 3.0f / 256, 0.5f, 0.5f};
  const float t2[4] = {0.5f, 0.5f + 4.0f / 256, 0.5f, 0.5f};
  EXPECT_NEAR(lambda_from_quad(s2, t2, 256, 256), 594.4, 1.0);
  // Constant coordinates: no derivative -> log2(0)
  const float c[4] = {0.3f, 0.3f, 0.3f, 0.3f};
  EXPECT_EQ(lambda_from_quad(c, c, 64, 64), kLodMinusInfinity);
  // Magnification by 4: 1/4 texel per pixel -> -2.
  EXPECT_EQ(lambda_from_gradients(0.25f / 64, 0.0f, 0.0f, 0.25f / 64, 64, 64), -512);
}

TEST(Lod, ExplicitBiasClamp) {
  EXPECT_EQ(lambda_explicit(1.5f), 384);
  EXPECT_EQ(lambda_explicit(-0.75f), -192);
  EXPECT_EQ(lambda_explicit(std::numeric_limits<float>::quiet_NaN()), 0);
  LodParams p;
  p.bias_q8 = 256;
  p.min_lod_q8 = 0;
  p.max_lod_q8 = 3 * 256;
  EXPECT_EQ(lambda_bias_clamp(384, p), 640);
  EXPECT_EQ(lambda_bias_clamp(-2000, p), 0);
  EXPECT_EQ(lambda_bias_clamp(5000, p), 768);
}

Texture flat_chain(int size) {
  Texture t;
  t.levels.emplace_back(size, size, Rgba8{1, 2, 3, 4});
  while (t.levels.back().width > 1) {
    const int w = t.levels.back().width / 2;
    t.levels.emplace_back(w, w, Rgba8{1, 2, 3, 4});
  }
  return t;
}

TEST(Lod, GlLevelSelection) {
  const Texture tex = flat_chain(16);  // levels 0..4
  SamplerDescriptor c;
  c.mode = {BaseFilter::Linear, MipMode::Nearest};
  const Sampler n(tex, c);
  EXPECT_TRUE(n.lod_info(0).magnify);
  EXPECT_EQ(n.lod_info(128).level0, 0);   // lambda = 0.5 -> level 0
  EXPECT_EQ(n.lod_info(129).level0, 1);   // just above 0.5
  EXPECT_EQ(n.lod_info(384).level0, 1);   // 1.5 -> ceil(2) - 1 = 1
  EXPECT_EQ(n.lod_info(385).level0, 2);
  EXPECT_EQ(n.lod_info(100 * 256).level0, 4);  // clamped to the last level
  c.mode = {BaseFilter::Linear, MipMode::Linear};
  const Sampler l(tex, c);
  const LodInfo li = l.lod_info(320);  // 1.25
  EXPECT_EQ(li.level0, 1);
  EXPECT_EQ(li.level1, 2);
  EXPECT_EQ(li.blend, 64);
  EXPECT_EQ(li.kernel_scale, 2);
  EXPECT_EQ(li.level0_width, 8);
  const LodInfo top = l.lod_info(4 * 256 + 10);
  EXPECT_EQ(top.level0, 4);
  EXPECT_EQ(top.level1, 4);
  EXPECT_EQ(top.blend, 0);
}

}  // namespace
}  // namespace tfu
