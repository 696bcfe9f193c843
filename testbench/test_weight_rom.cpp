// Tiled high-resolution weight ROMs (cmodel/weight_rom.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "cmodel/error.hpp"
#include "cmodel/unorm.hpp"
#include "cmodel/weight_rom.hpp"

namespace tfu {
namespace {

const char* const kCubics[] = {"bspline", "catmull-rom", "mitchell", "kaiser", "blackman"};

TEST(WeightRom, HandDerivedRowsAtFractionZero) {
  // Corner sampling puts entry 0 at f = 0: B-spline weights (1/6, 2/3, 1/6, 0) -> 42.5, 170, 42.5, 0.
  TileRomSpec s{16, 8, SamplePos::Corner, RomRounding::Nearest};
  const TileWeightRom rounded(FilterKernel::bspline(), s);
  ASSERT_EQ(rounded.taps(), 4);
  EXPECT_EQ(rounded.first_tap(), -1);
  EXPECT_EQ(rounded.row(0)[0].value(), 43);
  EXPECT_EQ(rounded.row(0)[1].value(), 170);
  EXPECT_EQ(rounded.row(0)[2].value(), 43);  // Eq. 3.4 rounds both halves up: the row sums to 256
  EXPECT_EQ(rounded.row(0)[3].value(), 0);
  s.rounding = RomRounding::SumPreserving;
  const TileWeightRom sum(FilterKernel::bspline(), s);
  // Largest remainder: one of the two .5 remainders rounds up; the tie goes to the tap nearer the
  // row centre (tap 2, offset +1).
  EXPECT_EQ(sum.row(0)[0].value(), 42);
  EXPECT_EQ(sum.row(0)[1].value(), 170);
  EXPECT_EQ(sum.row(0)[2].value(), 43);
  EXPECT_EQ(sum.row(0)[3].value(), 0);
  // Catmull-Rom interpolates: (0, 1, 0, 0) at f = 0 and (0, 0, 1, 0) at f = 1 (last corner entry).
  const TileWeightRom cr(FilterKernel::catmull_rom(), s);
  EXPECT_EQ(cr.row(0)[1].value(), 255);
  EXPECT_EQ(cr.row(0)[0].value(), 0);
  EXPECT_EQ(cr.row(16)[2].value(), 255);
  // f = 1/2: Catmull-Rom (-1/16, 9/16, 9/16, -1/16) * 255 = (-15.94, 143.44, 143.44, -15.94).
  EXPECT_EQ(cr.row(8)[0].value(), -16);
  EXPECT_TRUE(cr.row(8)[0].neg);
  EXPECT_EQ(cr.row(8)[0].mag, 16u);
  EXPECT_EQ(cr.row(8)[1].value() + cr.row(8)[2].value(), 287);  // 255 + 32: one of them rounds up
}

TEST(WeightRom, EveryEntryWithinOneLsbAndRowsSumExactly) {
  for (const char* name : kCubics)
    for (int R : {16, 64, 512})
      for (SamplePos pos : {SamplePos::Centre, SamplePos::Corner}) {
        const auto h = FilterKernel::by_name(name);
        const TileWeightRom rom(h, {R, 8, pos, RomRounding::SumPreserving});
        const TileWeightRom near(h, {R, 8, pos, RomRounding::Nearest});
        const double pou_dev = h.partition_of_unity_deviation();
        for (int k = 0; k < rom.entries(); ++k) {
          double exact_sum = 0.0;
          int32_t sum = 0, near_sum = 0;
          for (int t = 0; t < rom.taps(); ++t) {
            const double e = rom.exact(k, t) * 255.0;
            exact_sum += rom.exact(k, t);
            ASSERT_LT(std::abs(rom.row(k)[static_cast<size_t>(t)].value() - e), 1.0) << name << " k=" << k;
            ASSERT_LE(std::abs(near.row(k)[static_cast<size_t>(t)].value() - e), 0.5 + 1e-9) << name << " k=" << k;
            sum += rom.row(k)[static_cast<size_t>(t)].value();
            near_sum += near.row(k)[static_cast<size_t>(t)].value();
          }
          // Sum-preserving rows hit round(255 * sum of exact weights): exactly 255 for kernels with
          // the partition-of-unity property.
          ASSERT_EQ(sum, std::lround(255.0 * exact_sum)) << name << " R=" << R << " k=" << k;
          if (pou_dev < 1e-12) {
            ASSERT_EQ(sum, 255) << name;
          }
          // Plain rounding: within the documented bound T * 0.5 LSB (+ the kernel's own deviation).
          ASSERT_LE(std::abs(near_sum - 255.0), 0.5 * rom.taps() + 255.0 * pou_dev + 1e-9);
        }
      }
}

TEST(WeightRom, TileLayoutMatchesInterleavedLayoutAndKernel) {
  const TileWeightRom rom(FilterKernel::catmull_rom(), {32, 8, SamplePos::Centre, RomRounding::Nearest});
  for (int j = 0; j < rom.taps(); ++j)
    for (int k = 0; k < rom.entries(); ++k) {
      const double x = j - rom.taps() / 2 + (k + 0.5) / 32.0;  // tile j covers [j - 2, j - 1]
      EXPECT_EQ(rom.tile_word(j, k), quantize_weight(FilterKernel::catmull_rom()(x), 8));
    }
}

TEST(WeightRom, MirrorSymmetryOfRows) {
  // h even => the row for f is the reversed row for 1 - f (exactly, with independent rounding).
  for (const char* name : kCubics) {
    const TileWeightRom c(FilterKernel::by_name(name), {64, 8, SamplePos::Centre, RomRounding::Nearest});
    for (int k = 0; k < 64; ++k)
      for (int t = 0; t < 4; ++t) ASSERT_EQ(c.row(k)[static_cast<size_t>(t)], c.row(63 - k)[static_cast<size_t>(3 - t)]);
  }
}

TEST(WeightRom, NearestAddressing) {
  const TileWeightRom c(FilterKernel::bspline(), {16, 8, SamplePos::Centre, RomRounding::SumPreserving});
  for (uint32_t f = 0; f < 256; ++f) EXPECT_EQ(c.nearest_address(f, 8), static_cast<int>(f >> 4));
  const TileWeightRom k(FilterKernel::bspline(), {16, 8, SamplePos::Corner, RomRounding::SumPreserving});
  EXPECT_EQ(k.nearest_address(7, 8), 0);    // 7/256 * 16 = 0.44 -> 0
  EXPECT_EQ(k.nearest_address(8, 8), 1);    // 0.5 -> 1 (round half up)
  EXPECT_EQ(k.nearest_address(255, 8), 16); // last corner entry
  int32_t w[4];
  c.weights_nearest(0x35, 8, w);
  for (int t = 0; t < 4; ++t) EXPECT_EQ(w[t], c.row(3)[static_cast<size_t>(t)].value());
}

TEST(WeightRom, LinearReconstruction) {
  const TileWeightRom c(FilterKernel::catmull_rom(), {16, 8, SamplePos::Centre, RomRounding::SumPreserving});
  int32_t w[4];
  // At an entry's own position (f = (k + 1/2)/16 = (2k+1)/32) linear returns the entry.
  for (int k = 0; k < 16; ++k) {
    c.weights_linear(static_cast<uint32_t>((2 * k + 1) * 8), 8, 8, w);
    for (int t = 0; t < 4; ++t) ASSERT_EQ(w[t], c.row(k)[static_cast<size_t>(t)].value()) << k;
  }
  // Half-way between entries 4 and 5 (f = 5/16): the average, rounded half up.
  c.weights_linear(5 * 16, 8, 8, w);
  for (int t = 0; t < 4; ++t) {
    const int32_t a = c.row(4)[static_cast<size_t>(t)].value(), b = c.row(5)[static_cast<size_t>(t)].value();
    EXPECT_EQ(w[t], static_cast<int32_t>(std::floor((a + b) / 2.0 + 0.5)));
  }
  // Below the first entry's centre the tile edge clamps.
  c.weights_linear(2, 8, 8, w);
  for (int t = 0; t < 4; ++t) EXPECT_EQ(w[t], c.row(0)[static_cast<size_t>(t)].value());
}

TEST(WeightRom, TileWeightMultiplierSignsAndMagnitudes) {
  for (int32_t x = -255; x <= 255; x += 3)
    for (int32_t y = -255; y <= 255; y += 5) {
      const int32_t p = tile_weight_multiply(x, y, 8);
      const uint32_t mag = unorm::mul_round(static_cast<uint32_t>(std::abs(x)), static_cast<uint32_t>(std::abs(y)), 8);
      ASSERT_EQ(std::abs(p), static_cast<int32_t>(mag));
      if (mag != 0) {
        ASSERT_EQ(p < 0, (x < 0) != (y < 0));
      }
    }
  EXPECT_EQ(tile_weight_multiply(255, -255, 8), -255);
  EXPECT_EQ(tile_weight_multiply(-128, -128, 8), 64);
}

// Separable composition through the multiplier: the 16 products of two exact-sum rows sum to
// 255 within 16 x 0.5 LSB (one rounding per multiply; Eq. 3.9 per product).
TEST(WeightRom, SeparableCompositionPartitionOfUnity) {
  for (const char* name : {"bspline", "catmull-rom", "mitchell"}) {
    const TileWeightRom rom(FilterKernel::by_name(name), {32, 8, SamplePos::Centre, RomRounding::SumPreserving});
    int worst = 0;
    for (int ky = 0; ky < 32; ++ky)
      for (int kx = 0; kx < 32; ++kx) {
        int32_t sum = 0;
        for (const RomWord& wy : rom.row(ky))
          for (const RomWord& wx : rom.row(kx)) sum += tile_weight_multiply(wx.value(), wy.value(), 8);
        worst = std::max(worst, std::abs(sum - 255));
      }
    EXPECT_LE(worst, 8) << name;
    RecordProperty(std::string("worst_") + name, worst);
  }
}

TEST(WeightRom, SymmetricStorageOf2DTiles) {
  for (const char* name : {"bspline", "catmull-rom", "blackman"})
    for (SamplePos pos : {SamplePos::Centre, SamplePos::Corner}) {
      const TileWeightRom2D rom(FilterKernel::by_name(name), {16, 8, pos, RomRounding::Nearest});
      EXPECT_EQ(rom.full_tiles(), 16);
      EXPECT_EQ(rom.stored_tiles(), 3);  // 3 instead of 16
      const int n = pos == SamplePos::Centre ? 16 : 17;
      for (int ty = 0; ty < 4; ++ty)
        for (int tx = 0; tx < 4; ++tx)
          for (int ky = 0; ky < n; ++ky)
            for (int kx = 0; kx < n; ++kx) ASSERT_EQ(rom.word(tx, ty, kx, ky), rom.word_direct(tx, ty, kx, ky));
    }
}

TEST(WeightRom, SpecValidation) {
  EXPECT_THROW((TileWeightRom(FilterKernel::bspline(), {8, 8})), InputError);
  EXPECT_THROW((TileWeightRom(FilterKernel::bspline(), {1024, 8})), InputError);
  EXPECT_THROW((TileWeightRom(FilterKernel::bspline(), {64, 3})), InputError);
  EXPECT_THROW((TileWeightRom(FilterKernel::bspline(), {64, 17})), InputError);
  EXPECT_NO_THROW((TileWeightRom(FilterKernel::bspline(), {16, 16})));
  EXPECT_NO_THROW((TileWeightRom(FilterKernel::bspline(), {512, 4})));
}

TEST(WeightRom, BoxAndTentTiles) {
  // Tent (width 2): 2 taps; the row at f is (1 - f, f).
  const TileWeightRom tent(FilterKernel::tent(), {16, 8, SamplePos::Centre, RomRounding::SumPreserving});
  ASSERT_EQ(tent.taps(), 2);
  EXPECT_EQ(tent.first_tap(), 0);
  for (int k = 0; k < 16; ++k) {
    const double f = (k + 0.5) / 16;
    EXPECT_LT(std::abs(tent.row(k)[1].value() - 255 * f), 1.0);
    EXPECT_EQ(tent.row(k)[0].value() + tent.row(k)[1].value(), 255);
  }
  // Box (width 1) over 2 taps: nearest texel gets everything.
  const TileWeightRom box(FilterKernel::box(), {16, 8, SamplePos::Centre, RomRounding::SumPreserving});
  EXPECT_EQ(box.row(3)[0].value(), 255);
  EXPECT_EQ(box.row(12)[1].value(), 255);
}

}  // namespace
}  // namespace tfu
