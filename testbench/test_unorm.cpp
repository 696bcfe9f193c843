// Unsigned normalized formats (cmodel/unorm.hpp): exhaustive where the input space allows.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cmodel/unorm.hpp"

namespace tfu::unorm {
namespace {

// Exact rounding of x*y/m to the nearest integer (ties up), in exact integer arithmetic
// written independently of the implementation (compare remainders, no division trick).
uint32_t reference_round(uint64_t x, uint64_t y, uint64_t m) {
  const uint64_t p = x * y;
  const uint64_t q = p / m, r = p % m;
  return static_cast<uint32_t>(2 * r >= m ? q + 1 : q);
}

TEST(Unorm, MaxCodesAndGlMapping) {
  EXPECT_EQ(max_code(8), 255u);
  EXPECT_EQ(max_code(12), 4095u);
  EXPECT_EQ(max_code(16), 65535u);
  for (unsigned b : {8u, 12u, 16u}) {
    EXPECT_EQ(to_real(max_code(b), b), 1.0);
    EXPECT_EQ(to_real(0, b), 0.0);
    EXPECT_EQ(encode_round(1.0, b), max_code(b));
    EXPECT_EQ(encode_trunc(1.0, b), max_code(b));
  }
}

TEST(Unorm, EncodeHandDerived) {
  // Eq. 3.3 / 3.4 for b = 8: 0.5 * 255 = 127.5 -> trunc 127, round 128.
  EXPECT_EQ(encode_trunc(0.5, 8), 127u);
  EXPECT_EQ(encode_round(0.5, 8), 128u);
  EXPECT_EQ(encode_round(0.2, 8), 51u);   // 51.0 exactly
  EXPECT_EQ(encode_trunc(0.999, 8), 254u);
  EXPECT_EQ(encode_round(-0.3, 8), 0u);   // saturates
  EXPECT_EQ(encode_round(std::nan(""), 8), 0u);
  EXPECT_EQ(encode_round(7.0, 12), 4095u);
}

class UnormBits : public ::testing::TestWithParam<unsigned> {};

TEST_P(UnormBits, EncodeRoundTripsEveryCodeAndErrorBounds) {
  const unsigned b = GetParam();
  double worst_trunc = 0.0, worst_round = 0.0;
  for (uint32_t c = 0; c <= max_code(b); ++c) {
    ASSERT_EQ(encode_round(to_real(c, b), b), c);
    // Probe between codes: the quantization error bounds of Sec. 3.5.
    const double x = (c + 0.4999) / static_cast<double>(max_code(b));
    if (x <= 1.0) {
      worst_trunc = std::max(worst_trunc, x - to_real(encode_trunc(x, b), b));
      worst_round = std::max(worst_round, std::abs(x - to_real(encode_round(x, b), b)));
    }
  }
  EXPECT_LT(worst_trunc, eps_q_trunc(b));
  EXPECT_LE(worst_round, eps_q_round(b));
  EXPECT_GT(worst_round, 0.999 * eps_q_round(b));  // the bound is tight
}

INSTANTIATE_TEST_SUITE_P(Widths, UnormBits, ::testing::Values(8u, 12u, 16u));

TEST(Unorm, Mul8DivisionFreeEqualsExactRoundingAllPairs) {
  for (uint32_t x = 0; x < 256; ++x)
    for (uint32_t y = 0; y < 256; ++y) {
      const uint32_t exact = reference_round(x, y, 255);
      ASSERT_EQ(mul_round(x, y, 8), exact) << x << "*" << y;
      ASSERT_EQ(mul8_divfree(x, y), exact) << x << "*" << y;
      ASSERT_EQ(mul_divfree(x, y, 8), exact) << x << "*" << y;
    }
}

TEST(Unorm, MulDivisionFreeExact12BitExhaustive) {
  for (uint32_t x = 0; x < 4096; ++x)
    for (uint32_t y = 0; y < 4096; ++y) ASSERT_EQ(mul_divfree(x, y, 12), reference_round(x, y, 4095)) << x << "*" << y;
}

TEST(Unorm, MulDivisionFreeExact16BitRandomAndEdges) {
  std::mt19937_64 rng(16);
  std::uniform_int_distribution<uint32_t> d(0, 65535);
  for (int i = 0; i < 4'000'000; ++i) {
    const uint32_t x = d(rng), y = d(rng);
    ASSERT_EQ(mul_divfree(x, y, 16), reference_round(x, y, 65535)) << x << "*" << y;
  }
  for (uint32_t x : {0u, 1u, 2u, 32767u, 32768u, 65534u, 65535u})
    for (uint32_t y = 0; y < 65536; ++y) ASSERT_EQ(mul_divfree(x, y, 16), reference_round(x, y, 65535));
}

// Eq. 3.8 / 3.9: the measured worst multiplication error over every pair equals the analytic
// bound (it is attained), and stays below the simpler bounds 1/(2^b-1), 0.5/(2^b-1) (Eq. 3.10/3.11).
TEST(Unorm, MultiplicationErrorBoundsEq38To311) {
  for (unsigned b : {8u, 12u}) {
    const double m = max_code(b);
    double worst_round = 0.0, worst_trunc = 0.0;
    for (uint32_t x = 0; x <= max_code(b); ++x)
      for (uint32_t y = 0; y <= max_code(b); ++y) {
        const double exact = (x / m) * (y / m);
        worst_round = std::max(worst_round, std::abs(to_real(mul_round(x, y, b), b) - exact));
        worst_trunc = std::max(worst_trunc, std::abs(to_real(mul_trunc(x, y, b), b) - exact));
      }
    EXPECT_NEAR(worst_round, eps_m_round(b), 1e-15) << "b=" << b;
    EXPECT_NEAR(worst_trunc, eps_m_trunc(b), 1e-15) << "b=" << b;
    EXPECT_LT(eps_m_round(b), 0.5 / m);
    EXPECT_LT(eps_m_trunc(b), 1.0 / m);
  }
  // The dissertation's quoted figures (Eq. 3.10, 3.11) are the 0.5/(2^b-1) upper bounds.
  EXPECT_NEAR(0.5 / 255.0, 0.0019608, 5e-8);
  EXPECT_NEAR(0.5 / 4095.0, 0.0001221, 5e-8);
  EXPECT_NEAR(eps_m_round(8), 0.5 * 254.0 / (255.0 * 255.0), 1e-18);
}

TEST(Unorm, ConstexprUsable) {
  static_assert(mul8_divfree(255, 255) == 255);
  static_assert(mul8_divfree(128, 128) == 64);  // 16384/255 = 64.25 -> 64
  static_assert(mul_round(255, 1, 8) == 1);
  static_assert(encode_round(0.5, 8) == 128);
  SUCCEED();
}

}  // namespace
}  // namespace tfu::unorm
