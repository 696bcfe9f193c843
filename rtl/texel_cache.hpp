// texel_cache: blocked, set-associative, banked texel cache of the texture filter unit.
//
// Ports (per cycle, one footprint request):
//   in  texture [11:0]  texture descriptor (its level addresses, pitches and layout locate the lines)
//   in  level   [3:0]   MIP level
//   in  grid    TapGrid: columns x[4] and rows y[4] (wrapped texel coordinates; on a level of
//               compressed lines, CacheHolds::Compressed, the address generator's block columns and
//               block rows, TapBlocks in rtl/unit_ports.hpp), cols, rows, and the used[15:0] grid
//               cells: the footprint's taps (x[i], y[j]) that read the cache
//   out hits    [4:0]   distinct cache lines of the footprint found in the cache
//   out misses  [4:0]   distinct lines missing (their addresses go to the memory model)
//   out cycles  [4:0]   cycles the footprint occupies the banks (>= 1; bank conflicts add cycles)
//
// Organisation (docs/texel-cache.md):
//   * Tags are memory line addresses (byte address / line_bytes): one cache holds lines of every
//     texture of the frame, and nothing is flushed between textures. The descriptor's layout makes
//     the lines of a level a grid: a tiled texture has one tile per line (line column x >> t, line
//     row y >> t, t = log2 of the tile side), a linear texture line_bytes / bytes_per_texel texels
//     of one row per line (column x >> log2(line_bytes / bytes_per_texel), row y); the line address
//     is the level's first line + row * (row pitch / line_bytes) + column.
//   * Sets: line address modulo the number of sets; `ways` lines per set; LRU replacement. ways = 0
//     is the fully associative cache: one set of all the lines (a tag compare per line).
//   * Banks, two mappings (docs/texel-cache.md):
//       texel parity : texel (x, y) lives in bank (x & 1) + 2 (y & 1), one texel per bank and cycle;
//                      any 2x2 bilinear footprint reads in one cycle, a 4x4 cubic one in four, the
//                      12-texel edge cross in three.
//       block parity : the line in line column bx, line row by lives in bank (bx & 1) + 2 (by & 1)
//                      and a bank reads a whole
//                      line per cycle (Lee & Jen Sec. 3: the filter takes its texels from the
//                      blocks); the up to 2x2 blocks of any bilinear, cubic or cross footprint read
//                      in one cycle.
//     With banks = 1 every texel (texel parity) or line (block parity) is a separate read. A
//     footprint needs max over banks of (distinct texels or lines in that bank) cycles.
//   * Hits and misses are counted per texture and per level; the memory model (memory_model.hpp)
//     supplies missing lines.
//   * Sectors (the 32-byte sectors GPUs report hit rates in, e.g. l1tex__t_sector_hit_rate): a
//     footprint's sector lookups are the distinct 32-byte sectors of its lines that its used taps
//     fall in (a tap's sector: its byte offset inside its line / 32, from the level's layout: the
//     texel's index in the line times its bytes, or the block's for compressed lines); a sector
//     lookup is a hit when its line was a hit. The cache still fills whole lines: the sector
//     figures weight each line lookup by the sectors the footprint reads from it.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "cmodel/descriptors.hpp"
#include "rtl/unit_ports.hpp"

