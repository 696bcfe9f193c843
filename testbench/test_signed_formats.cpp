// Signed 9-bit and Strzodka's composite signed 16-bit (cmodel/signed_formats.hpp).
// Values are compared as exact integers / cross-multiplied rationals wherever the claim is exact.
// Runtime: about 1 s in a Release build (2 x 10^7 random add/sub checks, 10^7 random multiplies,
// ~1.4 x 10^7 structured add/sub checks, ~6 x 10^5 structured multiplies).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "cmodel/signed_formats.hpp"

namespace tfu::snorm {
namespace {

constexpr int kEdges[] = {0, 1, 127, 128, 129, 254, 255};

Vs16 code(int r, int a) { return Vs16{static_cast<uint8_t>(r), static_cast<uint8_t>(a)}; }

int64_t clamp16(int64_t v) { return std::clamp<int64_t>(v, kVs16Min, kVs16Max); }

// ---------------------------------------------------------------------------------- compile time
static_assert(to_numerator(kMinusOne) == -kVs16Denominator && to_numerator(kPlusOne) == kVs16Denominator);
static_assert(to_numerator(kZero) == 0 && Vs16{} == kZero);
static_assert(add(encode(0.5), encode(0.25)) == encode(0.75));
static_assert(mul(kPlusOne, kMinusOne) == kMinusOne && mul(kMinusOne, kMinusOne) == kPlusOne);
static_assert(to_numerator(mul(encode(0.5), encode(0.25))) == 4080);  // 0.125 exactly (docs example)
static_assert(s9_encode(-1.0) == -255 && s9_encode(1.0) == 255);

// ---------------------------------------------------------------------------------- signed 9-bit
TEST(Signed9, RoundTripEveryCode) {
  for (int32_t a = kS9Min; a <= kS9Max; ++a) {
    // a/255 decodes to the double nearest a/255; encode must recover a, except the over-range
    // code -256, which encode saturates to -1.
    ASSERT_EQ(s9_encode(s9_decode(a)), a == kS9Min ? -255 : a) << a;
  }
  EXPECT_EQ(s9_decode(-255), -1.0);
  EXPECT_EQ(s9_decode(0), 0.0);
  EXPECT_EQ(s9_decode(255), 1.0);
}

TEST(Signed9, EncodeRoundsHalfAwayAndSaturates) {
  EXPECT_EQ(s9_encode(0.0), 0);
  EXPECT_EQ(s9_encode(2.0), 255);
  EXPECT_EQ(s9_encode(-2.0), -255);  // saturates to -1, never to the over-range -256
  EXPECT_EQ(s9_encode(-1.002), -255);
  EXPECT_EQ(s9_encode(std::nan("")), 0);
  EXPECT_EQ(s9_encode(std::numeric_limits<double>::infinity()), 255);
  EXPECT_EQ(s9_encode(-std::numeric_limits<double>::infinity()), -255);
  EXPECT_EQ(s9_encode(0.1), 26);    // 25.5 -> 26 (0.1 * 255 = 25.500000000000004)
  EXPECT_EQ(s9_encode(-0.1), -26);
  EXPECT_EQ(s9_encode(0.5), 128);   // 127.5 exactly: tie, away from zero
  EXPECT_EQ(s9_encode(-0.5), -128);
  EXPECT_EQ(s9_saturate(-1000), -256);
  EXPECT_EQ(s9_saturate(-256), -256);
  EXPECT_EQ(s9_saturate(256), 255);
  EXPECT_EQ(s9_saturate(17), 17);
}

TEST(Signed9, RoundHalfAwayFromZeroHelper) {
  EXPECT_EQ(round_half_away_from_zero(2.5), 3);
  EXPECT_EQ(round_half_away_from_zero(-2.5), -3);
  EXPECT_EQ(round_half_away_from_zero(2.4999999999999996), 2);
  EXPECT_EQ(round_half_away_from_zero(0.49999999999999994), 0);  // naive floor(x + 0.5) gives 1
  EXPECT_EQ(round_half_away_from_zero(-0.49999999999999994), 0);
  EXPECT_EQ(round_half_away_from_zero(-7.0), -7);
  EXPECT_EQ(div_round(127, 255), 0);
  EXPECT_EQ(div_round(128, 255), 1);
  EXPECT_EQ(div_round(-127, 255), 0);
  EXPECT_EQ(div_round(-128, 255), -1);
  EXPECT_EQ(div_round(5, 2), 3);
  EXPECT_EQ(div_round(-5, 2), -3);
}

// ---------------------------------------------------------------------------------- Vs16 codes
TEST(Vs16Codes, ExactMinusOneZeroPlusOne) {
  EXPECT_EQ(to_numerator(kMinusOne), -32640);
  EXPECT_EQ(to_numerator(kZero), 0);
  EXPECT_EQ(to_numerator(kPlusOne), 32640);
  EXPECT_EQ(to_numerator(kMinCode), -32768);
  EXPECT_EQ(to_numerator(kMaxCode), 32767);
  EXPECT_EQ(decode(kMinusOne), -1.0);
  EXPECT_EQ(decode(kZero), 0.0);
  EXPECT_EQ(decode(kPlusOne), 1.0);
  EXPECT_EQ(encode(1.0), kPlusOne);
  EXPECT_EQ(encode(-1.0), kMinusOne);
  EXPECT_EQ(encode(0.0), kZero);
  EXPECT_EQ(encode(-0.0), kZero);
  EXPECT_EQ(encode(5.0), kPlusOne);  // saturates to +1, not to the over-range (255, 255)
  EXPECT_EQ(encode(-1.004), kMinusOne);
  EXPECT_EQ(encode(std::nan("")), kZero);
}

TEST(Vs16Codes, EveryCodeRoundTripsExhaustive) {
  int over_range = 0;
  for (int r = 0; r < 256; ++r)
    for (int a = 0; a < 256; ++a) {
      const Vs16 x = code(r, a);
      const int32_t v = to_numerator(x);
      ASSERT_EQ(v, 256 * (r - 128) + a);
      ASSERT_EQ(from_numerator(v), x);
      ASSERT_EQ(static_cast<int>(static_cast<uint16_t>(v + 32768)), r * 256 + a);  // offset-binary layout
      if (std::abs(v) <= kVs16Denominator) {
        ASSERT_EQ(encode(decode(x)), x) << r << "," << a;
      } else {
        ++over_range;
        ASSERT_EQ(encode(decode(x)), v > 0 ? kPlusOne : kMinusOne) << r << "," << a;
        ASSERT_TRUE((r == 255 && a > 128) || (r == 0 && a < 128)) << r << "," << a;  // Sec. 2
      }
    }
  EXPECT_EQ(over_range, 127 + 128);  // (255, 129..255) and (0, 0..127)
  EXPECT_EQ(from_numerator(40000), kMaxCode);
  EXPECT_EQ(from_numerator(-40000), kMinCode);
}

TEST(Vs16Codes, EncodeIsNearestWithinHalfLsb) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200'000; ++i) {
    const double x = u(rng);
    ASSERT_LE(std::abs(to_numerator(encode(x)) - x * kVs16Denominator), 0.5 + 1e-9) << x;
  }
  EXPECT_EQ(to_numerator(encode(0.5)), 16320);
  EXPECT_EQ(to_numerator(encode(-0.25)), -8160);
  EXPECT_EQ(to_numerator(encode(1.0 / 65536.0)), 0);   // 0.498 LSB -> 0
  EXPECT_EQ(to_numerator(encode(1.0 / 65000.0)), 1);   // 0.502 LSB -> 1
  EXPECT_EQ(to_numerator(encode(-1.0 / 65000.0)), -1);
}

