#include "rtl/texel_cache.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu::rtl {

void TexelCacheConfig::validate() const {
  if (block != 4 && block != 8) throw InputError(fmt::format("cache block {} must be 4 or 8 texels", block));
  if (bytes_per_texel != 1 && bytes_per_texel != 4)
    throw InputError(fmt::format("cache bytes_per_texel {} must be 1 or 4", bytes_per_texel));
  if (ways < 1) throw InputError(fmt::format("cache ways {} must be at least 1", ways));
  if (banks != 1 && banks != 4) throw InputError(fmt::format("cache banks {} must be 1 or 4", banks));
  if (capacity_bytes < line_bytes() * ways)
    throw InputError(fmt::format("cache capacity {} bytes is below one set ({} ways x {}-byte lines)", capacity_bytes, ways,
                                 line_bytes()));
  if (capacity_bytes % (line_bytes() * ways) != 0)
    throw InputError(fmt::format("cache capacity {} bytes is not a whole number of {}-way sets of {}-byte lines",
                                 capacity_bytes, ways, line_bytes()));
}

TexelCache::TexelCache(TexelCacheConfig cfg, std::vector<int> level_widths, std::vector<int> level_heights)
    : cfg_(cfg) {
  cfg_.validate();
  while ((1 << block_shift_) < cfg_.block) ++block_shift_;
  const auto sets = static_cast<uint64_t>(cfg_.sets());
  set_mask_ = (sets & (sets - 1)) == 0 ? sets - 1 : 0;  // power of two: a mask instead of a division
  if (sets == 1) set_mask_ = 0;
  if (level_widths.size() != level_heights.size() || level_widths.empty())
    throw InputError("texel cache: level sizes missing");
  uint64_t base = 0;
  for (size_t l = 0; l < level_widths.size(); ++l) {
    const int bx = (level_widths[l] + cfg_.block - 1) / cfg_.block;
    const int by = (level_heights[l] + cfg_.block - 1) / cfg_.block;
    blocks_per_row_.push_back(bx);
    level_base_.push_back(base);
    base += static_cast<uint64_t>(bx) * static_cast<uint64_t>(by);
  }
  ways_.resize(static_cast<size_t>(cfg_.sets()) * static_cast<size_t>(cfg_.ways));
  hits_.assign(level_widths.size(), 0);
  misses_.assign(level_widths.size(), 0);
}

uint64_t TexelCache::line_of(int level, int x, int y) const {
  const auto l = static_cast<size_t>(level);
  return level_base_[l] + static_cast<uint64_t>(y >> block_shift_) * static_cast<uint64_t>(blocks_per_row_[l]) +
         static_cast<uint64_t>(x >> block_shift_);
}

bool TexelCache::resident(int level, int x, int y) const {
  const uint64_t line = line_of(level, x, y);
  const size_t set = set_of(line);
  const Way* w = &ways_[set * static_cast<size_t>(cfg_.ways)];
  for (int i = 0; i < cfg_.ways; ++i)
    if (w[i].tag == line) return true;
  return false;
}

size_t TexelCache::set_of(uint64_t line) const {
  return set_mask_ ? static_cast<size_t>(line & set_mask_) : static_cast<size_t>(line % static_cast<uint64_t>(cfg_.sets()));
}

bool TexelCache::lookup(uint64_t line) {
  ++tick_;
  const size_t set = set_of(line);
  Way* w = &ways_[set * static_cast<size_t>(cfg_.ways)];
  Way* victim = w;
  for (int i = 0; i < cfg_.ways; ++i) {
    if (w[i].tag == line) {
      w[i].last_use = tick_;
      return true;
    }
    if (w[i].last_use < victim->last_use) victim = &w[i];
  }
  victim->tag = line;  // least recently used (an empty way has last_use 0)
  victim->last_use = tick_;
  return false;
}

FootprintResult TexelCache::access(int level, std::span<const TexelTap> taps) {
  FootprintResult r;
  const auto l = static_cast<size_t>(level);
  const uint64_t base = level_base_[l];
  const auto row = static_cast<uint64_t>(blocks_per_row_[l]);
  const bool four_banks = cfg_.banks == 4;
  // Distinct lines of the footprint (only the first nlines entries are written and read).
  std::array<uint64_t, 16> lines;
  size_t nlines = 0;
  // Reads per bank: the distinct lines (block parity) or distinct texels (texel parity) in it.
  std::array<int, 4> nbank{};
  if (cfg_.bank_mapping == BankMapping::BlockParity) {
    for (const TexelTap& t : taps) {
      const int bx = t.x >> block_shift_, by = t.y >> block_shift_;
      const uint64_t line = base + static_cast<uint64_t>(by) * row + static_cast<uint64_t>(bx);
      size_t i = 0;
      while (i < nlines && lines[i] != line) ++i;
      if (i < nlines) continue;  // a line already read: no second bank read either
      lines[nlines++] = line;
      ++nbank[four_banks ? static_cast<size_t>((bx & 1) + 2 * (by & 1)) : 0];
    }
  } else {
    std::array<uint32_t, 16> texels;  // distinct texels, packed y:x (16 bits each)
    size_t ntexels = 0;
    for (const TexelTap& t : taps) {
      const uint64_t line = base + static_cast<uint64_t>(t.y >> block_shift_) * row + static_cast<uint64_t>(t.x >> block_shift_);
      size_t i = 0;
      while (i < nlines && lines[i] != line) ++i;
      if (i == nlines) lines[nlines++] = line;
      const uint32_t texel = (static_cast<uint32_t>(t.y) << 16) | static_cast<uint32_t>(t.x);
      size_t k = 0;
      while (k < ntexels && texels[k] != texel) ++k;
      if (k < ntexels) continue;
      texels[ntexels++] = texel;
      ++nbank[four_banks ? static_cast<size_t>((t.x & 1) + 2 * (t.y & 1)) : 0];
    }
  }
  for (size_t i = 0; i < nlines; ++i) {
    if (lookup(lines[i])) {
      ++r.hits;
    } else {
      r.missed_lines[static_cast<size_t>(r.misses++)] = lines[i];
    }
  }
  r.cycles = std::max(std::max(1, nbank[0]), std::max(std::max(nbank[1], nbank[2]), nbank[3]));
  hits_[l] += static_cast<uint64_t>(r.hits);
  misses_[l] += static_cast<uint64_t>(r.misses);
  return r;
}

void TexelCache::reset() {
  std::fill(ways_.begin(), ways_.end(), Way{});
  std::fill(hits_.begin(), hits_.end(), 0);
  std::fill(misses_.begin(), misses_.end(), 0);
  tick_ = 0;
}

}  // namespace tfu::rtl
