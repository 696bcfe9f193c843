// Signed fixed-point formats of Strzodka 2002 ("Virtual 16 bit precise operations on RGBA8
// textures"), Sec. 2 (Table 1, the psi mapping), Sec. 3.2 (add/sub) and Sec. 3.3 (multiply).
// Header-only; every function except multiplication_table() is constexpr.
//
// Formats (numerator / denominator; all divisions below are exact rationals):
//
//   signed 9-bit (s9)   9-bit two's complement integer a in [-256, 255]; value a / 255
//                       (Table 1, "signed 9 bit"). Exact -1 (-255), 0 (0), +1 (255); -256/255 is
//                       the one over-range code.
//   Vs16                Strzodka's composite signed 16-bit number in two unsigned 8-bit channels
//                       (r, a), r, a in [0, 255] (Sec. 2):
//                         psi(r, a) = (256 (r - 128) + a) / (255 * 128)
//                       Numerator v = 256 (r - 128) + a in [-32768, 32767], denominator 32640.
//                       Bit layout: the 16-bit word r:a (r high byte) is v + 32768, i.e. v in
//                       offset binary (two's complement of v with the top bit inverted).
//                       Equivalently v = 128 R + A with R = 2r - 255 (odd, [-255, 255]) and
//                       A = a - 128 ([-128, 127]): r alone is the unorm8 expansion 2x - 1.
//                       Exact -1 = (0, 128), 0 = (128, 0), +1 = (255, 128). Codes with
//                       |v| > 32640 are over-range (r = 255, a > 128 and r = 0, a < 128).
//
// Saturation policy (a choice; Strzodka only says "additional clamping operations would solve"
// the over-range problem):
//   * encode (real -> code) saturates to [-1, 1]: it never produces an over-range code
//     (s9_encode never returns -256; encode never returns |v| > 32640).
//   * arithmetic (add_sub, mul, s9_saturate, from_numerator) saturates to the extreme codes of the
//     word: Vs16 (0, 0) = -32768 and (255, 255) = +32767; s9 -256 and +255.
//   * decode accepts every code, over-range ones included.
// Rounding: round half away from zero everywhere. In mul() ties cannot occur (the divisor 255 is
// odd), so the rule only matters for encode.
//
// Lossless expansions (Sec. 2): unorm8 x with x -> 2x - 1 is (r = x, a = 128), v = 128 (2x - 255);
// unorm8 x as x/255 is v = 128 x; s9 a is v = 128 a; signed 8-bit a/128 is v = 255 a.
//
// add_sub (Sec. 3.2), on the 8-bit channels; s = +1 (add) or -1 (sub):
//   H = (r1 - 128) + s (r2 - 128)      9-bit signed, [-256, 255] after the correction below
//   L = a1 + s (a2 - 128)              10-bit signed, [-128, 383]
//   ONE comparison: L < 128 ? (a = L + 128, H += (s - 1)/2) : (a = L - 128, H += (s + 1)/2)
//   r = H + 128, saturated to [0, 255]; on saturation a saturates with it (extreme code).
//   Exact: numerator(result) = v1 + s v2 whenever that lies in [-32768, 32767].
//
// mul (Sec. 3.3): with v = 128 R + A,
//   v1 v2 / 32640 = 128 R1 R2 / 255                 hi*hi: table M(r1, r2), rounded
//                 + (R1 A2 + R2 A1) / 255           mixed: computed, rounded
//                 + A1 A2 / 32640                   lo*lo: dropped
//   the two rounded terms are added with the carry scheme of add_sub (saturating).
//   Error bound, numerator LSBs (1 LSB = 1/32640), against the exact product of the decoded
//   operands (clamped to the word's range): each rounding of an integer / 255 is off by at most
//   127/255 (255 odd: the nearest integer is never 128/255 or more away); |A1 A2| <= 128 * 128, so
//   the dropped term is at most 16384/32640 = 128/255. Total 127/255 + 127/255 + 128/255 =
//   382/255 = 1.498039 LSB (kVs16MulErrorBound). In the exact integer form used by the tests:
//   |32640 * numerator(mul(x, y)) - clamp(v1 v2)| <= 382 * 128 = 48896 (kVs16MulErrorBoundScaled).
//
// Widths (hardware): s9 9 bits; Vs16 channels 8 bits; add_sub H 9-bit signed (+1 guard bit before
// the saturation check), L 10-bit signed; mul R 9-bit signed, A 8-bit signed, R A 16-bit signed,
// R1 A2 + R2 A1 17-bit signed, the rounded mixed term 10-bit signed ([-256, 256]); M entries are
// Vs16 codes (|entry| <= 32640). The model computes in int32_t / int64_t.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace tfu::snorm {

