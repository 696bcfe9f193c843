// The LOD unit's input stage, its speed-only form (cmodel/lod_fast.hpp) against the plain twin
// (derivatives_from_quad_plain, float_to_fixed), value for value: the conversion of one value for
// every exponent and sign with boundary and random mantissas and every kind of scale, a strided
// sweep of all 2^32 float bit patterns, and random and special quads through both forms of
// derivatives_from_quad (and the dispatch under the fast-path switch).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "cmodel/fast_paths.hpp"
#include "cmodel/fixed_coord.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/lod_fast.hpp"
#include "testbench/iterations.hpp"

namespace tfu {
namespace {

bool same(const TexelDerivatives& a, const TexelDerivatives& b) {
  return a.dudx == b.dudx && a.dvdx == b.dvdx && a.dudy == b.dudy && a.dvdy == b.dvdy;
}

// Scales of every kind: 1, powers of two, odd, the largest (2^15) and random.
uint32_t scale_for(int k, std::mt19937& rng) {
  if (k < 16) return 1u << k;
  if (k < 24) return 32768u - static_cast<uint32_t>(k - 16);
  if (k < 28) return 3u + 2u * static_cast<uint32_t>(k);
  return std::uniform_int_distribution<uint32_t>(1, 32768)(rng);
}

TEST(LodFast, ConversionEqualsFloatToFixedForEveryExponent) {
  std::mt19937 rng(20261207);
  std::uniform_int_distribution<uint32_t> mant(0, 0x7FFFFF);
  const int per_exponent = test::iterations(2000);
  int64_t saturated = 0, negative_tiny = 0;
  for (uint32_t exp = 0; exp < 256; ++exp)
    for (uint32_t sign = 0; sign < 2; ++sign)
      for (int k = 0; k < per_exponent; ++k) {
        const uint32_t m = k == 0 ? 0 : k == 1 ? 0x7FFFFF : k == 2 ? 1 : k == 3 ? 0x400000 : mant(rng);
        const float x = std::bit_cast<float>((sign << 31) | (exp << 23) | m);
        const uint32_t w = scale_for(k % 40, rng);
        const int64_t want = float_to_fixed(x, w, 16);
        ASSERT_EQ(lod_fast::to_fixed_q16(x, w), want) << std::bit_cast<uint32_t>(x) << " " << w;
        saturated += want == kFixedLimit || want == -kFixedLimit;
        negative_tiny += want == -1;
      }
  EXPECT_GT(saturated, 0);
  EXPECT_GT(negative_tiny, 0);
}

TEST(LodFast, ConversionEqualsFloatToFixedOnAStridedSweepOfAllFloats) {
  // Every 251st bit pattern (a prime stride: every exponent, both signs, mantissas of every residue).
  const uint64_t stride = 251 * static_cast<uint64_t>(test::kIterationDivisor);
  uint32_t w = 1;
  for (uint64_t b = 0; b < (uint64_t{1} << 32); b += stride) {
    const float x = std::bit_cast<float>(static_cast<uint32_t>(b));
    ASSERT_EQ(lod_fast::to_fixed_q16(x, w), float_to_fixed(x, w, 16)) << b << " " << w;
    w = w == 32768 ? 1 : w * 2 + (b & 1);  // odd and power-of-two scales
    if (w > 32768) w = 32768;
  }
}

// A random quad's (s, t): per pixel mostly a real quad (values within `spread` of a base),
// sometimes far apart, random bit patterns or special values.
class RandomQuad {
 public:
  explicit RandomQuad(uint32_t seed) : rng_(seed) {}
  std::mt19937& rng() { return rng_; }
  void next(float spread, float s[4], float t[4]) {
    const float base_s = near_(rng_), base_t = near_(rng_);
    for (size_t k = 0; k < 4; ++k) {
      const int kind = pick_(rng_);
      s[k] = kind < 6 ? base_s + near_(rng_) * spread : kind < 8 ? far_(rng_) : kind < 9 ? std::bit_cast<float>(bits_(rng_)) : special();
      t[k] = kind < 6 ? base_t + near_(rng_) * spread : kind < 8 ? far_(rng_) : kind < 9 ? std::bit_cast<float>(bits_(rng_)) : special();
    }
  }

