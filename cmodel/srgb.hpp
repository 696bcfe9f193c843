// sRGB decode and encode of the texel formats' 8-bit colour channels (EXT_texture_sRGB; IEC
// 61966-2-1; Vulkan "Colour Space Conversions"; docs/srgb.md). One definition of both tables: the
// golden sampler and the cycle model decode texel words through decode_texel (texture.hpp) and
// encode results through encode_texel, and the SystemVerilog generator writes these arrays as ROMs.
//
// Transfer functions (c, x in [0, 1]):
//   EOTF (decode)  x = c / 12.92                         if c <= 0.04045
//                  x = ((c + 0.055) / 1.055)^2.4         otherwise
//   OETF (encode)  c = 12.92 x                           if x <= 0.0031308
//                  c = 1.055 x^(1 / 2.4) - 0.055         otherwise
//
// Datapath (EXT_texture_sRGB: the conversion happens per texel, before filtering; alpha is linear):
//   decode ROM   256 x 12 bits: sRGB code c -> linear unorm12 round(4095 EOTF(c / 255)) (half up).
//                12 bits is the narrowest unorm width whose decode is one-to-one: the EOTF's
//                smallest slope (1 / 12.92 at 0) times 2^b - 1 is >= 255 from b = 12 (1.24 codes
//                per sRGB code), while at b = 8 the codes 0..6 all decode to 0 and 183 of the 256
//                codes remain distinct (test_srgb). The filter's lerp, blend, cubic and probe
//                units take the 12-bit channels unchanged (their widths hold 16 bits).
//   encode ROM   4096 x 8 bits: linear unorm12 x -> round(255 OETF(x / 4095)) (half up): the
//                result port carries the filtered linear value re-encoded to 8-bit sRGB, which a
//                consumer decodes with the same decode ROM. encode(decode(c)) = c for all 256 codes,
//                so NEAREST and any filter of a constant region return the stored byte.
//   alpha        never converted: 8 bits through the same units as RGBA8 (bit-identical alpha).
// Both ROMs are computed at compile time from the transfer functions (the x^2.4 and x^(1/2.4)
// powers by Newton iteration on integer roots); test_srgb checks every entry against std::pow and
// measures the decode ROM's error against the exact EOTF.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace tfu::srgb {

inline constexpr int kLinearBits = 12;                                  // the filter's linear width
inline constexpr int32_t kLinearMax = (int32_t{1} << kLinearBits) - 1;  // 4095 <-> 1.0
inline constexpr int32_t kCodeMax = 255;                                // 8-bit sRGB code of 1.0

namespace detail {
// The n-th root of a in (0, 1] by Newton's method from 1 (monotone from above; stops when the
// iterate no longer falls). Offline table generation only.
constexpr double nth_root(double a, int n) {
  if (a <= 0.0) return 0.0;
  double r = 1.0;
  for (int k = 0; k < 200; ++k) {
    double p = 1.0;
    for (int i = 0; i < n - 1; ++i) p *= r;
    const double next = ((n - 1) * r + a / p) / n;
    if (!(next < r)) break;
    r = next;
  }
  return r;
}
constexpr double eotf(double c) {  // ((c + 0.055) / 1.055)^(12 / 5) = y^2 (y^2)^(1/5)
  if (c <= 0.04045) return c / 12.92;
  const double y = (c + 0.055) / 1.055;
  return y * y * nth_root(y * y, 5);
}
constexpr double oetf(double x) {  // 1.055 x^(5 / 12) - 0.055
  if (x <= 0.0031308) return 12.92 * x;
  return 1.055 * nth_root(x * x * x * x * x, 12) - 0.055;
}
constexpr int32_t round_half_up(double v) { return static_cast<int32_t>(v + 0.5); }
}  // namespace detail

// Decode ROM: 8-bit sRGB code -> linear unorm12.
inline constexpr std::array<uint16_t, 256> kDecodeRom = [] {
  std::array<uint16_t, 256> t{};
  for (int c = 0; c < 256; ++c)
    t[static_cast<size_t>(c)] = static_cast<uint16_t>(detail::round_half_up(kLinearMax * detail::eotf(c / 255.0)));
  return t;
}();

// Encode ROM: linear unorm12 -> 8-bit sRGB code.
inline constexpr std::array<uint8_t, 4096> kEncodeRom = [] {
  std::array<uint8_t, 4096> t{};
  for (int x = 0; x < 4096; ++x)
    t[static_cast<size_t>(x)] = static_cast<uint8_t>(detail::round_half_up(kCodeMax * detail::oetf(x / 4095.0)));
  return t;
}();

constexpr int32_t decode(uint8_t code) { return kDecodeRom[code]; }
// x is clamped to 0..4095 first (a filter result is always inside; the clamp is the port's).
constexpr uint8_t encode(int32_t linear) {
  return kEncodeRom[static_cast<size_t>(linear < 0 ? 0 : (linear > kLinearMax ? kLinearMax : linear))];
}

}  // namespace tfu::srgb
