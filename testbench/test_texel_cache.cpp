// texel_cache and memory_model: blocked line mapping, LRU, bank conflicts, configuration errors,
// bandwidth and latency.
#include <vector>

#include <gtest/gtest.h>

#include "cmodel/error.hpp"
#include "rtl/memory_model.hpp"
#include "rtl/texel_cache.hpp"

namespace tfu::rtl {
namespace {

TexelCacheConfig small(int block, int capacity, int ways, int banks = 4,
                       BankMapping mapping = BankMapping::TexelParity) {
  TexelCacheConfig c;
  c.bank_mapping = mapping;
  c.block = block;
  c.capacity_bytes = capacity;
  c.ways = ways;
  c.banks = banks;
  return c;
}

TEST(TexelCache, ConfigurationErrorsNameTheField) {
  EXPECT_THROW(small(6, 4096, 2).validate(), InputError);   // B not 4 or 8
  EXPECT_THROW(small(4, 32, 1).validate(), InputError);     // below one 64-byte line
  EXPECT_THROW(small(4, 4096, 0).validate(), InputError);   // zero ways
  EXPECT_THROW(small(4, 4096, 2, 0).validate(), InputError);  // zero banks
  EXPECT_THROW(small(4, 100, 1).validate(), InputError);    // not whole sets
  EXPECT_NO_THROW(small(8, 256 * 4, 1).validate());
  try {
    small(4, 32, 1).validate();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("capacity 32 bytes"), std::string::npos) << e.what();
  }
}

TEST(TexelCache, BlockedLineNumbering) {
  const TexelCache c(small(4, 4096, 2), {16, 8}, {16, 8});
  EXPECT_EQ(c.line_of(0, 0, 0), 0u);
  EXPECT_EQ(c.line_of(0, 3, 3), 0u);
  EXPECT_EQ(c.line_of(0, 4, 0), 1u);
  EXPECT_EQ(c.line_of(0, 0, 4), 4u);    // 4 blocks per row
  EXPECT_EQ(c.line_of(1, 0, 0), 16u);   // level 1 starts after level 0's 16 lines
  EXPECT_EQ(c.line_of(1, 7, 7), 19u);
}

TEST(TexelCache, BilinearFootprintOneCycleCubicFour) {
  TexelCache c(small(4, 4096, 2), {16}, {16});
  const std::vector<TexelTap> quad{{5, 6}, {6, 6}, {5, 7}, {6, 7}};
  FootprintResult r = c.access(0, quad);
  EXPECT_EQ(r.cycles, 1);  // one texel per parity bank
  EXPECT_EQ(r.misses, 1);  // all in block (1, 1)
  EXPECT_EQ(c.access(0, quad).hits, 1);
  std::vector<TexelTap> cubic;
  for (int y = 4; y < 8; ++y)
    for (int x = 4; x < 8; ++x) cubic.push_back({x, y});
  EXPECT_EQ(c.access(0, cubic).cycles, 4);  // 16 texels over 4 banks
  TexelCache one_bank(small(4, 4096, 2, 1), {16}, {16});
  EXPECT_EQ(one_bank.access(0, quad).cycles, 4);
  // A footprint across a block corner touches four lines.
  const std::vector<TexelTap> corner{{3, 3}, {4, 3}, {3, 4}, {4, 4}};
  const FootprintResult rc = c.access(0, corner);
  EXPECT_EQ(rc.misses + rc.hits, 4);
}

TEST(TexelCache, BlockParityBanksReadWholeLines) {
  TexelCache c(small(4, 4096, 4, 4, BankMapping::BlockParity), {16}, {16});
  std::vector<TexelTap> cubic, cross;
  for (int y = 2; y < 6; ++y)
    for (int x = 2; x < 6; ++x) cubic.push_back({x, y});  // 4x4 over the corner of 4 blocks
  EXPECT_EQ(c.access(0, cubic).cycles, 1);             // one line from each bank
  for (const auto& [x, y] : std::vector<std::pair<int, int>>{{5, 4}, {6, 4}, {4, 5}, {5, 5}, {6, 5}, {7, 5},
                                                             {4, 6}, {5, 6}, {6, 6}, {7, 6}, {5, 7}, {6, 7}})
    cross.push_back({x, y});  // the 12-texel cross inside block (1, 1)
  EXPECT_EQ(c.access(0, cross).cycles, 1);
  // Blocks (0, 0) and (2, 0) share bank 0: two cycles.
  EXPECT_EQ(c.access(0, std::vector<TexelTap>{{0, 0}, {8, 0}}).cycles, 2);
  TexelCache one(small(4, 4096, 4, 1, BankMapping::BlockParity), {16}, {16});
  EXPECT_EQ(one.access(0, cubic).cycles, 4);  // four lines through one port
  EXPECT_EQ(one.access(0, cross).cycles, 1);
}

TEST(TexelCache, ResidencyProbeDoesNotAllocate) {
  TexelCache c(small(4, 4096, 2), {16}, {16});
  EXPECT_FALSE(c.resident(0, 5, 5));
  EXPECT_FALSE(c.resident(0, 5, 5));  // a probe does not allocate
  c.access(0, std::vector<TexelTap>{{5, 5}});
  EXPECT_TRUE(c.resident(0, 4, 7));   // same block
  EXPECT_FALSE(c.resident(0, 8, 5));
}

TEST(TexelCache, LruEvictsTheLeastRecentlyUsedWay) {
  // Direct lines 0, 2, 4 all map to set 0 of a 2-set, 2-way cache.
  TexelCache c(small(4, 256, 2), {64}, {4});  // 4 lines = 2 sets x 2 ways; 16 blocks in one row
  const auto at = [](int block) { return std::vector<TexelTap>{{4 * block, 0}}; };
  EXPECT_EQ(c.access(0, at(0)).misses, 1);
  EXPECT_EQ(c.access(0, at(2)).misses, 1);
  EXPECT_EQ(c.access(0, at(0)).hits, 1);    // 0 becomes most recent
  EXPECT_EQ(c.access(0, at(4)).misses, 1);  // evicts 2, the LRU
  EXPECT_EQ(c.access(0, at(0)).hits, 1);
  EXPECT_EQ(c.access(0, at(2)).misses, 1);
  EXPECT_EQ(c.hits(0), 2u);
  EXPECT_EQ(c.misses(0), 4u);
}

TEST(TexelCache, ScanlineHitRateOfABlockedCache) {
  // Bilinear footprints along texel rows of a 64x64 texture: each 4x4 block is fetched once per
  // row of blocks when the cache holds a whole row of blocks (16 lines), so misses = 16 x 16.
  TexelCache c(small(4, 64 * 64, 4), {64}, {64});
  uint64_t misses = 0;
  for (int y = 0; y < 63; ++y)
    for (int x = 0; x < 63; ++x) {
      const std::vector<TexelTap> q{{x, y}, {x + 1, y}, {x, y + 1}, {x + 1, y + 1}};
      misses += static_cast<uint64_t>(c.access(0, q).misses);
    }
  EXPECT_EQ(misses, 256u);
}

TEST(MemoryModel, BandwidthAndLatency) {
  MemoryModel m({100, 16});
  EXPECT_EQ(m.read(0, 64), 104u);   // 4 cycles on the interface + 100 latency
  EXPECT_EQ(m.read(0, 64), 108u);   // queued behind the first: outstanding misses overlap latency
  EXPECT_EQ(m.read(500, 1), 601u);  // idle interface: 1 cycle + latency
  EXPECT_EQ(m.bytes_read(), 129u);
  EXPECT_EQ(m.requests(), 3u);
  EXPECT_THROW(MemoryModel({10, 0}), InputError);
}

}  // namespace
}  // namespace tfu::rtl
