// The probe quad path's batched tag lookup (rtl/texel_cache_probe_squares.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include <fmt/format.h>

#include "cmodel/descriptors.hpp"
#include "cmodel/texture_memory.hpp"
#include "rtl/texel_cache.hpp"
#include "testbench/cache_pairs.hpp"
#include "testbench/iterations.hpp"

namespace tfu::rtl {
namespace {

// access_squares of a batch of 2 x 2 footprints (a pixel's probe footprints: level0, level1,
// level0, ... or one level) gives what access_square gives footprint by footprint on a second cache
// fed the same stream: per footprint its bank cycles, misses and missed lines in order; per level
// the hits, misses and sectors summed; at the end every counter of the cache. Footprints inside the
// level (every offset against the line grid), wrapped across its right or bottom edge and clamped
// at it (levels down to 1 x 1: one column or row), on tiled and linear-row levels of RGBA8 and L8
// textures, both bank mappings, 1 and 4 banks, 64- to 1024-byte lines, 1 to 4 ways (misses,
// evictions and the LRU order all matter), batches of 1 to 32 footprints.
TEST(TexelCache, ProbeSquaresEqualAccessSquare) {
  std::mt19937 rng(29);
  int footprints = 0, missed = 0, two_lines = 0;
  test::for_every_cache_pair(
      [&](const TexelCacheConfig& cfg, const std::vector<TextureDescriptor>& tex, TexelCache& fast, TexelCache& plain) {
        for (int batch = 0; batch < test::iterations(120); ++batch) {
          const int t = static_cast<int>(rng() % tex.size()), nlevels = 1 + static_cast<int>(rng() % 2);
          const int level0 = static_cast<int>(rng() % (test::kCachePairLevels - 1));
          const std::array<int, 2> levels{level0, nlevels == 2 ? level0 + 1 : level0};
          const size_t n = static_cast<size_t>(nlevels) * (1 + rng() % 16);
          std::vector<TapGrid> grids(n);
          for (size_t j = 0; j < n; ++j) {
            const TextureDescriptor& d = tex[static_cast<size_t>(t)];
            const int level = levels[j % static_cast<size_t>(nlevels)];
            const int w = d.level_width(level), h = d.level_height(level);
            TapGrid& g = grids[j];
            g.cols = g.rows = 2;
            g.used = square_cells(2, 2);
            const int x0 = static_cast<int>(rng() % static_cast<uint32_t>(w)),
                      y0 = static_cast<int>(rng() % static_cast<uint32_t>(h));
            const bool clamp = rng() % 2 == 0;  // at the right or bottom edge: clamped, else wrapped to 0
            g.x[0] = static_cast<int16_t>(x0);
            g.y[0] = static_cast<int16_t>(y0);
            g.x[1] = static_cast<int16_t>(x0 + 1 < w ? x0 + 1 : clamp ? x0 : 0);
            g.y[1] = static_cast<int16_t>(y0 + 1 < h ? y0 + 1 : clamp ? y0 : 0);
          }
          std::vector<SquareLookup> got(n);
          std::vector<uint64_t> got_missed(4 * n);
          uint16_t nmissed = 0;
          std::array<LineCounts, 2> counts{};
          fast.access_squares(t, levels, nlevels, grids.data(), n, got.data(), got_missed.data(), nmissed, counts);
          std::array<LineCounts, 2> want_counts{};
          size_t want_missed = 0;
          for (size_t j = 0; j < n; ++j) {
            const size_t k = j % static_cast<size_t>(nlevels);
            const FootprintResult want = plain.access_square(t, levels[k], grids[j]);
            const auto where = [&] {
              return fmt::format("mapping {} cfg.banks {} line {} cfg.ways {}: batch {} footprint {}",
                                 static_cast<int>(cfg.bank_mapping), cfg.banks, cfg.line_bytes, cfg.ways, batch, j);
            };
            ASSERT_EQ(got[j].cycles, want.cycles) << where();
            ASSERT_EQ(got[j].misses, want.misses) << where();
            ASSERT_EQ(got[j].first_miss, want_missed) << where();
            for (size_t m = 0; m < static_cast<size_t>(want.misses); ++m)
              ASSERT_EQ(got_missed[want_missed + m], want.missed_lines[m]) << where();
            want_missed += static_cast<size_t>(want.misses);
            want_counts[k].hits += want.hits;
            want_counts[k].misses += want.misses;
            want_counts[k].sector_hits += want.sector_hits;
            want_counts[k].sector_lookups += want.sector_lookups;
            missed += want.misses;
            two_lines += want.hits + want.misses > 1 ? 1 : 0;
          }
          ASSERT_EQ(nmissed, want_missed);
          for (size_t k = 0; k < 2; ++k) {
            EXPECT_EQ(counts[k].hits, want_counts[k].hits) << "batch " << batch;
            EXPECT_EQ(counts[k].misses, want_counts[k].misses) << "batch " << batch;
            EXPECT_EQ(counts[k].sector_hits, want_counts[k].sector_hits) << "batch " << batch;
            EXPECT_EQ(counts[k].sector_lookups, want_counts[k].sector_lookups) << "batch " << batch;
          }
          footprints += static_cast<int>(n);
        }
      });
  // The stream exercises misses and footprints of two and four lines.
  EXPECT_GT(missed, footprints / 10);
  EXPECT_GT(two_lines, footprints / 10);
}

}  // namespace
}  // namespace tfu::rtl