TEST(Vs16Codes, LosslessExpansionsExactRationals) {
  for (int x = 0; x < 256; ++x) {
    // unorm8 with x -> 2x - 1: value (2x - 255)/255. Cross-multiplied: v * 255 == (2x - 255) * 32640.
    const Vs16 e = from_unorm8_expanded(static_cast<uint8_t>(x));
    ASSERT_EQ(int64_t{to_numerator(e)} * 255, int64_t{2 * x - 255} * kVs16Denominator) << x;
    ASSERT_EQ(e.r, x);  // the high channel alone is the unorm8 value (Sec. 2, second condition)
    ASSERT_EQ(e.a, 128);
    // unorm8 as x/255.
    ASSERT_EQ(int64_t{to_numerator(from_unorm8(static_cast<uint8_t>(x)))} * 255, int64_t{x} * kVs16Denominator) << x;
  }
  for (int32_t a = kS9Min; a <= kS9Max; ++a)  // all 512 signed 9-bit codes: value a/255
    ASSERT_EQ(int64_t{to_numerator(from_s9(a))} * 255, int64_t{a} * kVs16Denominator) << a;
  EXPECT_EQ(from_s9(-256), kMinCode);  // the s9 over-range code maps onto the Vs16 extreme code
  for (int a = -128; a <= 127; ++a)    // signed 8-bit: value a/128
    ASSERT_EQ(int64_t{to_numerator(from_s8(static_cast<int8_t>(a)))} * 128, int64_t{a} * kVs16Denominator) << a;
}

