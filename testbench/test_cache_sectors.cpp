// The texel cache's 32-byte sector statistics (rtl/texel_cache.hpp, "Sectors") through the whole
// unit: hand-derived request sequences with their line and sector lookups and hits, the same in the
// clocked and the recurrence engine, tiled and linear layouts; and the fully associative cache
// (cache.ways 0) in a unit run; the 2x2 footprint's sector counts (TexelCache::access_quad, which
// counts them per axis) against the taps' byte addresses.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <vector>

#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/texture_memory.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_stats.hpp"
#include "testbench/iterations.hpp"

namespace tfu::rtl {
namespace {

struct CacheCounts {
  uint64_t line_hits = 0, line_misses = 0, sector_hits = 0, sector_lookups = 0;
  friend bool operator==(const CacheCounts&, const CacheCounts&) = default;
};
std::ostream& operator<<(std::ostream& os, const CacheCounts& c) {
  return os << "lines " << c.line_hits << "/" << c.line_hits + c.line_misses << ", sectors " << c.sector_hits << "/"
            << c.sector_lookups;
}

// A 16 x 16 RGBA8 texture of one level in `layout` (tiled: 4 x 4 texels per 64-byte line).
Texture texture16(MemoryLayout layout) {
  Texture t;
  t.layout = layout;
  t.levels.emplace_back(16, 16, Rgba8{10, 20, 30, 255});
  return t;
}

// Requests at texel-space positions (u, v) = (s, t) x 16 on level 0 through the default unit
// (64-byte lines, 16 KiB, 4 ways, block parity) by `engine`.
CacheCounts run(const Texture& tex, const char* mode, const std::vector<std::pair<float, float>>& uv, UnitEngine engine,
                int ways = 4) {
  UnitConfig u;
  u.cache.ways = ways;
  FrameBuilder b(u.cache.line_bytes);
  b.add_texture(std::make_shared<const Texture>(tex), {"test", {}});
  SamplerDescriptor s;
  s.mode = filter_mode_from_name(mode);
  b.add_sampler(s);
  Trace tr;
  tr.mode = TraceMode::Lod;
  for (const auto& [x, y] : uv) {
    TraceRequest r;
    r.s = x / 16.0f;
    r.t = y / 16.0f;
    tr.requests.push_back(r);
  }
  bind_requests(b, tr);
  const Frame frame = b.finish();
  const UnitOutput o = run_unit(frame, tr, u, engine, VcdOptions{});
  CacheCounts c{counter(o.stats, UnitStat::CacheLineHits), counter(o.stats, UnitStat::CacheLineMisses),
                counter(o.stats, UnitStat::CacheSectorHits), counter(o.stats, UnitStat::CacheSectorLookups)};
  const double rate = c.sector_lookups ? static_cast<double>(c.sector_hits) / static_cast<double>(c.sector_lookups) : 1.0;
  EXPECT_EQ(value(o.stats, UnitStat::CacheSectorHitRate), rate);
  return c;
}

constexpr UnitEngine kEngines[] = {UnitEngine::Clocked, UnitEngine::Recurrence};

// Tiled, 4 x 4 texels per line: a tile row is 16 bytes, so sector 0 holds the tile's rows 0-1 and
// sector 1 rows 2-3.
TEST(CacheSectors, HandDerivedTiledSequenceInBothEngines) {
  const Texture tex = texture16(MemoryLayout::Tiled);
  for (const UnitEngine e : kEngines) {
    // NEAREST, one tap each: texel (1,1) misses tile (0,0), sector 0; (2,3) hits its line, sector
    // 1; (5,0) misses tile (1,0); (1,0) hits tile (0,0), sector 0.
    EXPECT_EQ(run(tex, "NEAREST", {{1.5f, 1.5f}, {2.5f, 3.5f}, {5.5f, 0.5f}, {1.5f, 0.5f}}, e), (CacheCounts{2, 2, 2, 4}))
        << unit_engine_name(e);
    // LINEAR, 2x2 taps at (u - 1/2, v - 1/2):
    //   (4, 2): columns 3, 4, rows 1, 2: tiles (0,0) and (1,0) missed, each rows 1 and 2 = sectors 0, 1: 4 lookups
    //   (2, 1): columns 1, 2, rows 0, 1: tile (0,0) hit, sector 0 only
    //   (5, 3): columns 4, 5, rows 2, 3: tile (1,0) hit, sector 1 only
    //   (8, 4): columns 7, 8, rows 3, 4: tile (1,0) hit (row 3: sector 1); (2,0) row 3, (1,1) and (2,1) row 4 (sector
    //           0) missed: 4 lookups, 1 hit
    // Lines 3 hits of 8; sectors 3 hits of 10.
    EXPECT_EQ(run(tex, "LINEAR", {{4, 2}, {2, 1}, {5, 3}, {8, 4}}, e), (CacheCounts{3, 5, 3, 10})) << unit_engine_name(e);
  }
}

// Linear, a 64-byte line is one texel row of 16 texels: sector 0 holds columns 0-7, sector 1 8-15.
TEST(CacheSectors, HandDerivedLinearSequenceInBothEngines) {
  const Texture tex = texture16(MemoryLayout::Linear);
  for (const UnitEngine e : kEngines) {
    //   (8, 1): columns 7, 8, rows 0, 1: two lines missed, each sectors 0 and 1: 4 lookups
    //   (9, 2): columns 8, 9, rows 1, 2: row 1 hit (sector 1), row 2 missed (sector 1)
    EXPECT_EQ(run(tex, "LINEAR", {{8, 1}, {9, 2}}, e), (CacheCounts{1, 3, 1, 6})) << unit_engine_name(e);
    // NEAREST: (1,0) missed; (9,0) its line hit, sector 1; (15,0) sector 1 again, hit.
    EXPECT_EQ(run(tex, "NEAREST", {{1.5f, 0.5f}, {9.5f, 0.5f}, {15.5f, 0.5f}}, e), (CacheCounts{2, 1, 2, 3}))
        << unit_engine_name(e);
  }
}

// cache.ways 0 in a unit run: one set of all 256 lines (16 KiB of 64 bytes); tiles (0,0) to (0,3)
// twice miss 4 lines and hit 4 in both engines (the replacement itself: TexelCache tests).
TEST(CacheSectors, FullyAssociativeUnitRun) {
  const Texture tex = texture16(MemoryLayout::Tiled);
  const std::vector<std::pair<float, float>> column{{0.5f, 0.5f}, {0.5f, 4.5f}, {0.5f, 8.5f}, {0.5f, 12.5f},
                                                    {0.5f, 0.5f}, {0.5f, 4.5f}, {0.5f, 8.5f}, {0.5f, 12.5f}};
  for (const UnitEngine e : kEngines) EXPECT_EQ(run(tex, "NEAREST", column, e, 0), (CacheCounts{4, 4, 4, 8})) << unit_engine_name(e);
  UnitConfig u;
  u.cache.ways = 0;
  EXPECT_EQ(u.cache.way_count(), 256);
  EXPECT_EQ(u.cache.sets(), 1);
  EXPECT_NO_THROW(u.validate());
  u.cache.capacity_bytes = 1 << 20;  // 16384 lines: above the fully associative bound
  EXPECT_THROW(u.validate(), InputError);
}

// The LINEAR 2x2 footprint under block parity (access_quad) counts a footprint's sectors per axis,
// not per tap: against the distinct (line, address % line_bytes / 32) of its four taps' byte
// addresses (TextureDescriptor::texel_address), with hits where the line hit (the cache's own line
// hits, r.hits; every line of the footprint holds the same number of sectors). Every line size (64, 256, 1024),
// RGBA8 and L8, tiled and linear, random positions with wrapped and clamped edges, several levels.
TEST(CacheSectors, QuadSectorsEqualTheTapsAddresses) {
  std::mt19937 rng(11);
  for (const int line : {64, 256, 1024})
    for (const TexelFormat f : {TexelFormat::RGBA8, TexelFormat::L8})
      for (const MemoryLayout layout : {MemoryLayout::Tiled, MemoryLayout::Linear}) {
        SCOPED_TRACE(::testing::Message() << line << " " << static_cast<int>(f) << " " << static_cast<int>(layout));
        Texture t;
        t.format = f;
        t.layout = layout;
        t.tile_bytes = line;
        for (int l = 0; l < 4; ++l) t.levels.emplace_back(mip_extent(96, l), mip_extent(80, l));
        TextureMemory mem;
        const std::vector<TextureDescriptor> d{place_texture(mem, t, static_cast<uint64_t>(line))};
        TexelCacheConfig cfg;
        cfg.line_bytes = line;
        cfg.capacity_bytes = 8 * line;
        cfg.ways = 2;
        cfg.bank_mapping = BankMapping::BlockParity;
        TexelCache c(cfg, d);
        for (int n = 0; n < test::iterations(4000); ++n) {
          const int level = static_cast<int>(rng() % 4);
          const int w = mip_extent(96, level), h = mip_extent(80, level);
          const int x0 = static_cast<int>(rng() % static_cast<uint32_t>(w)),
                    y0 = static_cast<int>(rng() % static_cast<uint32_t>(h));
          const bool clamp = rng() % 2 == 0;
          TapGrid g{};
          g.cols = g.rows = 2;
          g.used = square_cells(2, 2);
          for (int i = 0; i < 2; ++i) {
            g.x[static_cast<size_t>(i)] = static_cast<int16_t>(clamp ? std::min(x0 + i, w - 1) : (x0 + i) % w);
            g.y[static_cast<size_t>(i)] = static_cast<int16_t>(clamp ? std::min(y0 + i, h - 1) : (y0 + i) % h);
          }
          std::vector<uint64_t> lines;
          std::vector<std::pair<uint64_t, uint64_t>> sectors;
          for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
              const uint64_t a = d[0].texel_address(level, g.x[static_cast<size_t>(i)], g.y[static_cast<size_t>(j)]);
              const std::pair sector{a / static_cast<uint64_t>(line), a % static_cast<uint64_t>(line) / 32};
              if (std::find(lines.begin(), lines.end(), sector.first) == lines.end()) lines.push_back(sector.first);
              if (std::find(sectors.begin(), sectors.end(), sector) == sectors.end()) sectors.push_back(sector);
            }
          const uint64_t before_hits = c.sector_hits();
          const FootprintResult r = c.access(0, level, g);
          ASSERT_EQ(static_cast<size_t>(r.hits + r.misses), lines.size());
          ASSERT_EQ(static_cast<size_t>(r.sector_lookups), sectors.size()) << n;
          // Every line of a 2x2 footprint holds the same number of its sectors (the product of the
          // line's distinct column and row sectors), so a hit line brings that many sector hits.
          const auto per_line = static_cast<size_t>(
              std::count_if(sectors.begin(), sectors.end(), [&](const auto& q) { return q.first == lines[0]; }));
          for (const uint64_t l : lines)
            ASSERT_EQ(static_cast<size_t>(
                          std::count_if(sectors.begin(), sectors.end(), [&](const auto& q) { return q.first == l; })),
                      per_line);
          ASSERT_EQ(static_cast<size_t>(r.sector_hits), static_cast<size_t>(r.hits) * per_line) << n;
          ASSERT_EQ(c.sector_hits() - before_hits, static_cast<uint64_t>(r.sector_hits));
        }
      }
}

}  // namespace
}  // namespace tfu::rtl
