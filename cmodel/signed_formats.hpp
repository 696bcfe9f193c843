// Signed formats (Strzodka 2002, Sec. 2 and 3).
//
//   signed 9-bit  : integer a in [-256, 255], value a / 255 (Table 1). 9 bits two's complement.
//                   Exact -1, 0, +1; -256/255 is the one over-range code.
//   Vs16          : Strzodka's composite signed 16-bit number in two unsigned 8-bit channels
//                   (r, a), value psi(r, a) = (256 (r - 128) + a) / (255 * 128).
//                   Numerator v = 256 (r - 128) + a in [-32768, 32767] (a 16-bit two's complement
//                   number whose high byte is r - 128 and low byte a), denominator 32640.
//                   Exact -1 = (0, 128), 0 = (128, 0), +1 = (255, 128). Codes beyond +-32640 exist
//                   (over-range); encode() saturates to [-1, 1], arithmetic saturates to the
//                   extreme codes (0, 0) and (255, 255).
//                   The high channel alone is the unorm8 expansion 2R - 1 (with a = 128), so the
//                   format is a superset of unorm8 (x -> 2x - 1) and of signed 9-bit (a -> v = 128 a).
//
// Operations, written on the 8-bit channels as the combiner hardware of Sec. 3 does them:
//   add_sub (Sec. 3.2): component-wise sums with the low channel biased by -128, ONE comparison of
//       the low sum against 128 decides the carry direction for both addition and subtraction.
//   mul (Sec. 3.3): hi*hi from a 256x256 multiplication table (16-bit precise), the two mixed
//       products rounded, lo*lo dropped; error <= kMulErrorBound numerator LSBs.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace tfu::snorm {

// ---------------------------------------------------------------- signed 9-bit
inline constexpr int32_t kS9Min = -256, kS9Max = 255;

constexpr double s9_to_real(int32_t a) { return static_cast<double>(a) / 255.0; }
// Round half away from zero, saturate to [-256, 255]; NaN -> 0.
constexpr int32_t s9_encode(double x) {
  if (!(x == x)) return 0;
  const double s = x * 255.0;
  if (s >= kS9Max) return kS9Max;
  if (s <= kS9Min) return kS9Min;
  return static_cast<int32_t>(s < 0 ? s - 0.5 : s + 0.5);
}

// ---------------------------------------------------------------- Vs16
inline constexpr int32_t kVs16Denominator = 255 * 128;  // 32640
inline constexpr int32_t kVs16Min = -32768, kVs16Max = 32767;

struct Vs16 {
  uint8_t r = 128;  // high channel
  uint8_t a = 0;    // low channel
  friend constexpr bool operator==(const Vs16&, const Vs16&) = default;
};

constexpr int32_t numerator(Vs16 x) { return 256 * (static_cast<int32_t>(x.r) - 128) + x.a; }
// Inverse of numerator() for v in [-32768, 32767].
constexpr Vs16 from_numerator(int32_t v) {
  const int32_t hi = (v >= 0 ? v / 256 : -((-v + 255) / 256));  // floor(v / 256)
  return Vs16{static_cast<uint8_t>(hi + 128), static_cast<uint8_t>(v - 256 * hi)};
}
constexpr double to_real(Vs16 x) { return static_cast<double>(numerator(x)) / kVs16Denominator; }

// Round half away from zero to the nearest numerator; saturate to [-1, 1]; NaN -> 0.
constexpr Vs16 encode(double x) {
  if (!(x == x)) return from_numerator(0);
  if (x >= 1.0) return from_numerator(kVs16Denominator);
  if (x <= -1.0) return from_numerator(-kVs16Denominator);
  const double s = x * kVs16Denominator;
  return from_numerator(static_cast<int32_t>(s < 0 ? s - 0.5 : s + 0.5));
}

inline constexpr Vs16 kMinusOne{0, 128};
inline constexpr Vs16 kZero{128, 0};
inline constexpr Vs16 kPlusOne{255, 128};