// Round half away from zero to an integer, exact for |s| < 2^53 (s - trunc(s) is exact in binary
// floating point). std::round is not constexpr in C++20.
constexpr int64_t round_half_away_from_zero(double s) {
  const auto t = static_cast<int64_t>(s);  // truncation toward zero
  const double f = s - static_cast<double>(t);
  if (f >= 0.5) return t + 1;
  if (f <= -0.5) return t - 1;
  return t;
}

// Nearest integer to n / d (d > 0), ties away from zero.
constexpr int64_t div_round(int64_t n, int64_t d) { return n >= 0 ? (2 * n + d) / (2 * d) : -((-2 * n + d) / (2 * d)); }

// ============================================================================ signed 9-bit
inline constexpr int32_t kS9Min = -256;  // over-range: -256/255
inline constexpr int32_t kS9Max = 255;   // +1
inline constexpr int32_t kS9One = 255;   // the denominator: value = a / 255

constexpr double s9_decode(int32_t a) { return static_cast<double>(a) / kS9One; }

// Clamp an arithmetic result to the 9-bit register range [-256, 255].
constexpr int32_t s9_saturate(int64_t a) {
  return static_cast<int32_t>(a < kS9Min ? kS9Min : (a > kS9Max ? kS9Max : a));
}

// Nearest code, ties away from zero; saturates to [-1, 1] (never -256); NaN -> 0.
constexpr int32_t s9_encode(double x) {
  if (x != x) return 0;
  if (x >= 1.0) return kS9One;
  if (x <= -1.0) return -kS9One;
  return static_cast<int32_t>(round_half_away_from_zero(x * kS9One));
}

// ============================================================================ Vs16
inline constexpr int32_t kVs16Denominator = 255 * 128;  // 32640: value = v / 32640
inline constexpr int32_t kVs16Min = -32768;             // code (0, 0)
inline constexpr int32_t kVs16Max = 32767;              // code (255, 255)

struct Vs16 {
  uint8_t r = 128;  // high channel: r - 128 is the signed high byte of v
  uint8_t a = 0;    // low channel: the low byte of v
  friend constexpr bool operator==(const Vs16&, const Vs16&) = default;
};

inline constexpr Vs16 kMinusOne{0, 128};   // v = -32640
inline constexpr Vs16 kZero{128, 0};       // v = 0
inline constexpr Vs16 kPlusOne{255, 128};  // v = +32640
inline constexpr Vs16 kMinCode{0, 0};      // v = -32768 (negative saturation)
inline constexpr Vs16 kMaxCode{255, 255};  // v = +32767 (positive saturation)

constexpr int32_t to_numerator(Vs16 x) { return 256 * (static_cast<int32_t>(x.r) - 128) + x.a; }

// Inverse of to_numerator on [-32768, 32767]; v outside saturates to the extreme code.
// r = floor(v / 256) + 128 (C++20 >> on a negative value is an arithmetic shift), a = v mod 256.
constexpr Vs16 from_numerator(int64_t v) {
  if (v < kVs16Min) return kMinCode;
  if (v > kVs16Max) return kMaxCode;
  return Vs16{static_cast<uint8_t>((v >> 8) + 128), static_cast<uint8_t>(v & 0xFF)};
}

constexpr double decode(Vs16 x) { return static_cast<double>(to_numerator(x)) / kVs16Denominator; }

// Nearest code, ties away from zero; saturates to [-1, 1] (never an over-range code); NaN -> 0.
constexpr Vs16 encode(double x) {
  if (x != x) return kZero;
  if (x >= 1.0) return kPlusOne;
  if (x <= -1.0) return kMinusOne;
  return from_numerator(round_half_away_from_zero(x * kVs16Denominator));
}

