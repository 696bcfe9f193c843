// B-spline prefilter (offline, driver-side; Hadwiger 2004 Sec. 3.2): the cubic B-spline interpolates
// when it is applied to prefiltered coefficients instead of the texels (kernel "bspline-interp").
// The coefficients are computed in double precision (Unser's recursive filter, pole sqrt(3) - 2,
// periodic for repeat, mirror-extended otherwise) and stored as 8-bit codes with a per-texture
// scale S and bias B (Q.12 registers of the texture descriptor, decoded by dp::cubic_normalize):
//   S = ceil((c_max - c_min) 2^12),  B = floor(255 c_min 2^12)   (c in units of full scale)
//   code q = clamp(round((255 c 2^12 - B) / S), 0, 255)
// The driver uploads the codes as an RGBA8 texture of their own (TextureContent::BsplineCoefficients);
// the golden sampler computes the same codes from the texels with this same function.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cmodel/texture.hpp"

namespace tfu {

struct BsplineCoefficients {
  std::vector<Image> codes;                              // per level, RGBA8 codes
  std::vector<std::vector<std::array<double, 4>>> exact;  // per level, the exact coefficients (ideal path)
  int64_t scale_q = 0, bias_q = 0;                        // S and B (Q.12)
};

// Coefficients of every level of an 8-bit texture (throws InputError for vs16x2).
BsplineCoefficients prefilter_bspline(const Texture& tex, WrapMode wrap_s, WrapMode wrap_t);
// The codes as a texture of their own (RGBA8, the source's layout), as the driver uploads it.
Texture bspline_coefficient_texture(const Texture& source, const BsplineCoefficients& c);

}  // namespace tfu
