// median_network: the twelve medians of Lee & Jen Eq. 4 as a network of explicit compare cells
// (Lee & Jen Fig. 10), cells that share both inputs merged (TFU-C; TFU-D generates its
// SystemVerilog from this same netlist).
//
// Ports:
//   in  key[n]  n = 1..12   luma key Y * 16 + n (RGBA8/L8: Y = 5R + 9G + 2B is 12 bits, key 16 bits;
//                           VS16X2: Y = ch0 + ch1 is 17 bits signed, key 21 bits signed)
//   in  shape   [11:0]      available texels (bit n-1 = Cn): the cross, a T or an L (Sec. 3)
//   out low[n]  [3:0]       number of the texel whose value is the median for Cn (defined for
//                           available Cn)
//
// Structure (docs/edge-preserving.md, "median network"):
//   input select : per missing texel, the key of the texel that Sec. 3 substitutes (the diagonally
//                  opposite centre texel) or, when both outer neighbours of a centre texel are
//                  missing (the corner of an L), +inf and -inf, which turns that five-point median
//                  into the three-point median of the texel and its centre neighbours. One mux per
//                  input: every other median that reads a missing texel is itself missing.
//   cells        : a three-point median is 3 cells (one on an input pair, two after it); a
//                  five-point median is 7 (two input pairs, min of the maxima, max of the minima, a
//                  three-point median). The input pairs are chosen so that eight pairs serve all 16
//                  uses (found by exhaustive search over the pairings), giving 44 cells instead of
//                  8 x 3 + 4 x 7 = 52. Lee & Jen report 40.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "cmodel/edge_filter.hpp"

namespace tfu::rtl {

// A compare cell: lo = min(in_a, in_b), hi = max(in_a, in_b). Wires 0..11 are the network inputs
// (texel n on wire n - 1); every cell drives two new wires.
struct CompareCell {
  int in_a, in_b;
  int lo, hi;
};

struct MedianNetlist {
  int inputs = lee_jen::kTexels;
  int wires = 0;
  std::vector<CompareCell> cells;             // in topological order
  std::array<int, lee_jen::kTexels + 1> out{};  // out[n] = wire carrying Cn's median key
  int depth = 0;                              // cells on the longest input-to-output path
};
const MedianNetlist& median_netlist();

inline constexpr int32_t kKeyPlusInfinity = INT32_MAX;
inline constexpr int32_t kKeyMinusInfinity = INT32_MIN;

// Input select: the key driven onto each input wire for a shape (see header).
std::array<int32_t, lee_jen::kTexels> median_input_select(const lee_jen::LumaKeys& key, lee_jen::TexelMask shape);
// The whole block: input select, then the cells in order; low[n] = key & 15 of Cn's output wire.
lee_jen::LowIndex median_network_eval(const lee_jen::LumaKeys& key, lee_jen::TexelMask shape);

}  // namespace tfu::rtl
