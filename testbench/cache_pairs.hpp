// Two texel caches of one configuration over the same textures, for the tests that feed a fast
// lookup and its plain twin the same stream of footprints (test_cubic_quad_path.cpp,
// test_probe_quad_path.cpp): every cache shape whose lookups differ (both bank mappings, 1 and 4
// banks, 64- to 1024-byte lines, 1 and 4 ways, four sets: misses, evictions and the LRU order all
// matter), over tiled and linear-row RGBA8 and L8 textures of 72 x 40 texels with every level.
#pragma once

#include <vector>

#include <gtest/gtest.h>

#include "cmodel/descriptors.hpp"
#include "cmodel/texture_memory.hpp"
#include "rtl/texel_cache.hpp"

namespace tfu::test {

inline constexpr int kCachePairLevels = 7;  // 72 x 40 down to 1 x 1

// body(cfg, textures, fast, plain) once per configuration, with two fresh caches; then every
// counter of the two caches compared (per level, per texture, sectors).
template <class Body>
void for_every_cache_pair(Body&& body) {
  for (const rtl::BankMapping mapping : {rtl::BankMapping::TexelParity, rtl::BankMapping::BlockParity})
    for (const int banks : {1, 4})
      for (const int line_bytes : {64, 256, 1024})
        for (const int ways : {1, 4}) {
          rtl::TexelCacheConfig cfg;
          cfg.line_bytes = line_bytes;
          cfg.ways = ways;
          cfg.capacity_bytes = line_bytes * ways * 4;
          cfg.banks = banks;
          cfg.bank_mapping = mapping;
          TextureMemory mem;
          std::vector<TextureDescriptor> tex;
          for (const MemoryLayout layout : {MemoryLayout::Tiled, MemoryLayout::Linear})
            for (const TexelFormat format : {TexelFormat::RGBA8, TexelFormat::L8}) {
              Texture t;
              t.format = format;
              t.layout = layout;
              t.tile_bytes = line_bytes;
              for (int l = 0; l < kCachePairLevels; ++l) t.levels.emplace_back(mip_extent(72, l), mip_extent(40, l));
              tex.push_back(place_texture(mem, t, static_cast<uint64_t>(line_bytes)));
            }
          rtl::TexelCache fast(cfg, tex), plain(cfg, tex);
          body(static_cast<const rtl::TexelCacheConfig&>(cfg), static_cast<const std::vector<TextureDescriptor>&>(tex),
               fast, plain);
          for (int l = 0; l < kCachePairLevels; ++l) {
            EXPECT_EQ(fast.level_hits(l), plain.level_hits(l));
            EXPECT_EQ(fast.level_misses(l), plain.level_misses(l));
          }
          for (int t = 0; t < static_cast<int>(tex.size()); ++t) {
            EXPECT_EQ(fast.texture_hits(t), plain.texture_hits(t));
            EXPECT_EQ(fast.texture_misses(t), plain.texture_misses(t));
          }
          EXPECT_EQ(fast.sector_hits(), plain.sector_hits());
          EXPECT_EQ(fast.sector_lookups(), plain.sector_lookups());
        }
}

}  // namespace tfu::test
