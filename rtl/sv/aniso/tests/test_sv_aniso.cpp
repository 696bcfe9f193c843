// Equivalence of the anisotropic LOD unit and probe generator in SystemVerilog (rtl/sv/aniso/,
// Verilated) with the C++ model (cmodel/aniso.hpp, cmodel/lod.hpp), bit for bit (docs/anisotropic.md):
// a dense derivative grid and >= 10^6 random derivative sets through the whole LOD unit, exact and
// near ties of the probe count, every N at every leading-one position of Pmax^2, the ellipse axes'
// dot-and-cross, hypot and count blocks on directed and random inputs, and every probe ROM address
// at every level. Every mismatch is counted; the first few are printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cmodel/aniso.hpp"
#include "cmodel/lod.hpp"
#include "testbench/iterations.hpp"

#include "Vtfu_aniso_axis_len2.h"
#include "Vtfu_aniso_count.h"
#include "Vtfu_aniso_count_ellipse.h"
#include "Vtfu_aniso_dot_cross.h"
#include "Vtfu_aniso_ellipse_major.h"
#include "Vtfu_aniso_lambda.h"
#include "Vtfu_aniso_lod.h"
#include "Vtfu_aniso_probe.h"
#include "verilated.h"

namespace {

constexpr uint64_t kSeed = 0xa115ULL;
constexpr int kRandomVectors = tfu::test::iterations(1'000'000);  // testbench/iterations.hpp
constexpr int kMaxReports = 8;
constexpr int64_t kOneTexel = 65536;
constexpr int64_t kInputLimit = int64_t{1} << 47;  // |derivative| at the 49-bit input port

struct Mismatches {
  int count = 0;
  void add(const std::string& what) {
    if (++count <= kMaxReports) ADD_FAILURE() << what;
  }
};

int64_t sext(uint64_t v, int bits) {
  const uint64_t m = uint64_t{1} << (bits - 1);
  v &= (bits == 64) ? ~uint64_t{0} : ((uint64_t{1} << bits) - 1);
  return static_cast<int64_t>((v ^ m) - m);
}
uint64_t port(int64_t v, int bits) { return static_cast<uint64_t>(v) & ((uint64_t{1} << bits) - 1); }

// Derivative components: zero, sub-texel, around one texel, powers of two and neighbours, the
// clamp 2^31 - 1 and beyond it up to the port's range; both signs.
std::vector<int64_t> grid_values() {
  std::vector<int64_t> v{0};
  for (const int64_t m : std::initializer_list<int64_t>{1, 255, 40000, kOneTexel - 1, kOneTexel, 98304, 5 * kOneTexel + 12345,
                                                        16 * kOneTexel, 100 * kOneTexel + 77, int64_t{3} << 28,
                                                        (int64_t{1} << 31) - 1, int64_t{1} << 31, kInputLimit}) {
    v.push_back(m);
    if (m != kInputLimit) v.push_back(-m);
  }
  v.push_back(-kInputLimit);
  return v;
}

int64_t random_derivative(std::mt19937_64& rng) {
  const int e = static_cast<int>(rng() % 48);
  const auto m = static_cast<int64_t>(rng() >> (63 - e));  // < 2^(e + 1) <= 2^48
  const int64_t c = std::min(m, kInputLimit);
  return rng() % 2 ? -c : c;
}

// ------------------------------------------------------------------ squared axis length
TEST(SvAnisoAxisLen2, MatchesDerivativeLengthSq) {
  VerilatedContext ctx;
  Vtfu_aniso_axis_len2 m{&ctx};
  Mismatches bad;
  const auto check = [&](int64_t du, int64_t dv) {
    m.du = port(du, 49);
    m.dv = port(dv, 49);
    m.eval();
    const uint64_t want = tfu::derivative_length_sq(du, dv);
    if (m.len2 != want || m.mag_u != tfu::derivative_magnitude(du) || m.mag_v != tfu::derivative_magnitude(dv))
      bad.add(fmt::format("du {} dv {}: sv {} |{}| |{}| c++ {}", du, dv, m.len2, m.mag_u, m.mag_v, want));
  };
  const std::vector<int64_t> g = grid_values();
  for (const int64_t a : g)
    for (const int64_t b : g) check(a, b);
  for (int64_t a = -300; a <= 300; ++a)
    for (int64_t b = -300; b <= 300; ++b) check(a, b);
  for (int k = 0; k < 31; ++k) check(int64_t{1} << k, (int64_t{1} << k) - 1);  // every single partial-product row
  std::mt19937_64 rng(kSeed);
  for (int k = 0; k < kRandomVectors; ++k) check(random_derivative(rng), random_derivative(rng));
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ probe count
TEST(SvAnisoCount, MatchesAnisoProbeCountAtTiesAndEveryMaxAniso) {
  VerilatedContext ctx;
  Vtfu_aniso_count m{&ctx};
  Mismatches bad;
  int64_t vectors = 0;
  const auto check = [&](uint64_t pmax2, uint64_t pmin2) {
    if (pmin2 > pmax2) std::swap(pmin2, pmax2);
    if (pmax2 >= (uint64_t{1} << 63)) return;
    m.pmax2 = pmax2;
    m.pmin2 = pmin2;
    for (int max_aniso = 0; max_aniso < 32; ++max_aniso)
      for (const bool pow2 : {false, true}) {
        // The threshold: 0 (the spec's N) at every maxAniso, and one of 1..7 in rotation at the
        // maxAniso values 1, 2, 4, 8, 15, 16 and 31 (the cap below, at and above 16).
        const bool with_threshold = max_aniso == 1 || max_aniso == 2 || max_aniso == 4 || max_aniso == 8 || max_aniso == 15 ||
                                    max_aniso == 16 || max_aniso == 31;
        for (const int t : {0, 1 + static_cast<int>((vectors / 64) % 7)}) {
          if (t != 0 && !with_threshold) continue;
          m.max_aniso = static_cast<uint8_t>(max_aniso);
          m.aniso_rounding = pow2;
          m.aniso_threshold = static_cast<uint8_t>(t);
          m.eval();
          ++vectors;
          const int want =
              tfu::aniso_probe_count(pmax2, pmin2, {max_aniso, pow2 ? tfu::AnisoRounding::PowerOfTwo : tfu::AnisoRounding::Integer, t});
          if (m.probes != want)
            bad.add(fmt::format("pmax2 {} pmin2 {} max {} pow2 {} t {}: sv {} c++ {}", pmax2, pmin2, max_aniso, pow2, t, m.probes, want));
        }
      }
  };
  std::mt19937_64 rng(kSeed + 1);
  // Exact ties k^2 Pmin^2 = Pmax^2 and one unit either side, at every magnitude.
  for (int e = 0; e < 55; ++e)
    for (uint64_t k = 1; k <= 17; ++k)
      for (int it = 0; it < 20; ++it) {
        const uint64_t pmin2 = (uint64_t{1} << e) | (rng() >> (64 - std::max(e, 1)));
        const uint64_t pmax2 = k * k * pmin2;
        for (const uint64_t d : {pmax2 - 1, pmax2, pmax2 + 1}) check(d, pmin2);
      }
  // Threshold ties k (8 + t) m = Pmax, 8 m = Pmin, and one unit of Pmax^2 either side.
  for (uint64_t t = 1; t <= 7; ++t)
    for (uint64_t k = 1; k <= 17; ++k)
      for (int it = 0; it < 20; ++it) {
        const uint64_t mm = 1 + (rng() >> (41 + it));  // Pmax = k (8 + t) m < 2^31.5
        const uint64_t pmax = k * (8 + t) * mm, pmin = 8 * mm;
        for (const uint64_t d : {pmax * pmax - 1, pmax * pmax, pmax * pmax + 1}) check(d, pmin * pmin);
      }
  for (const uint64_t pmax2 : {uint64_t{0}, uint64_t{1}, uint64_t{1} << 40, (uint64_t{1} << 63) - 1}) {
    check(pmax2, 0);
    check(pmax2, pmax2);
  }
  for (int k = 0; k < kRandomVectors / 64; ++k) {
    const uint64_t pmax2 = rng() >> 1;
    check(pmax2, pmax2 >> (rng() % 12) >> (rng() % 2 ? 0 : rng() % 50));
  }
  EXPECT_EQ(bad.count, 0);
  EXPECT_GT(vectors, 1'000'000);
}

// ------------------------------------------------------------------ lambda
TEST(SvAnisoLambda, MatchesAnisoLambdaForEveryNAndExponent) {
  VerilatedContext ctx;
  Vtfu_aniso_lambda m{&ctx};
  Mismatches bad;
  std::mt19937_64 rng(kSeed + 2);
  const auto check = [&](uint64_t pmax2, int n) {
    m.pmax2 = pmax2;
    m.probes = static_cast<uint8_t>(n);
    m.eval();
    const int64_t got = sext(m.lambda_q8, 16);
    const int32_t want = tfu::aniso_lambda(pmax2, n);
    if (got != want) bad.add(fmt::format("pmax2 {} N {}: sv {} c++ {}", pmax2, n, got, want));
  };
  for (int n = 1; n <= tfu::kMaxAniso; ++n) {
    check(0, n);
    for (int e = 0; e < 64; ++e) {  // bit 63: Pmax'^2 of the ellipse axes
      const uint64_t p = uint64_t{1} << e;
      for (const uint64_t x : {p, p + 1, p | (p - 1), p | (p >> 1)}) check(x, n);
      for (int it = 0; it < 1000; ++it) check(p | (e == 0 ? 0 : rng() >> (64 - e)), n);
    }
  }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ ellipse axes
TEST(SvAnisoDotCross, MatchesAnisoDotCross) {
  VerilatedContext ctx;
  Vtfu_aniso_dot_cross m{&ctx};
  Mismatches bad;
  const auto check = [&](const tfu::TexelDerivatives& d) {
    m.mag_udx = tfu::derivative_magnitude(d.dudx);
    m.mag_vdx = tfu::derivative_magnitude(d.dvdx);
    m.mag_udy = tfu::derivative_magnitude(d.dudy);
    m.mag_vdy = tfu::derivative_magnitude(d.dvdy);
    m.neg_udx = d.dudx < 0;
    m.neg_vdx = d.dvdx < 0;
    m.neg_udy = d.dudy < 0;
    m.neg_vdy = d.dvdy < 0;
    m.eval();
    const tfu::DotCross want = tfu::aniso_dot_cross(d);
    if (sext(m.dot, 64) != want.dot_q32 || sext(m.det, 64) != want.det_q32)
      bad.add(fmt::format("d ({}, {}, {}, {}): sv {} {} c++ {} {}", d.dudx, d.dvdx, d.dudy, d.dvdy, sext(m.dot, 64),
                          sext(m.det, 64), want.dot_q32, want.det_q32));
  };
  const std::vector<int64_t> g = grid_values();
  for (const int64_t a : g)
    for (const int64_t b : g) {
      check({a, b, b, a});
      check({a, b, -b, a});
      check({a, a, b, b});
    }
  std::mt19937_64 rng(kSeed + 5);
  for (int i = 0; i < kRandomVectors; ++i)
    check({random_derivative(rng), random_derivative(rng), random_derivative(rng), random_derivative(rng)});
  EXPECT_EQ(bad.count, 0);
}

TEST(SvAnisoEllipseMajor, MatchesEllipseMajorLen2) {
  VerilatedContext ctx;
  Vtfu_aniso_ellipse_major m{&ctx};
  Mismatches bad;
  const auto check = [&](uint64_t px2, uint64_t py2, int64_t dot) {
    m.px2 = px2;
    m.py2 = py2;
    m.dot = static_cast<uint64_t>(dot);
    m.eval();
    const uint64_t want = tfu::ellipse_major_len2(px2, py2, dot);
    if (m.pmax2 != want) bad.add(fmt::format("px2 {} py2 {} dot {}: sv {} c++ {}", px2, py2, dot, m.pmax2, want));
  };
  constexpr uint64_t kMax63 = (uint64_t{1} << 63) - 1;
  // Exact cases: the 8:1 Pythagorean footprint of test_aniso_ellipse at every scale 2^k, F = 0, E = 0,
  // the largest inputs, and every leading-one position of E and of F (the mantissa shift s).
  for (int k = 0; k <= 52; ++k) check(uint64_t{592} << k, uint64_t{1033} << k, int64_t{756} << k);
  for (const uint64_t v : {uint64_t{0}, uint64_t{1}, uint64_t{3} << 40, kMax63}) {
    check(v, 0, 0);
    check(0, v, 0);
    check(v, v, 0);
    check(v, v, static_cast<int64_t>(v >> 1));
    check(v, v, -static_cast<int64_t>(v >> 1));
  }
  check(kMax63, kMax63, static_cast<int64_t>(kMax63));
  check(kMax63, kMax63, -static_cast<int64_t>(kMax63));
  std::mt19937_64 rng(kSeed + 6);
  for (int e = 0; e < 63; ++e)
    for (int it = 0; it < 200; ++it) {
      const uint64_t x = (uint64_t{1} << e) | (rng() >> (64 - std::max(e, 1)));
      const uint64_t y = rng() >> (1 + rng() % 63);
      check(x + y > kMax63 ? kMax63 : x + y, y, static_cast<int64_t>(rng() >> (1 + rng() % 63)) * (it % 2 ? 1 : -1));
      check(y, y, static_cast<int64_t>(x >> 1) * (it % 2 ? 1 : -1));  // E = 0: F alone, leading one at e
    }
  // Random inputs of every magnitude, and consistent ones from random derivatives.
  for (int i = 0; i < kRandomVectors; ++i) {
    if (i % 2 == 0) {
      const uint64_t px2 = rng() >> (1 + rng() % 63), py2 = rng() >> (1 + rng() % 63);
      check(px2, py2, static_cast<int64_t>(rng() >> (1 + rng() % 63)) * (rng() % 2 ? 1 : -1));
    } else {
      const tfu::TexelDerivatives d{random_derivative(rng), random_derivative(rng), random_derivative(rng),
                                    random_derivative(rng)};
      check(tfu::derivative_length_sq(d.dudx, d.dvdx), tfu::derivative_length_sq(d.dudy, d.dvdy), tfu::aniso_dot_cross(d).dot_q32);
    }
  }
  EXPECT_EQ(bad.count, 0);
}

TEST(SvAnisoCountEllipse, MatchesAnisoProbeCountEllipseAtTiesAndEveryMaxAniso) {
  VerilatedContext ctx;
  Vtfu_aniso_count_ellipse m{&ctx};
  Mismatches bad;
  int64_t vectors = 0;
  const auto check = [&](uint64_t pmax2, uint64_t det) {
    m.pmax2 = pmax2;
    m.det = det;
    for (int max_aniso = 0; max_aniso < 32; ++max_aniso)
      for (const bool pow2 : {false, true})
        for (const int t : {0, 1 + static_cast<int>((vectors / 64) % 7)}) {
          m.max_aniso = static_cast<uint8_t>(max_aniso);
          m.aniso_rounding = pow2;
          m.aniso_threshold = static_cast<uint8_t>(t);
          m.eval();
          ++vectors;
          const int want = tfu::aniso_probe_count_ellipse(
              pmax2, det, {max_aniso, pow2 ? tfu::AnisoRounding::PowerOfTwo : tfu::AnisoRounding::Integer, t, tfu::AnisoAxes::Ellipse});
          if (m.probes != want)
            bad.add(fmt::format("pmax2 {} det {} max {} pow2 {} t {}: sv {} c++ {}", pmax2, det, max_aniso, pow2, t, m.probes, want));
        }
  };
  std::mt19937_64 rng(kSeed + 7);
  // Ties n (8 + t) |D| = 8 Pmax'^2: |D| = 8 q, Pmax'^2 = n (8 + t) q, and one unit either side.
  for (uint64_t t = 0; t <= 7; ++t)
    for (uint64_t n = 1; n <= 17; ++n)
      for (int it = 0; it < 20; ++it) {
        const uint64_t q = 1 + (rng() >> (9 + 2 * it));  // Pmax'^2 = n (8 + t) q < 2^64
        const uint64_t p = n * (8 + t) * q;
        for (const uint64_t d : {p - 1, p, p + 1}) check(d, 8 * q);
      }
  for (const uint64_t pmax2 : {uint64_t{0}, uint64_t{1}, uint64_t{1} << 40, ~uint64_t{0}}) {
    check(pmax2, 0);
    check(pmax2, (uint64_t{1} << 63) - 1);
  }
  for (int k = 0; k < kRandomVectors / 256; ++k) {
    const uint64_t pmax2 = rng();
    check(pmax2, (pmax2 >> 1) >> (rng() % 6) >> (rng() % 2 ? 0 : rng() % 50));
  }
  EXPECT_EQ(bad.count, 0);
  EXPECT_GT(vectors, 1'000'000);
}

// ------------------------------------------------------------------ whole LOD unit
TEST(SvAnisoLod, MatchesAnisoLodOnTheDerivativeGridAndRandomDerivatives) {
  VerilatedContext ctx;
  Vtfu_aniso_lod m{&ctx};
  Mismatches bad;
  int64_t vectors = 0;
  const auto check = [&](const tfu::TexelDerivatives& d, int max_aniso, bool pow2, int t, bool ellipse) {
    m.dudx = port(d.dudx, 49);
    m.dvdx = port(d.dvdx, 49);
    m.dudy = port(d.dudy, 49);
    m.dvdy = port(d.dvdy, 49);
    m.max_aniso = static_cast<uint8_t>(max_aniso);
    m.aniso_rounding = pow2;
    m.aniso_threshold = static_cast<uint8_t>(t);
    m.aniso_axes = ellipse;
    m.eval();
    ++vectors;
    const tfu::AnisoLod a = tfu::aniso_lod(d, {max_aniso, pow2 ? tfu::AnisoRounding::PowerOfTwo : tfu::AnisoRounding::Integer, t,
                                               ellipse ? tfu::AnisoAxes::Ellipse : tfu::AnisoAxes::Screen});
    const bool same = m.px2 == a.px2_q32 && m.py2 == a.py2_q32 && (m.major_x != 0) == a.major_x &&
                      sext(m.major_du, 32) == a.major_du_q16 && sext(m.major_dv, 32) == a.major_dv_q16 &&
                      m.probes == a.probes && sext(m.lambda_q8, 16) == a.lambda_q8 && m.pmax2 == a.pmax2_q32 &&
                      m.det == a.det_q32;
    if (!same)
      bad.add(fmt::format("d ({}, {}, {}, {}) max {} pow2 {} t {} ellipse {}: sv N {} lambda {} major ({}, {}) c++ N {} lambda {} major ({}, {})",
                          d.dudx, d.dvdx, d.dudy, d.dvdy, max_aniso, pow2, t, ellipse, m.probes, sext(m.lambda_q8, 16),
                          sext(m.major_du, 32), sext(m.major_dv, 32), a.probes, a.lambda_q8, a.major_du_q16,
                          a.major_dv_q16));
  };
  const std::vector<int64_t> g = grid_values();
  int k = 0;
  for (const int64_t dudx : g)
    for (const int64_t dvdx : g)
      for (const int64_t dudy : g)
        for (const int64_t dvdy : g) {
          ++k;
          check({dudx, dvdx, dudy, dvdy}, 1 + k % 16, (k / 16) % 2 == 1, (k / 32) % 8, (k / 256) % 2 == 1);
        }
  std::mt19937_64 rng(kSeed + 3);
  for (int i = 0; i < kRandomVectors; ++i) {
    const tfu::TexelDerivatives d{random_derivative(rng), random_derivative(rng), random_derivative(rng),
                                  random_derivative(rng)};
    check(d, static_cast<int>(rng() % 32), rng() % 2 == 1, i % 8, (i / 8) % 2 == 1);
  }
  EXPECT_EQ(bad.count, 0);
  const auto n = static_cast<int64_t>(g.size());
  EXPECT_EQ(vectors, n * n * n * n + kRandomVectors);  // the whole grid, then the random vectors
}

// ------------------------------------------------------------------ probe generator
TEST(SvAnisoProbe, MatchesProbeOffsetsAndWeightsAtEveryAddressAndLevel) {
  VerilatedContext ctx;
  Vtfu_aniso_probe m{&ctx};
  Mismatches bad;
  std::mt19937_64 rng(kSeed + 4);
  const auto& rom = tfu::probe_rom();
  const auto check = [&](int64_t du, int64_t dv, int n, int i, int level) {
    m.major_du = static_cast<uint32_t>(port(du, 32));
    m.major_dv = static_cast<uint32_t>(port(dv, 32));
    m.probes = static_cast<uint8_t>(n);
    m.index = static_cast<uint8_t>(i);
    m.level = static_cast<uint8_t>(level);
    m.eval();
    tfu::AnisoLod a;
    a.major_du_q16 = du;
    a.major_dv_q16 = dv;
    a.probes = n;
    const tfu::ProbeOffset o = tfu::probe_offset(a, i);
    const bool same = sext(m.off_du_q16, 31) == o.du_q16 && sext(m.off_dv_q16, 31) == o.dv_q16 &&
                      sext(m.off_du_q8, 23) == tfu::dp::probe_offset_on_level(o.du_q16, level) &&
                      sext(m.off_dv_q8, 23) == tfu::dp::probe_offset_on_level(o.dv_q16, level) &&
                      m.weight == rom[static_cast<size_t>(tfu::probe_rom_address(n, i))].weight;
    if (!same)
      bad.add(fmt::format("d ({}, {}) N {} i {} L {}: sv ({}, {}) L ({}, {}) w {}; c++ ({}, {})", du, dv, n, i, level,
                          sext(m.off_du_q16, 31), sext(m.off_dv_q16, 31), sext(m.off_du_q8, 23), sext(m.off_dv_q8, 23),
                          m.weight, o.du_q16, o.dv_q16));
  };
  constexpr int64_t kMax = tfu::kDerivativeClamp;
  const std::vector<int64_t> ds{0, 1, -1, 255, -32768, kOneTexel, -kOneTexel, 3 * kOneTexel + 1, -(100 * kOneTexel + 77),
                                int64_t{1} << 30, kMax, -kMax};
  for (int n = 1; n <= tfu::kMaxAniso; ++n)
    for (int i = 1; i <= n; ++i)
      for (int level = 0; level < 16; ++level) {
        for (size_t a = 0; a < ds.size(); ++a) check(ds[a], ds[ds.size() - 1 - a], n, i, level);
        for (int it = 0; it < 60; ++it) {
          const auto mag = [&] { return static_cast<int64_t>(rng() >> (33 + rng() % 31)); };  // < 2^31
          const int64_t du = mag(), dv = mag();
          check(rng() % 2 ? -du : du, rng() % 2 ? -dv : dv, n, i, level);
        }
      }
  EXPECT_EQ(bad.count, 0);
}

}  // namespace
