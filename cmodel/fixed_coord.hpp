// Input conversion of the texture filter unit: FP32 request values -> fixed point, in integers.
//
// Requests arrive as IEEE-754 binary32 values (as a shader hands them to a texture unit). The first
// stage multiplies by an integer scale (the texture extent) and converts to two's-complement fixed
// point with F fraction bits, exactly:  floor(x * scale * 2^F), computed from the float's sign,
// exponent and 24-bit significand with integer shifts and one 24 x 15-bit multiply; no floating-point
// operation is involved, so every platform gives the same bits.
//   NaN          -> 0       (documented defined result, docs/sampler.md, "Input conversion")
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
  const int64_t v = neg ? -static_cast<int64_t>(prod) : static_cast<int64_t>(prod);
  if (e >= 0) {
    if (e > 46 || (prod << e) >> e != prod || (prod << e) > static_cast<uint64_t>(kFixedLimit))
      return neg ? -kFixedLimit : kFixedLimit;
    return v * (int64_t{1} << e);
  }
  if (e <= -63) return neg ? -1 : 0;  // |value| < 1: floor is -1 or 0
  return v >> -e;  // arithmetic shift = floor for both signs (C++20)
}

// float_to_fixed with its common case in a few integer operations, for the per-pixel datapath (the
// address generator, the LOD unit's derivatives): a normal float whose value needs a right shift
// of 1..62 bits (e = exp - 150 + frac_bits in -62..-1; every usual texture coordinate) is
// (+-sig scale) >> -e, exactly what float_to_fixed computes for it (prod != 0); every other value
// (NaN, infinities, denormals, zero, large values) takes float_to_fixed.
[[gnu::noinline]] inline int64_t float_to_fixed_general(float x, uint32_t scale, int frac_bits) {
  return float_to_fixed(x, scale, frac_bits);  // out of line: the rare case stays out of the fast path
}
[[gnu::always_inline]] inline int64_t float_to_fixed_fast(float x, uint32_t scale, int frac_bits) {
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  const int exp = static_cast<int>((bits >> 23) & 0xFF);
  const int shift = 150 - frac_bits - exp;  // -e
  if (exp == 0 || static_cast<unsigned>(shift - 1) >= 62u) return float_to_fixed_general(x, scale, frac_bits);
  const auto prod = static_cast<int64_t>(static_cast<uint64_t>((bits & 0x7FFFFF) | 0x800000) * scale);
  return ((bits >> 31) ? -prod : prod) >> shift;
}

// Nearest fixed-point value, ties toward +infinity: floor(x * scale * 2^F + 1/2).
constexpr int64_t float_to_fixed_round(float x, uint32_t scale, int frac_bits) {
  const int64_t v = float_to_fixed(x, scale, frac_bits + 1);
  return (v + 1) >> 1;
}

}  // namespace tfu