namespace tfu::rtl {

enum class BankMapping { TexelParity, BlockParity };
// What the lines of a block-compressed texture hold (docs/texel-cache.md, "Compressed textures"):
//   Compressed  the blocks as memory stores them (a line = line_bytes / block_bytes blocks of one
//               block row); the decoders sit after the cache and decode each footprint's texels
//   Decoded     decoded RGBA8 texels, a line = a square tile of line_bytes / 4 texels (4x4 at 64
//               bytes) in a tag space of its own; a miss fetches the blocks that cover the tile
//               and the decoders decode the tile on fill
// Uncompressed textures are cached as before under either.
enum class CacheHolds { Compressed, Decoded };

inline constexpr int kSectorBytes = 32;
inline constexpr int kSectorBytesLog2 = 5;
static_assert(1 << kSectorBytesLog2 == kSectorBytes);
// The fully associative cache compares every tag on a miss: bounded so that a model run stays fast.
inline constexpr int kMaxFullyAssociativeLines = 4096;

struct TexelCacheConfig {
  int line_bytes = 64;         // 64, 256 or 1024
  int capacity_bytes = 16384;  // total data capacity
  int ways = 4;                // associativity; 0: fully associative (ways = lines, one set)
  int banks = 4;               // 1 or 4
  BankMapping bank_mapping = BankMapping::BlockParity;
  CacheHolds holds = CacheHolds::Compressed;
  int lines() const { return capacity_bytes / line_bytes; }
  int way_count() const { return ways == 0 ? lines() : ways; }
  int sets() const { return lines() / way_count(); }
  // Throws InputError with one line naming the bad field (capacity below one set or not a whole
  // number of sets; products in 64 bits; a fully associative cache of more than
  // kMaxFullyAssociativeLines lines).
  void validate() const;
  friend bool operator==(const TexelCacheConfig&, const TexelCacheConfig&) = default;
};

// The block decoders of the unit (cmodel/block_formats.hpp decode_block): `units` decoders, each
// producing `texels_per_clock` texels per clock, pipelined with `latency` clocks from the first
// texel in to the last texel out. Where they sit is TexelCacheConfig::holds; rtl/cache_stage.hpp
// states their timing.
struct DecoderConfig {
  int texels_per_clock = 4;  // a bilinear footprint per clock per decoder
  int units = 1;
  int latency = 2;
  int texels_per_cycle() const { return texels_per_clock * units; }
  friend bool operator==(const DecoderConfig&, const DecoderConfig&) = default;
};

// Where the lines of one level lie: line(x, y) = first + (y >> shift_y) * stride + (x >> shift_x),
// where for a level of compressed lines x and y are the block column and block row (the address
// generator's block coordinates, rtl/address_gen_blocks.hpp: a line holds 2^shift_x blocks of one
// block row, shift_y = 0).
struct LevelLines {
  uint64_t first = 0;
  uint64_t stride = 0;
  int shift_x = 0, shift_y = 0;
};
// The line grid of level `level` of a texture for lines of `line_bytes`; InputError (naming the
// texture) when its tiles are not one line each or a linear row pitch is not whole lines.
LevelLines level_lines(const TextureDescriptor& d, int level, int line_bytes, const std::string& what);

struct FootprintResult {
  int hits = 0, misses = 0;
  int sector_hits = 0, sector_lookups = 0;  // the lines' 32-byte sectors the taps read (see the header)
  int cycles = 1;                           // bank occupancy
  std::array<uint64_t, 16> missed_lines;  // distinct line addresses fetched from memory: [0, misses)
};
// access_squares' answer for one footprint: its bank cycles, and its missed lines, `misses` of
// them from position `first_miss` of the batch's list.
struct SquareLookup {
  uint8_t cycles, misses;
  uint16_t first_miss;
};
// Line and sector lookups summed over footprints (the cache stage's counters per level).
struct LineCounts {
  int hits = 0, misses = 0, sector_hits = 0, sector_lookups = 0;
};
// The most distinct lines one footprint looks up (and may miss): the line-buffer slots the texel
// cache stage needs free before it accepts a footprint (rtl/cache_stage.hpp).
inline constexpr int kMaxFootprintLines = static_cast<int>(std::tuple_size_v<decltype(FootprintResult::missed_lines)>);

class TexelCache {
 public:
  // The line grids of every level of every texture in `textures` (the unit's descriptor table).
  TexelCache(TexelCacheConfig cfg, const std::vector<TextureDescriptor>& textures);
  const TexelCacheConfig& config() const { return cfg_; }
  // Looks up every used tap of one footprint (allocating missed lines, LRU update, lines in the
  // order the taps first reach them, row-major) and reports hits, misses and the bank cycles.
  // Taps that share a line count one access to that line. On a level of compressed lines
  // (CacheHolds::Compressed) the grid is in blocks (the ports above).
  FootprintResult access(int texture, int level, const TapGrid& grid) {
    const size_t l = level_index(texture, level);
    if (cfg_.bank_mapping == BankMapping::BlockParity && grid.cols == 2 && grid.rows == 2 &&
        grid.used == square_cells(2, 2))
      return access_quad(l, grid);  // every LINEAR footprint
    return access_grid(l, grid);
  }
  // access() of a 2 x 2 footprint whose four taps are all used (the recurrences' LINEAR quad path):
  // inline, so that the caller keeps the result in registers.
  [[gnu::always_inline]] FootprintResult access_square(int texture, int level, const TapGrid& grid) {
    const size_t l = level_index(texture, level);
    if (cfg_.bank_mapping == BankMapping::BlockParity) [[likely]]
      return access_quad(l, grid);
    return access_grid(l, grid);
  }
  // access_square of `n` footprints in order (the recurrences' probe and LINEAR quad paths: a
  // quad's level footprints), footprint j on level levels[j % nlevels] (nlevels 1 or 2) with grid grids[j]:
  // out[j] its bank cycles and misses, whose lines go to missed[first_miss ...] (`nmissed` the
  // list's length, advanced); counts[j % nlevels] summed. The per-level work once per batch
  // (rtl/texel_cache_probe_squares.cpp, software speed only; its plain twin is access_square).
  void access_squares(int texture, const std::array<int, 2>& levels, int nlevels, const TapGrid* grids, size_t n,
                      SquareLookup* out, uint64_t* missed, uint16_t& nmissed, std::array<LineCounts, 2>& counts);
  // access() of a full 4 x 4 grid (every cell used: CUBIC's footprint with a 4-tap ROM), for the
  // recurrences' CUBIC quad path: its lines, bank cycles and sectors in closed form
  // (rtl/texel_cache_full_squares.cpp, software speed only; its plain twin is access_grid); any
  // other grid goes to access().
  FootprintResult access_square4(int texture, int level, const TapGrid& grid);
  // Decoded lines of a compressed level (CacheHolds::Decoded): how many blocks a fill of `line`
  // fetches (those covering the line's tile, clipped to the level), and in `texels` the tile's
  // texels inside the level (what the decoders produce).
  int fill_blocks(int texture, int level, uint64_t line, int& texels) const;
  // Memory line address of texel (x, y) of `level` of `texture` (of block column x, block row y on
  // a level of compressed lines).
  uint64_t line_of(int texture, int level, int x, int y) const;
  // Tag probe without allocation or LRU update (the kernel-shape selector's cache-aware policy),
  // of the line of (x, y) as line_of takes it.
  bool resident(int texture, int level, int x, int y) const;
  // Lines found / fetched, by texture and by level.
  uint64_t texture_hits(int texture) const;
  uint64_t texture_misses(int texture) const;
  uint64_t level_hits(int level) const;
  uint64_t level_misses(int level) const;
  // 32-byte sectors found / looked up, over every texture and level.
  uint64_t sector_hits() const;
  uint64_t sector_lookups() const;
  int textures() const { return static_cast<int>(first_level_.size()) - 1; }
  void reset();

