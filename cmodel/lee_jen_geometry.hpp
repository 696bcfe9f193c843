// The 12-texel cross kernel of Lee & Jen 2003 (Fig. 2, Eq. 4, Sec. 3), defined once.
//
// Texel numbering (Eq. 4), x right, y down, C4 at (0,0); the sample point is in [0,1)^2:
//            C1  C2
//        C3  C4  C5  C6
//        C7  C8  C9  C10
//            C11 C12
//
// kTexelPos is the one table typed in; everything else below is derived from it at compile time:
//   kCentreSquare   C4 C5 C8 C9, the texels at x, y in {0, 1}, in the order of the bilinear weights
//                   of Eq. 5: (0,0) (1,0) (0,1) (1,1)
//   kArms           the four arms, one per side of the centre square: the two texels one step beyond
//                   it (top C1 C2, bottom C11 C12, left C3 C7, right C6 C10); a T kernel lacks one arm,
//                   an L two adjacent arms (Sec. 3, Fig. 3)
//   kBoundaryMedians, kCentreMedians
//                   the Eq. 4 neighbourhoods: Cn_low is the median of Cn and its 4-connected neighbours
//                   in the cross, three points for a texel outside the centre square, five inside
//                   (two centre-square neighbours, two outer ones); `opposite` is the diagonally
//                   opposite centre texel that stands in for a missing outer neighbour (Sec. 3)
//   grid_col, grid_row, kCentreCols, kCentreRows
//                   the cross on the 4 x 4 grid of texel columns and rows -1..2 that the samplers and
//                   the unit fetch (grid column i holds x = i - 1): C4 at column 1, row 1
// testbench/test_lee_jen_geometry.cpp checks the derived tables against the paper's listing.
// Masks of texels: bit n-1 = texel Cn.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace tfu::lee_jen {

inline constexpr int kTexels = 12;

using TexelMask = uint16_t;
inline constexpr TexelMask kAllTexels = 0x0FFF;
constexpr TexelMask texel_bit(int n) { return static_cast<TexelMask>(1u << (n - 1)); }
constexpr bool has_texel(TexelMask m, int n) { return ((m >> (n - 1)) & 1u) != 0; }

struct TexelPos {
  int x, y;
};
// Position of texel Cn (n = 1..12): kTexelPos[n - 1].
inline constexpr TexelPos kTexelPos[kTexels] = {{0, -1}, {1, -1}, {-1, 0}, {0, 0}, {1, 0}, {2, 0},
                                                {-1, 1}, {0, 1},  {1, 1},  {2, 1}, {0, 2}, {1, 2}};
constexpr TexelPos texel_pos(int n) { return kTexelPos[n - 1]; }
// Texel number at (x, y), or 0 if (x, y) is not part of the 12-texel cross.
constexpr int texel_at(int x, int y) {
  for (int i = 0; i < kTexels; ++i)
    if (kTexelPos[i].x == x && kTexelPos[i].y == y) return i + 1;
  return 0;
}
constexpr bool in_centre_square(TexelPos p) { return p.x >= 0 && p.x <= 1 && p.y >= 0 && p.y <= 1; }
constexpr bool in_centre_square(int n) { return in_centre_square(texel_pos(n)); }

// ---- The centre square C4 C5 C8 C9 (bilinear order) ----
inline constexpr std::array<int, 4> kCentreSquare = [] {
  std::array<int, 4> c{};
  for (int k = 0; k < 4; ++k) c[static_cast<size_t>(k)] = texel_at(k & 1, k >> 1);
  return c;
}();
inline constexpr TexelMask kCentreSquareMask = [] {
  TexelMask m = 0;
  for (const int n : kCentreSquare) m = static_cast<TexelMask>(m | texel_bit(n));
  return m;
}();

