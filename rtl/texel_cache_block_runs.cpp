// The texel cache's lines of a 4 x 4 grid whose columns and rows are runs of consecutive texels
// within at most two lines per axis (the edge cross and the 4 x 4 CUBIC footprint away from wraps
// and clamps, in tiles of 4 or more texels a side), under block parity. Software speed only: the
// plain form is TexelCache::group_lines in rtl/texel_cache.cpp, which handles any grid; this one
// must give the same lines in the same order and the same bank reads
// (TexelCache.GridAccessEqualsAPerTapReferenceModel checks both against a per-tap reference
// model, with cross-shaped 4 x 4 grids among its cases). Off with the fast-path switch
// (cmodel/fast_paths.hpp: TFU_PLAIN=1, the CLI's --plain): every grid then takes group_lines.
#include <algorithm>
#include <bit>

#include "rtl/texel_cache.hpp"

namespace tfu::rtl {

// Columns x[0..3] = x0, x0 + 1, x0 + 2, x0 + 3 fall into line columns x0 >> s and, from the first
// column that crosses into the next line, (x0 >> s) + 1; so do the rows. The grid cells split into
// four quarter masks by (line row, line column); a line is looked up iff its quarter holds a used
// cell, in order of its lowest used cell, and every cell of line row 0 comes before every cell of
// line row 1 in the row-major order: so only the two quarters of each line row need ordering.
bool TexelCache::block_run_lines(size_t l, const TapGrid& g, LineSet& s) const {
  const LevelLines& ll = lines_[l];
  const int x0 = g.x[0], y0 = g.y[0];
  if (g.x[1] != x0 + 1 || g.x[2] != x0 + 2 || g.x[3] != x0 + 3 || g.y[1] != y0 + 1 || g.y[2] != y0 + 2 || g.y[3] != y0 + 3)
    return false;
  if (ll.shift_x < 2 || ll.shift_y < 2 || x0 < 0 || y0 < 0) return false;  // more than two lines per axis
  const int bx0 = x0 >> ll.shift_x, by0 = y0 >> ll.shift_y;
  // Columns (rows) in the first line: up to the line's end, at most 4.
  const int cols0 = std::min(4, ((bx0 + 1) << ll.shift_x) - x0), rows0 = std::min(4, ((by0 + 1) << ll.shift_y) - y0);
  const uint32_t left = 0x1111u * ((1u << cols0) - 1u), top = (1u << (4 * rows0)) - 1u;
  const uint32_t used = g.used;
  const uint32_t quarter[4] = {used & left & top, used & ~left & top, used & left & ~top, used & ~left & ~top};
  const bool four_banks = cfg_.banks == 4;
  const auto add = [&](int q) {
    const int bx = bx0 + (q & 1), by = by0 + (q >> 1);
    s.lines[s.n++] = ll.first + static_cast<uint64_t>(by) * ll.stride + static_cast<uint64_t>(bx);
    ++s.nbank[four_banks ? static_cast<size_t>((bx & 1) + 2 * (by & 1)) : 0];
  };
  for (int q = 0; q < 4; q += 2) {  // line row 0, then line row 1: its two quarters by lowest cell
    const uint32_t a = quarter[q], b = quarter[q + 1];
    if (a != 0 && (b == 0 || std::countr_zero(a) < std::countr_zero(b))) {
      add(q);
      if (b != 0) add(q + 1);
    } else if (b != 0) {
      add(q + 1);
      if (a != 0) add(q);
    }
  }
  return true;
}

}  // namespace tfu::rtl
