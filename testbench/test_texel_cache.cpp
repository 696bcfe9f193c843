// texel_cache and memory_model: line mapping by memory address (tiled and linear layouts, several
// textures in one cache), LRU, bank conflicts, configuration errors, bandwidth and latency.
#include <algorithm>
#include <deque>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "cmodel/error.hpp"
#include "cmodel/texture_memory.hpp"
#include "rtl/memory_model.hpp"
#include "rtl/texel_cache.hpp"

namespace tfu::rtl {
namespace {

// B = 4: 64-byte lines (4x4 RGBA8 tiles); B = 8: 256-byte lines (8x8).
TexelCacheConfig small(int block, int capacity, int ways, int banks = 4,
                       BankMapping mapping = BankMapping::TexelParity) {
  TexelCacheConfig c;
  c.bank_mapping = mapping;
  c.line_bytes = block * block * 4;
  c.capacity_bytes = capacity;
  c.ways = ways;
  c.banks = banks;
  return c;
}

// A w x h texture with `levels` levels placed in `mem` (one tile per line of `line_bytes`).
TextureDescriptor placed(TextureMemory& mem, int w, int h, int levels, int line_bytes = 64,
                         MemoryLayout layout = MemoryLayout::Tiled, TexelFormat f = TexelFormat::RGBA8) {
  Texture t;
  t.format = f;
  t.layout = layout;
  t.tile_bytes = line_bytes;
  for (int l = 0; l < levels; ++l) t.levels.emplace_back(mip_extent(w, l), mip_extent(h, l));
  return place_texture(mem, t, static_cast<uint64_t>(line_bytes));
}
// One texture in a fresh memory.
std::vector<TextureDescriptor> one(int w, int h, int levels = 1, int line_bytes = 64) {
  TextureMemory mem;
  return {placed(mem, w, h, levels, line_bytes)};
}

// A full grid of the columns xs and rows ys (every tap reads the cache).
TapGrid grid(std::initializer_list<int> xs, std::initializer_list<int> ys) {
  TapGrid g{};
  for (int x : xs) g.x[static_cast<size_t>(g.cols++)] = static_cast<int16_t>(x);
  for (int y : ys) g.y[static_cast<size_t>(g.rows++)] = static_cast<int16_t>(y);
  g.used = square_cells(g.cols, g.rows);
  return g;
}
TapGrid tap(int x, int y) { return grid({x}, {y}); }

TEST(TexelCache, ConfigurationErrorsNameTheField) {
  EXPECT_THROW(small(6, 4096 * 9, 2).validate(), InputError);  // 144-byte lines
  EXPECT_THROW(small(4, 32, 1).validate(), InputError);     // below one 64-byte line
  EXPECT_THROW(small(4, 4096, -1).validate(), InputError);  // negative ways
  EXPECT_NO_THROW(small(4, 4096, 0).validate());            // fully associative: 64 lines in one set
  EXPECT_THROW(small(4, 64 * (kMaxFullyAssociativeLines + 1), 0).validate(), InputError);
  EXPECT_THROW(small(4, 4096, 2, 0).validate(), InputError);  // zero banks
  EXPECT_THROW(small(4, 100, 1).validate(), InputError);    // not whole sets
  EXPECT_NO_THROW(small(8, 256 * 4, 1).validate());
  try {
    small(4, 32, 1).validate();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("capacity 32 bytes"), std::string::npos) << e.what();
  }
}

TEST(TexelCache, LinesAreMemoryAddresses) {
  // A 16x16 RGBA8 texture with two levels at 0x1000, tiled 4x4: level 0 is 4 tile rows of 256
  // bytes (lines 64..79), level 1 (8x8, 2 tiles = 128 bytes per tile row, pitch 256) at 0x1400.
  const TexelCache c(small(4, 4096, 2), one(16, 16, 2));
  EXPECT_EQ(c.line_of(0, 0, 0, 0), 0x1000u / 64);
  EXPECT_EQ(c.line_of(0, 0, 3, 3), 64u);
  EXPECT_EQ(c.line_of(0, 0, 4, 0), 65u);
  EXPECT_EQ(c.line_of(0, 0, 0, 4), 68u);   // 4 tiles per row
  EXPECT_EQ(c.line_of(0, 1, 0, 0), 80u);   // level 1 starts after level 0's 16 lines
  EXPECT_EQ(c.line_of(0, 1, 7, 7), 85u);   // tile (1, 1): pitch 256 = 4 lines per tile row
}

// Property: the line of every texel is its byte address / line_bytes, for both layouts, both
// texel sizes, every line size, odd level sizes, several textures in one memory.
TEST(TexelCache, LineOfEveryTexelIsItsAddressOverTheLineSize) {
  for (const int line : {64, 256, 1024})
    for (const MemoryLayout layout : {MemoryLayout::Tiled, MemoryLayout::Linear}) {
      TextureMemory mem;
      std::vector<TextureDescriptor> d{placed(mem, 37, 11, 4, line, layout),
                                       placed(mem, 50, 70, 3, line, layout, TexelFormat::L8)};
      TexelCacheConfig cfg = small(4, 1 << 20, 4);
      cfg.line_bytes = line;
      const TexelCache c(cfg, d);
      for (int t = 0; t < 2; ++t)
        for (int l = 0; l < d[static_cast<size_t>(t)].levels; ++l)
          for (int y = 0; y < d[static_cast<size_t>(t)].level_height(l); ++y)
            for (int x = 0; x < d[static_cast<size_t>(t)].level_width(l); ++x)
              ASSERT_EQ(c.line_of(t, l, x, y), d[static_cast<size_t>(t)].texel_address(l, x, y) / static_cast<uint64_t>(line))
                  << line << " " << memory_layout_name(layout) << " " << t << " " << l << " " << x << "," << y;
    }
}

TEST(TexelCache, TexturesShareTheCacheWithoutFlush) {
  TextureMemory mem;
  const std::vector<TextureDescriptor> d{placed(mem, 16, 16, 1), placed(mem, 16, 16, 1)};
  TexelCache c(small(4, 4096, 4, 4, BankMapping::BlockParity), d);
  EXPECT_EQ(c.access(0, 0, tap(5, 5)).misses, 1);
  EXPECT_EQ(c.access(1, 0, tap(5, 5)).misses, 1);  // the same texel of another texture: another line
  EXPECT_EQ(c.access(0, 0, tap(5, 5)).hits, 1);    // the first texture's line is still there
  EXPECT_EQ(c.texture_hits(0), 1u);
  EXPECT_EQ(c.texture_misses(1), 1u);
  // A tiled texture whose tiles are not one line is refused, naming it.
  TextureMemory m2;
  const std::vector<TextureDescriptor> big{placed(m2, 16, 16, 1, 256)};
  EXPECT_THROW(TexelCache(small(4, 4096, 4), big), InputError);
}

TEST(TexelCache, BilinearFootprintOneCycleCubicFour) {
  TexelCache c(small(4, 4096, 2), one(16, 16));
  const TapGrid quad = grid({5, 6}, {6, 7});
  FootprintResult r = c.access(0, 0, quad);
  EXPECT_EQ(r.cycles, 1);  // one texel per parity bank
  EXPECT_EQ(r.misses, 1);  // all in block (1, 1)
  EXPECT_EQ(c.access(0, 0, quad).hits, 1);
  const TapGrid cubic = grid({4, 5, 6, 7}, {4, 5, 6, 7});
  EXPECT_EQ(c.access(0, 0, cubic).cycles, 4);  // 16 texels over 4 banks
  TexelCache one_bank(small(4, 4096, 2, 1), one(16, 16));
  EXPECT_EQ(one_bank.access(0, 0, quad).cycles, 4);
  // A footprint across a block corner touches four lines.
  const TapGrid corner = grid({3, 4}, {3, 4});
  const FootprintResult rc = c.access(0, 0, corner);
  EXPECT_EQ(rc.misses + rc.hits, 4);
}

TEST(TexelCache, BlockParityBanksReadWholeLines) {
  TexelCache c(small(4, 4096, 4, 4, BankMapping::BlockParity), one(16, 16));
  const TapGrid cubic = grid({2, 3, 4, 5}, {2, 3, 4, 5});  // 4x4 over the corner of 4 blocks
  EXPECT_EQ(c.access(0, 0, cubic).cycles, 1);                   // one line from each bank
  TapGrid cross = grid({4, 5, 6, 7}, {4, 5, 6, 7});
  cross.used = cross_cells(lee_jen::kAllTexels);  // the 12-texel cross inside block (1, 1)
  EXPECT_EQ(cross.used, 0x6FF6);
  EXPECT_EQ(c.access(0, 0, cross).cycles, 1);
  // Blocks (0, 0) and (2, 0) share bank 0: two cycles.
  EXPECT_EQ(c.access(0, 0, grid({0, 8}, {0})).cycles, 2);
  TexelCache c1(small(4, 4096, 4, 1, BankMapping::BlockParity), one(16, 16));
  EXPECT_EQ(c1.access(0, 0, cubic).cycles, 4);  // four lines through one port
  EXPECT_EQ(c1.access(0, 0, cross).cycles, 1);
}

TEST(TexelCache, ResidencyProbeDoesNotAllocate) {
  TexelCache c(small(4, 4096, 2), one(16, 16));
  EXPECT_FALSE(c.resident(0, 0, 5, 5));
  EXPECT_FALSE(c.resident(0, 0, 5, 5));  // a probe does not allocate
  c.access(0, 0, tap(5, 5));
  EXPECT_TRUE(c.resident(0, 0, 4, 7));   // same block
  EXPECT_FALSE(c.resident(0, 0, 8, 5));
}

TEST(TexelCache, LruEvictsTheLeastRecentlyUsedWay) {
  // Blocks 0, 2, 4 (lines 64, 66, 68) all map to set 0 of a 2-set, 2-way cache.
  TexelCache c(small(4, 256, 2), one(64, 4));  // 4 lines = 2 sets x 2 ways; 16 blocks in one row
  const auto at = [](int block) { return tap(4 * block, 0); };
  EXPECT_EQ(c.access(0, 0, at(0)).misses, 1);
  EXPECT_EQ(c.access(0, 0, at(2)).misses, 1);
  EXPECT_EQ(c.access(0, 0, at(0)).hits, 1);    // 0 becomes most recent
  EXPECT_EQ(c.access(0, 0, at(4)).misses, 1);  // evicts 2, the LRU
  EXPECT_EQ(c.access(0, 0, at(0)).hits, 1);
  EXPECT_EQ(c.access(0, 0, at(2)).misses, 1);
  EXPECT_EQ(c.level_hits(0), 2u);
  EXPECT_EQ(c.level_misses(0), 4u);
}

TEST(TexelCache, ScanlineHitRateOfABlockedCache) {
  // Bilinear footprints along texel rows of a 64x64 texture: each 4x4 block is fetched once per
  // row of blocks when the cache holds a whole row of blocks (16 lines), so misses = 16 x 16.
  TexelCache c(small(4, 64 * 64, 4), one(64, 64));
  uint64_t misses = 0;
  for (int y = 0; y < 63; ++y)
    for (int x = 0; x < 63; ++x) {
      misses += static_cast<uint64_t>(c.access(0, 0, grid({x, x + 1}, {y, y + 1})).misses);
    }
  EXPECT_EQ(misses, 256u);
}

// Property: the grid lookup equals a per-tap reference model, footprint after footprint: the taps
// (x[i], y[j]) of the used cells in row-major order, their distinct lines in order of first
// appearance through an LRU list per set, the bank cycles counted from distinct lines (block
// parity) or distinct texels (texel parity), and the sectors: the distinct (line, byte address
// mod line_bytes / 32) of the used taps, hits where the line hit. Random grids with repeated columns and rows (clamped
// or wrapped runs), random used cells, full 2x2 grids (access_quad) and 4x4 grids with the edge
// cross's cells or a random part of them (block_run_lines), two levels of two textures (one tiled,
// one linear), both mappings, 1 or 4 banks, 64- and 256-byte lines.
TEST(TexelCache, GridAccessEqualsAPerTapReferenceModel) {
  std::mt19937 rng(5);
  const std::vector<int> widths{40, 20}, heights{24, 12};
  for (const BankMapping mapping : {BankMapping::TexelParity, BankMapping::BlockParity})
    for (const int banks : {1, 4})
      for (const int block : {4, 8}) {
        const TexelCacheConfig cfg = small(block, 8 * block * block * 4, 2, banks, mapping);
        TextureMemory mem;
        const std::vector<TextureDescriptor> tex{placed(mem, 40, 24, 2, cfg.line_bytes),
                                                 placed(mem, 40, 24, 2, cfg.line_bytes, MemoryLayout::Linear)};
        TexelCache c(cfg, tex);
        std::vector<std::deque<uint64_t>> lru(static_cast<size_t>(cfg.sets()));  // front: most recent
        for (int n = 0; n < 3000; ++n) {
          const int level = static_cast<int>(rng() % 2), t = static_cast<int>(rng() % 2);
          // Line columns of `t`: tiles of `block` texels, or line_bytes / 4 texels of a row.
          const int line_w = t == 0 ? block : cfg.line_bytes / 4, line_h = t == 0 ? block : 1;
          const int w = widths[static_cast<size_t>(level)], h = heights[static_cast<size_t>(level)];
          TapGrid g{};
          const bool quad = n % 4 == 0;   // a full 2x2 grid: the cache's LINEAR fast path
          const bool cross = n % 4 == 1;  // 4x4, the edge cross's cells (block runs: block_run_lines)
          g.cols = quad ? 2 : cross ? 4 : 1 + static_cast<int>(rng() % 4);
          g.rows = quad ? 2 : cross ? 4 : 1 + static_cast<int>(rng() % 4);
          const int x0 = static_cast<int>(rng() % static_cast<uint32_t>(w)), y0 = static_cast<int>(rng() % static_cast<uint32_t>(h));
          const bool clamp = rng() % 2 == 0;
          for (int i = 0; i < g.cols; ++i)
            g.x[static_cast<size_t>(i)] = static_cast<int16_t>(clamp ? std::min(x0 + i, w - 1) : (x0 + i) % w);
          for (int j = 0; j < g.rows; ++j)
            g.y[static_cast<size_t>(j)] = static_cast<int16_t>(clamp ? std::min(y0 + j, h - 1) : (y0 + j) % h);
          g.used = square_cells(g.cols, g.rows);
          if (cross) g.used = static_cast<uint16_t>(cross_cells(lee_jen::kAllTexels) & (rng() % 4 == 0 ? 0xFFFFu : rng()));
          if (!quad && !cross && rng() % 2 == 0) g.used = static_cast<uint16_t>(g.used & rng());
          // Reference.
          std::vector<uint64_t> lines;
          std::vector<std::pair<uint64_t, uint64_t>> sectors;  // (line, sector)
          std::vector<std::pair<int, int>> texels;
          std::array<int, 4> nbank{};
          for (int cell = 0; cell < 16; ++cell) {
            if (!((g.used >> cell) & 1)) continue;
            const int x = g.x[static_cast<size_t>(cell & 3)], y = g.y[static_cast<size_t>(cell >> 2)];
            const uint64_t address = tex[static_cast<size_t>(t)].texel_address(level, x, y);
            const uint64_t line = address / static_cast<uint64_t>(cfg.line_bytes);
            const std::pair sector{line, address % static_cast<uint64_t>(cfg.line_bytes) / 32};
            if (std::find(sectors.begin(), sectors.end(), sector) == sectors.end()) sectors.push_back(sector);
            if (std::find(lines.begin(), lines.end(), line) == lines.end()) {
              lines.push_back(line);
              if (mapping == BankMapping::BlockParity)
                ++nbank[banks == 4 ? static_cast<size_t>((x / line_w) % 2 + 2 * ((y / line_h) % 2)) : 0];
            }
            if (mapping == BankMapping::TexelParity &&
                std::find(texels.begin(), texels.end(), std::pair{x, y}) == texels.end()) {
              texels.emplace_back(x, y);
              ++nbank[banks == 4 ? static_cast<size_t>(x % 2 + 2 * (y % 2)) : 0];
            }
          }
          int hits = 0;
          std::vector<uint64_t> missed;
          for (const uint64_t line : lines) {
            auto& set = lru[line % static_cast<uint64_t>(cfg.sets())];
            const auto it = std::find(set.begin(), set.end(), line);
            if (it != set.end()) {
              ++hits;
              set.erase(it);
            } else {
              missed.push_back(line);
              if (set.size() == static_cast<size_t>(cfg.ways)) set.pop_back();
            }
            set.push_front(line);
          }
          int sector_hits = 0;
          for (const auto& [line, sector] : sectors)
            sector_hits += std::find(missed.begin(), missed.end(), line) == missed.end() ? 1 : 0;
          const FootprintResult r = c.access(t, level, g);
          ASSERT_EQ(r.sector_lookups, static_cast<int>(sectors.size())) << n;
          ASSERT_EQ(r.sector_hits, sector_hits) << n;
          ASSERT_EQ(r.hits, hits) << n;
          ASSERT_EQ(r.misses, static_cast<int>(missed.size())) << n;
          ASSERT_EQ(std::vector<uint64_t>(r.missed_lines.begin(), r.missed_lines.begin() + r.misses), missed) << n;
          ASSERT_EQ(r.cycles, std::max({1, nbank[0], nbank[1], nbank[2], nbank[3]})) << n;
        }
      }
}

// Sectors by hand. 64-byte tiled lines (4x4 RGBA8: sector 0 = tile rows 0-1, 1 = rows 2-3),
// 256-byte tiled lines (8x8: a sector is one tile row of 8 texels), 64-byte linear lines of L8
// (64 texels of a row: sector 0 = columns 0-31); a footprint's sector counts weight its lines.
TEST(TexelCache, SectorsOfHandDerivedFootprints) {
  TexelCache c(small(4, 4096, 2, 4, BankMapping::BlockParity), one(16, 16));
  FootprintResult r = c.access(0, 0, grid({3, 4}, {1, 2}));  // tiles (0,0) and (1,0), rows 1 and 2 each
  EXPECT_EQ(r.misses, 2);
  EXPECT_EQ(r.sector_lookups, 4);
  EXPECT_EQ(r.sector_hits, 0);
  r = c.access(0, 0, grid({0, 1, 2, 3}, {0, 1, 2, 3}));  // cubic 4x4 in tile (0,0): both sectors, hit
  EXPECT_EQ(r.hits, 1);
  EXPECT_EQ(r.sector_lookups, 2);
  EXPECT_EQ(r.sector_hits, 2);
  r = c.access(0, 0, grid({4, 5}, {3, 4}));  // tile (1,0) row 3 (sector 1, hit), tile (1,1) row 4 (sector 0, miss)
  EXPECT_EQ(r.hits, 1);
  EXPECT_EQ(r.sector_lookups, 2);
  EXPECT_EQ(r.sector_hits, 1);
  EXPECT_EQ(c.sector_lookups(), 8u);
  EXPECT_EQ(c.sector_hits(), 3u);

  TexelCacheConfig big = small(8, 8192, 2, 4, BankMapping::TexelParity);
  TexelCache c8(big, one(16, 16, 1, 256));
  r = c8.access(0, 0, grid({1, 2, 3, 4}, {3, 4, 5, 6}));  // one 8x8 tile, rows 3..6: 4 sectors
  EXPECT_EQ(r.misses, 1);
  EXPECT_EQ(r.sector_lookups, 4);

  TextureMemory mem;
  const std::vector<TextureDescriptor> l8{placed(mem, 128, 4, 1, 64, MemoryLayout::Linear, TexelFormat::L8)};
  TexelCache cl(small(4, 4096, 2, 4, BankMapping::BlockParity), l8);
  r = cl.access(0, 0, grid({31, 32}, {0, 1}));  // rows 0 and 1, columns 31 | 32: sectors 0 and 1 of each line
  EXPECT_EQ(r.misses, 2);
  EXPECT_EQ(r.sector_lookups, 4);
  r = cl.access(0, 0, grid({63}, {0}));
  EXPECT_EQ(r.hits, 1);
  EXPECT_EQ(r.sector_hits, 1);
}

// ways 0: one set of every line, LRU over all of them. Tiles (0,0), (0,1), (0,2), (0,3) of a
// 16x16 texture are lines 4 apart: in 4 direct-mapped sets they evict each other, in the fully
// associative cache of 4 lines all stay; a fifth line evicts the least recently used.
TEST(TexelCache, FullyAssociativeHoldsAnyLines) {
  TexelCache direct(small(4, 256, 1, 4, BankMapping::BlockParity), one(16, 16));
  TexelCache full(small(4, 256, 0, 4, BankMapping::BlockParity), one(16, 16));
  EXPECT_EQ(full.config().sets(), 1);
  for (int pass = 0; pass < 2; ++pass)
    for (int y = 0; y < 16; y += 4) {
      EXPECT_EQ(direct.access(0, 0, tap(0, y)).hits, 0);
      EXPECT_EQ(full.access(0, 0, tap(0, y)).hits, pass);
    }
  EXPECT_EQ(full.access(0, 0, tap(4, 0)).misses, 1);  // evicts tile (0,0), the least recently used
  EXPECT_FALSE(full.resident(0, 0, 0, 0));
  EXPECT_TRUE(full.resident(0, 0, 0, 4));
}

TEST(MemoryModel, BandwidthAndLatency) {
  MemoryModel m({100, 16}, 2);
  EXPECT_EQ(m.read(0, 64, 0, 0), 104u);    // 4 cycles on the interface + 100 latency
  EXPECT_EQ(m.read(0, 64, 1, 64), 108u);   // queued behind the first: outstanding misses overlap latency
  EXPECT_EQ(m.read(500, 1, 1, 128), 601u);  // idle interface: 1 cycle + latency (the address is the DRAM's only)
  EXPECT_EQ(m.bytes_read(), 129u);
  EXPECT_EQ(m.texture_bytes(0), 64u);
  EXPECT_EQ(m.texture_bytes(1), 65u);
  EXPECT_EQ(m.requests(), 3u);
  EXPECT_THROW(MemoryModel({10, 0}, 1), InputError);
}

// With a DRAM part the interface still serializes the bytes, and the data arrives when the DRAM
// delivers it (rtl/dram.hpp): DDR4-2400 at a unit clock of 1200 MHz, so a unit clock is a DRAM clock.
TEST(MemoryModel, DramPartServesTheMisses) {
  MemoryConfig cfg;
  cfg.dram = 1;  // ddr4-2400-x64
  cfg.unit_clock_mhz = 1200;
  MemoryModel m(cfg, 1);
  // Interface 0..3 (64 bytes at 16 per cycle); the DRAM takes it at 0: ACT 0, READ 16, data 32..36.
  EXPECT_EQ(m.read(0, 64, 0, 0), 36u);
  ASSERT_NE(m.dram(), nullptr);
  EXPECT_EQ(m.dram()->stats().bursts, 1u);
  MemoryConfig bad = cfg;
  bad.dram = 9;
  EXPECT_THROW(MemoryModel(bad, 1), InputError);
}

}  // namespace
}  // namespace tfu::rtl