// ---------------------------------------------------------------------------------- add / sub
// Checks one (x, y) pair for both operations: exact when v1 + s v2 fits in 16 bits, the extreme
// code of the right sign otherwise. Counts the saturated results.
testing::AssertionResult add_sub_ok(Vs16 x, Vs16 y, int& saturated) {
  for (int s : {+1, -1}) {
    const int64_t want = int64_t{to_numerator(x)} + s * int64_t{to_numerator(y)};
    const Vs16 got = add_sub(x, y, s);
    const Vs16 expect = want > kVs16Max ? kMaxCode : want < kVs16Min ? kMinCode : from_numerator(want);
    saturated += want > kVs16Max || want < kVs16Min;
    if (want >= kVs16Min && want <= kVs16Max && to_numerator(got) != want)
      return testing::AssertionFailure() << "(" << int{x.r} << "," << int{x.a} << (s > 0 ? ") + (" : ") - (") << int{y.r}
                                         << "," << int{y.a} << ") = " << to_numerator(got) << ", want " << want;
    if (got != expect)
      return testing::AssertionFailure() << "(" << int{x.r} << "," << int{x.a} << (s > 0 ? ") + (" : ") - (") << int{y.r}
                                         << "," << int{y.a} << ") did not saturate to the extreme code";
  }
  return testing::AssertionSuccess();
}

// Operand pairs from the bits of one 64-bit random word.
Vs16 code_from_bits(uint64_t b, int shift) {
  return Vs16{static_cast<uint8_t>(b >> shift), static_cast<uint8_t>(b >> (shift + 8))};
}

// The low channels alone decide the carry: with r1 = r2 = 128 (H = 0) the result must be
// a1 + s a2 for every (a1, a2, s); the result's low channel and carry are a function of
// (a1, a2, s) only, so this covers the carry logic completely.
TEST(Vs16AddSub, CarryLemmaEveryLowChannelPair) {
  for (int a1 = 0; a1 < 256; ++a1)
    for (int a2 = 0; a2 < 256; ++a2)
      for (int s : {+1, -1}) {
        const Vs16 got = add_sub(code(128, a1), code(128, a2), s);
        ASSERT_EQ(to_numerator(got), a1 + s * a2) << a1 << " " << s << " " << a2;
        // One comparison, as documented: L < 128 <=> the result's low channel is L + 128.
        const int l = a1 + s * (a2 - 128);
        ASSERT_EQ(int{got.a}, l < 128 ? l + 128 : l - 128);
      }
}

