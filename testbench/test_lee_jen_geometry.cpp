// cmodel/lee_jen_geometry.hpp: the tables derived from the texel positions against Lee & Jen's own
// listing (Eq. 4, Fig. 2 and 3), typed here independently (Eq. 4 in testbench/median_inputs.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "cmodel/lee_jen_geometry.hpp"
#include "testbench/median_inputs.hpp"

namespace tfu::lee_jen {
namespace {

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

TEST(LeeJenGeometry, PositionsAndInverse) {
  for (int n = 1; n <= kTexels; ++n) EXPECT_EQ(texel_at(texel_pos(n).x, texel_pos(n).y), n);
  EXPECT_EQ(texel_at(-1, -1), 0);  // the corners of the 4 x 4 grid are not in the cross
  EXPECT_EQ(texel_at(2, 2), 0);
  EXPECT_EQ(texel_at(0, 0), 4);
}

TEST(LeeJenGeometry, CentreSquareInBilinearOrder) {
  EXPECT_EQ(kCentreSquare, (std::array<int, 4>{4, 5, 8, 9}));
  EXPECT_EQ(kCentreSquareMask, 0x198);  // bits 3, 4, 7, 8
}

TEST(LeeJenGeometry, FourArms) {
  EXPECT_EQ(arm(Side::Top).texels, (std::array<int, 2>{1, 2}));
  EXPECT_EQ(arm(Side::Bottom).texels, (std::array<int, 2>{11, 12}));
  EXPECT_EQ(arm(Side::Left).texels, (std::array<int, 2>{3, 7}));
  EXPECT_EQ(arm(Side::Right).texels, (std::array<int, 2>{6, 10}));
  TexelMask all = kCentreSquareMask;
  for (const Arm& a : kArms) {
    EXPECT_EQ(a.mask, texel_bit(a.texels[0]) | texel_bit(a.texels[1]));
    EXPECT_EQ(all & a.mask, 0) << "arms overlap";
    all = static_cast<TexelMask>(all | a.mask);
  }
  EXPECT_EQ(all, kAllTexels);
}

TEST(LeeJenGeometry, Eq4NeighbourhoodsMatchThePaper) {
  std::set<int> seen;
  for (const BoundaryMedian& b : kBoundaryMedians) {
    EXPECT_FALSE(in_centre_square(b.self));
    EXPECT_EQ(sorted({b.self, b.nb[0], b.nb[1]}), sorted(testing::median_inputs(b.self))) << "C" << b.self;
    seen.insert(b.self);
  }
  for (const CentreMedian& c : kCentreMedians) {
    EXPECT_TRUE(in_centre_square(c.self));
    EXPECT_EQ(sorted({c.self, c.centre[0], c.centre[1], c.outer[0], c.outer[1]}), sorted(testing::median_inputs(c.self)))
        << "C" << c.self;
    EXPECT_TRUE(in_centre_square(c.centre[0]) && in_centre_square(c.centre[1]));
    EXPECT_FALSE(in_centre_square(c.outer[0]) || in_centre_square(c.outer[1]));
    seen.insert(c.self);
  }
  EXPECT_EQ(seen.size(), 12u);
  // Sec. 3: the diagonally opposite centre texel (the paper's T example: C4 takes C9, C5 takes C8).
  for (const auto& [self, opposite] : {std::pair{4, 9}, std::pair{5, 8}, std::pair{8, 5}, std::pair{9, 4}}) {
    const int texel = self;  // a lambda does not capture a structured binding in clang 14
    const auto it = std::find_if(kCentreMedians.begin(), kCentreMedians.end(), [&](const CentreMedian& c) { return c.self == texel; });
    ASSERT_NE(it, kCentreMedians.end());
    EXPECT_EQ(it->opposite, opposite);
  }
  // Outer neighbours of C4 are C1 (top arm) and C3 (left arm).
  EXPECT_EQ(kCentreMedians[0].self, 4);
  EXPECT_EQ(kCentreMedians[0].outer, (std::array<int, 2>{1, 3}));
}

TEST(LeeJenGeometry, FetchGrid) {
  EXPECT_EQ(grid_col(4), 1);
  EXPECT_EQ(grid_row(4), 1);
  EXPECT_EQ(grid_col(3), 0);   // left arm: column 0
  EXPECT_EQ(grid_row(1), 0);   // top arm: row 0
  EXPECT_EQ(grid_col(10), 3);  // right arm: column 3
  EXPECT_EQ(grid_row(12), 3);  // bottom arm: row 3
  EXPECT_EQ(kCentreCols, (std::array<int, 2>{1, 2}));
  EXPECT_EQ(kCentreRows, (std::array<int, 2>{1, 2}));
  for (int n = 1; n <= kTexels; ++n) {
    EXPECT_GE(grid_col(n), 0);
    EXPECT_LT(grid_col(n), kGridSide);
    EXPECT_GE(grid_row(n), 0);
    EXPECT_LT(grid_row(n), kGridSide);
  }
}

}  // namespace
}  // namespace tfu::lee_jen
