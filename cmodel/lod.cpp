#include "cmodel/lod.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "cmodel/fast_paths.hpp"
#include "cmodel/fixed_coord.hpp"
#include "cmodel/lod_fast.hpp"

namespace tfu {

const std::array<uint16_t, 1u << kLog2RomIndexBits>& log2_rom() {
  // Offline table generation (double precision), the one source of the ROM contents.
  static const auto rom = [] {
    std::array<uint16_t, 1u << kLog2RomIndexBits> r{};
    constexpr double n = 1u << kLog2RomIndexBits;
    for (size_t k = 0; k < r.size(); ++k)
      r[k] = static_cast<uint16_t>(std::floor(256.0 * std::log2(1.0 + (static_cast<double>(k) + 0.5) / n) + 0.5));
    return r;
  }();
  return rom;
}

int32_t log2_q8(uint64_t x) {
  if (x == 0) return kLodMinusInfinity;
  const int e = 63 - std::countl_zero(x);  // leading-one detector
  uint32_t index;
  if (e >= kLog2RomIndexBits) {
    index = static_cast<uint32_t>((x >> (e - kLog2RomIndexBits)) & ((1u << kLog2RomIndexBits) - 1));
  } else {
    index = static_cast<uint32_t>((x << (kLog2RomIndexBits - e)) & ((1u << kLog2RomIndexBits) - 1));
  }
  // Small inputs (e < 9) are exact in the index, so the ROM's +1/2 centring costs at most its own
  // half-interval error there as well; the bound holds for every x (see the tests).
  return (e << kLodFracBits) + log2_rom()[index];
}

int32_t lambda_from_length_sq(uint64_t rho2_q32, int32_t log2_div_sq_q8) {
  if (rho2_q32 == 0) return kLodMinusInfinity;
  const int32_t l2 = log2_q8(rho2_q32) - (32 << kLodFracBits) - log2_div_sq_q8;  // log2(rho^2 / D^2), Q.8
  return (l2 + 1) >> 1;                                                           // halve, round half up
}

int32_t lambda_from_derivatives(int64_t dudx, int64_t dvdx, int64_t dudy, int64_t dvdy) {
  const uint64_t lx = derivative_length_sq(dudx, dvdx);
  const uint64_t ly = derivative_length_sq(dudy, dvdy);
  return lambda_from_length_sq(std::max(lx, ly));  // rho^2, Q.32
}

TexelDerivatives derivatives_from_quad(const float s[4], const float t[4], int width, int height) {
  // The speed-only form (lod_fast.hpp, equal for every input: LodFast.*) unless the fast paths are off.
  return fast_paths_enabled() ? lod_fast::derivatives_from_quad(s, t, width, height)
                              : derivatives_from_quad_plain(s, t, width, height);
}

TexelDerivatives derivatives_from_quad_plain(const float s[4], const float t[4], int width, int height) {
  // Each of the three pixels' coordinates converted once (the out-of-line general case keeps the
  // compiler from merging repeated conversions).
  const auto w = static_cast<uint32_t>(width), h = static_cast<uint32_t>(height);
  const int64_t u0 = float_to_fixed_fast(s[0], w, 16), v0 = float_to_fixed_fast(t[0], h, 16);
  return {float_to_fixed_fast(s[1], w, 16) - u0, float_to_fixed_fast(t[1], h, 16) - v0,
          float_to_fixed_fast(s[2], w, 16) - u0, float_to_fixed_fast(t[2], h, 16) - v0};
}

TexelDerivatives derivatives_from_gradients(float dsdx, float dtdx, float dsdy, float dtdy, int width, int height) {
  const auto w = static_cast<uint32_t>(width), h = static_cast<uint32_t>(height);
  return {float_to_fixed_fast(dsdx, w, 16), float_to_fixed_fast(dtdx, h, 16), float_to_fixed_fast(dsdy, w, 16),
          float_to_fixed_fast(dtdy, h, 16)};
}

int32_t lambda_from_quad(const float s[4], const float t[4], int width, int height) {
  return lambda_from_derivatives(derivatives_from_quad(s, t, width, height));
}

int32_t lambda_from_gradients(float dsdx, float dtdx, float dsdy, float dtdy, int width, int height) {
  return lambda_from_derivatives(derivatives_from_gradients(dsdx, dtdx, dsdy, dtdy, width, height));
}

int32_t lambda_explicit(float lod) {
  const int64_t v = float_to_fixed_round(lod, 1, kLodFracBits);
  return static_cast<int32_t>(std::clamp<int64_t>(v, kLodMinusInfinity, -int64_t{kLodMinusInfinity}));
}

}  // namespace tfu
