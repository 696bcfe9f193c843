// The texel cache's lookup of a full 4 x 4 grid whose columns and rows are runs of consecutive
// texels (CUBIC's footprint with a 4-tap ROM away from the wraps), in closed form, for the
// recurrences' CUBIC quad path (rtl/unit_recurrence_cubic_quads.hpp). Software speed only: the
// plain form is TexelCache::access_grid in rtl/texel_cache.cpp (its line set by group_lines /
// block_run_lines or cell_lines, then line_sectors, per tap), which handles any grid; this one must
// give the same lines in the same order, the same hits, misses, sectors and bank cycles, and the
// same counters (TexelCache.SquareRunsEqualGridAccess, testbench/test_cubic_quad_path.cpp, on both
// bank mappings, 1 or 4 banks, tiled and linear levels, 64- to 1024-byte lines). Off with the
// fast-path switch (cmodel/fast_paths.hpp: TFU_PLAIN=1, the CLI's --plain), which turns the CUBIC
// quad path off.
#include <algorithm>

#include "rtl/texel_cache.hpp"

namespace tfu::rtl {

namespace {

// One axis of the grid: the run v0 .. v0 + 3 crosses `n` line columns (or line rows) from `first`,
// and in line column i its taps fall in `sectors[i]` distinct values of v >> k.
struct RunAxis {
  int first = 0, n = 0;
  std::array<int, 4> sectors{};
  RunAxis(int v0, int shift, int k) : first(v0 >> shift), n(((v0 + 3) >> shift) - first + 1) {
    for (int i = 0; i < n; ++i) {
      const int lo = std::max(v0, (first + i) << shift), hi = std::min(v0 + 3, ((first + i + 1) << shift) - 1);
      sectors[static_cast<size_t>(i)] = (hi >> k) - (lo >> k) + 1;
    }
  }
};

}  // namespace

// Every cell is used and the columns x0 .. x0 + 3 and rows y0 .. y0 + 3 are runs, so:
//   lines    the grid's cells in line (column, row) groups are the products of the runs' line
//            columns and line rows, all of them used; the row-major scan first reaches the line of
//            line row j and line column i at (first row of j, first column of i), so the lines go
//            row by row, column by column (group_lines' and cell_lines' order);
//   sectors  a tap's sector in its line is the pair (y >> ky, x >> kx) (access_quad's rule, kx =
//            max(0, 5 - b), ky = max(0, 5 - shift_x - b), b = log2 of a tap's bytes), one to one,
//            so a line holds (distinct column sectors) x (distinct row sectors) of its taps;
//   banks    block parity: the lines of one bank share the parity of their line column and line
//            row, so the busiest of 4 banks reads ceil(n_x / 2) ceil(n_y / 2) lines, one bank all
//            n_x n_y; texel parity: the 16 texels are distinct, 4 in each of 4 banks, 16 in one.
FootprintResult TexelCache::access_square4(int texture, int level, const TapGrid& g) {
  const size_t l = level_index(texture, level);
  const LevelLines& ll = lines_[l];
  const int x0 = g.x[0], y0 = g.y[0];
  const int b = line_log2_ - ll.shift_x - ll.shift_y;  // log2 of a tap's bytes (texel, or block)
  if (g.cols != 4 || g.rows != 4 || g.used != square_cells(4, 4) || x0 < 0 || y0 < 0 || g.x[1] != x0 + 1 ||
      g.x[2] != x0 + 2 || g.x[3] != x0 + 3 || g.y[1] != y0 + 1 || g.y[2] != y0 + 2 || g.y[3] != y0 + 3 ||
      b > kSectorBytesLog2)
    return access(texture, level, g);
  const RunAxis cols(x0, ll.shift_x, std::max(0, kSectorBytesLog2 - b));
  const RunAxis rows(y0, ll.shift_y, std::max(0, kSectorBytesLog2 - ll.shift_x - b));
  FootprintResult r;
  for (size_t j = 0; j < static_cast<size_t>(rows.n); ++j) {
    const uint64_t row = ll.first + static_cast<uint64_t>(rows.first + static_cast<int>(j)) * ll.stride;
    for (size_t i = 0; i < static_cast<size_t>(cols.n); ++i) {
      const int sectors = cols.sectors[i] * rows.sectors[j];
      r.sector_lookups += sectors;
      if (probe(row + static_cast<uint64_t>(cols.first + static_cast<int>(i)), r)) r.sector_hits += sectors;
    }
  }
  if (cfg_.bank_mapping == BankMapping::BlockParity)
    r.cycles = cfg_.banks == 4 ? ((cols.n + 1) / 2) * ((rows.n + 1) / 2) : cols.n * rows.n;
  else
    r.cycles = cfg_.banks == 4 ? 4 : 16;
  tally(l, r);
  return r;
}

}  // namespace tfu::rtl
