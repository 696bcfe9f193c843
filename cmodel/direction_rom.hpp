// Lee & Jen 2003 direction-weight ROMs and kernel shapes (Eq. 1-3, Sec. 3, Sec. 6).
//
// One ROM per measured direction i:
//   in  fu4 [3:0]  4-bit x fraction of the sample point in the centre square
//   in  fv4 [3:0]  4-bit y fraction
//   out w   [7:0]  weight w_i = 1 / (1 - d_i / ROI_i) (Eq. 2), unsigned 4.4 fixed point:
//                  code = min(254, round(16 w)); code 255 = "never choose" (d_i >= ROI_i,
//                  i.e. 1 - d/ROI <= 1e-9)
// address = (fv4 << 4) | fu4; the 256 sub-regions are sampled at their centres
// ((fu4 + 1/2)/16, (fv4 + 1/2)/16). Contents are generated here, in double precision, and nowhere
// else (the cycle model and the SystemVerilog read these tables; Lee & Jen Sec. 6: "four-bit
// precision for each coordinate", 256 sub-regions, eight-bit w, < 550 gates per table).
// Exact form (see docs/directions.md, checked by the tests): with X = 2 fu4 + 1, Y = 2 fv4 + 1 and
// u = Cq - Cp, C = |(X - 32 px) uy - (Y - 32 py) ux| is an integer and d/ROI = C/16 exactly, so a
// ROM holds at most 17 codes: round(256 / (16 - C)) (saturated at 254) for C < 16, 255 for C >= 16.
// ROI (Lee & Jen Sec. 2.2): 0.5 axis, sqrt(2)/4 diagonals, 1/(2 sqrt 5) 2x1, i.e. 1/(2 |u|).
// Blend parameter t of Eq. 3: the axis on which Cp, Cq have coordinates exactly {0, 1} (Cp at 0);
// x takes precedence for the two centre diagonals.
//
// Texel numbering and the kernel geometry: cmodel/lee_jen_geometry.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "cmodel/lee_jen_geometry.hpp"

namespace tfu::lee_jen {

inline constexpr int kDirections = 22;
inline constexpr uint8_t kNeverChoose = 255;
inline constexpr uint8_t kMaxWeightCode = 254;
inline constexpr int kWeightFracBits = 4;  // 4.4 fixed point
// 1 - d/ROI at or below this counts as d >= ROI (Lee & Jen: "a very small threshold").
inline constexpr double kNeverChooseThreshold = 1e-9;

enum class BlendAxis { X, Y };  // t of Eq. 3 is fu or fv

struct Direction {
  int index;        // 0..21, the order used by every block
  int p, q;         // endpoint texel numbers: C_low = (1 - t) Cp + t Cq (Eq. 3)
  double roi;       // region of influence
  BlendAxis axis;   // Cp has coordinate 0 and Cq coordinate 1 on this axis
  std::string name() const;  // e.g. "C4-C5"
  const char* family() const;  // horizontal, vertical, centre-diagonal, outer-diagonal, 2x1
};
const std::array<Direction, kDirections>& directions();

// Euclidean distance from (x, y) to the infinite line through the endpoints of direction i.
double distance_to_direction(int dir, double x, double y);
// Exact weight w = 1/(1 - d/ROI) at (x, y); +infinity when d >= ROI.
double exact_weight(int dir, double x, double y);
// The ROM of direction i: 256 codes, address (fv4 << 4) | fu4.
const std::array<uint8_t, 256>& direction_weight_rom(int dir);
// The 22 ROMs' never flags at one address, as a 22-bit mask: bit i = direction i's code at
// `address` (0..255) is not kNeverChoose (read once from the ROMs into a table).
uint32_t choosable_directions(size_t address);
// Real weight of a code (infinity for kNeverChoose).
double decode_weight(uint8_t code);

// ---- Kernel shapes (Sec. 3): which of the 12 texels are available, bit n-1 = texel Cn ----

enum class ShapeKind { Cross, T, L };
struct KernelShape {
  ShapeKind kind;
  int rotation;  // quarter turns clockwise about the centre of the centre square, 0..3
  TexelMask mask;
  std::string name() const;  // "cross", "T0".."T3", "L0".."L3"
};
// Rotate a mask by one quarter turn clockwise about (0.5, 0.5).
TexelMask rotate_mask(TexelMask m);
// The 9 shapes: cross, T (C1, C2 missing) and L (C1, C2, C3, C7 missing) in four rotations.
const std::vector<KernelShape>& kernel_shapes();
// Directions whose both endpoints are available, as a 22-bit mask (bit i = direction i).
uint32_t usable_directions(TexelMask available);

}  // namespace tfu::lee_jen
