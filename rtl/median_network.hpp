// median_network: the twelve medians of Lee & Jen Eq. 4 as a network of explicit compare cells and
// three-point selectors (Lee & Jen Sec. 6, Fig. 10), cells on the same two inputs merged: 40 cells
// (rtl/sv/ generates its SystemVerilog from this same netlist).
//
// Ports:
//   in  key[n]  n = 1..12   luma key Y * 16 + n (RGBA8/L8: Y = 5R + 9G + 2B is 12 bits, key 16 bits;
//                           VS16X2: Y = ch0 + ch1 is 17 bits signed, key 21 bits signed)
//   in  shape   [11:0]      available texels (bit n-1 = Cn): the cross, a T or an L (Sec. 3)
//   out low[n]  [3:0]       number of the texel whose value is the median for Cn (defined for
//                           available Cn)
//
// Structure (docs/edge-preserving.md, "Median network"; geometry from cmodel/lee_jen_geometry.hpp):
//   input select : per missing texel, the key of the texel that Sec. 3 substitutes (the diagonally
//                  opposite centre texel) or, when both outer neighbours of a centre texel are
//                  missing (the corner of an L), +inf and -inf, which turns that five-point median
//                  into the three-point median of the texel and its centre neighbours. One mux per
//                  input: every other median that reads a missing texel is itself missing.
//   compare cell : lo = min(a, b), hi = max(a, b) and the flag a_gt_b = a > b ("the larger result
//                  from the right-hand side, the smaller result from the left-hand side, and a
//                  one-bit flag indicating comparison result"). Inputs are ordered: in_a < in_b.
//   3-pt median  : three cells in parallel on the pairs (a, b), (a, c), (b, c) and a selector on
//                  their flags: b if a_gt_b == b_gt_c, else a if a_gt_b != a_gt_c, else c.
//   5-pt median  : two cells on input pairs (p, q), (r, s); max of their minima and min of their
//                  maxima (two cells: the largest and the smallest of the four are dropped, neither
//                  can be the median of five); then the three-point median of those two and the
//                  fifth input e. 7 cells.
//   sharing      : a cell on two wires already compared is that cell. The eight three-point medians
//                  compare 24 input pairs, 20 distinct (the two texels of each arm are compared for
//                  both of their medians: C1 C2, C3 C7, C6 C10, C11 C12). A five-point median pairs
//                  each outer neighbour of its texel with the centre neighbour diagonal to it and
//                  keeps the texel itself as e (C4: C1-C5, C3-C8, e = C4), and each such pair is
//                  one a three-point median already compares (C1-C5 in C2's, C3-C8 in C7's). 8 x 3 +
//                  4 x 7 = 52 cells less 4 + 8 shared = 40 (Lee & Jen: 40), 3 cells deep plus the
//                  selector. Fewer is impossible with these medians: the 20 distinct pairs of the
//                  three-point medians are all needed, and each five-point median has 5 cells on
//                  wires of its own.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cmodel/edge_filter.hpp"

namespace tfu::rtl {

// A compare cell: lo = min(in_a, in_b), hi = max(in_a, in_b), flag a_gt_b = in_a > in_b. Wires
// 0..11 are the network inputs (texel n on wire n - 1); every cell drives two new wires; in_a < in_b.
struct CompareCell {
  int in_a, in_b;
  int lo, hi;
};
// The selector of a three-point median of wires a < b < c, driven by the flags of the cells `ab`,
// `ac`, `bc` (indices into MedianNetlist::cells, on (a, b), (a, c), (b, c)): out = the median of the
// three. It drives one new wire.
struct Median3Select {
  int a, b, c;
  int ab, ac, bc;
  int out;
};

struct MedianNetlist {
  int inputs = lee_jen::kTexels;
  int wires = 0;
  std::vector<CompareCell> cells;               // in topological order
  std::vector<Median3Select> selects;           // after every cell (no cell reads a selector)
  std::array<int, lee_jen::kTexels + 1> out{};  // out[n] = wire carrying Cn's median key (a selector)
  int depth = 0;                                // cells on the longest input-to-output path (then one selector)
};
const MedianNetlist& median_netlist();

inline constexpr int32_t kKeyPlusInfinity = INT32_MAX;
inline constexpr int32_t kKeyMinusInfinity = INT32_MIN;

// Input select: the key driven onto each input wire for a shape (see header).
std::array<int32_t, lee_jen::kTexels> median_input_select(const lee_jen::LumaKeys& key, lee_jen::TexelMask shape);
// The whole block: input select, the cells in order, the selectors; low[n] = key & 15 of Cn's output wire.
lee_jen::LowIndex median_network_eval(const lee_jen::LumaKeys& key, lee_jen::TexelMask shape);

}  // namespace tfu::rtl
