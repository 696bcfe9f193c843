// Lee & Jen direction-weight ROMs and kernel shapes (cmodel/direction_rom.hpp, rom_dump.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

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

// The never-flag word both models read (choosable_directions) is the ROM contents, exhaustively;
// every address has some choosable direction.
TEST(DirectionRom, ChoosableWordsAreTheRomsNeverFlags) {
  int never = 0;
  for (size_t a = 0; a < 256; ++a) {
    const uint32_t word = choosable_directions(a);
    EXPECT_EQ(word >> kDirections, 0u) << a;
    EXPECT_NE(word, 0u) << a;
    for (int i = 0; i < kDirections; ++i) {
      const bool choosable = direction_weight_rom(i)[a] != kNeverChoose;
      ASSERT_EQ(((word >> i) & 1u) != 0, choosable) << a << ' ' << i;
      never += !choosable;
    }
  }
  EXPECT_GT(never, 0);  // some entries say never: the word is not all ones
}

TEST(DirectionRom, HandDerivedCodes) {
  const auto& h = direction_weight_rom(0);  // C4-C5, horizontal, ROI 0.5
  // fu4 = fv4 = 0: d = 1/32, w = 1/(1 - 1/16) = 16/15, code round(17.07) = 17.
  EXPECT_EQ(h[0x00], 17);
  // fv4 = 7: d = 15/32, w = 1/(1 - 15/16) = 16, code 256 saturates at 254.
  EXPECT_EQ(h[0x70], 254);
  // fv4 = 8: d = 17/32 > 1/2: never choose.
  EXPECT_EQ(h[0x80], kNeverChoose);
  // C4-C8 vertical at fu4 = 3: d = 7/32, w = 1/(1 - 7/16) = 16/9, code round(28.44) = 28.
  EXPECT_EQ(direction_weight_rom(2)[0x03], 28);
  EXPECT_EQ(decode_weight(16), 1.0);
  EXPECT_TRUE(std::isinf(decode_weight(kNeverChoose)));
}

TEST(DirectionRom, CentreDiagonalsAreChosenNearTheirLine) {
  // On the C4-C9 diagonal (fu = fv) the distance is 0: weight 1.
  for (int k = 0; k < 16; ++k) EXPECT_EQ(direction_weight_rom(4)[static_cast<size_t>(k * 17)], 16);
  // C5-C8 (fu + fv = 1): address (fv4, fu4) with fu4 + fv4 = 15.
  for (int k = 0; k < 16; ++k) EXPECT_EQ(direction_weight_rom(5)[static_cast<size_t>((k << 4) | (15 - k))], 16);
}

TEST(DirectionRom, EndpointsDifferByExactlyOneOnTheBlendAxis) {
  for (const Direction& d : directions()) {
    const TexelPos p = texel_pos(d.p), q = texel_pos(d.q);
    const int dt = d.axis == BlendAxis::X ? q.x - p.x : q.y - p.y;
    EXPECT_EQ(dt, 1) << d.name();
    // x takes precedence: t = fv only when the x coordinates are not exactly {0, 1}.
    if (d.axis == BlendAxis::Y) {
      EXPECT_FALSE(std::min(p.x, q.x) == 0 && std::max(p.x, q.x) == 1) << d.name();
    }
    EXPECT_EQ(d.index, &d - directions().data());
  }
  // The brief's examples and the centre diagonals.
  EXPECT_EQ(directions()[14].p, 3);  // C3-C9: t = fv, Cp = C3
  EXPECT_EQ(directions()[14].axis, BlendAxis::Y);
  EXPECT_EQ(directions()[18].p, 1);  // C1-C9: t = fu, Cp = C1
  EXPECT_EQ(directions()[18].axis, BlendAxis::X);
  EXPECT_EQ(directions()[4].axis, BlendAxis::X);  // C4-C9
  EXPECT_EQ(directions()[5].axis, BlendAxis::X);  // C5-C8: Cp = C8 (x = 0)
  EXPECT_EQ(directions()[5].p, 8);
}