TEST(Vs16AddSub, ExactOnBoundaryChannelsExhaustive) {
  int saturated = 0;
  // High channels at the boundary values, every low-channel pair ...
  for (int r1 : kEdges)
    for (int r2 : kEdges)
      for (int a1 = 0; a1 < 256; ++a1)
        for (int a2 = 0; a2 < 256; ++a2) ASSERT_TRUE(add_sub_ok(code(r1, a1), code(r2, a2), saturated));
  // ... and low channels at the boundary values, every high-channel pair.
  for (int a1 : kEdges)
    for (int a2 : kEdges)
      for (int r1 = 0; r1 < 256; ++r1)
        for (int r2 = 0; r2 < 256; ++r2) ASSERT_TRUE(add_sub_ok(code(r1, a1), code(r2, a2), saturated));
  EXPECT_GT(saturated, 0);  // the saturating branch was exercised
}

TEST(Vs16AddSub, ExactOnTenMillionRandomPairs) {
  std::mt19937_64 rng(2002);
  int saturated = 0;
  for (int i = 0; i < 10'000'000; ++i) {
    const uint64_t b = rng();
    ASSERT_TRUE(add_sub_ok(code_from_bits(b, 0), code_from_bits(b, 16), saturated));
  }
  EXPECT_GT(saturated, 0);
}

TEST(Vs16AddSub, SaturatesToExtremeCodes) {
  EXPECT_EQ(add(kPlusOne, kPlusOne), kMaxCode);
  EXPECT_EQ(sub(kMinusOne, kPlusOne), kMinCode);
  EXPECT_EQ(add(kMaxCode, from_numerator(1)), kMaxCode);
  EXPECT_EQ(to_numerator(add(kMaxCode, from_numerator(-1))), 32766);
  EXPECT_EQ(sub(kMinCode, from_numerator(1)), kMinCode);
  EXPECT_EQ(to_numerator(add(kMinusOne, kPlusOne)), 0);
  EXPECT_EQ(add(kMinusOne, kPlusOne), kZero);
}

// The worked examples of docs/number-formats-signed.md, channel by channel.
TEST(Vs16AddSub, WorkedExamples) {
  const Vs16 half = encode(0.5), quarter = encode(0.25);
  EXPECT_EQ(half, code(191, 192));     // 16320 = 256 * 63 + 192
  EXPECT_EQ(quarter, code(159, 224));  // 8160 = 256 * 31 + 224
  EXPECT_EQ(add(half, quarter), code(223, 160));      // L = 288 >= 128: a = 160, H = 94 + 1 = 95
  EXPECT_EQ(sub(half, quarter), code(159, 224));      // L = 96 < 128: a = 224, H = 32 - 1 = 31
  EXPECT_EQ(sub(quarter, half), code(96, 32));        // L = 160 >= 128: a = 32, H = -32 + 0
  EXPECT_EQ(add(kMinusOne, quarter), code(32, 96));   // L = 224: a = 96, H = -97 + 1 = -96
  EXPECT_EQ(add(encode(-0.5), encode(-0.5)), kMinusOne);  // (64, 64) twice: L = 0 < 128: a = 128, H = -128
  EXPECT_EQ(to_numerator(add(half, quarter)), 24480);
  EXPECT_EQ(to_numerator(sub(quarter, half)), -8160);
  EXPECT_EQ(to_numerator(add(kMinusOne, quarter)), -24480);
}

