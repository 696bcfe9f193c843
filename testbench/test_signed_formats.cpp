// Signed 9-bit and Strzodka's composite signed 16-bit (cmodel/signed_formats.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cmodel/signed_formats.hpp"

namespace tfu::snorm {
namespace {

TEST(Signed9, ExactValuesAndRoundTrip) {
  EXPECT_EQ(s9_encode(-1.0), -255);
  EXPECT_EQ(s9_encode(0.0), 0);
  EXPECT_EQ(s9_encode(1.0), 255);
  EXPECT_EQ(s9_encode(-2.0), -256);  // saturates to the over-range code
  EXPECT_EQ(s9_encode(std::nan("")), 0);
  for (int32_t a = kS9Min; a <= kS9Max; ++a) ASSERT_EQ(s9_encode(s9_to_real(a)), a);
}

TEST(Vs16, ExactMinusOneZeroPlusOne) {
  EXPECT_EQ(numerator(kMinusOne), -32640);
  EXPECT_EQ(numerator(kZero), 0);
  EXPECT_EQ(numerator(kPlusOne), 32640);
  EXPECT_EQ(to_real(kMinusOne), -1.0);
  EXPECT_EQ(to_real(kZero), 0.0);
  EXPECT_EQ(to_real(kPlusOne), 1.0);
  EXPECT_EQ(encode(1.0), kPlusOne);
  EXPECT_EQ(encode(-1.0), kMinusOne);
  EXPECT_EQ(encode(0.0), kZero);
  EXPECT_EQ(encode(5.0), kPlusOne);  // saturates
}

TEST(Vs16, EveryCodeRoundTripsExhaustive) {
  for (int r = 0; r < 256; ++r)
    for (int a = 0; a < 256; ++a) {
      const Vs16 x{static_cast<uint8_t>(r), static_cast<uint8_t>(a)};
      const int32_t v = numerator(x);
      ASSERT_EQ(v, 256 * (r - 128) + a);
      ASSERT_EQ(from_numerator(v), x);
      if (std::abs(v) <= kVs16Denominator) {
        ASSERT_EQ(encode(to_real(x)), x) << r << "," << a;
      }
    }
}

TEST(Vs16, LosslessExpansionFromUnorm8AndSigned9) {
  for (int x = 0; x < 256; ++x) {
    // unorm8 expanded: (2x - 255)/255 = 128 (2x - 255) / 32640, compared as integers.
    const Vs16 e = from_unorm8_expanded(static_cast<uint8_t>(x));
    ASSERT_EQ(numerator(e), 128 * (2 * x - 255));
    ASSERT_EQ(e.r, x);  // the high channel alone is the unorm8 value
  }
  for (int32_t a = kS9Min; a <= kS9Max; ++a) ASSERT_EQ(numerator(from_s9(a)), 128 * a);  // a/255 = 128a/32640
}

TEST(Vs16, AddSubExactWithOneCarryCheck) {
  auto check = [](Vs16 x, Vs16 y) {
    for (int s : {+1, -1}) {
      const int64_t want = int64_t{numerator(x)} + s * numerator(y);
      const Vs16 got = add_sub(x, y, s);
      if (want > kVs16Max) {
        ASSERT_EQ(got, (Vs16{255, 255}));
      } else if (want < kVs16Min) {
        ASSERT_EQ(got, (Vs16{0, 0}));
      } else {
        ASSERT_EQ(numerator(got), want) << int(x.r) << "," << int(x.a) << " s=" << s << " " << int(y.r) << "," << int(y.a);
      }
    }
  };
  // Every pair whose channels take boundary values, exhaustively over the other channel pair.
  const int edges[] = {0, 1, 127, 128, 129, 254, 255};
  for (int r1 : edges)
    for (int r2 : edges)
      for (int a1 = 0; a1 < 256; ++a1)
        for (int a2 = 0; a2 < 256; ++a2)
          check(Vs16{static_cast<uint8_t>(r1), static_cast<uint8_t>(a1)}, Vs16{static_cast<uint8_t>(r2), static_cast<uint8_t>(a2)});
  std::mt19937_64 rng(2002);
  for (int i = 0; i < 10'000'000; ++i) {
    const uint64_t b = rng();
    check(Vs16{static_cast<uint8_t>(b), static_cast<uint8_t>(b >> 8)}, Vs16{static_cast<uint8_t>(b >> 16), static_cast<uint8_t>(b >> 24)});
  }
  // Worked example (docs): 0.5 + 0.25.
  EXPECT_EQ(numerator(add(encode(0.5), encode(0.25))), 16320 + 8160);
}

TEST(Vs16, MultiplyErrorBound) {
  double worst = 0.0;
  auto check = [&](Vs16 x, Vs16 y) {
    const double exact = static_cast<double>(numerator(x)) * numerator(y) / kVs16Denominator;  // numerator units
    if (std::abs(exact) > kVs16Max) return;  // saturates; not part of the bound
    const double err = std::abs(numerator(mul(x, y)) - exact);
    worst = std::max(worst, err);
    ASSERT_LE(err, kMulErrorBound + 1e-9) << int(x.r) << "," << int(x.a) << " * " << int(y.r) << "," << int(y.a);
  };
  for (int a1 : {0, 128, 255})
    for (int a2 : {0, 128, 255})
      for (int r1 = 0; r1 < 256; ++r1)
        for (int r2 = 0; r2 < 256; ++r2)
          check(Vs16{static_cast<uint8_t>(r1), static_cast<uint8_t>(a1)}, Vs16{static_cast<uint8_t>(r2), static_cast<uint8_t>(a2)});
  std::mt19937_64 rng(33);
  for (int i = 0; i < 10'000'000; ++i) {
    const uint64_t b = rng();
    check(Vs16{static_cast<uint8_t>(b), static_cast<uint8_t>(b >> 8)}, Vs16{static_cast<uint8_t>(b >> 16), static_cast<uint8_t>(b >> 24)});
  }
  EXPECT_GT(worst, 1.0);  // the bound is nearly reached: the dropped lo*lo term matters
  // Exact cases: 1 * x = x for x from the unorm8 expansion (a = 128 makes the low parts vanish).
  for (int x = 0; x < 256; ++x) {
    const Vs16 e = from_unorm8_expanded(static_cast<uint8_t>(x));
    EXPECT_EQ(mul(kPlusOne, e), e);
    EXPECT_EQ(numerator(mul(kMinusOne, e)), -numerator(e));
  }
}

TEST(Vs16, MulTableIsGeneratedFromTheFormula) {
  const auto& t = mul_table();
  EXPECT_EQ(t[255 * 256 + 255], 32640);   // (+1)(+1)
  EXPECT_EQ(t[0 * 256 + 255], -32640);    // (-1)(+1)
  EXPECT_EQ(t[128 * 256 + 128], 1);       // (1/255)^2 x 32640 = 128/255 = 0.502 -> 1
  EXPECT_EQ(t[127 * 256 + 128], -1);      // (-1/255)(1/255) x 32640 = -0.502 -> -1 (half away from zero)
  for (int r1 = 0; r1 < 256; ++r1)
    for (int r2 = 0; r2 < 256; ++r2) {
      const double exact = 128.0 * (2 * r1 - 255) * (2 * r2 - 255) / 255.0;
      ASSERT_LE(std::abs(t[static_cast<size_t>(r1 * 256 + r2)] - exact), 0.5);
    }
}

}  // namespace
}  // namespace tfu::snorm
