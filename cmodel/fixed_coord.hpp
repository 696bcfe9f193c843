// Input conversion of the texture filter unit: FP32 request values -> fixed point, in integers.
//
// Requests arrive as IEEE-754 binary32 values (as a shader hands them to a texture unit). The first
// stage multiplies by an integer scale (the texture extent) and converts to two's-complement fixed
// point with F fraction bits, exactly:  floor(x * scale * 2^F), computed from the float's sign,
// exponent and 24-bit significand with integer shifts and one 24 x 15-bit multiply; no floating-point
// operation is involved, so every platform gives the same bits.
//   NaN          -> 0       (documented defined result, docs/textures.md)
//   +Inf / -Inf  -> saturate to +/-kFixedLimit
//   |result| > kFixedLimit saturates (kFixedLimit = 2^46: 2^23 texels at F = 16 with margin)
#pragma once

#include <bit>
#include <cstdint>

namespace tfu {

inline constexpr int64_t kFixedLimit = int64_t{1} << 46;

// floor(x * scale * 2^frac_bits), saturated; scale in 1..2^15, frac_bits in 0..24.
constexpr int64_t float_to_fixed(float x, uint32_t scale, int frac_bits) {
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  const bool neg = (bits >> 31) != 0;
  const int exp = static_cast<int>((bits >> 23) & 0xFF);
  const uint32_t frac = bits & 0x7FFFFF;
  if (exp == 0xFF) {
    if (frac != 0) return 0;  // NaN
    return neg ? -kFixedLimit : kFixedLimit;
  }
  // value = sig * 2^(e), sig a 24-bit integer (denormals: no hidden bit, e = -149).
  const uint64_t sig = exp == 0 ? frac : (frac | 0x800000u);
  const int e = (exp == 0 ? -149 : exp - 150) + frac_bits;
  const uint64_t prod = sig * scale;  // < 2^39
  if (prod == 0) return 0;
  int64_t mag;  // floor of |x| scale 2^F for positive; for negative we need ceil of magnitude
  bool inexact = false;
  if (e >= 0) {
    if (e > 46 || (prod << e) >> e != prod || (prod << e) > static_cast<uint64_t>(kFixedLimit))
      return neg ? -kFixedLimit : kFixedLimit;
    mag = static_cast<int64_t>(prod << e);
  } else if (e <= -64) {
    mag = 0;
    inexact = true;
  } else {
    const int sh = -e;
    mag = static_cast<int64_t>(prod >> sh);
    inexact = (prod & ((uint64_t{1} << sh) - 1)) != 0;
  }
  if (mag > kFixedLimit) mag = kFixedLimit;
  if (!neg) return mag;
  return -(mag + (inexact ? 1 : 0));  // floor of a negative value
}

// Nearest fixed-point value, ties toward +infinity: floor(x * scale * 2^F + 1/2).
constexpr int64_t float_to_fixed_round(float x, uint32_t scale, int frac_bits) {
  const int64_t v = float_to_fixed(x, scale, frac_bits + 1);
  return (v + 1) >> 1;
}

}  // namespace tfu