TEST(DirectionRom, DistanceHandValues) {
  EXPECT_DOUBLE_EQ(distance_to_direction(0, 0.25, 0.3), 0.3);              // C4-C5: d = fv
  EXPECT_DOUBLE_EQ(distance_to_direction(1, 0.25, 0.3), 0.7);              // C8-C9: d = 1 - fv
  EXPECT_DOUBLE_EQ(distance_to_direction(3, 0.25, 0.3), 0.75);             // C5-C9: d = 1 - fu
  EXPECT_NEAR(distance_to_direction(4, 1.0, 0.0), std::sqrt(0.5), 1e-15);  // C4-C9 to corner C5
  EXPECT_NEAR(distance_to_direction(6, 0.0, 0.0), std::sqrt(0.5), 1e-15);  // C1-C5 to C4
  EXPECT_NEAR(distance_to_direction(14, 0.0, 0.0), 1.0 / std::sqrt(5.0), 1e-15);  // C3-C9 to C4
  // ROI = half the distance from the line to the nearest centre-square corner off the line.
  EXPECT_NEAR(directions()[14].roi, 0.5 * distance_to_direction(14, 0.0, 0.0), 1e-15);
  EXPECT_NEAR(directions()[6].roi, 0.5 * distance_to_direction(6, 0.0, 0.0), 1e-15);
  EXPECT_TRUE(std::isinf(exact_weight(0, 0.5, 0.5)));   // d == ROI: never
  EXPECT_DOUBLE_EQ(exact_weight(0, 0.5, 0.25), 2.0);    // d = ROI / 2: w = 2
}

// Exact integer form, independent of floating point: with X = 32 fu = 2 fu4 + 1 and
// Y = 32 fv = 2 fv4 + 1, C = (X - 32 px) uy - (Y - 32 py) ux is an integer (u = Cq - Cp), and since
// ROI = 1 / (2 |u|) for all three families, d / ROI = |C| / 16 exactly. Hence
// d >= ROI <=> |C| >= 16, and otherwise w = 16 / (16 - |C|), code = round(256 / (16 - |C|)).
TEST(DirectionRom, ExactIntegerFormAndNeverChooseIffOutsideRoi) {
  int never_total = 0, boundary = 0;
  for (int i = 0; i < kDirections; ++i) {
    const Direction& d = directions()[static_cast<size_t>(i)];
    const TexelPos p = texel_pos(d.p), q = texel_pos(d.q);
    const int ux = q.x - p.x, uy = q.y - p.y;
    EXPECT_NEAR(d.roi, 0.5 / std::sqrt(ux * ux + uy * uy), 1e-15) << d.name();
    for (int a = 0; a < 256; ++a) {
      const int X = 2 * (a & 15) + 1, Y = 2 * (a >> 4) + 1;
      const int c = std::abs((X - 32 * p.x) * uy - (Y - 32 * p.y) * ux);
      const int n = 16 - c;  // 16 (1 - d/ROI)
      const uint8_t code = direction_weight_rom(i)[static_cast<size_t>(a)];
      if (c == 16) ++boundary;
      if (n <= 0) {
        ++never_total;
        ASSERT_EQ(code, kNeverChoose) << d.name() << " address " << a;
      } else {
        // round half up of 256 / n; n = 1 gives 256 and saturates.
        const int want = std::min(254, (512 + n) / (2 * n));
        ASSERT_EQ(code, want) << d.name() << " address " << a;
        ASSERT_LT(distance_to_direction(i, (X) / 32.0, (Y) / 32.0), d.roi);
      }
    }
  }
  EXPECT_GT(boundary, 0);  // exact d == ROI occurs (diagonals): it must read as never choose
  EXPECT_GT(never_total, 0);
}