// ---------------------------------------------------------------------------------- multiply
TEST(Vs16Mul, TableGeneratedFromTheFormula) {
  const auto& t = multiplication_table();
  EXPECT_EQ(to_numerator(t[255 * 256 + 255]), 32640);  // (+1)(+1)
  EXPECT_EQ(to_numerator(t[0 * 256 + 255]), -32640);   // (-1)(+1)
  EXPECT_EQ(to_numerator(t[0 * 256 + 0]), 32640);      // (-1)(-1)
  EXPECT_EQ(to_numerator(t[128 * 256 + 128]), 1);      // (1/255)^2 * 32640 = 128/255 = 0.502 -> 1
  EXPECT_EQ(to_numerator(t[127 * 256 + 128]), -1);     // -0.502 -> -1
  EXPECT_EQ(to_numerator(t[191 * 256 + 159]), 4016);   // 128 * 127 * 63 / 255 = 4016.19
  for (int r1 = 0; r1 < 256; ++r1)
    for (int r2 = 0; r2 < 256; ++r2) {
      const int64_t entry = to_numerator(t[static_cast<std::size_t>(r1 * 256 + r2)]);
      ASSERT_EQ(entry, mul_table_entry(static_cast<uint8_t>(r1), static_cast<uint8_t>(r2)));
      // Nearest integer to 128 R1 R2 / 255, checked by the remainder: |255 e - 128 R1 R2| <= 127.
      ASSERT_LE(std::abs(255 * entry - int64_t{128} * (2 * r1 - 255) * (2 * r2 - 255)), 127) << r1 << "," << r2;
      ASSERT_LE(std::abs(entry), kVs16Denominator);  // every entry is an in-range code
      ASSERT_EQ(t[static_cast<std::size_t>(r1 * 256 + r2)], t[static_cast<std::size_t>(r2 * 256 + r1)]);
    }
}

// |32640 * numerator(mul(x, y)) - clamp(v1 v2)| in units of 1/32640 LSB (exact integer).
int64_t mul_error_scaled(Vs16 x, Vs16 y) {
  const int64_t p = int64_t{to_numerator(x)} * to_numerator(y);
  const int64_t pc = std::clamp<int64_t>(p, int64_t{kVs16Min} * kVs16Denominator, int64_t{kVs16Max} * kVs16Denominator);
  return std::abs(int64_t{kVs16Denominator} * to_numerator(mul(x, y)) - pc);
}

TEST(Vs16Mul, ErrorBoundStructuredExhaustive) {
  static_assert(kVs16MulErrorBoundScaled == 48896);
  EXPECT_DOUBLE_EQ(kVs16MulErrorBound, static_cast<double>(kVs16MulErrorBoundScaled) / kVs16Denominator);
  int64_t worst = 0;
  for (int a1 : {0, 128, 255})
    for (int a2 : {0, 128, 255})
      for (int r1 = 0; r1 < 256; ++r1)
        for (int r2 = 0; r2 < 256; ++r2) {
          const int64_t e = mul_error_scaled(code(r1, a1), code(r2, a2));
          ASSERT_LE(e, kVs16MulErrorBoundScaled) << r1 << "," << a1 << " * " << r2 << "," << a2;
          worst = std::max(worst, e);
        }
  // 380/255 LSB at (48, 0) * (81, 0): the maximum over all 2^32 pairs (tfu formats --exhaustive);
  // 2/255 below the analytic bound 382/255, which needs both roundings at 127/255 at once.
  EXPECT_EQ(worst, 380 * 128);
  EXPECT_EQ(mul_error_scaled(code(48, 0), code(81, 0)), 380 * 128);
}

TEST(Vs16Mul, ErrorBoundTenMillionRandomPairs) {
  std::mt19937_64 rng(33);
  int64_t worst = 0;
  for (int i = 0; i < 10'000'000; ++i) {
    const uint64_t b = rng();
    const Vs16 x = code_from_bits(b, 0), y = code_from_bits(b, 16);
    const int64_t e = mul_error_scaled(x, y);
    ASSERT_LE(e, kVs16MulErrorBoundScaled) << int{x.r} << "," << int{x.a} << " * " << int{y.r} << "," << int{y.a};
    worst = std::max(worst, e);
  }
  EXPECT_GT(worst, 48000);  // > 1.47 LSB: the dropped lo*lo term and both roundings matter
}

