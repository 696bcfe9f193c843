// Unsigned normalized fixed-point numbers with the GL mapping 1.0 <-> 2^b - 1
// (Hadwiger 2004, Sec. 3.5 "Fixed-point representation").
//
//   encode_trunc  : Eq. 3.3   x_bar = floor(x * (2^b - 1))
//   encode_round  : Eq. 3.4   x_bar = floor(x * (2^b - 1) + 0.5)
//   mul_round     : Eq. 3.7   x (x) y = floor(x_bar * y_bar / (2^b - 1) + 0.5)
//   mul_trunc     :           floor(x_bar * y_bar / (2^b - 1))
//   mul8_divfree  : the division-free b = 8 form  i = x*y + 128; r = (i + (i >> 8)) >> 8
//
// Error bounds in the [0, 1] domain:
//   eps_q_trunc = 1 / (2^b - 1)           eps_q_round = 0.5 / (2^b - 1)        (Sec. 3.5)
//   eps_m_trunc = (2^b - 2) / (2^b - 1)^2 (Eq. 3.8)
//   eps_m_round = 0.5 (2^b - 2) / (2^b - 1)^2 (Eq. 3.9); 0.0019608 for b = 8 (Eq. 3.10)...
//
// Widths: a b-bit operand is held in uint32_t; products of two b <= 16 operands fit in 32 bits,
// and every intermediate below is computed in uint64_t so that b = 16 cannot overflow.
#pragma once

#include <cmath>
#include <cstdint>

namespace tfu::unorm {

// Largest code of a b-bit unorm, which represents 1.0.
constexpr uint32_t max_code(unsigned bits) { return (uint32_t{1} << bits) - 1u; }

constexpr double to_real(uint32_t code, unsigned bits) {
  return static_cast<double>(code) / static_cast<double>(max_code(bits));
}

// Eq. 3.3 (truncation). Inputs outside [0, 1] saturate; NaN maps to 0.
constexpr uint32_t encode_trunc(double x, unsigned bits) {
  if (!(x > 0.0)) return 0;
  if (x >= 1.0) return max_code(bits);
  return static_cast<uint32_t>(x * static_cast<double>(max_code(bits)));
}

// Eq. 3.4 (round half up). Inputs outside [0, 1] saturate; NaN maps to 0.
constexpr uint32_t encode_round(double x, unsigned bits) {
  if (!(x > 0.0)) return 0;
  if (x >= 1.0) return max_code(bits);
  return static_cast<uint32_t>(x * static_cast<double>(max_code(bits)) + 0.5);
}

// Normalized multiply with exact rounding, Eq. 3.7: floor(x*y / (2^b-1) + 0.5), computed as
// floor((2*x*y + m) / (2*m)) in integers (m = 2^b - 1).
constexpr uint32_t mul_round(uint32_t x, uint32_t y, unsigned bits) {
  const uint64_t m = max_code(bits);
  return static_cast<uint32_t>((2u * uint64_t{x} * y + m) / (2u * m));
}

// Normalized multiply with truncation: floor(x*y / (2^b-1)).
constexpr uint32_t mul_trunc(uint32_t x, uint32_t y, unsigned bits) {
  return static_cast<uint32_t>(uint64_t{x} * y / max_code(bits));
}

// Division-free 8-bit normalized multiply (Blinn; quoted in Hadwiger 2004 Sec. 3.5).
// Inputs are 8-bit; the intermediate i is 17 bits; the result is 8 bits and equals mul_round.
constexpr uint32_t mul8_divfree(uint32_t x, uint32_t y) {
  const uint32_t i = x * y + 128u;
  return (i + (i >> 8)) >> 8;
}

// Generalisation of the same shift-and-add identity to any b (exact for b <= 16; verified by the
// tests exhaustively for b = 8 and b = 12, randomly for b = 16). This is what the hardware
// tile-weight multiplier uses: no divider, one extra adder.
constexpr uint32_t mul_divfree(uint32_t x, uint32_t y, unsigned bits) {
  const uint64_t i = uint64_t{x} * y + (uint64_t{1} << (bits - 1));
  return static_cast<uint32_t>((i + (i >> bits)) >> bits);
}

// Quantization error bounds (Sec. 3.5) and multiplication error bounds (Eq. 3.8, 3.9).
constexpr double eps_q_trunc(unsigned bits) { return 1.0 / static_cast<double>(max_code(bits)); }
constexpr double eps_q_round(unsigned bits) { return 0.5 / static_cast<double>(max_code(bits)); }
constexpr double eps_m_trunc(unsigned bits) {
  const double m = static_cast<double>(max_code(bits));
  return (m - 1.0) / (m * m);
}
constexpr double eps_m_round(unsigned bits) { return 0.5 * eps_m_trunc(bits); }

}  // namespace tfu::unorm
