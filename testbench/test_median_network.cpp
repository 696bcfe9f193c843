// rtl/median_network (compare-cell netlist) against the plain median of each Eq. 4 input set (with the
// Sec. 3 substitutes of T and L kernels, testbench/median_inputs.hpp) and against the behavioural
// medians of the golden model (lee_jen::median_low_pass): every ordering of every median's inputs in
// every kernel shape, plus random key vectors; and the netlist's structure (40 cells, Lee & Jen Sec. 6).
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <set>

#include "rtl/median_network.hpp"
#include "testbench/iterations.hpp"
#include "testbench/median_inputs.hpp"

namespace tfu::rtl {
namespace {

using lee_jen::kTexels;

using tfu::testing::median_inputs_in_shape;
using tfu::testing::plain_median;

lee_jen::LumaKeys keys_from_y(const std::array<int32_t, kTexels + 1>& y) {
  lee_jen::LumaKeys k{};
  for (int n = 1; n <= kTexels; ++n) k[static_cast<size_t>(n)] = y[static_cast<size_t>(n)] * 16 + n;
  return k;
}

TEST(MedianNetwork, FortyCellsThreeDeepAndTheSharedPairs) {
  const MedianNetlist& net = median_netlist();
  // 8 x 3 + 4 x 7 = 52 cells, less 4 pairs common to two three-point medians and the 8 first-level
  // pairs of the five-point medians that three-point medians already compare (Lee & Jen: 40).
  EXPECT_EQ(net.cells.size(), 40u);
  EXPECT_EQ(net.selects.size(), 12u);
  EXPECT_EQ(net.wires, kTexels + 2 * 40 + 12);
  // Longest path: a five-point median's input pair, the min/max of the pairs, the three parallel
  // cells of its three-point median (then the selector).
  EXPECT_EQ(net.depth, 3);
  std::set<std::pair<int, int>> seen;
  size_t input_pairs = 0;
  for (const CompareCell& c : net.cells) {
    EXPECT_TRUE(seen.insert({c.in_a, c.in_b}).second) << "two cells on the same inputs";
    EXPECT_LT(c.in_a, c.in_b);
    EXPECT_LT(c.in_b, c.lo);  // topological order
    EXPECT_EQ(c.hi, c.lo + 1);
    input_pairs += c.in_b < kTexels;
  }
  EXPECT_EQ(input_pairs, 20u);  // the distinct input pairs of the eight three-point medians
  // Selectors: on three wires, driven by the three cells on their pairs; one per output.
  std::set<int> outs;
  for (const Median3Select& s : net.selects) {
    ASSERT_LT(s.a, s.b);
    ASSERT_LT(s.b, s.c);
    const auto on = [&](int cell, int x, int y) {
      const CompareCell& c = net.cells[static_cast<size_t>(cell)];
      return c.in_a == x && c.in_b == y;
    };
    EXPECT_TRUE(on(s.ab, s.a, s.b) && on(s.ac, s.a, s.c) && on(s.bc, s.b, s.c));
    outs.insert(s.out);
  }
  for (int n = 1; n <= kTexels; ++n) EXPECT_TRUE(outs.count(net.out[static_cast<size_t>(n)])) << "C" << n;
  EXPECT_EQ(outs.size(), 12u);
  // The input pairs whose minimum and maximum feed the five-point medians: each outer neighbour of a
  // centre texel with the centre neighbour diagonal to it (texel numbers).
  std::set<int> min_max_read;
  for (const CompareCell& c : net.cells) {
    min_max_read.insert(c.in_a);
    min_max_read.insert(c.in_b);
  }
  std::set<std::pair<int, int>> first_level;
  for (const CompareCell& c : net.cells)
    if (c.in_b < kTexels && (min_max_read.count(c.lo) || min_max_read.count(c.hi))) first_level.insert({c.in_a + 1, c.in_b + 1});
  const std::set<std::pair<int, int>> want{{1, 5}, {3, 8}, {2, 4}, {6, 9}, {4, 7}, {9, 11}, {5, 10}, {8, 12}};
  EXPECT_EQ(first_level, want);
}

// Every ordering of the inputs of each median in every kernel shape in which that median is needed:
// exhaustive, since a median depends only on the order of its inputs.
TEST(MedianNetwork, EveryInputOrderingOfEveryMedianInEveryShape) {
  std::mt19937 rng(7);
  size_t cases = 0;
  for (const lee_jen::KernelShape& shape : lee_jen::kernel_shapes())
    for (int n = 1; n <= kTexels; ++n) {
      if (!lee_jen::has_texel(shape.mask, n)) continue;
      const std::vector<int> in = median_inputs_in_shape(n, shape.mask);
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
          const int want = plain_median(key, in);
          ASSERT_EQ(median_network_eval(key, shape.mask)[static_cast<size_t>(n)], want) << shape.name() << " C" << n;
          ASSERT_EQ(lee_jen::median_low_pass(key, shape.mask)[static_cast<size_t>(n)], want) << shape.name() << " C" << n;
          ++cases;
        }
      } while (std::next_permutation(rank.begin(), rank.end()));
    }
  // Per shape: 8 x 3! + 4 x 5! orderings in the cross; a T has two boundary medians fewer; an L
  // four fewer, and its corner's median has three inputs.
  EXPECT_EQ(cases, 3u * ((8 * 6 + 4 * 120) + 4 * (6 * 6 + 4 * 120) + 4 * (4 * 6 + 3 * 120 + 6)));
}

void check_random(std::mt19937& rng, int iterations, int32_t y_min, uint32_t y_range) {
  for (int it = 0; it < iterations; ++it) {
    std::array<int32_t, kTexels + 1> y{};
    const uint32_t range = it % 3 == 0 ? 4 : y_range;  // many ties on small ranges
    for (int m = 1; m <= kTexels; ++m) y[static_cast<size_t>(m)] = y_min + static_cast<int32_t>(rng() % range);
    const lee_jen::LumaKeys key = keys_from_y(y);
    for (const lee_jen::KernelShape& shape : lee_jen::kernel_shapes()) {
      const lee_jen::LowIndex got = median_network_eval(key, shape.mask);
      const lee_jen::LowIndex model = lee_jen::median_low_pass(key, shape.mask);
      for (int n = 1; n <= kTexels; ++n)
        if (lee_jen::has_texel(shape.mask, n)) {
          const int want = plain_median(key, median_inputs_in_shape(n, shape.mask));
          ASSERT_EQ(got[static_cast<size_t>(n)], want) << shape.name() << " C" << n;
          ASSERT_EQ(model[static_cast<size_t>(n)], want) << shape.name() << " C" << n;
        }
    }
  }
}

TEST(MedianNetwork, RandomKeysAllShapesAllOutputs) {
  std::mt19937 rng(11);
  check_random(rng, test::iterations(100000), 0, 4081);
}

TEST(MedianNetwork, SignedKeysOfVs16x2) {
  std::mt19937 rng(5);
  check_random(rng, test::iterations(20000), -32640, 65281);
}

}  // namespace
}  // namespace tfu::rtl