// The carry-scheme combination equals an independently written saturating sum of the two
// rounded terms (rounding by remainders, not by div_round).
TEST(Vs16Mul, MatchesIndependentReference) {
  auto nearest = [](int64_t n, int64_t d) {  // d odd and > 0: no ties
    int64_t q = n / d, rem = n % d;          // rem has the sign of n
    if (2 * rem > d) ++q;
    if (2 * rem < -d) --q;
    return q;
  };
  std::mt19937_64 rng(555);
  for (int i = 0; i < 2'000'000; ++i) {
    const uint64_t b = rng();
    const int r1 = 2 * int(b & 0xFF) - 255, a1 = int(b >> 8 & 0xFF) - 128;
    const int r2 = 2 * int(b >> 16 & 0xFF) - 255, a2 = int(b >> 24 & 0xFF) - 128;
    const int64_t want = clamp16(nearest(int64_t{128} * r1 * r2, 255) + nearest(int64_t{r1} * a2 + int64_t{r2} * a1, 255));
    const Vs16 x = code_from_bits(b, 0), y = code_from_bits(b, 16);
    ASSERT_EQ(to_numerator(mul(x, y)), want) << i;
  }
}

TEST(Vs16Mul, IdentityNegationCommutativityAndZero) {
  int zero_not_exact = 0;
  for (int r = 0; r < 256; ++r)
    for (int a = 0; a < 256; ++a) {
      const Vs16 x = code(r, a);
      ASSERT_EQ(mul(x, kPlusOne), x) << r << "," << a;  // 1 is neutral, exactly (A = 0, R = 255)
      ASSERT_EQ(mul(kPlusOne, x), x) << r << "," << a;
      ASSERT_EQ(to_numerator(mul(x, kMinusOne)), clamp16(-int64_t{to_numerator(x)})) << r << "," << a;
      const int32_t z = to_numerator(mul(x, kZero));  // 0 = (128, 0) has R = 1, A = -128: two roundings
      ASSERT_LE(std::abs(z), 1) << r << "," << a;
      zero_not_exact += z != 0;
    }
  EXPECT_EQ(zero_not_exact, 16385);  // documented: x * 0 is within 1 LSB of 0, not always 0
  std::mt19937_64 rng(99);
  for (int i = 0; i < 1'000'000; ++i) {
    const uint64_t b = rng();
    const Vs16 x = code_from_bits(b, 0), y = code_from_bits(b, 16);
    ASSERT_EQ(mul(x, y), mul(y, x));
  }
  // The worked example: 0.5 * 0.25 = 0.125 = 4080 / 32640; M = 4016, mixed = 64.
  EXPECT_EQ(mul_mixed_term(encode(0.5), encode(0.25)), 64);
  EXPECT_EQ(to_numerator(mul(encode(0.5), encode(0.25))), 4080);
  EXPECT_EQ(mul(kMaxCode, kMaxCode), kMaxCode);  // 32767^2 / 32640 > 32767: saturates
  EXPECT_EQ(mul(kMinCode, kMaxCode), kMinCode);
}

// mul() in constant evaluation computes M from the formula; at run time it reads the table.
TEST(Vs16Mul, ConstexprPathEqualsTablePath) {
  constexpr Vs16 kX{48, 0}, kY{81, 0}, kZ{200, 17};
  constexpr Vs16 kXY = mul(kX, kY), kXZ = mul(kX, kZ), kZZ = mul(kZ, kZ);
  Vs16 x = kX, y = kY, z = kZ;  // non-constant copies take the table path
  EXPECT_EQ(mul(x, y), kXY);
  EXPECT_EQ(mul(x, z), kXZ);
  EXPECT_EQ(mul(z, z), kZZ);
  EXPECT_EQ(to_numerator(kXY), 7548);  // exact 7549.490: the worst case, 380/255 LSB
}

}  // namespace
}  // namespace tfu::snorm