// ---- The four arms ----
enum class Side { Top, Bottom, Left, Right };
struct Arm {
  Side side;
  int dx, dy;                  // step from the centre square towards the arm
  std::array<int, 2> texels;   // ascending
  TexelMask mask;
};
inline constexpr std::array<Arm, 4> kArms = [] {
  std::array<Arm, 4> arms{{{Side::Top, 0, -1, {}, 0},
                           {Side::Bottom, 0, 1, {}, 0},
                           {Side::Left, -1, 0, {}, 0},
                           {Side::Right, 1, 0, {}, 0}}};
  for (Arm& a : arms) {
    size_t k = 0;
    for (int n = 1; n <= kTexels; ++n) {
      const TexelPos p = texel_pos(n);
      if (in_centre_square(p) || !in_centre_square(TexelPos{p.x - a.dx, p.y - a.dy})) continue;
      a.texels[k++] = n;  // two per side by construction (checked by the test)
      a.mask = static_cast<TexelMask>(a.mask | texel_bit(n));
    }
  }
  return arms;
}();
constexpr const Arm& arm(Side s) { return kArms[static_cast<size_t>(s)]; }

// ---- The Eq. 4 neighbourhoods ----
// Neighbours of Cn in the cross (4-connected), ascending; unused entries 0.
struct Neighbours {
  std::array<int, 4> n{};
  int count = 0;
};
constexpr Neighbours neighbours(int n) {
  Neighbours out;
  for (int m = 1; m <= kTexels; ++m) {
    const TexelPos p = texel_pos(n), q = texel_pos(m);
    const int d = (p.x > q.x ? p.x - q.x : q.x - p.x) + (p.y > q.y ? p.y - q.y : q.y - p.y);
    if (d == 1) out.n[static_cast<size_t>(out.count++)] = m;
  }
  return out;
}
// Three-point median of a texel outside the centre square: Cn_low = median(self, nb[0], nb[1]).
struct BoundaryMedian {
  int self;
  std::array<int, 2> nb;
};
// Five-point median of a centre texel: Cn_low = median(self, centre[0], centre[1], outer[0], outer[1]).
struct CentreMedian {
  int self;
  std::array<int, 2> centre;  // its two neighbours in the centre square
  std::array<int, 2> outer;   // its two neighbours outside it (on two different arms)
  int opposite;               // the diagonally opposite centre texel (C4 <-> C9, C5 <-> C8)
};
inline constexpr std::array<BoundaryMedian, kTexels - 4> kBoundaryMedians = [] {
  std::array<BoundaryMedian, kTexels - 4> t{};
  size_t k = 0;
  for (int n = 1; n <= kTexels; ++n) {
    if (in_centre_square(n)) continue;
    const Neighbours nb = neighbours(n);
    t[k++] = {n, {nb.n[0], nb.n[1]}};
  }
  return t;
}();
inline constexpr std::array<CentreMedian, 4> kCentreMedians = [] {
  std::array<CentreMedian, 4> t{};
  size_t k = 0;
  for (int n = 1; n <= kTexels; ++n) {
    if (!in_centre_square(n)) continue;
    const Neighbours nb = neighbours(n);
    CentreMedian c{n, {}, {}, texel_at(1 - texel_pos(n).x, 1 - texel_pos(n).y)};
    size_t ci = 0, oi = 0;
    for (int i = 0; i < nb.count; ++i) {
      const int m = nb.n[static_cast<size_t>(i)];
      if (in_centre_square(m)) {
        c.centre[ci++] = m;
      } else {
        c.outer[oi++] = m;
      }
    }
    t[k++] = c;
  }
  return t;
}();

// ---- The cross on the 4 x 4 fetch grid (columns and rows -1..2) ----
inline constexpr int kGridSide = 4;
inline constexpr int kGridOrigin = -1;  // x (and y) of grid column (row) 0
constexpr int grid_col(int n) { return texel_pos(n).x - kGridOrigin; }
constexpr int grid_row(int n) { return texel_pos(n).y - kGridOrigin; }
// Grid columns and rows of the centre square: {1, 2} each.
inline constexpr std::array<int, 2> kCentreCols{grid_col(kCentreSquare[0]), grid_col(kCentreSquare[1])};
inline constexpr std::array<int, 2> kCentreRows{grid_row(kCentreSquare[0]), grid_row(kCentreSquare[2])};

}  // namespace tfu::lee_jen
