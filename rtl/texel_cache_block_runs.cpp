// The texel cache's lines of a 4 x 4 grid whose columns and rows are runs of consecutive texels
// within at most two lines per axis (the edge cross and the 4 x 4 CUBIC footprint away from wraps
// and clamps, in tiles of 4 or more texels a side), under block parity, with each line's sectors.
// Software speed only: the plain form is TexelCache::group_lines in rtl/texel_cache.cpp, which
// handles any grid, then line_sectors (a line search and sector_bit per used tap); this one must
// give the same lines in the same order, the same bank reads and the same sector masks
// (TexelCache.GridAccessEqualsAPerTapReferenceModel checks both against a per-tap reference
// model, sectors included, with cross-shaped 4 x 4 grids among its cases). Off with the fast-path
// switch (cmodel/fast_paths.hpp: TFU_PLAIN=1, the CLI's --plain): every grid then takes
// group_lines and line_sectors.
#include <algorithm>
#include <bit>

#include "rtl/texel_cache.hpp"

namespace tfu::rtl {

// Columns x[0..3] = x0, x0 + 1, x0 + 2, x0 + 3 fall into line columns x0 >> s and, from the first
// column that crosses into the next line, (x0 >> s) + 1; so do the rows. The grid cells split into
// four quarter masks by (line row, line column); a line is looked up iff its quarter holds a used
// cell, in order of its lowest used cell, and every cell of line row 0 comes before every cell of
// line row 1 in the row-major order: so only the two quarters of each line row need ordering.
// Sectors (line_sectors' rule): a used cell (i, j) lies in the line of its quarter, (i >= cols0) +
// 2 (j >= rows0), at byte offset (row in the line << (shift_x + b)) | (column in the line << b), b
// = log2 of a tap's bytes, which is sector_bit's (index << b) with index = (row << shift_x) |
// column; its sector bit, 1 << (offset >> 5), goes into its quarter's mask.
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
  const int tap_log2 = line_log2_ - ll.shift_x - ll.shift_y;  // b above
  const int mask_x = (1 << ll.shift_x) - 1, mask_y = (1 << ll.shift_y) - 1;
  std::array<uint32_t, 4> col_offset, row_offset;  // the offset's parts of the grid's columns and rows
  for (int i = 0; i < 4; ++i) {
    col_offset[static_cast<size_t>(i)] = static_cast<uint32_t>(((x0 + i) & mask_x) << tap_log2);
    row_offset[static_cast<size_t>(i)] = static_cast<uint32_t>(((y0 + i) & mask_y) << (ll.shift_x + tap_log2));
  }
  std::array<uint32_t, 4> sectors{};  // per quarter
  for (uint32_t cells = used; cells != 0; cells &= cells - 1) {
    const auto c = static_cast<size_t>(std::countr_zero(cells));
    const size_t i = c & 3u, j = c >> 2;
    const size_t q = (static_cast<int>(i) >= cols0 ? 1u : 0u) + (static_cast<int>(j) >= rows0 ? 2u : 0u);
    sectors[q] |= 1u << ((row_offset[j] | col_offset[i]) >> kSectorBytesLog2);
  }
  const bool four_banks = cfg_.banks == 4;
  const auto add = [&](int q) {
    const int bx = bx0 + (q & 1), by = by0 + (q >> 1);
    s.sectors[s.n] = sectors[static_cast<size_t>(q)];
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