 private:
  TexelCacheConfig cfg_;
  int ways_per_set_;                 // cfg_.way_count()
  int line_log2_;                    // log2 line_bytes
  bool block_runs_;                  // the block-run fast path is on (cmodel/fast_paths.hpp), read once
  std::vector<LevelLines> lines_;    // every level of every texture
  std::vector<size_t> first_level_;  // texture t's levels: lines_[first_level_[t] ...]
  std::vector<int> level_of_;        // lines_ entry -> its level number
  std::vector<int> texture_of_;      // lines_ entry -> its texture
  size_t level_index(int texture, int level) const { return first_level_[static_cast<size_t>(texture)] + static_cast<size_t>(level); }
  uint64_t set_mask_ = 0;  // sets - 1 when sets is a power of two (> 1), else 0 (use %)
  size_t set_of(uint64_t line) const;
  struct Way {
    uint64_t tag = ~uint64_t{0};
    uint64_t last_use = 0;
  };
  std::vector<Way> ways_;  // sets * ways
  uint64_t tick_ = 0;
  // Software memo (not hardware state): per slot (line address mod kHints) the way of the latest
  // lookup of a line in that slot, checked against the way's tag before use, so that runs of
  // footprints in a few lines (of several interleaved textures) skip the way search. Hit, miss and
  // LRU behaviour are those of the search.
  static constexpr size_t kHints = 1024;
  std::array<uint32_t, kHints> hint_{};
  // Per lines_ entry (texture and level): its counters, and the shifts that take a tap's column and
  // row to its sector's column and row part (access_quad).
  struct LevelCounters {
    uint64_t hits = 0, misses = 0;
    uint64_t sector_hits = 0, sector_lookups = 0;
  };
  std::vector<LevelCounters> counters_;
  struct SectorShifts {
    int x = 0, y = 0;
  };
  std::vector<SectorShifts> sector_shifts_;
  bool lookup(uint64_t line);  // true on hit; allocates (LRU victim) on miss
  // The sector of tap (x, y) inside its line of level ll, as a bit of a line's sector mask: the
  // tap's index in the line, ((y mod 2^shift_y) << shift_x) + x mod 2^shift_x (row-major in a
  // tile, the column in a linear row or block row), times its bytes 2^(log2 line_bytes - shift_x -
  // shift_y) (a texel's or a block's), / 32.
  uint32_t sector_bit(const LevelLines& ll, int x, int y) const {
    const int index = ((y & ((1 << ll.shift_y) - 1)) << ll.shift_x) | (x & ((1 << ll.shift_x) - 1));
    const int bytes_log2 = line_log2_ - ll.shift_x - ll.shift_y;
    return 1u << ((index << bytes_log2) / kSectorBytes);
  }
  FootprintResult access_quad(size_t l, const TapGrid& g);
  SquareLookup square_lines(const LevelLines& ll, SectorShifts k, bool four_banks, const TapGrid& g, uint64_t* missed,
                            uint16_t& nmissed, LineCounts& sum);
  FootprintResult access_grid(size_t l, const TapGrid& g);
  struct FillTile {  // CacheHolds::Decoded, per lines_ entry of a compressed level: fill_blocks()
    int tile_log2 = 0, width = 0, height = 0, block_w = 1, block_h = 1;
  };
  std::vector<FillTile> fill_;  // The lookup tail both share: one line into r's hits or misses; the level's counters.
  bool probe(uint64_t line, FootprintResult& r);                    // true on a hit
  void probe(uint64_t line, uint32_t sectors, FootprintResult& r);  // and the sectors of its mask
  void tally(size_t l, const FootprintResult& r);
  // The distinct lines of one footprint, in the order its row-major taps first reach them (the LRU
  // order), and the reads per bank: distinct lines (block parity) or distinct texels (texel parity).
  struct LineSet {
    std::array<uint64_t, 16> lines;  // [0, n) written and read
    std::array<uint32_t, 16> sectors{};  // per line, the sector mask of the taps in it (line_sectors)
    size_t n = 0;
    std::array<int, 4> nbank{};
  };
  void group_lines(size_t l, const TapGrid& g, LineSet& s) const;
  // group_lines and line_sectors for a 4 x 4 grid of column and row runs in at most two lines per
  // axis (software speed only, rtl/texel_cache_block_runs.cpp); false (nothing written) for any
  // other grid.
  bool block_run_lines(size_t l, const TapGrid& g, LineSet& s) const;
  void cell_lines(size_t l, const TapGrid& g, LineSet& s) const;
  void line_sectors(size_t l, const TapGrid& g, LineSet& s) const;
};

// Inline: the tag lookup and the 2x2 path run once per LINEAR pixel.

inline size_t TexelCache::set_of(uint64_t line) const {
  return set_mask_ ? static_cast<size_t>(line & set_mask_) : static_cast<size_t>(line % static_cast<uint64_t>(cfg_.sets()));
}

[[gnu::always_inline]] inline bool TexelCache::lookup(uint64_t line) {
  ++tick_;
  uint32_t& hint = hint_[line & (kHints - 1)];
  if (ways_[hint].tag == line) {  // the line is still in the way its slot remembers (a hit)
    ways_[hint].last_use = tick_;
    return true;
  }
  Way* w = &ways_[set_of(line) * static_cast<size_t>(ways_per_set_)];
  Way* victim = w;
  for (int i = 0; i < ways_per_set_; ++i) {
    if (w[i].tag == line) {
      w[i].last_use = tick_;
      hint = static_cast<uint32_t>(&w[i] - ways_.data());
      return true;
    }
    if (w[i].last_use < victim->last_use) victim = &w[i];
  }
  victim->tag = line;  // least recently used (an empty way has last_use 0)
  victim->last_use = tick_;
  hint = static_cast<uint32_t>(victim - ways_.data());
  return false;
}

[[gnu::always_inline]] inline bool TexelCache::probe(uint64_t line, FootprintResult& r) {
  if (lookup(line)) {
    ++r.hits;
    return true;
  }
  r.missed_lines[static_cast<size_t>(r.misses++)] = line;
  return false;
}

[[gnu::always_inline]] inline void TexelCache::probe(uint64_t line, uint32_t sectors, FootprintResult& r) {
  const int n = std::popcount(sectors);
  r.sector_lookups += n;
  if (probe(line, r)) r.sector_hits += n;
}

inline void TexelCache::tally(size_t l, const FootprintResult& r) {
  LevelCounters& c = counters_[l];
  c.hits += static_cast<uint64_t>(r.hits);
  c.misses += static_cast<uint64_t>(r.misses);
  c.sector_hits += static_cast<uint64_t>(r.sector_hits);
  c.sector_lookups += static_cast<uint64_t>(r.sector_lookups);
}

// The bilinear 2x2 footprint under block parity: its block columns bx0, bx1 and rows by0, by1 give
// one, two or four lines, looked up row-major, each with the sectors of its taps. Banks: the lines in one bank share the parity of bx
// and of by, so per axis two distinct blocks of equal parity (a wrap over an odd number of blocks)
// put two lines into every bank touched; with one bank every line is a read.
[[gnu::always_inline]] inline FootprintResult TexelCache::access_quad(size_t l, const TapGrid& g) {
  const LevelLines& ll = lines_[l];
  const int bx0 = g.x[0] >> ll.shift_x, bx1 = g.x[1] >> ll.shift_x;
  const int by0 = g.y[0] >> ll.shift_y, by1 = g.y[1] >> ll.shift_y;
  const uint64_t row = ll.stride;
  const uint64_t line0 = ll.first + static_cast<uint64_t>(by0) * row + static_cast<uint64_t>(bx0);
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
  // Sectors (sector_bit's rule without a mask per line): a tap's byte offset in its line is
  // (row in the line << (shift_x + b)) | (column in the line << b), b = log2 of a texel's or a
  // block's bytes, so its sector (offset >> kSectorBytesLog2) is a pair (row >> ky, column >> kx),
  // one to one, with kx = max(0, 5 - b), ky = max(0, 5 - shift_x - b) (per level: sector_shifts_).
  // A line's taps are the product of its columns and its rows, so it holds (distinct column
  // sectors) x (distinct row sectors): two columns in one line 1 or 2 (x0 >> kx against x1 >> kx),
  // columns in two lines 1 each; rows alike. Every line of the footprint has the same count:
  // lookups and hits times it.
  const SectorShifts k = sector_shifts_[l];
  const int kx = k.x, ky = k.y;
  const int per_line =
      (two_cols || (g.x[0] >> kx) == (g.x[1] >> kx) ? 1 : 2) * (two_rows || (g.y[0] >> ky) == (g.y[1] >> ky) ? 1 : 2);
  r.sector_lookups = (r.hits + r.misses) * per_line;
  r.sector_hits = r.hits * per_line;
  if (cfg_.banks == 4) {
    r.cycles = (two_cols && !((bx0 ^ bx1) & 1) ? 2 : 1) * (two_rows && !((by0 ^ by1) & 1) ? 2 : 1);
  } else {
    r.cycles = (two_cols ? 2 : 1) * (two_rows ? 2 : 1);
  }
  tally(l, r);
  return r;
}

}  // namespace tfu::rtl
