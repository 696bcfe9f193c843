// texel_cache: blocked, set-associative, banked texel cache of the texture filter unit (TFU-C).
//
// Ports (per cycle, one footprint request):
//   in  level   [3:0]   MIP level
//   in  grid    TapGrid: columns x[4] and rows y[4] (wrapped texel coordinates), cols, rows, and the
//               used[15:0] grid cells: the footprint's taps (x[i], y[j]) that read the cache
//   out hits    [4:0]   distinct cache lines of the footprint found in the cache
//   out misses  [4:0]   distinct lines missing (their addresses go to the memory model)
//   out cycles  [4:0]   cycles the footprint occupies the banks (>= 1; bank conflicts add cycles)
//
// Organisation (docs/texel-cache.md):
//   * Memory layout: each level is stored in BxB blocks (B = 4 or 8), one block per cache line, so
//     a line is B*B*bytes_per_texel bytes. Lines of a level are numbered row-major by block.
//   * Sets: line index modulo the number of sets; `ways` lines per set; LRU replacement.
//   * Banks, two mappings (docs/texel-cache.md):
//       texel parity : texel (x, y) lives in bank (x & 1) + 2 (y & 1), one texel per bank and cycle;
//                      any 2x2 bilinear footprint reads in one cycle, a 4x4 cubic one in four, the
//                      12-texel edge cross in three.
//       block parity : line (bx, by) lives in bank (bx & 1) + 2 (by & 1) and a bank reads a whole
//                      line per cycle (Lee & Jen Sec. 3: the filter takes its texels from the
//                      blocks); the up to 2x2 blocks of any bilinear, cubic or cross footprint read
//                      in one cycle.
//     With banks = 1 every texel (texel parity) or line (block parity) is a separate read. A
//     footprint needs max over banks of (distinct texels or lines in that bank) cycles.
//   * Misses are counted per level; the memory model (memory_model.hpp) supplies missing lines.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rtl/unit_ports.hpp"

namespace tfu::rtl {

enum class BankMapping { TexelParity, BlockParity };

inline constexpr int kMaxCacheBytes = 16 << 20;  // 16 MiB: capacity_bytes in 1..kMaxCacheBytes
inline constexpr int kMaxCacheWays = 4096;       // associativity in 1..kMaxCacheWays

struct TexelCacheConfig {
  int block = 4;               // B: block side in texels (power of two, 4 or 8)
  int bytes_per_texel = 4;     // 1 (L8) or 4
  int capacity_bytes = 16384;  // total data capacity
  int ways = 4;                // associativity
  int banks = 4;               // 1 or 4
  BankMapping bank_mapping = BankMapping::BlockParity;
  int line_bytes() const { return block * block * bytes_per_texel; }
  int lines() const { return capacity_bytes / line_bytes(); }
  int sets() const { return lines() / ways; }
  // Throws InputError with one line naming the bad field (capacity below one set or above
  // kMaxCacheBytes, B not 4 or 8, ways outside 1..kMaxCacheWays, banks not 1 or 4, ...).
  void validate() const;
};

struct FootprintResult {
  int hits = 0, misses = 0;
  int cycles = 1;                           // bank occupancy
  std::array<uint64_t, 16> missed_lines;  // distinct line addresses fetched from memory: [0, misses)
};

class TexelCache {
 public:
  // level_widths[l] = width of level l in texels (line numbering needs the blocks per row).
  TexelCache(TexelCacheConfig cfg, std::vector<int> level_widths, std::vector<int> level_heights);
  const TexelCacheConfig& config() const { return cfg_; }
  // Looks up every used tap of one footprint (allocating missed lines, LRU update, lines in the
  // order the taps first reach them, row-major) and reports hits, misses and the bank cycles.
  // Taps that share a line count one access to that line.
  FootprintResult access(int level, const TapGrid& grid) {
    if (cfg_.bank_mapping == BankMapping::BlockParity && grid.cols == 2 && grid.rows == 2 &&
        grid.used == square_cells(2, 2))
      return access_quad(static_cast<size_t>(level), grid);  // every LINEAR footprint
    return access_grid(static_cast<size_t>(level), grid);
  }
  // Line address (unique over all levels) of the block that holds texel (x, y) of `level`.
  uint64_t line_of(int level, int x, int y) const;
  // Tag probe without allocation or LRU update (the kernel-shape selector's cache-aware policy).
  bool resident(int level, int x, int y) const;
  uint64_t hits(int level) const { return hits_.at(static_cast<size_t>(level)); }
  uint64_t misses(int level) const { return misses_.at(static_cast<size_t>(level)); }
  void reset();

