// The texel cache's lookup of a batch of 2 x 2 footprints whose four taps are all used (a quad's
// level footprints on the recurrences' probe quad path, rtl/unit_recurrence_probes.hpp, and on
// their LINEAR quad path, rtl/unit_recurrence_linear_quads.hpp). Software
// speed only: the plain form is TexelCache::access_square (access_quad under block parity, else
// access_grid, and tally), footprint by footprint; this one does the same lookups in the same
// order (the tags, the LRU and the hints see the same sequence) with the per-level work (the
// level's line grid, its sector shifts, the bank mapping, the counters) once per batch, and must
// give every footprint the same misses, missed lines and bank cycles, and the levels the same
// line and sector counts (TexelCache.ProbeSquaresEqualAccessSquare, testbench/test_tfu_unit.cpp:
// random grids, wrapped and not, both bank mappings, 1 or 4 banks, tiled and linear levels,
// 64- to 1024-byte lines). Off with the fast-path switch (cmodel/fast_paths.hpp: TFU_PLAIN=1, the
// CLI's --plain), which turns the probe and LINEAR quad paths off.
#include "rtl/texel_cache.hpp"

namespace tfu::rtl {

// access_quad of one footprint with its level's registers `ll`, `k` in hand (its derivation is
// there): its lookups in order, the missed lines appended to missed[nmissed ...], its sums into `sum`;
// returns its answer.
[[gnu::always_inline]] inline SquareLookup TexelCache::square_lines(const LevelLines& ll, SectorShifts k,
                                                                    bool four_banks, const TapGrid& g, uint64_t* missed,
                                                                    uint16_t& nmissed, LineCounts& sum) {
  const int bx0 = g.x[0] >> ll.shift_x, bx1 = g.x[1] >> ll.shift_x;
  const int by0 = g.y[0] >> ll.shift_y, by1 = g.y[1] >> ll.shift_y;
  const uint64_t line0 = ll.first + static_cast<uint64_t>(by0) * ll.stride + static_cast<uint64_t>(bx0);
  const bool two_cols = bx1 != bx0, two_rows = by1 != by0;
  const uint16_t first_miss = nmissed;
  int lines = 1;
  const auto look = [&](uint64_t line) __attribute__((always_inline)) {
    if (!lookup(line)) missed[nmissed++] = line;
  };
  look(line0);
  if (two_cols) {
    look(line0 + static_cast<uint64_t>(static_cast<int64_t>(bx1 - bx0)));  // modulo 2^64
    ++lines;
  }
  if (two_rows) {
    const uint64_t dy = static_cast<uint64_t>(static_cast<int64_t>(by1 - by0)) * ll.stride;
    look(line0 + dy);
    ++lines;
    if (two_cols) {
      look(line0 + dy + static_cast<uint64_t>(static_cast<int64_t>(bx1 - bx0)));
      ++lines;
    }
  }
  const int misses = nmissed - first_miss, hits = lines - misses;
  const int per_line = (two_cols || (g.x[0] >> k.x) == (g.x[1] >> k.x) ? 1 : 2) *
                       (two_rows || (g.y[0] >> k.y) == (g.y[1] >> k.y) ? 1 : 2);
  const int cycles = four_banks ? (two_cols && !((bx0 ^ bx1) & 1) ? 2 : 1) * (two_rows && !((by0 ^ by1) & 1) ? 2 : 1)
                                : (two_cols ? 2 : 1) * (two_rows ? 2 : 1);
  sum.hits += hits;
  sum.misses += misses;
  sum.sector_hits += hits * per_line;
  sum.sector_lookups += lines * per_line;
  return {static_cast<uint8_t>(cycles), static_cast<uint8_t>(misses), first_miss};
}

void TexelCache::access_squares(int texture, const std::array<int, 2>& levels, int nlevels, const TapGrid* grids,
                                size_t n, SquareLookup* out, uint64_t* missed, uint16_t& nmissed,
                                std::array<LineCounts, 2>& counts) {
  if (cfg_.bank_mapping != BankMapping::BlockParity) {  // texel parity: access_grid, footprint by footprint
    for (size_t j = 0; j < n; ++j) {
      const size_t k = j % static_cast<size_t>(nlevels);
      const FootprintResult r = access_square(texture, levels[k], grids[j]);
      out[j] = {static_cast<uint8_t>(r.cycles), static_cast<uint8_t>(r.misses), nmissed};
      for (int m = 0; m < r.misses; ++m) missed[nmissed++] = r.missed_lines[static_cast<size_t>(m)];
      counts[k].hits += r.hits;
      counts[k].misses += r.misses;
      counts[k].sector_hits += r.sector_hits;
      counts[k].sector_lookups += r.sector_lookups;
    }
    return;
  }
  // Block parity: access_quad with each level's registers read once, footprints level0, level1,
  // level0, ... (two levels) in order.
  const bool four_banks = cfg_.banks == 4;
  const size_t l0 = level_index(texture, levels[0]), l1 = level_index(texture, levels[1]);
  const LevelLines ll0 = lines_[l0], ll1 = lines_[l1];
  const SectorShifts k0 = sector_shifts_[l0], k1 = sector_shifts_[l1];
  LineCounts sum0, sum1;
  if (nlevels == 1) {
    for (size_t j = 0; j < n; ++j) out[j] = square_lines(ll0, k0, four_banks, grids[j], missed, nmissed, sum0);
  } else {
    for (size_t j = 0; j + 1 < n; j += 2) {
      out[j] = square_lines(ll0, k0, four_banks, grids[j], missed, nmissed, sum0);
      out[j + 1] = square_lines(ll1, k1, four_banks, grids[j + 1], missed, nmissed, sum1);
    }
  }
  // tally's counters per level, and the batch's.
  const auto add = [&](size_t l, const LineCounts& c, LineCounts& to) {
    LevelCounters& t = counters_[l];
    t.hits += static_cast<uint64_t>(c.hits);
    t.misses += static_cast<uint64_t>(c.misses);
    t.sector_hits += static_cast<uint64_t>(c.sector_hits);
    t.sector_lookups += static_cast<uint64_t>(c.sector_lookups);
    to.hits += c.hits;
    to.misses += c.misses;
    to.sector_hits += c.sector_hits;
    to.sector_lookups += c.sector_lookups;
  };
  add(l0, sum0, counts[0]);
  if (nlevels == 2) add(l1, sum1, counts[1]);
}

}  // namespace tfu::rtl
