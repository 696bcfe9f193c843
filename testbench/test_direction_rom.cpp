// Lee & Jen direction-weight ROMs and kernel shapes (cmodel/direction_rom.hpp, rom_dump.hpp).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <set>
#include <sstream>
#include <string>

#include "cmodel/direction_rom.hpp"
#include "cmodel/rom_dump.hpp"

namespace tfu::lee_jen {
namespace {

TEST(DirectionRom, TwentyTwoDistinctDirectionsWithPaperRois) {
  const auto& dirs = directions();
  ASSERT_EQ(dirs.size(), 22u);
  std::set<std::string> names;
  int axis = 0, diag = 0, two_by_one = 0;
  for (const Direction& d : dirs) {
    names.insert(d.name());
    const TexelPos p = texel_pos(d.p), q = texel_pos(d.q);
    const int dx = std::abs(q.x - p.x), dy = std::abs(q.y - p.y);
    if (dx + dy == 1) {
      ++axis;
      EXPECT_DOUBLE_EQ(d.roi, 0.5) << d.name();
    } else if (dx == 1 && dy == 1) {
      ++diag;
      EXPECT_DOUBLE_EQ(d.roi, std::sqrt(2.0) / 4.0) << d.name();
    } else {
      ++two_by_one;
      EXPECT_EQ(dx * dy, 2) << d.name();
      EXPECT_DOUBLE_EQ(d.roi, 1.0 / (2.0 * std::sqrt(5.0))) << d.name();
    }
    // Blend axis: Cp at 0 and Cq at 1 on that axis (Eq. 3's t in [0, 1]).
    if (d.axis == BlendAxis::X) {
      EXPECT_EQ(p.x, 0) << d.name();
      EXPECT_EQ(q.x, 1) << d.name();
    } else {
      EXPECT_EQ(p.y, 0) << d.name();
      EXPECT_EQ(q.y, 1) << d.name();
    }
  }
  EXPECT_EQ(names.size(), 22u);
  EXPECT_EQ(axis, 4);
  EXPECT_EQ(diag, 10);
  EXPECT_EQ(two_by_one, 8);
}

// Every address of every ROM against an independent recomputation from the geometry.
TEST(DirectionRom, EveryAddressMatchesGeometryExhaustive) {
  for (int i = 0; i < kDirections; ++i) {
    const Direction& d = directions()[static_cast<size_t>(i)];
    const TexelPos p = texel_pos(d.p), q = texel_pos(d.q);
    const auto& rom = direction_weight_rom(i);
    for (int a = 0; a < 256; ++a) {
      const double x = ((a & 15) + 0.5) / 16.0, y = ((a >> 4) + 0.5) / 16.0;
      // Distance to the line through p and q via the cross product with the unit direction.
      const double ux = q.x - p.x, uy = q.y - p.y, len = std::hypot(ux, uy);
      const double dist = std::abs((x - p.x) * uy - (y - p.y) * ux) / len;
      const bool never = 1.0 - dist / d.roi <= 1e-9;  // d >= ROI, with the paper's small threshold
      const int want = never ? 255 : static_cast<int>(std::min(254.0, std::floor(16.0 / (1.0 - dist / d.roi) + 0.5)));
      ASSERT_EQ(rom[static_cast<size_t>(a)], want) << d.name() << " address " << a;
      ASSERT_EQ(rom[static_cast<size_t>(a)] == kNeverChoose, never);
      ASSERT_GE(rom[static_cast<size_t>(a)], 16);  // w >= 1
    }
  }
}

TEST(DirectionRom, HandDerivedCodes) {
  const auto& h = direction_weight_rom(0);  // C4-C5, horizontal, ROI 0.5
  // xf4 = yf4 = 0: d = 1/32, w = 1/(1 - 1/16) = 16/15, code round(17.07) = 17.
  EXPECT_EQ(h[0x00], 17);
  // yf4 = 7: d = 15/32, w = 1/(1 - 15/16) = 16, code 256 saturates at 254.
  EXPECT_EQ(h[0x70], 254);
  // yf4 = 8: d = 17/32 > 1/2: never choose.
  EXPECT_EQ(h[0x80], kNeverChoose);
  // C4-C8 vertical at xf4 = 3: d = 7/32, w = 1/(1 - 7/16) = 16/9, code round(28.44) = 28.
  EXPECT_EQ(direction_weight_rom(2)[0x03], 28);
  EXPECT_EQ(decode_weight(16), 1.0);
  EXPECT_TRUE(std::isinf(decode_weight(kNeverChoose)));
}

TEST(DirectionRom, CentreDiagonalsAreChosenNearTheirLine) {
  // On the C4-C9 diagonal (xf = yf) the distance is 0: weight 1.
  for (int k = 0; k < 16; ++k) EXPECT_EQ(direction_weight_rom(4)[static_cast<size_t>(k * 17)], 16);
  // C5-C8 (xf + yf = 1): address (yf4, xf4) with xf4 + yf4 = 15.
  for (int k = 0; k < 16; ++k) EXPECT_EQ(direction_weight_rom(5)[static_cast<size_t>((k << 4) | (15 - k))], 16);
}

TEST(KernelShapes, CountsAndRotations) {
  const auto& shapes = kernel_shapes();
  ASSERT_EQ(shapes.size(), 9u);
  EXPECT_EQ(usable_directions(kAllTexels), (1u << 22) - 1);
  for (const KernelShape& s : shapes) {
    const int texels = std::popcount(static_cast<unsigned>(s.mask));
    const int dirs = std::popcount(usable_directions(s.mask));
    switch (s.kind) {
      case ShapeKind::Cross: EXPECT_EQ(texels, 12); EXPECT_EQ(dirs, 22); break;
      case ShapeKind::T: EXPECT_EQ(texels, 10) << s.name(); EXPECT_EQ(dirs, 18) << s.name(); break;
      case ShapeKind::L: EXPECT_EQ(texels, 8) << s.name(); EXPECT_EQ(dirs, 14) << s.name(); break;
    }
    // The centre square is always available.
    for (int n : {4, 5, 8, 9}) EXPECT_TRUE(s.mask >> (n - 1) & 1) << s.name();
    // Four quarter turns return to the start.
    EXPECT_EQ(rotate_mask(rotate_mask(rotate_mask(rotate_mask(s.mask)))), s.mask);
  }
  // T0 lacks C1 and C2 (Fig. 3a); rotating once clockwise removes the right-hand pair C6, C10.
  EXPECT_EQ(shapes[1].mask, kAllTexels & ~0x3);
  EXPECT_EQ(shapes[2].mask, kAllTexels & ~((1 << 5) | (1 << 9)));
  // All four T rotations are distinct, and so are the L rotations.
  std::set<TexelMask> t, l;
  for (const auto& s : shapes) (s.kind == ShapeKind::T ? t : l).insert(s.mask);
  EXPECT_EQ(t.size(), 4u);
  EXPECT_EQ(l.size(), 5u);  // 4 L masks + the cross mask inserted into `l`
}

TEST(RomDump, DirectionHexAndCsvParseBack) {
  std::ostringstream hex, csv;
  dump_direction_rom_hex(-1, hex);
  dump_direction_rom_csv(7, csv);
  std::istringstream in(hex.str());
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ASSERT_EQ(line.size(), 2u);
    ASSERT_EQ(std::stoi(line, nullptr, 16), direction_weight_rom(n / 256)[static_cast<size_t>(n % 256)]);
    ++n;
  }
  EXPECT_EQ(n, 22 * 256);
  std::istringstream c(csv.str());
  std::getline(c, line);
  EXPECT_EQ(line, "direction,address,xf4,yf4,code,weight");
  n = 0;
  while (std::getline(c, line)) {
    std::istringstream f(line);
    std::string dir, addr, xf, yf, code;
    std::getline(f, dir, ',');
    std::getline(f, addr, ',');
    std::getline(f, xf, ',');
    std::getline(f, yf, ',');
    std::getline(f, code, ',');
    ASSERT_EQ(std::stoi(dir), 7);
    ASSERT_EQ(std::stoi(addr), n);
    ASSERT_EQ(std::stoi(xf) + 16 * std::stoi(yf), n);
    ASSERT_EQ(std::stoi(code), direction_weight_rom(7)[static_cast<size_t>(n)]);
    ++n;
  }
  EXPECT_EQ(n, 256);
}

TEST(RomDump, TileHexIsSignMagnitudeInterleaved) {
  const TileWeightRom rom(FilterKernel::catmull_rom(), {32, 8, SamplePos::Centre, RomRounding::SumPreserving});
  std::ostringstream hex;
  dump_tile_rom_hex(rom, hex);
  std::istringstream in(hex.str());
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ASSERT_EQ(line.size(), 3u);  // 9-bit words -> 3 hex digits
    const int w = std::stoi(line, nullptr, 16);
    const RomWord want = rom.row(n / 4)[static_cast<size_t>(n % 4)];
    ASSERT_EQ(static_cast<uint32_t>(w & 0xff), want.mag);
    ASSERT_EQ((w >> 8) == 1, want.neg);
    ++n;
  }
  EXPECT_EQ(n, 32 * 4);
}

}  // namespace
}  // namespace tfu::lee_jen
