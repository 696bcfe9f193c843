#include "rtl/texel_cache.hpp"

#include <algorithm>
#include <bit>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/fast_paths.hpp"

namespace tfu::rtl {

void TexelCacheConfig::validate() const {
  // 64-bit: no overflow for any int fields; fully associative (ways 0): one set of whole lines.
  const auto set_bytes = static_cast<int64_t>(line_bytes) * (ways == 0 ? 1 : ways);
  if (line_bytes != 64 && line_bytes != 256 && line_bytes != 1024)
    throw InputError(fmt::format("cache line_bytes {} must be 64, 256 or 1024", line_bytes));
  if (ways < 0) throw InputError(fmt::format("cache ways {} must be at least 1, or 0 (fully associative)", ways));
  if (banks != 1 && banks != 4) throw InputError(fmt::format("cache banks {} must be 1 or 4", banks));
  if (capacity_bytes < set_bytes)
    throw InputError(fmt::format("cache capacity {} bytes is below one set ({} ways x {}-byte lines)", capacity_bytes, ways,
                                 line_bytes));
  if (capacity_bytes % set_bytes != 0)
    throw InputError(fmt::format("cache capacity {} bytes is not a whole number of {}-way sets of {}-byte lines",
                                 capacity_bytes, ways, line_bytes));
  if (ways == 0 && capacity_bytes / line_bytes > kMaxFullyAssociativeLines)
    throw InputError(fmt::format("cache capacity {} bytes is {} lines: a fully associative cache (ways 0) holds at most {}",
                                 capacity_bytes, capacity_bytes / line_bytes, kMaxFullyAssociativeLines));
}

LevelLines level_lines(const TextureDescriptor& d, int level, int line_bytes, const std::string& what) {
  const LevelDescriptor& ld = d.level[static_cast<size_t>(level)];
  const auto lb = static_cast<uint64_t>(line_bytes);
  if (ld.address % lb != 0 || ld.row_pitch % lb != 0)
    throw InputError(fmt::format("{}: level {} (address {:#x}, row pitch {}) is not aligned to the {}-byte cache line", what,
                                 level, ld.address, ld.row_pitch, line_bytes));
  LevelLines ll;
  ll.first = ld.address / lb;
  ll.stride = ld.row_pitch / lb;
  if (d.compressed) {  // block rows (cmodel/texture_memory.hpp): line_bytes / block_bytes blocks per line
    ll.shift_x = std::countr_zero(static_cast<unsigned>(line_bytes / d.block().block_bytes));
    ll.shift_y = 0;
    return ll;
  }
  if (d.layout == MemoryLayout::Tiled) {
    if (d.tile_bytes() != line_bytes)
      throw InputError(fmt::format("{}: its {}-byte tiles are not one {}-byte cache line each", what, d.tile_bytes(), line_bytes));
    ll.shift_x = ll.shift_y = d.tile_log2;
  } else {
    ll.shift_x = std::countr_zero(static_cast<unsigned>(line_bytes / bytes_per_texel(d.format)));
    ll.shift_y = 0;
  }
  return ll;
}

TexelCache::TexelCache(TexelCacheConfig cfg, const std::vector<TextureDescriptor>& textures)
    : cfg_(cfg), block_runs_(fast_paths_enabled()) {
  cfg_.validate();
  ways_per_set_ = cfg_.way_count();
  line_log2_ = std::countr_zero(static_cast<unsigned>(cfg_.line_bytes));
  const auto sets = static_cast<uint64_t>(cfg_.sets());
  set_mask_ = (sets & (sets - 1)) == 0 ? sets - 1 : 0;  // power of two: a mask instead of a division
  if (sets == 1) set_mask_ = 0;
  // Decoded lines of compressed levels: tiles of line_bytes / 4 texels, tagged from 2^41 / line_bytes
  // up (above every memory line: addresses are below 2^40), level after level.
  const int tile_log2 = std::countr_zero(static_cast<unsigned>(cfg_.line_bytes / 4)) / 2;
  uint64_t decoded_next = (uint64_t{1} << 41) / static_cast<uint64_t>(cfg_.line_bytes);
  for (size_t t = 0; t < textures.size(); ++t) {
    first_level_.push_back(lines_.size());
    for (int l = 0; l < textures[t].levels; ++l) {
      const TextureDescriptor& d = textures[t];
      FillTile fill;
      if (d.compressed && cfg_.holds == CacheHolds::Decoded) {
        LevelLines ll;
        const int w = d.level_width(l), h = d.level_height(l);
        ll.first = decoded_next;
        ll.stride = static_cast<uint64_t>((w + (1 << tile_log2) - 1) >> tile_log2);
        ll.shift_x = ll.shift_y = tile_log2;
        decoded_next += ll.stride * static_cast<uint64_t>((h + (1 << tile_log2) - 1) >> tile_log2);
        fill = {tile_log2, w, h, d.block().block_w, d.block().block_h};
        lines_.push_back(ll);
        fill_.push_back(fill);
        level_of_.push_back(l);
        texture_of_.push_back(static_cast<int>(t));
        continue;
      }
      fill_.push_back(fill);
      lines_.push_back(level_lines(textures[t], l, cfg_.line_bytes, fmt::format("texture {}", t)));
      level_of_.push_back(l);
      texture_of_.push_back(static_cast<int>(t));
    }
  }
  first_level_.push_back(lines_.size());
  ways_.resize(static_cast<size_t>(cfg_.sets()) * static_cast<size_t>(ways_per_set_));
  counters_.assign(lines_.size(), LevelCounters{});
  for (const LevelLines& ll : lines_) {  // access_quad's kx and ky
    const int b = line_log2_ - ll.shift_x - ll.shift_y;
    sector_shifts_.push_back({std::max(0, kSectorBytesLog2 - b), std::max(0, kSectorBytesLog2 - ll.shift_x - b)});
  }
}

int TexelCache::fill_blocks(int texture, int level, uint64_t line, int& texels) const {
  const size_t l = level_index(texture, level);
  const LevelLines& ll = lines_[l];
  const FillTile& f = fill_[l];
  const uint64_t offset = line - ll.first;
  const int ty = static_cast<int>(offset / ll.stride), tx = static_cast<int>(offset % ll.stride);
  const int side = 1 << f.tile_log2;
  const int x0 = tx * side, x1 = std::min(x0 + side, f.width) - 1, y0 = ty * side,
            y1 = std::min(y0 + side, f.height) - 1;
  texels = (x1 - x0 + 1) * (y1 - y0 + 1);
  return (x1 / f.block_w - x0 / f.block_w + 1) * (y1 / f.block_h - y0 / f.block_h + 1);
}

uint64_t TexelCache::line_of(int texture, int level, int x, int y) const {
  const LevelLines& ll = lines_[level_index(texture, level)];
  return ll.first + static_cast<uint64_t>(y >> ll.shift_y) * ll.stride + static_cast<uint64_t>(x >> ll.shift_x);
}

bool TexelCache::resident(int texture, int level, int x, int y) const {
  const uint64_t line = line_of(texture, level, x, y);
  const size_t set = set_of(line);
  const Way* w = &ways_[set * static_cast<size_t>(ways_per_set_)];
  for (int i = 0; i < ways_per_set_; ++i)
    if (w[i].tag == line) return true;
  return false;
}

uint64_t TexelCache::texture_hits(int texture) const {
  uint64_t n = 0;
  for (size_t l = first_level_[static_cast<size_t>(texture)]; l < first_level_[static_cast<size_t>(texture) + 1]; ++l)
    n += counters_[l].hits;
  return n;
}
uint64_t TexelCache::texture_misses(int texture) const {
  uint64_t n = 0;
  for (size_t l = first_level_[static_cast<size_t>(texture)]; l < first_level_[static_cast<size_t>(texture) + 1]; ++l)
    n += counters_[l].misses;
  return n;
}
uint64_t TexelCache::level_hits(int level) const {
  uint64_t n = 0;
  for (size_t l = 0; l < lines_.size(); ++l) n += level_of_[l] == level ? counters_[l].hits : 0;
  return n;
}
uint64_t TexelCache::level_misses(int level) const {
  uint64_t n = 0;
  for (size_t l = 0; l < lines_.size(); ++l) n += level_of_[l] == level ? counters_[l].misses : 0;
  return n;
}
uint64_t TexelCache::sector_hits() const {
  uint64_t n = 0;
  for (const LevelCounters& c : counters_) n += c.sector_hits;
  return n;
}
uint64_t TexelCache::sector_lookups() const {
  uint64_t n = 0;
  for (const LevelCounters& c : counters_) n += c.sector_lookups;
  return n;
}

namespace {

// Column and row groups of a grid, padded to 4 x 4 with column / row 0 (unused cells never read the
// padding): the distinct values of x >> shift_x over the columns (vx[0, nx)) and of y >> shift_y
// over the rows, in order of first appearance, and per grid column / row the index of its group.
// With the level's line shifts, taps share a line iff they share both groups; with 0, a texel.
struct GridGroups {
  std::array<int, 4> vx, vy;
  std::array<uint8_t, 4> gx, gy;
  int nx, ny;
  GridGroups(const TapGrid& g, int shift_x, int shift_y) {
    std::array<int, 4> cx, cy;
    for (size_t i = 0; i < 4; ++i) {
      cx[i] = g.x[i < static_cast<size_t>(g.cols) ? i : 0] >> shift_x;
      cy[i] = g.y[i < static_cast<size_t>(g.rows) ? i : 0] >> shift_y;
    }
    nx = distinct(cx, vx, gx);
    ny = distinct(cy, vy, gy);
  }
  static int distinct(const std::array<int, 4>& v, std::array<int, 4>& out, std::array<uint8_t, 4>& group) {
    // A run that steps by 0 or 1 (no wrap inside the footprint, the common case): the values are
    // v[0], v[0] + 1, ..., v[3], met in that order (out[] past them is never read).
    const int d1 = v[1] - v[0], d2 = v[2] - v[1], d3 = v[3] - v[2];
    if (static_cast<unsigned>(d1) <= 1u && static_cast<unsigned>(d2) <= 1u && static_cast<unsigned>(d3) <= 1u) {
      for (size_t i = 0; i < 4; ++i) {
        out[i] = v[0] + static_cast<int>(i);
        group[i] = static_cast<uint8_t>(v[i] - v[0]);
      }
      return v[3] - v[0] + 1;
    }
    int m = 0;
    for (size_t i = 0; i < 4; ++i) {
      int k = 0;
      while (k < m && out[static_cast<size_t>(k)] != v[i]) ++k;
      if (k == m) out[static_cast<size_t>(m++)] = v[i];
      group[i] = static_cast<uint8_t>(k);
    }
    return m;
  }
};

}  // namespace

// Any set of used cells of a grid under block parity: the lines are the (block column, block row)
// groups that hold a used cell, each looked up when the row-major scan of the cells first reaches
// it, i.e. in order of its lowest used cell.
void TexelCache::group_lines(size_t l, const TapGrid& g, LineSet& s) const {
  const LevelLines& ll = lines_[l];
  const GridGroups b(g, ll.shift_x, ll.shift_y);
  std::array<uint16_t, 4> col_cells{}, row_cells{};  // grid cells of each block column / row group
  for (size_t i = 0; i < 4; ++i) col_cells[b.gx[i]] = static_cast<uint16_t>(col_cells[b.gx[i]] | (0x1111u << i));
  for (size_t j = 0; j < 4; ++j) row_cells[b.gy[j]] = static_cast<uint16_t>(row_cells[b.gy[j]] | (0xFu << (4 * j)));
  std::array<uint32_t, 16> key;  // first cell << 8 | by group << 4 | bx group, [0, n)
  size_t n = 0;
  for (size_t h = 0; h < static_cast<size_t>(b.ny); ++h)
    for (size_t k = 0; k < static_cast<size_t>(b.nx); ++k) {
      const uint32_t cells = g.used & col_cells[k] & row_cells[h];
      if (cells == 0) continue;
      uint32_t v = static_cast<uint32_t>(std::countr_zero(cells)) << 8 | static_cast<uint32_t>(h << 4 | k);
      size_t m = n++;
      for (; m > 0 && key[m - 1] > v; --m) key[m] = key[m - 1];  // insertion by first cell
      key[m] = v;
    }
  const uint64_t base = ll.first, row = ll.stride;
  for (size_t m = 0; m < n; ++m) {
    const int bx = b.vx[key[m] & 15u], by = b.vy[(key[m] >> 4) & 15u];
    s.lines[s.n++] = base + static_cast<uint64_t>(by) * row + static_cast<uint64_t>(bx);
    ++s.nbank[cfg_.banks == 4 ? static_cast<size_t>((bx & 1) + 2 * (by & 1)) : 0];
  }
}

// Any set of used cells under texel parity: a scan of the used cells in row-major order; the
// banks count distinct texels.
void TexelCache::cell_lines(size_t l, const TapGrid& g, LineSet& s) const {
  const LevelLines& ll = lines_[l];
  const GridGroups b(g, ll.shift_x, ll.shift_y), t(g, 0, 0);
  const bool four_banks = cfg_.banks == 4;
  const uint64_t base = ll.first, row = ll.stride;
  uint32_t seen_line = 0, seen_texel = 0;  // bit 4 gy + gx of the block groups, of the texel groups
  for (uint32_t cells = g.used; cells != 0; cells &= cells - 1) {
    const auto c = static_cast<size_t>(std::countr_zero(cells));
    const size_t i = c & 3, j = c >> 2;
    const uint32_t line_bit = 1u << (4 * b.gy[j] + b.gx[i]);
    if (!(seen_line & line_bit)) {
      seen_line |= line_bit;
      s.lines[s.n++] = base + static_cast<uint64_t>(b.vy[b.gy[j]]) * row + static_cast<uint64_t>(b.vx[b.gx[i]]);
    }
    const uint32_t texel_bit = 1u << (4 * t.gy[j] + t.gx[i]);
    if (!(seen_texel & texel_bit)) {
      seen_texel |= texel_bit;
      ++s.nbank[four_banks ? static_cast<size_t>((g.x[i] & 1) + 2 * (g.y[j] & 1)) : 0];
    }
  }
}

// The sector mask of each line of s: every used tap ORs its sector into the mask of its line.
void TexelCache::line_sectors(size_t l, const TapGrid& g, LineSet& s) const {
  const LevelLines& ll = lines_[l];
  for (uint32_t cells = g.used; cells != 0; cells &= cells - 1) {
    const auto c = static_cast<size_t>(std::countr_zero(cells));
    const int x = g.x[c & 3u], y = g.y[c >> 2];
    const uint64_t line = ll.first + static_cast<uint64_t>(y >> ll.shift_y) * ll.stride + static_cast<uint64_t>(x >> ll.shift_x);
    size_t k = 0;
    while (k + 1 < s.n && s.lines[k] != line) ++k;
    s.sectors[k] |= sector_bit(ll, x, y);
  }
}

// Any other footprint (and every footprint under texel parity): its line set with each line's
// sectors, then the lookups in that order and the bank reads.
FootprintResult TexelCache::access_grid(size_t l, const TapGrid& g) {
  LineSet s;
  if (cfg_.bank_mapping == BankMapping::TexelParity) {
    cell_lines(l, g, s);
    line_sectors(l, g, s);
  } else if (g.cols != 4 || g.rows != 4 || !block_runs_ || !block_run_lines(l, g, s)) {
    group_lines(l, g, s);
    line_sectors(l, g, s);
  }  // else block_run_lines formed the sectors too
  FootprintResult r;
  for (size_t i = 0; i < s.n; ++i) probe(s.lines[i], s.sectors[i], r);
  r.cycles = std::max(std::max(1, s.nbank[0]), std::max(std::max(s.nbank[1], s.nbank[2]), s.nbank[3]));
  tally(l, r);
  return r;
}

void TexelCache::reset() {
  std::fill(ways_.begin(), ways_.end(), Way{});
  hint_.fill(0);
  std::fill(counters_.begin(), counters_.end(), LevelCounters{});
  tick_ = 0;
}

}  // namespace tfu::rtl
