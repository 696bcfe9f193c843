// Edge-preserving interpolation of Lee & Jen 2003 (Sec. 2.2, 2.3, 3), bit-accurate.
//
// Inputs : the 12 cross-kernel texels C1..C12 (numbering of lee_jen_geometry.hpp), a mask of the
//          texels the cache can supply (cross, T or L shape), the 8-bit fractions fu, fv of the
//          sample point inside the centre square C4 C5 C8 C9, and the texel format.
// Output : the interpolated texel (datapath channels, clamped to the format's range).
//
// Datapath (widths for RGBA8; docs/edge-preserving.md has the full table):
//   Y        = 5 R + 9 G + 2 B            shift-and-add (R<<2 + R, G<<3 + G, B<<1): 12 bits,
//                                         Y/16 ~ 0.3125 R + 0.5625 G + 0.125 B (BT.601 0.299/0.587/0.114)
//                                         VS16X2: Y = ch0 + ch1 (17-bit signed)
//   low      = Eq. 4 medians ordered by (Y, texel number): ties go to the lower texel number; the
//              whole texel (RGBA) is carried. Adjusted medians for missing texels (Sec. 3): a missing
//              outer neighbour of a centre texel is replaced by the diagonally opposite centre texel
//              (C4 <-> C9, C5 <-> C8), which is exactly the paper's T-shape rule; when both outer
//              neighbours are missing (the corner texel of an L) the median is that of the texel and
//              its two centre-square neighbours.
//   dP_i     = |dR| + |dG| + |dB| between the low-pass endpoints (10 bits; VS16X2: (|d0|+|d1|) >> 6)
//   w_i      = direction ROM code (4.4, 255 = never choose), address (fv >> 4) << 4 | (fu >> 4)
//   choice   = argmin over usable directions of w_i * dP_i (18 bits); ties -> lowest direction index
//              (the order of lee_jen::directions(): axis, centre diagonals, outer diagonals, 2x1)
//   C_low    = ((256 - t) Cp_low + t Cq_low + 128) >> 8, t = fu or fv of the direction (Eq. 3)
//   H_n      = C_n - Cn_low (9-bit signed) for n = 4, 5, 8, 9
//   C_high   = (sum H_n w_n + 2^15) >> 16, w_n the bilinear weights (256 - fu | fu)(256 - fv | fv) (Eq. 5)
//   I        = clamp(C_low + C_high) (Eq. 6)
// Alpha is carried like a colour channel through medians, Eq. 3 and Eq. 5, but takes no part in Y
// or dP.
#pragma once

#include <array>
#include <cstdint>

#include "cmodel/direction_rom.hpp"
#include "cmodel/texture.hpp"

namespace tfu::lee_jen {

struct EdgeDecision {
  int direction = -1;     // chosen direction index (0..21)
  uint32_t cost = 0;      // w * dP of the chosen direction
  TexelMask read = 0;     // texels the filter actually read (must be a subset of the mask)
};

// Luma of the median ordering (see header).
constexpr int32_t edge_luma(const Texel4& c, TexelFormat f) {
  if (f == TexelFormat::VS16X2) return c[0] + c[1];
  return 5 * c[0] + 9 * c[1] + 2 * c[2];
}

// ---- The datapath stages, in pipeline order (each a block of the cycle model and of the SV) ----
// Stage 1, RGB->Y: key[n] = edge_luma(Cn) * 16 + n for available texels (0 otherwise; key[0] unused).
// The key is unique, so one comparator orders by (Y, texel number).
using LumaKeys = std::array<int32_t, kTexels + 1>;
LumaKeys luma_keys(const std::array<Texel4, kTexels>& c, TexelMask available, TexelFormat fmt);
// Stage 2, Eq. 4 medians with the Sec. 3 adjustments (behavioural reference of the compare-cell
// network in rtl/median_network): low[n] = number of the texel whose value is Cn's median; only
// entries of available texels are defined.
using LowIndex = std::array<int, kTexels + 1>;
LowIndex median_low_pass(const LumaKeys& key, TexelMask available);
// dP between two low-pass endpoints (Eq. 1): |dR| + |dG| + |dB| (VS16X2: (|d0| + |d1|) >> 6).
inline uint32_t direction_difference(const Texel4& p, const Texel4& q, TexelFormat fmt) {
  const auto d = [](int32_t a, int32_t b) { return a > b ? a - b : b - a; };
  if (fmt == TexelFormat::VS16X2) return static_cast<uint32_t>(d(p[0], q[0]) + d(p[1], q[1])) >> 6;
  return static_cast<uint32_t>(d(p[0], q[0]) + d(p[1], q[1]) + d(p[2], q[2]));
}
// Stage 3, Eq. 1-2: argmin over usable directions of w_i * dP_i (ties -> lowest index); `read` is 0.
EdgeDecision select_direction(const std::array<Texel4, kTexels>& c, const LowIndex& low, TexelMask available,
                              uint32_t fu, uint32_t fv, TexelFormat fmt);
// Stage 4, Eq. 3, 5, 6: directional lerp of the low-pass endpoints + bilinear high frequency, clamp.
Texel4 edge_merge(const std::array<Texel4, kTexels>& c, const LowIndex& low, int direction, uint32_t fu, uint32_t fv,
                  TexelFormat fmt);

// The four stages chained. c[n - 1] is texel Cn. Only texels in `available` are read.
Texel4 edge_preserving_interpolate(const std::array<Texel4, kTexels>& c, TexelMask available, uint32_t fu, uint32_t fv,
                                   TexelFormat fmt, EdgeDecision* decision = nullptr);

// Double-precision ideal of the same algorithm (quality reference only): channels as reals
// (0..1, or -1..1 for VS16X2), exact fractions, exact Eq. 2 weights, no rounding.
std::array<double, 4> edge_preserving_ideal(const std::array<std::array<double, 4>, kTexels>& c, TexelMask available,
                                            double fu, double fv, TexelFormat fmt);

// Texels that are unavailable at a centre square (x4, y4)-(x5, y8) (wrapped memory coordinates)
// when only the BxB cache blocks holding the centre square may be read (Sec. 3, Fig. 4).
TexelMask cache_block_mask(int x4, int x5, int y4, int y8, int block);
// The same from the wrapped columns and rows -1..2 of the cross's fetch grid (grid_col, grid_row).
template <typename Grid>
TexelMask cache_block_mask_of_grid(const Grid& col, const Grid& row, int block) {
  return cache_block_mask(col[kCentreCols[0]], col[kCentreCols[1]], row[kCentreRows[0]], row[kCentreRows[1]], block);
}

}  // namespace tfu::lee_jen
