// rtl/median_network (compare-cell netlist) against the behavioural Eq. 4 medians of the golden
// model (lee_jen::median_low_pass): every ordering of every median's inputs in every kernel shape,
// plus random key vectors.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <set>

#include "rtl/median_network.hpp"
#include "testbench/median_inputs.hpp"

namespace tfu::rtl {
namespace {

using lee_jen::kTexels;

using tfu::testing::median_inputs;

lee_jen::LumaKeys keys_from_y(const std::array<int32_t, kTexels + 1>& y) {
  lee_jen::LumaKeys k{};
  for (int n = 1; n <= kTexels; ++n) k[static_cast<size_t>(n)] = y[static_cast<size_t>(n)] * 16 + n;
  return k;
}

TEST(MedianNetwork, CellCountDepthAndSharing) {
  const MedianNetlist& net = median_netlist();
  // 8 x 3 + 4 x 7 = 52 without sharing; eight shared input pairs remove 8 (docs/edge-preserving.md).
  EXPECT_EQ(net.cells.size(), 44u);
  EXPECT_EQ(net.wires, kTexels + 2 * static_cast<int>(net.cells.size()));
  std::set<std::pair<int, int>> seen;
  for (const CompareCell& c : net.cells) {
    EXPECT_TRUE(seen.insert(std::minmax(c.in_a, c.in_b)).second) << "two cells on the same inputs";
    EXPECT_LT(c.in_a, c.lo);  // topological order
    EXPECT_LT(c.in_b, c.lo);
  }
  // Longest path, a five-point median: input pair, min/max of the pairs, then the three-point median
  // (its pair and two more cells).
  EXPECT_EQ(net.depth, 5);
}

// Every ordering of each median's inputs, in every kernel shape in which that median is needed.
TEST(MedianNetwork, EveryInputOrderingOfEveryMedianInEveryShape) {
  std::mt19937 rng(7);
  size_t cases = 0;
  for (const lee_jen::KernelShape& shape : lee_jen::kernel_shapes())
    for (int n = 1; n <= kTexels; ++n) {
      if (!((shape.mask >> (n - 1)) & 1u)) continue;
      std::vector<int> in = median_inputs(n);
      std::vector<int> rank(in.size());
      std::iota(rank.begin(), rank.end(), 0);
      do {
        for (int rep = 0; rep < 3; ++rep) {
          std::array<int32_t, kTexels + 1> y{};
          for (int m = 1; m <= kTexels; ++m) y[static_cast<size_t>(m)] = static_cast<int32_t>(rng() % 4081);
          // The median's own inputs take the ordering `rank` (values spread over the Y range; rep 2
          // makes them all equal, so the texel number decides).
          for (size_t k = 0; k < in.size(); ++k) y[static_cast<size_t>(in[k])] = rep == 2 ? 1000 : 500 + 700 * rank[k] + rep;
          const lee_jen::LumaKeys key = keys_from_y(y);
          const lee_jen::LowIndex want = lee_jen::median_low_pass(key, shape.mask);
          const lee_jen::LowIndex got = median_network_eval(key, shape.mask);
          ASSERT_EQ(got[static_cast<size_t>(n)], want[static_cast<size_t>(n)]) << shape.name() << " C" << n;
          ++cases;
        }
      } while (std::next_permutation(rank.begin(), rank.end()));
    }
  EXPECT_GT(cases, 3000u);
}

TEST(MedianNetwork, RandomKeysAllShapesAllOutputs) {
  std::mt19937 rng(11);
  for (int it = 0; it < 100000; ++it) {
    std::array<int32_t, kTexels + 1> y{};
    const auto range = static_cast<uint32_t>(it % 3 == 0 ? 4 : 4081);  // many ties on small ranges
    for (int m = 1; m <= kTexels; ++m) y[static_cast<size_t>(m)] = static_cast<int32_t>(rng() % range);
    const lee_jen::LumaKeys key = keys_from_y(y);
    for (const lee_jen::KernelShape& shape : lee_jen::kernel_shapes()) {
      const lee_jen::LowIndex want = lee_jen::median_low_pass(key, shape.mask);
      const lee_jen::LowIndex got = median_network_eval(key, shape.mask);
      for (int n = 1; n <= kTexels; ++n)
        if ((shape.mask >> (n - 1)) & 1u) {
          ASSERT_EQ(got[static_cast<size_t>(n)], want[static_cast<size_t>(n)]) << shape.name() << " C" << n;
        }
    }
  }
}

TEST(MedianNetwork, SignedKeysOfVs16x2) {
  std::mt19937 rng(5);
  for (int it = 0; it < 20000; ++it) {
    std::array<int32_t, kTexels + 1> y{};
    for (int m = 1; m <= kTexels; ++m) y[static_cast<size_t>(m)] = static_cast<int32_t>(rng() % 65281) - 32640;
    const lee_jen::LumaKeys key = keys_from_y(y);
    for (const lee_jen::KernelShape& shape : lee_jen::kernel_shapes()) {
      const lee_jen::LowIndex want = lee_jen::median_low_pass(key, shape.mask);
      const lee_jen::LowIndex got = median_network_eval(key, shape.mask);
      for (int n = 1; n <= kTexels; ++n)
        if ((shape.mask >> (n - 1)) & 1u) {
          ASSERT_EQ(got[static_cast<size_t>(n)], want[static_cast<size_t>(n)]);
        }
    }
  }
}

}  // namespace
}  // namespace tfu::rtl
