// MIP-map generation (offline, but integer and bit-exact like the rest of the model).
//
//   box      Lee & Jen Eq. 8: M_{n+1}(x, y) = (M(2x,2y) + M(2x+1,2y) + M(2x,2y+1) + M(2x+1,2y+1) + 2) >> 2
//            (round half up). A dimension that is already 1 averages 2 texels: (a + b + 1) >> 1.
//            Odd sizes follow the GL floor rule: the last row/column of an odd level is not read.
//   gaussian separable binomial [1 3 3 1] / 8 per axis centred on the 2x2 block (sigma ~ 0.87 texel of
//            the finer level): (sum w c + 32) >> 6, neighbours outside the level clamped to the edge.
//   edge     Lee & Jen Eq. 7: M_{n+1} = ((256 - a) G + a I + 128) >> 8 with G the box of Eq. 8, I the
//            edge-preserving interpolation (edge_filter.hpp, 12-texel cross, clamp-to-edge fetches) at
//            the centre of the even square (fu = fv = 1/2, i.e. 128), a = round(alpha 256).
// VS16X2 textures filter their signed numerators with the same formulas (arithmetic shifts).
#pragma once

#include <string>

#include "cmodel/texture.hpp"

namespace tfu {

enum class MipMethod { Box, Gaussian, Edge };
inline constexpr EnumNames<MipMethod, 3> kMipMethodNames{
    "MIP method", {{{MipMethod::Box, "box"}, {MipMethod::Gaussian, "gaussian"}, {MipMethod::Edge, "edge"}}}};
MipMethod mip_method_from_name(const std::string& name);  // kMipMethodNames
const char* mip_method_name(MipMethod m);

// Next level from `src` (src must be larger than 1x1).
Image downsample(const Image& src, TexelFormat fmt, MipMethod method, int alpha_q8);
// Replaces every level above 0 with a complete chain generated from level 0.
void generate_mipmaps(Texture& tex, MipMethod method, double alpha = 0.5);

}  // namespace tfu
