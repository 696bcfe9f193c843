// The texel cache's lookup of a full 4 x 4 grid (every cell used: CUBIC's footprint with a 4-tap ROM
// and no clamp-to-border) in closed form, for the recurrences' CUBIC quad path
// (rtl/unit_recurrence_cubic_quads.hpp). Software speed only: the plain form is
// TexelCache::access_grid in rtl/texel_cache.cpp (its line set by group_lines / block_run_lines or
// cell_lines, then line_sectors, tap by tap), which handles any grid; this one must give the same
// lines in the same order, the same hits, misses, sectors and bank cycles, and the same counters
// (TexelCache.FullSquareInClosedFormEqualsGridAccess, testbench/test_cubic_quad_path.cpp: runs,
// wrapped and clamped grids, both bank mappings, 1 or 4 banks, tiled and linear levels of 1- and
// 4-byte texels, 64- to 1024-byte lines). Off with the fast-path switch (cmodel/fast_paths.hpp:
// TFU_PLAIN=1, the CLI's --plain), which turns the CUBIC quad path off.
#include <algorithm>

#include "rtl/texel_cache.hpp"

namespace tfu::rtl {

namespace {

// One axis of a full grid, its four columns (or rows) v[0..3] on a level whose lines are 2^shift
// texels wide (high): the distinct line columns v >> shift in order of first appearance, and for
// each how many distinct values v >> k its columns take (the sectors along this axis); the most
// line columns of one parity; the distinct columns and the most of one parity.
struct GridAxis {
  int n = 0;
  std::array<int, 4> line{}, sectors{};
  int most_lines_one_parity = 0, texels = 0, most_texels_one_parity = 0;
  GridAxis(const std::array<int16_t, 4>& v, int shift, int k) {
    const int v0 = v[0];
    if (v[1] == v0 + 1 && v[2] == v0 + 2 && v[3] == v0 + 3) {  // a run (no wrap or clamp inside): in order
      const int first = v0 >> shift;
      n = ((v0 + 3) >> shift) - first + 1;
      for (int i = 0; i < n; ++i) {
        const int lo = std::max(v0, (first + i) << shift), hi = std::min(v0 + 3, ((first + i + 1) << shift) - 1);
        line[static_cast<size_t>(i)] = first + i;
        sectors[static_cast<size_t>(i)] = (hi >> k) - (lo >> k) + 1;
      }
      most_lines_one_parity = (n + 1) / 2;
      texels = 4;
      most_texels_one_parity = 2;
      return;
    }
    std::array<uint32_t, 4> members{};  // per line column: its grid columns (bits)
    for (size_t i = 0; i < 4; ++i) {
      const int g = v[i] >> shift;
      size_t j = 0;
      while (j < static_cast<size_t>(n) && line[j] != g) ++j;
      if (j == static_cast<size_t>(n)) line[static_cast<size_t>(n++)] = g;
      members[j] |= 1u << i;
    }
    std::array<int, 2> lines_of_parity{}, texels_of_parity{};
    for (size_t j = 0; j < static_cast<size_t>(n); ++j) {
      ++lines_of_parity[static_cast<size_t>(line[j] & 1)];
      int seen[4], m = 0;  // the distinct v >> k of its columns
      for (size_t i = 0; i < 4; ++i) {
        if (!((members[j] >> i) & 1u)) continue;
        const int s = v[i] >> k;
        if (std::find(seen, seen + m, s) == seen + m) seen[m++] = s;
      }
      sectors[j] = m;
    }
    for (size_t i = 0; i < 4; ++i)
      if (std::find(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(i), v[i]) ==
          v.begin() + static_cast<std::ptrdiff_t>(i)) {
        ++texels;
        ++texels_of_parity[static_cast<size_t>(v[i] & 1)];
      }
    most_lines_one_parity = std::max(lines_of_parity[0], lines_of_parity[1]);
    most_texels_one_parity = std::max(texels_of_parity[0], texels_of_parity[1]);
  }
};

}  // namespace

// Every cell of the grid is used, so:
//   lines    a line is a pair (line column, line row) of the axes' groups, all of them used; the
//            row-major scan first reaches line rows in their order of first appearance and, in a
//            row, line columns in theirs, so the lines go row group by row group, column group by
//            column group (group_lines' and cell_lines' order);
//   sectors  a tap's sector in its line is the pair (y >> ky, x >> kx) (access_quad's rule: kx =
//            max(0, 5 - b), ky = max(0, 5 - shift_x - b), b = log2 of a tap's bytes), one to one,
//            so a line holds (distinct column sectors of its columns) x (distinct row sectors of
//            its rows);
//   banks    block parity: the lines of one bank share the parity of their line column and line
//            row, so the busiest of 4 banks reads (most line columns of one parity) x (most line
//            rows of one parity) lines, one bank all of them; texel parity: the distinct texels
//            are the products of the distinct columns and rows, and the busiest of 4 banks reads
//            (most columns of one parity) x (most rows of one parity).
FootprintResult TexelCache::access_square4(int texture, int level, const TapGrid& g) {
  const size_t l = level_index(texture, level);
  const LevelLines& ll = lines_[l];
  const int b = line_log2_ - ll.shift_x - ll.shift_y;  // log2 of a tap's bytes (texel, or block)
  if (g.cols != 4 || g.rows != 4 || g.used != square_cells(4, 4) || b > kSectorBytesLog2 ||
      *std::min_element(g.x.begin(), g.x.end()) < 0 || *std::min_element(g.y.begin(), g.y.end()) < 0)
    return access(texture, level, g);
  const GridAxis cols(g.x, ll.shift_x, std::max(0, kSectorBytesLog2 - b));
  const GridAxis rows(g.y, ll.shift_y, std::max(0, kSectorBytesLog2 - ll.shift_x - b));
  FootprintResult r;
  for (size_t j = 0; j < static_cast<size_t>(rows.n); ++j) {
    const uint64_t row = ll.first + static_cast<uint64_t>(rows.line[j]) * ll.stride;
    for (size_t i = 0; i < static_cast<size_t>(cols.n); ++i) {
      const int sectors = cols.sectors[i] * rows.sectors[j];
      r.sector_lookups += sectors;
      if (probe(row + static_cast<uint64_t>(cols.line[i]), r)) r.sector_hits += sectors;
    }
  }
  const bool four_banks = cfg_.banks == 4;
  if (cfg_.bank_mapping == BankMapping::BlockParity)
    r.cycles = four_banks ? cols.most_lines_one_parity * rows.most_lines_one_parity : cols.n * rows.n;
  else
    r.cycles = four_banks ? cols.most_texels_one_parity * rows.most_texels_one_parity : cols.texels * rows.texels;
  tally(l, r);
  return r;
}

}  // namespace tfu::rtl