// Lossless expansions (Sec. 2, Table 1): the decoded value is exactly the source value.
constexpr Vs16 from_unorm8_expanded(uint8_t x) { return Vs16{x, 128}; }  // (2x - 255)/255 = 128(2x - 255)/32640
constexpr Vs16 from_unorm8(uint8_t x) { return from_numerator(128 * int32_t{x}); }  // x/255
constexpr Vs16 from_s9(int32_t a) { return from_numerator(128 * int64_t{a}); }      // a/255; -256 -> (0, 0)
constexpr Vs16 from_s8(int8_t a) { return from_numerator(255 * int32_t{a}); }       // a/128

// ---------------------------------------------------------------------------- add / sub (Sec. 3.2)
// x + s y for s = +1 (add) or -1 (sub), written on the 8-bit channels. The low channel of y is
// biased by -128 (the paper's input mapping x -> x - 1/2), so a single comparison of L against
// 128 selects the carry for both operations and both directions.
constexpr Vs16 add_sub(Vs16 x, Vs16 y, int s) {
  int32_t h = (static_cast<int32_t>(x.r) - 128) + s * (static_cast<int32_t>(y.r) - 128);  // [-256, 254] / [-255, 255]
  const int32_t l = static_cast<int32_t>(x.a) + s * (static_cast<int32_t>(y.a) - 128);   // [-128, 383]
  int32_t low;
  if (l < 128) {
    low = l + 128;
    h += (s - 1) / 2;
  } else {
    low = l - 128;
    h += (s + 1) / 2;
  }
  if (h > 127) return kMaxCode;
  if (h < -128) return kMinCode;
  return Vs16{static_cast<uint8_t>(h + 128), static_cast<uint8_t>(low)};
}
constexpr Vs16 add(Vs16 x, Vs16 y) { return add_sub(x, y, +1); }
constexpr Vs16 sub(Vs16 x, Vs16 y) { return add_sub(x, y, -1); }

// ---------------------------------------------------------------------------- multiply (Sec. 3.3)
// Entry M(r1, r2) of the multiplication table in numerator units:
// round(128 (2 r1 - 255)(2 r2 - 255) / 255), |entry| <= 32640 (the hi*hi product of two values).
constexpr int32_t mul_table_entry(uint8_t r1, uint8_t r2) {
  const int64_t p = int64_t{128} * (2 * int32_t{r1} - 255) * (2 * int32_t{r2} - 255);  // 24-bit signed
  return static_cast<int32_t>(div_round(p, 255));
}

// The 256 x 256 table M as Vs16 codes (128 KiB), index r1 * 256 + r2, generated once from
// mul_table_entry at first use (never typed; run-time generation keeps compile time low).
inline const std::array<Vs16, 65536>& multiplication_table() {
  static const std::array<Vs16, 65536> table = [] {
    std::array<Vs16, 65536> t{};
    for (std::size_t i = 0; i < t.size(); ++i)
      t[i] = from_numerator(mul_table_entry(static_cast<uint8_t>(i >> 8), static_cast<uint8_t>(i & 0xFF)));
    return t;
  }();
  return table;
}

// Rounded mixed term round((R1 A2 + R2 A1) / 255) in numerator units, [-256, 256].
constexpr int32_t mul_mixed_term(Vs16 x, Vs16 y) {
  const int32_t r1 = 2 * int32_t{x.r} - 255, r2 = 2 * int32_t{y.r} - 255;  // 9-bit signed, odd
  const int32_t a1 = int32_t{x.a} - 128, a2 = int32_t{y.a} - 128;          // 8-bit signed
  return static_cast<int32_t>(div_round(r1 * a2 + r2 * a1, 255));          // 17-bit signed / 255
}

// x * y = M(r1, r2) + mixed, added with the carry scheme (saturating); lo*lo dropped.
// In constant evaluation the table entry is computed from the formula that generates the table.
constexpr Vs16 mul(Vs16 x, Vs16 y) {
  const Vs16 hh = std::is_constant_evaluated() ? from_numerator(mul_table_entry(x.r, y.r))
                                               : multiplication_table()[std::size_t{x.r} * 256 + y.r];
  return add(hh, from_numerator(mul_mixed_term(x, y)));  // mixed as a code: r in {127, 128, 129}
}

// Multiply error bound (derivation above): |numerator(mul(x, y)) - clamp(v1 v2 / 32640)| <= 382/255.
inline constexpr int64_t kVs16MulErrorBoundScaled = 382 * 128;  // 48896, units of 1/32640 LSB
inline constexpr double kVs16MulErrorBound = 382.0 / 255.0;       // 1.498039... LSB

}  // namespace tfu::snorm
