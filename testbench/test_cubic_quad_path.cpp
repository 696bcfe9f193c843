// The parts of the timing recurrences' CUBIC quad path (rtl/unit_recurrence_cubic_quads.hpp) against
// their plain twins: the word-lane adder tree and normalise stage and the weight memo
// (cmodel/cubic_fast.hpp) against the channel datapath of cmodel/datapath.hpp, and the texel
// cache's closed-form lookup of a full 4 x 4 grid (rtl/texel_cache_full_squares.cpp) against
// access_grid. The whole path against the plain blocks and the clocked unit:
// TfuUnit.CubicQuadPathEqualsThePlainBlocks (test_tfu_unit.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include <fmt/format.h>

#include "cmodel/cubic_fast.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/kernels.hpp"
#include "cmodel/texture_memory.hpp"
#include "rtl/texel_cache.hpp"
#include "testbench/cache_pairs.hpp"
#include "testbench/iterations.hpp"

namespace tfu {
namespace {

// The adder tree on 16 words (both forms) equals dp::cubic_accumulate of their channels, and the normalise stage
// equals dp::cubic_normalize + encode_texel, for the default 8-bit ROM's divisor, other ROM widths
// and the B-spline coefficients' scale and bias registers: words at the channel extremes and at
// random, weights of real ROMs (tile_weights_2d of random fractions) and random weights of up to
// 16 bits with either sign, sums from far below zero to far above the largest code.
TEST(CubicFast, WordUnitsEqualTheChannelDatapath) {
  std::mt19937 rng(11);
  const std::vector<TileRomSpec> specs{
      {}, {16, 4, SamplePos::Corner}, {512, 16}, {64, 12, SamplePos::Centre, RomRounding::Nearest}};
  std::vector<TileWeightRom> roms;
  for (const char* kernel : {"catmull-rom", "bspline", "mitchell", "kaiser"})
    for (const TileRomSpec& spec : specs) roms.emplace_back(FilterKernel::by_name(kernel), spec);
  int compared = 0, narrow = 0;
  for (int it = 0; it < test::iterations(20000); ++it) {
    std::array<Rgba8, 16> words;
    std::array<Texel4, 16> channels;
    for (size_t k = 0; k < 16; ++k) {
      const auto byte = [&] { return static_cast<uint8_t>(it % 4 == 0 ? (rng() % 2) * 255 : rng() % 256); };
      words[k] = {byte(), byte(), byte(), byte()};
      channels[k] = decode_texel(words[k], TexelFormat::RGBA8);
    }
    const TileWeightRom& rom = roms[static_cast<size_t>(it) % roms.size()];
    std::array<int32_t, 16> w{};
    if (it % 3 == 0) {
      const uint32_t range = it % 2 ? 131071 : 65535;  // |w| <= 2^16 - 1, or 2^15 - 1 (narrow)
      for (int32_t& x : w) x = static_cast<int32_t>(rng() % range) - static_cast<int32_t>(range / 2);
    } else {
      dp::tile_weights_2d(rom, it % 2 ? RomRecon::Linear : RomRecon::Nearest, rng() % 256, rng() % 256, w);
    }
    const std::array<int64_t, 4> want = dp::cubic_accumulate(channels.data(), w.data(), 16);
    ASSERT_EQ(dp::fast::cubic_accumulate8(words.data(), w.data()), want) << it;
    if (std::all_of(w.begin(), w.end(), dp::fast::narrow_weight)) {
      ASSERT_EQ(dp::fast::cubic_accumulate8_narrow(words.data(), w.data()), want) << it;
      ++narrow;
    }
    // Normalise: this sum, and sums spread over the whole range of the stage's input.
    std::array<int64_t, 4> acc = want;
    if (it % 2 == 0)
      for (int64_t& a : acc) a = static_cast<int64_t>(rng() % (1u << 27)) - (1 << 26);
    for (const bool prefiltered : {false, true}) {
      dp::CubicNormalize n;
      n.M = static_cast<int64_t>(unorm::max_code(rom.spec().bits));
      n.prefiltered = prefiltered;
      n.scale_q = 1 + static_cast<int64_t>(rng() % 8192);
      n.bias_q = static_cast<int64_t>(rng() % 8192) - 4096;
      const Rgba8 got = dp::fast::cubic_normalize8(acc, n);
      ASSERT_EQ(got, encode_texel(dp::cubic_normalize(acc, n), TexelFormat::RGBA8)) << it;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 2 * test::iterations(20000));
  EXPECT_GT(narrow, test::iterations(20000) / 2);  // the multiply-add form on most of them
}

// The weight memo gives dp::tile_weights_2d's 16 weights for every fraction pair, whichever pair of
// a class fills the entry first, and tells whether they are all narrow: every (fu, fv) in a random order, twice, on
// ROMs of 16 to 512 samples, centre and corner sampling, nearest and linear reconstruction (a memo per ROM and
// reconstruction, as the quad path keeps one per sampler).
TEST(CubicFast, WeightMemoEqualsTheWeightStage) {
  std::mt19937 rng(12);
  const std::vector<std::pair<TileRomSpec, RomRecon>> cases{{{}, RomRecon::Nearest},
                                                            {{16, 8, SamplePos::Corner}, RomRecon::Nearest},
                                                            {{512, 16}, RomRecon::Nearest},
                                                            {{64, 12}, RomRecon::Linear}};
  std::vector<uint32_t> pairs(65536);
  for (uint32_t k = 0; k < pairs.size(); ++k) pairs[k] = k;
  const size_t step = static_cast<size_t>(test::kIterationDivisor);  // every pair; every tenth under the sanitizers
  int wide = 0;
  for (const auto& [spec, recon] : cases) {
    const TileWeightRom rom(FilterKernel::by_name("catmull-rom"), spec);
    dp::fast::TileWeightMemo memo(rom, recon);
    for (int round = 0; round < 2; ++round) {
      std::shuffle(pairs.begin(), pairs.end(), rng);
      for (size_t k = 0; k < pairs.size(); k += step) {
        const uint32_t fu = pairs[k] & 255, fv = pairs[k] >> 8;
        std::array<int32_t, 16> want{};
        dp::tile_weights_2d(rom, recon, fu, fv, want);
        bool narrow = false;
        const int32_t* got = memo.weights(fu, fv, narrow);
        ASSERT_EQ(std::vector<int32_t>(got, got + 16), std::vector<int32_t>(want.begin(), want.end()))
            << "samples " << spec.samples << " fu " << fu << " fv " << fv;
        ASSERT_EQ(narrow, std::all_of(want.begin(), want.end(), dp::fast::narrow_weight));
        wide += narrow ? 0 : 1;
      }
    }
  }
  EXPECT_GT(wide, 0);  // the 16-bit ROM's weights reach 2^15
}

}  // namespace

namespace rtl {
namespace {

// The closed-form lookup of a full 4 x 4 grid (access_square4) gives what access() gives, footprint
// after footprint on two caches fed the same stream: hits, misses, the missed lines in order,
// sectors and bank cycles, and at the end every counter. The stream mixes full 4 x 4 grids of runs
// (every offset against the line grid), of wrapped and of clamped columns and rows (on levels down
// to 1 x 1: repeated columns and rows), 4 x 4 grids with unused cells (both caches take access()
// for those) and 2 x 2 grids, on tiled and linear-row levels of RGBA8 and L8 textures, every bank
// mapping, 1 and 4 banks, 64- to 1024-byte lines and 1 to 4 ways (misses, evictions and LRU
// order all matter).
TEST(TexelCache, FullSquareInClosedFormEqualsGridAccess) {
  std::mt19937 rng(13);
  int closed_form = 0;
  test::for_every_cache_pair([&](const TexelCacheConfig& cfg, const std::vector<TextureDescriptor>& tex,
                                 TexelCache& fast, TexelCache& plain) {
    for (int n = 0; n < test::iterations(1500); ++n) {
      const int t = static_cast<int>(rng() % tex.size()), level = static_cast<int>(rng() % test::kCachePairLevels);
      const int w = tex[static_cast<size_t>(t)].level_width(level), h = tex[static_cast<size_t>(t)].level_height(level);
      TapGrid g{};
      const int kind = n % 8;  // 0-4: runs (cut below 4 texels); 5: wrapped or clamped; 6: unused cells; 7: 2x2
      g.cols = g.rows = kind == 7 ? 2 : 4;
      const int x0 = static_cast<int>(rng() % static_cast<uint32_t>(std::max(1, w - 3)));
      const int y0 = static_cast<int>(rng() % static_cast<uint32_t>(std::max(1, h - 3)));
      const bool clamp = rng() % 2 == 0;
      for (int i = 0; i < g.cols; ++i) {
        const int x = kind == 5 ? x0 + w - 2 + i : x0 + i, y = kind == 5 ? y0 + h - 2 + i : y0 + i;
        g.x[static_cast<size_t>(i)] = static_cast<int16_t>(clamp ? std::min(x, w - 1) : x % w);
        g.y[static_cast<size_t>(i)] = static_cast<int16_t>(clamp ? std::min(y, h - 1) : y % h);
      }
      g.used = square_cells(g.cols, g.rows);
      if (kind == 6) g.used = static_cast<uint16_t>(g.used & (rng() | 1u));
      closed_form += g.cols == 4 && g.used == square_cells(4, 4) ? 1 : 0;
      const FootprintResult want = plain.access(t, level, g);
      const FootprintResult got = g.cols == 4 ? fast.access_square4(t, level, g) : fast.access(t, level, g);
      const auto where = [&] {
        return fmt::format("{} line {} cfg.ways {} cfg.banks {}: footprint {}", static_cast<int>(cfg.bank_mapping),
                           cfg.line_bytes, cfg.ways, cfg.banks, n);
      };
      ASSERT_EQ(got.hits, want.hits) << where();
      ASSERT_EQ(got.misses, want.misses) << where();
      for (size_t m = 0; m < static_cast<size_t>(want.misses); ++m)
        ASSERT_EQ(got.missed_lines[m], want.missed_lines[m]) << where();
      ASSERT_EQ(got.sector_hits, want.sector_hits) << where();
      ASSERT_EQ(got.sector_lookups, want.sector_lookups) << where();
      ASSERT_EQ(got.cycles, want.cycles) << where();
    }
  });
  EXPECT_GT(closed_form, 24 * test::iterations(1500) / 2);  // 6 of 8 footprints (some kind-6 masks are full)
}

}  // namespace
}  // namespace rtl
}  // namespace tfu