TEST(DirectionKernelShapes, CountsAndRotations) {
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

TEST(DirectionKernelShapes, RotationPermutesTexelsAndDirectionsForEveryMask) {
  for (unsigned m = 0; m <= kAllTexels; ++m) {
    const auto mask = static_cast<TexelMask>(m);
    const TexelMask r = rotate_mask(mask);
    ASSERT_EQ(r & ~kAllTexels, 0);
    ASSERT_EQ(std::popcount(static_cast<unsigned>(r)), std::popcount(m));
    ASSERT_EQ(rotate_mask(rotate_mask(rotate_mask(r))), mask);
    // The 22 directions are closed under quarter turns, so the usable count is invariant.
    ASSERT_EQ(std::popcount(usable_directions(r)), std::popcount(usable_directions(mask)));
  }
  // Single texels: C4 -> C5 -> C9 -> C8 -> C4 (clockwise, y down); C1 -> C6 -> C12 -> C7.
  const auto bit = [](int n) { return static_cast<TexelMask>(1u << (n - 1)); };
  EXPECT_EQ(rotate_mask(bit(4)), bit(5));
  EXPECT_EQ(rotate_mask(bit(5)), bit(9));
  EXPECT_EQ(rotate_mask(bit(9)), bit(8));
  EXPECT_EQ(rotate_mask(bit(1)), bit(6));
  EXPECT_EQ(rotate_mask(bit(6)), bit(12));
  EXPECT_EQ(rotate_mask(bit(12)), bit(7));
}

TEST(DirectionKernelShapes, DroppedDirectionsOfT0AndL0) {
  const auto dropped = [](TexelMask m) {
    std::set<std::string> out;
    for (const Direction& d : directions())
      if (!(usable_directions(m) >> d.index & 1u)) out.insert(d.name());
    return out;
  };
  const auto& shapes = kernel_shapes();
  EXPECT_EQ(shapes[0].name(), "cross");
  EXPECT_EQ(shapes[1].name(), "T0");
  EXPECT_EQ(shapes[5].name(), "L0");
  EXPECT_EQ(dropped(shapes[1].mask), (std::set<std::string>{"C1-C5", "C2-C4", "C1-C9", "C2-C8"}));
  EXPECT_EQ(dropped(shapes[5].mask), (std::set<std::string>{"C1-C5", "C2-C4", "C1-C9", "C2-C8", "C3-C8", "C4-C7",
                                                            "C3-C9", "C5-C7"}));
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
    std::string dir, addr, fu, fv, code;
    std::getline(f, dir, ',');
    std::getline(f, addr, ',');
    std::getline(f, fu, ',');
    std::getline(f, fv, ',');
    std::getline(f, code, ',');
    ASSERT_EQ(std::stoi(dir), 7);
    ASSERT_EQ(std::stoi(addr), n);
    ASSERT_EQ(std::stoi(fu) + 16 * std::stoi(fv), n);
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

namespace {
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> f;
  std::istringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) f.push_back(cell);
  return f;
}
}  // namespace

TEST(RomDump, TileCsvParsesBackToTheRom) {
  for (const SamplePos pos : {SamplePos::Centre, SamplePos::Corner}) {
    const TileWeightRom rom(FilterKernel::catmull_rom(), {16, 10, pos, RomRounding::SumPreserving});
    std::ostringstream csv;
    dump_tile_rom_csv(rom, csv);
    std::istringstream in(csv.str());
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line,
              "address,w[-1],w[+0],w[+1],w[+2],s[-1],mag[-1],s[+0],mag[+0],s[+1],mag[+1],s[+2],mag[+2],row_sum,position");
    int k = 0, negatives = 0;
    while (std::getline(in, line)) {
      const auto f = split_csv(line);
      ASSERT_EQ(f.size(), 15u) << line;
      ASSERT_EQ(std::stoi(f[0]), k);
      int32_t sum = 0;
      for (int t = 0; t < 4; ++t) {
        const RomWord w = rom.row(k)[static_cast<size_t>(t)];
        ASSERT_EQ(std::stoi(f[static_cast<size_t>(1 + t)]), w.value()) << line;
        ASSERT_EQ(std::stoi(f[static_cast<size_t>(5 + 2 * t)]), w.neg ? 1 : 0) << line;
        ASSERT_EQ(std::stoul(f[static_cast<size_t>(6 + 2 * t)]), w.mag) << line;
        sum += w.value();
        negatives += w.neg ? 1 : 0;
      }
      ASSERT_EQ(std::stoi(f[13]), sum);
      ASSERT_NEAR(std::stod(f[14]), rom.spec().position(k), 1e-6);
      ++k;
    }
    EXPECT_EQ(k, rom.entries());
    EXPECT_GT(negatives, 0);  // Catmull-Rom has negative lobes: the sign column is exercised
  }
}

TEST(RomDump, GenericHexIsFixedWidthAndRejectsWideWords) {
  const std::vector<uint32_t> words{0, 1, 0x1ff, 0x100};
  std::ostringstream hex, csv;
  dump_rom_hex(words, 9, hex);
  EXPECT_EQ(hex.str(), "000\n001\n1ff\n100\n");
  dump_rom_csv(words, csv);
  EXPECT_EQ(csv.str(), "address,value\n0,0\n1,1\n2,511\n3,256\n");
  std::ostringstream sink;
  EXPECT_THROW(dump_rom_hex(std::vector<uint32_t>{0x200}, 9, sink), std::invalid_argument);
  EXPECT_EQ(hex_digits(8), 2);
  EXPECT_EQ(hex_digits(9), 3);
  EXPECT_EQ(hex_digits(17), 5);
}

TEST(RomDump, SingleDirectionHexHas256Lines) {
  std::ostringstream hex;
  dump_direction_rom_hex(0, hex);
  std::istringstream in(hex.str());
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ASSERT_EQ(std::stoi(line, nullptr, 16), direction_weight_rom(0)[static_cast<size_t>(n)]);
    ++n;
  }
  EXPECT_EQ(n, 256);
}

}  // namespace
}  // namespace tfu::lee_jen
