// Lee & Jen Eq. 4 and the Sec. 3 kernel adjustments, written out independently of the models for the
// median-network tests (the C++ netlist in testbench/test_median_network.cpp and the SystemVerilog in
// rtl/sv/edge/tests/), and the plain median definition they are checked against.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace tfu::testing {

// The input set of Cn's median in the full cross (Eq. 4).
inline std::vector<int> median_inputs(int n) {
  switch (n) {
    case 1: return {1, 2, 4};
    case 2: return {1, 2, 5};
    case 3: return {3, 4, 7};
    case 6: return {5, 6, 10};
    case 7: return {3, 7, 8};
    case 10: return {6, 9, 10};
    case 11: return {8, 11, 12};
    case 12: return {9, 11, 12};
    case 4: return {1, 3, 4, 5, 8};
    case 5: return {2, 4, 5, 6, 9};
    case 8: return {4, 7, 8, 9, 11};
    case 9: return {5, 8, 9, 10, 12};
  }
  return {};
}

// The input set of Cn's median in a kernel shape (bit m-1 of `shape` = Cm available), as
// docs/edge-preserving.md reads Sec. 3: a centre texel missing one outer neighbour takes the
// diagonally opposite centre texel instead (C4 <-> C9, C5 <-> C8); missing both, its median is over
// itself and its two centre neighbours.
inline std::vector<int> median_inputs_in_shape(int n, uint16_t shape) {
  constexpr std::array<int, 13> kOpposite{0, 0, 0, 0, 9, 8, 0, 0, 5, 4, 0, 0, 0};
  std::vector<int> have;
  size_t missing = 0;
  for (const int m : median_inputs(n)) {
    if ((shape >> (m - 1)) & 1u) {
      have.push_back(m);
    } else {
      ++missing;
    }
  }
  if (missing > 0 && kOpposite[static_cast<size_t>(n)] == 0) throw std::logic_error("a boundary texel's median misses an input");
  if (missing == 1) have.push_back(kOpposite[static_cast<size_t>(n)]);
  return have;
}

// The plain median: the middle one of the sorted keys of `in` (keys are unique: Y * 16 + texel
// number); returns its texel number (key & 15).
inline int plain_median(const std::array<int32_t, 13>& key, const std::vector<int>& in) {
  std::vector<int32_t> k;
  for (const int m : in) k.push_back(key[static_cast<size_t>(m)]);
  std::sort(k.begin(), k.end());
  return static_cast<int>(k[k.size() / 2] & 15);
}

}  // namespace tfu::testing