// Lossless expansions: unorm8 x -> 2x/255 - 1 is (r = x, a = 128); signed 9-bit a -> v = 128 a.
constexpr Vs16 from_unorm8_expanded(uint8_t x) { return Vs16{x, 128}; }
constexpr Vs16 from_s9(int32_t a) { return from_numerator(128 * a); }

// Saturate a (high, low) pair whose high part may be outside [-128, 127].
constexpr Vs16 saturate_pair(int32_t h, int32_t low) {
  if (h > 127) return Vs16{255, 255};
  if (h < -128) return Vs16{0, 0};
  return Vs16{static_cast<uint8_t>(h + 128), static_cast<uint8_t>(low)};
}

// Sec. 3.2: x + s*y for s = +1 (add) or -1 (sub).
//   H = (r1 - 128) + s (r2 - 128)            9-bit signed
//   L = a1 + s (a2 - 128)                    10-bit signed, in [-127, 383]
//   one comparison: L < 128 ? (a = L + 128, H += (s - 1)/2) : (a = L - 128, H += (s + 1)/2)
// Exact (numerator(x) + s numerator(y)) unless the result leaves [-32768, 32767], where it saturates.
constexpr Vs16 add_sub(Vs16 x, Vs16 y, int s) {
  int32_t H = (static_cast<int32_t>(x.r) - 128) + s * (static_cast<int32_t>(y.r) - 128);
  const int32_t L = static_cast<int32_t>(x.a) + s * (static_cast<int32_t>(y.a) - 128);
  int32_t low;
  if (L < 128) {
    low = L + 128;
    H += (s - 1) / 2;
  } else {
    low = L - 128;
    H += (s + 1) / 2;
  }
  return saturate_pair(H, low);
}
constexpr Vs16 add(Vs16 x, Vs16 y) { return add_sub(x, y, +1); }
constexpr Vs16 sub(Vs16 x, Vs16 y) { return add_sub(x, y, -1); }

// Round-half-away-from-zero division of a signed integer by a positive constant.
constexpr int32_t div_round(int64_t n, int64_t d) {
  return static_cast<int32_t>(n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d));
}

// Entry (r1, r2) of the multiplication table M of Sec. 3.3: the hi*hi product
// (2 r1 - 255)(2 r2 - 255) / 255^2 in numerator units (x 32640), rounded: 17-bit signed.
constexpr int32_t mul_table_entry(uint8_t r1, uint8_t r2) {
  return div_round(int64_t{128} * (2 * r1 - 255) * (2 * r2 - 255), 255);
}
// The whole table, generated (never typed): 65,536 entries.
const std::array<int32_t, 65536>& mul_table();

// Sec. 3.3 multiply: v = M(r1, r2) + round(((2 r1 - 255)(a2 - 128) + (2 r2 - 255)(a1 - 128)) / 255),
// the lo*lo term (a1 - 128)(a2 - 128)/(128^2 255^2) dropped, result saturated.
inline Vs16 mul(Vs16 x, Vs16 y) {
  const int32_t hh = mul_table()[static_cast<size_t>(x.r) * 256 + y.r];
  const int32_t mixed = div_round(int64_t{2 * x.r - 255} * (y.a - 128) + int64_t{2 * y.r - 255} * (x.a - 128), 255);
  const int32_t v = hh + mixed;
  if (v > kVs16Max) return Vs16{255, 255};
  if (v < kVs16Min) return Vs16{0, 0};
  return from_numerator(v);
}

// Error bound of mul() against the exact product of the decoded operands, in numerator LSBs
// (1/32640): 0.5 (table rounding) + 0.5 (mixed-term rounding) + max |lo*lo| term
// = 128 * 128 / (128 * 255) = 128/255 (from (a-128) in [-128, 127]), total 1 + 128/255 = 1.502.
inline constexpr double kMulErrorBound = 1.0 + 128.0 / 255.0;

}  // namespace tfu::snorm