 private:
  TexelCacheConfig cfg_;
  std::vector<int> blocks_per_row_;
  int block_shift_ = 2;  // log2(B)
  uint64_t set_mask_ = 0;  // sets - 1 when sets is a power of two (> 1), else 0 (use %)
  size_t set_of(uint64_t line) const;
  std::vector<uint64_t> level_base_;  // first line address of each level
  struct Way {
    uint64_t tag = ~uint64_t{0};
    uint64_t last_use = 0;
  };
  std::vector<Way> ways_;  // sets * ways
  uint64_t tick_ = 0;
  // Software memo (not hardware state): the line of the latest lookup and its way, so that a run of
  // footprints in one block skips the way search. A lookup always leaves its line resident.
  uint64_t mru_line_ = ~uint64_t{0};
  size_t mru_way_ = 0;
  std::vector<uint64_t> hits_, misses_;
  bool lookup(uint64_t line);  // true on hit; allocates (LRU victim) on miss
  FootprintResult access_quad(size_t level, const TapGrid& g);
  FootprintResult access_grid(size_t level, const TapGrid& g);
  // The lookup tail both share: one line into r's hits or misses; the level's counters.
  void probe(uint64_t line, FootprintResult& r);
  void tally(size_t level, const FootprintResult& r);
  struct LineSet;
  void group_lines(size_t level, const TapGrid& g, LineSet& s) const;
  void cell_lines(size_t level, const TapGrid& g, LineSet& s) const;
};

// Inline: the tag lookup and the 2x2 path run once per LINEAR pixel.

inline size_t TexelCache::set_of(uint64_t line) const {
  return set_mask_ ? static_cast<size_t>(line & set_mask_) : static_cast<size_t>(line % static_cast<uint64_t>(cfg_.sets()));
}

inline bool TexelCache::lookup(uint64_t line) {
  ++tick_;
  if (line == mru_line_) {  // the line of the previous lookup is still where it was (a hit)
    ways_[mru_way_].last_use = tick_;
    return true;
  }
  Way* w = &ways_[set_of(line) * static_cast<size_t>(cfg_.ways)];
  Way* victim = w;
  for (int i = 0; i < cfg_.ways; ++i) {
    if (w[i].tag == line) {
      w[i].last_use = tick_;
      mru_line_ = line;
      mru_way_ = static_cast<size_t>(&w[i] - ways_.data());
      return true;
    }
    if (w[i].last_use < victim->last_use) victim = &w[i];
  }
  victim->tag = line;  // least recently used (an empty way has last_use 0)
  victim->last_use = tick_;
  mru_line_ = line;
  mru_way_ = static_cast<size_t>(victim - ways_.data());
  return false;
}

[[gnu::always_inline]] inline void TexelCache::probe(uint64_t line, FootprintResult& r) {
  if (lookup(line)) {
    ++r.hits;
  } else {
    r.missed_lines[static_cast<size_t>(r.misses++)] = line;
  }
}

inline void TexelCache::tally(size_t l, const FootprintResult& r) {
  hits_[l] += static_cast<uint64_t>(r.hits);
  misses_[l] += static_cast<uint64_t>(r.misses);
}

// The bilinear 2x2 footprint under block parity: its block columns bx0, bx1 and rows by0, by1 give
// one, two or four lines, looked up row-major. Banks: the lines in one bank share the parity of bx
// and of by, so per axis two distinct blocks of equal parity (a wrap over an odd number of blocks)
// put two lines into every bank touched; with one bank every line is a read.
inline FootprintResult TexelCache::access_quad(size_t l, const TapGrid& g) {
  const int bx0 = g.x[0] >> block_shift_, bx1 = g.x[1] >> block_shift_;
  const int by0 = g.y[0] >> block_shift_, by1 = g.y[1] >> block_shift_;
  const auto row = static_cast<uint64_t>(blocks_per_row_[l]);
  const uint64_t line0 = level_base_[l] + static_cast<uint64_t>(by0) * row + static_cast<uint64_t>(bx0);
  const auto dx = static_cast<uint64_t>(static_cast<int64_t>(bx1 - bx0));  // modulo 2^64
  const uint64_t dy = static_cast<uint64_t>(static_cast<int64_t>(by1 - by0)) * row;
  const bool two_cols = bx1 != bx0, two_rows = by1 != by0;
  FootprintResult r;
  probe(line0, r);
  if (two_cols) probe(line0 + dx, r);
  if (two_rows) {
    probe(line0 + dy, r);
    if (two_cols) probe(line0 + dy + dx, r);
  }
  if (cfg_.banks == 4) {
    r.cycles = (two_cols && !((bx0 ^ bx1) & 1) ? 2 : 1) * (two_rows && !((by0 ^ by1) & 1) ? 2 : 1);
  } else {
    r.cycles = (two_cols ? 2 : 1) * (two_rows ? 2 : 1);
  }
  tally(l, r);
  return r;
}

}  // namespace tfu::rtl