 private:
  float special() {
    static constexpr float kSpecials[] = {0.0f, -0.0f, std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                                          std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::denorm_min(),
                                          -std::numeric_limits<float>::denorm_min(), 1e30f, -1e30f, 0.5f};
    return kSpecials[bits_(rng_) % 10];
  }
  std::mt19937 rng_;
  std::uniform_real_distribution<float> near_{-2.0f, 2.0f}, far_{-1e6f, 1e6f};
  std::uniform_int_distribution<uint32_t> bits_;
  std::uniform_int_distribution<int> pick_{0, 9};
};

TEST(LodFast, QuadDerivativesEqualThePlainTwin) {
  RandomQuad quad(7);
  std::mt19937& rng = quad.rng();
  std::uniform_int_distribution<int> size(1, 32768);
  const int quads = test::iterations(200000);
  for (int n = 0; n < quads; ++n) {
    float s[4], t[4];
    quad.next(1e-3f, s, t);
    const int w = n % 7 == 0 ? 32768 : n % 7 == 1 ? 1 : size(rng), h = n % 5 == 0 ? 32768 : size(rng);
    const TexelDerivatives want = derivatives_from_quad_plain(s, t, w, h);
    ASSERT_TRUE(same(lod_fast::derivatives_from_quad(s, t, w, h), want)) << n;
    ASSERT_TRUE(same(derivatives_from_quad(s, t, w, h), want)) << n;
  }
}

// The inline lambda of the renderer (lod_fast::lambda_from_length_sq, lambda_from_quad) against
// the LOD unit's plain path: every leading-one position of rho^2 (0..63) with boundary and random
// lower bits, and 0; then quads as above against lambda_from_derivatives(derivatives_from_quad_plain).
TEST(LodFast, LambdaFromLengthEqualsThePlainUnit) {
  std::mt19937_64 rng(11);
  ASSERT_EQ(lod_fast::lambda_from_length_sq(0), lambda_from_length_sq(0));
  for (int e = 0; e < 64; ++e) {
    const uint64_t top = uint64_t{1} << e, low = top - 1;
    std::vector<uint64_t> xs{top, top | low, top | (low >> 1), top | 1, top | (low & 0x5555555555555555u)};
    for (int k = 0; k < 2000; ++k) xs.push_back(top | (rng() & low));
    for (uint64_t x : xs) ASSERT_EQ(lod_fast::lambda_from_length_sq(x), lambda_from_length_sq(x)) << x;
  }
  for (uint64_t x = 1; x < (1u << 20); ++x) ASSERT_EQ(lod_fast::lambda_from_length_sq(x), lambda_from_length_sq(x)) << x;
}

TEST(LodFast, LambdaFromQuadEqualsThePlainTwin) {
  RandomQuad quad(9);
  std::mt19937& rng = quad.rng();
  std::uniform_real_distribution<float> spread(1e-6f, 1e-1f);
  std::uniform_int_distribution<int> size(1, 32768);
  const int quads = test::iterations(200000);
  for (int n = 0; n < quads; ++n) {
    float s[4], t[4];
    quad.next(spread(rng), s, t);
    if (n % 11 == 0) std::copy(s, s + 4, t);  // equal lengths
    if (n % 13 == 0) s[1] = s[0], s[2] = s[0], t[1] = t[0], t[2] = t[0];  // rho = 0
    const int w = n % 7 == 0 ? 32768 : n % 7 == 1 ? 1 : size(rng), h = n % 5 == 0 ? 32768 : size(rng);
    ASSERT_EQ(lod_fast::lambda_from_quad(s, t, w, h), lambda_from_derivatives(derivatives_from_quad_plain(s, t, w, h))) << n;
  }
}

TEST(LodFast, HandValuesAndTheSwitch) {
  // A quad one texel apart in x and two in y on a 256 x 128 texture: du/dx = 1, dv/dy = 2 texels (Q.16).
  const float s[4] = {0.25f, 0.25f + 1.0f / 256, 0.25f, 0.0f}, t[4] = {0.5f, 0.5f, 0.5f + 2.0f / 128, 0.0f};
  const TexelDerivatives d = lod_fast::derivatives_from_quad(s, t, 256, 128);
  EXPECT_EQ(d.dudx, 65536);
  EXPECT_EQ(d.dvdx, 0);
  EXPECT_EQ(d.dudy, 0);
  EXPECT_EQ(d.dvdy, 131072);
  // NaN converts to 0, +Inf saturates at 2^46: du/dx = 2^46 - 0.
  const float sn[4] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), -1.0f, 0.0f};
  const TexelDerivatives e = lod_fast::derivatives_from_quad(sn, t, 256, 128);
  EXPECT_EQ(e.dudx, kFixedLimit);
  EXPECT_EQ(e.dudy, -256 * 65536);
  const bool was = fast_paths_enabled();
  set_fast_paths(false);
  EXPECT_TRUE(same(derivatives_from_quad(s, t, 256, 128), d));
  set_fast_paths(was);
}

}  // namespace
}  // namespace tfu
