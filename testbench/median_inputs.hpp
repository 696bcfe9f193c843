// Lee & Jen Eq. 4, written out independently of the models for the median-network tests (the C++
// netlist in testbench/test_median_network.cpp and the SystemVerilog in rtl/sv/edge/tests/): the
// input set of Cn's median in the full cross.
#pragma once

#include <vector>

namespace tfu::testing {

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

}  // namespace tfu::testing
