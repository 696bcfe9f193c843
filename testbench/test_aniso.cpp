// Anisotropic LOD unit and probe generator (cmodel/aniso.hpp; docs/anisotropic.md): N and lambda
// against a long-double reference of the EXT_texture_filter_anisotropic formulas over a dense
// derivative grid, N = 1 bit-identical to the isotropic LOD unit, the probe ROM (fractions and
// weights), probe positions against the exact formula, the averaging unit, degenerate inputs.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "cmodel/aniso.hpp"
#include "cmodel/aniso_fast.hpp"
#include "cmodel/datapath.hpp"
#include "cmodel/fixed_coord.hpp"
#include "cmodel/lod.hpp"

namespace tfu {
namespace {

__extension__ using u128 = unsigned __int128;  // exact n^2 Pmin^2 in the reference (up to 71 bits)

constexpr int64_t kOneTexel = 65536;  // Q.16
constexpr AnisoRounding rounding(bool pow2) { return pow2 ? AnisoRounding::PowerOfTwo : AnisoRounding::Integer; }
constexpr double kLambdaBoundLsb = 1.2;  // docs/anisotropic.md: 0.45 (log2 ROM) + 0.25 (R ROM) + 0.5 (halving)

// Derivative components of the grid (Q.16 level-0 texels): zero, sub-texel, around one texel,
// powers of two and their neighbours, large, the clamp and beyond it; both signs.
std::vector<int64_t> grid_values() {
  std::vector<int64_t> v{0};
  for (const int64_t m : std::initializer_list<int64_t>{1, 3, 255, 4096, 40000, kOneTexel - 1, kOneTexel,
                          kOneTexel + 1, 98304, 2 * kOneTexel, 5 * kOneTexel + 12345, 7 * kOneTexel, 16 * kOneTexel,
                          int64_t{1} << 24, 100 * kOneTexel + 77, int64_t{1} << 28, int64_t{3} << 28,
                          (int64_t{1} << 31) - 1, int64_t{1} << 40}) {
    v.push_back(m);
    v.push_back(-m);
  }
  return v;
}

// Reference N = min(ceil(Pmax / Pmin), maxAniso) from the (exact integer) squared lengths: ceil of
// the long-double ratio, decided in exact 128-bit arithmetic where the ratio is within 1e-9 of an
// integer (where the rounding of sqrt could move the ceiling).
int reference_probe_count(uint64_t pmax2, uint64_t pmin2, int max_aniso) {
  int n;
  if (pmax2 == 0) {
    n = 1;
  } else if (pmin2 == 0) {
    n = max_aniso;
  } else {
    const long double ratio = std::sqrt(static_cast<long double>(pmax2)) / std::sqrt(static_cast<long double>(pmin2));
    const long double k = std::round(ratio);
    if (std::fabs(ratio - k) < 1e-9L * k && k <= 64) {
      const auto ki = static_cast<uint64_t>(k);
      n = static_cast<u128>(ki * ki) * pmin2 >= pmax2 ? static_cast<int>(ki) : static_cast<int>(ki) + 1;
    } else {
      n = ratio > 64 ? 65 : static_cast<int>(std::ceil(ratio));
    }
    n = std::min(n, max_aniso);
  }
  return n;
}

// 256 log2(Pmax / N) in long double.
long double reference_lambda_q8(uint64_t pmax2, int n) {
  return 256.0L * (0.5L * std::log2(static_cast<long double>(pmax2)) - 16.0L - std::log2(static_cast<long double>(n)));
}

// ---------------------------------------------------------------- ROMs

TEST(AnisoLog2SqRom, HandValuesAndRounding) {
  const auto& r = aniso_log2_sq_rom();
  EXPECT_EQ(r[0], 0);
  EXPECT_EQ(r[1], 512);
  EXPECT_EQ(r[2], 812);  // 512 log2 3 = 811.5008
  EXPECT_EQ(r[3], 1024);
  EXPECT_EQ(r[7], 1536);
  EXPECT_EQ(r[15], 2048);
  for (int n = 1; n <= kMaxAniso; ++n)
    EXPECT_LE(std::fabs(r[static_cast<size_t>(n - 1)] - 512.0 * std::log2(n)), 0.5) << n;
}

TEST(ProbeRom, FractionsAreTheReferencePositionsRounded) {
  const auto& rom = probe_rom();
  EXPECT_EQ(rom[static_cast<size_t>(probe_rom_address(1, 1))].frac_q16, 0);
  EXPECT_EQ(rom[static_cast<size_t>(probe_rom_address(2, 1))].frac_q16, -10923);  // -65536 / 6 = -10922.67
  EXPECT_EQ(rom[static_cast<size_t>(probe_rom_address(2, 2))].frac_q16, 10923);
  EXPECT_EQ(rom[static_cast<size_t>(probe_rom_address(3, 1))].frac_q16, -16384);  // -1/4 exactly
  EXPECT_EQ(rom[static_cast<size_t>(probe_rom_address(16, 16))].frac_q16, 28913);  // 15/34 = 0.441176
  for (int n = 1; n <= kMaxAniso; ++n) {
    for (int i = 1; i <= n; ++i) {
      const int32_t q = rom[static_cast<size_t>(probe_rom_address(n, i))].frac_q16;
      // x - 1/2 + i/(N+1) of the EXT spec, i.e. (2i - N - 1) / (2 (N + 1)) probe spacings of the major vector.
      const double exact = 65536.0 * (-0.5 + static_cast<double>(i) / (n + 1));
      EXPECT_LE(std::fabs(q - exact), 0.5) << n << " " << i;
      EXPECT_EQ(q, -rom[static_cast<size_t>(probe_rom_address(n, n + 1 - i))].frac_q16) << n << " " << i;
      EXPECT_LT(std::abs(q), 1 << 15);
    }
    for (int i = n + 1; i <= kMaxAniso; ++i) {
      EXPECT_EQ(rom[static_cast<size_t>(probe_rom_address(n, i))].frac_q16, 0);
      EXPECT_EQ(rom[static_cast<size_t>(probe_rom_address(n, i))].weight, 0);
    }
  }
}

TEST(ProbeRom, WeightsSumExactlyTo256AndAreSymmetric) {
  const auto& rom = probe_rom();
  const auto w = [&](int n, int i) { return rom[static_cast<size_t>(probe_rom_address(n, i))].weight; };
  EXPECT_EQ(w(1, 1), 256);
  EXPECT_EQ(w(3, 1), 85);
  EXPECT_EQ(w(3, 2), 86);
  EXPECT_EQ(w(3, 3), 85);
  const std::vector<int> w6{42, 43, 43, 43, 43, 42};
  const std::vector<int> w7{36, 37, 37, 36, 37, 37, 36};
  for (int i = 1; i <= 6; ++i) EXPECT_EQ(w(6, i), w6[static_cast<size_t>(i - 1)]) << i;
  for (int i = 1; i <= 7; ++i) EXPECT_EQ(w(7, i), w7[static_cast<size_t>(i - 1)]) << i;
  for (int n = 1; n <= kMaxAniso; ++n) {
    int sum = 0;
    for (int i = 1; i <= n; ++i) {
      sum += w(n, i);
      EXPECT_EQ(w(n, i), w(n, n + 1 - i)) << n << " " << i;
      EXPECT_TRUE(w(n, i) == 256 / n || w(n, i) == 256 / n + 1) << n << " " << i;
      // Off the centre, never lighter than a probe further out (the extra ones go to the innermost
      // pairs; an odd N with an even 256 mod N leaves the centre at floor(256 / N)).
      if (2 * (i + 1) < n + 1) {
        EXPECT_LE(w(n, i), w(n, i + 1)) << n << " " << i;
      }
    }
    EXPECT_EQ(sum, 256) << n;
    if (std::has_single_bit(static_cast<unsigned>(n))) {
      for (int i = 1; i <= n; ++i) EXPECT_EQ(w(n, i), 256 / n);
    }
  }
}

// ---------------------------------------------------------------- N and lambda

TEST(AnisoLod, ProbeCountAndLambdaMatchTheReferenceOnTheGrid) {
  const std::vector<int64_t> g = grid_values();
  long double worst = 0;
  int64_t points = 0;
  for (const int64_t dudx : g)
    for (const int64_t dvdx : g)
      for (const int64_t dudy : g)
        for (const int64_t dvdy : g) {
          const TexelDerivatives d{dudx, dvdx, dudy, dvdy};
          const uint64_t px2 = derivative_length_sq(dudx, dvdx), py2 = derivative_length_sq(dudy, dvdy);
          const uint64_t pmax2 = std::max(px2, py2), pmin2 = std::min(px2, py2);
          const int ref_uncapped = reference_probe_count(pmax2, pmin2, 64);
          for (const int max_aniso : {1, 3, 7, 16}) {
            for (const bool pow2 : {false, true}) {
              const AnisoLod a = aniso_lod(d, {max_aniso, rounding(pow2)});
              ++points;
              ASSERT_EQ(a.px2_q32, px2);
              ASSERT_EQ(a.py2_q32, py2);
              ASSERT_EQ(a.major_x, px2 >= py2);
              const int ref = std::min(ref_uncapped, max_aniso);
              const int want = pow2 ? static_cast<int>(std::bit_ceil(static_cast<unsigned>(ref))) : ref;
              ASSERT_EQ(a.probes, want) << dudx << " " << dvdx << " " << dudy << " " << dvdy << " max " << max_aniso;
              if (pmax2 == 0) {
                ASSERT_EQ(a.lambda_q8, kLodMinusInfinity);
                continue;
              }
              const long double err = std::fabs(a.lambda_q8 - reference_lambda_q8(pmax2, a.probes));
              worst = std::max(worst, err);
              ASSERT_LE(err, kLambdaBoundLsb) << dudx << " " << dvdx << " " << dudy << " " << dvdy << " N " << a.probes;
            }
          }
        }
  EXPECT_GT(points, 10'000'000);
  RecordProperty("lambda_max_error_lsb", std::to_string(static_cast<double>(worst)));
  std::printf("grid: %lld LOD evaluations, max |lambda - 256 log2(Pmax/N)| = %.4Lf LSB (bound %.2f)\n",
              static_cast<long long>(points), worst, kLambdaBoundLsb);
}

// Random footprints with a controlled ratio: exact integer ratios (Px = k Py, where ceil is decided
// by equality), ratios one unit off an integer, and log-uniform random ones.
TEST(AnisoLod, ProbeCountAtExactAndNearIntegerRatios) {
  std::mt19937_64 rng(0xa11505);
  long double worst = 0;
  for (int it = 0; it < 400'000; ++it) {
    const int k = 1 + static_cast<int>(rng() % 20);
    const int e = static_cast<int>(rng() % 22);
    const auto a = static_cast<int64_t>(rng() % (uint64_t{1} << e)) - (int64_t{1} << e) / 2;
    const auto b = static_cast<int64_t>(rng() % (uint64_t{1} << e));
    TexelDerivatives d{k * a, k * b, -b, a};  // |x| = k |y| exactly, y perpendicular to x
    switch (it % 4) {
      case 1: d.dudx += 1; break;   // just over k
      case 2: d.dvdx -= 1; break;   // just under or over, depending on the sign of b
      case 3: std::swap(d.dudx, d.dudy), std::swap(d.dvdx, d.dvdy); break;  // y major
      default: break;
    }
    const int max_aniso = 1 + static_cast<int>(rng() % 16);
    for (const bool pow2 : {false, true}) {
      const AnisoLod r = aniso_lod(d, {max_aniso, rounding(pow2)});
      const uint64_t pmax2 = std::max(r.px2_q32, r.py2_q32), pmin2 = std::min(r.px2_q32, r.py2_q32);
      const int ref = reference_probe_count(pmax2, pmin2, max_aniso);
      ASSERT_EQ(r.probes, pow2 ? static_cast<int>(std::bit_ceil(static_cast<unsigned>(ref))) : ref)
          << d.dudx << " " << d.dvdx << " " << d.dudy << " " << d.dvdy << " max " << max_aniso;
      if (it % 4 == 0 && pmin2 != 0) {
        ASSERT_EQ(ref, std::min(k, max_aniso));  // the tie is exact
      }
      if (pmax2 != 0) {
        const long double err = std::fabs(r.lambda_q8 - reference_lambda_q8(pmax2, r.probes));
        worst = std::max(worst, err);
        ASSERT_LE(err, kLambdaBoundLsb);
      }
    }
  }
  std::printf("ratios: max |lambda - 256 log2(Pmax/N)| = %.4Lf LSB\n", worst);
}

// Every N at every leading-one position of Pmax^2 (the log2 unit's whole range): lambda within the bound.
TEST(AnisoLod, LambdaBoundAtEveryExponentAndN) {
  std::mt19937_64 rng(77);
  long double worst = 0;
  for (int e = 0; e < 63; ++e)
    for (int n = 1; n <= kMaxAniso; ++n)
      for (int it = 0; it < 2000; ++it) {
        const uint64_t x = (uint64_t{1} << e) | (e == 0 ? 0 : rng() >> (64 - e));
        const long double err = std::fabs(aniso_lambda(x, n) - reference_lambda_q8(x, n));
        worst = std::max(worst, err);
        ASSERT_LE(err, kLambdaBoundLsb) << x << " " << n;
      }
  std::printf("log2 range: max |lambda - 256 log2(Pmax/N)| = %.4Lf LSB\n", worst);
}

// N = 1 (maxAniso = 1, or a round footprint) is the isotropic LOD unit bit for bit, with its one
// probe at the centre; a power-of-two N is the isotropic lambda minus log2 N levels exactly.
TEST(AnisoLod, OneProbeIsTheIsotropicLodBitForBit) {
  const std::vector<int64_t> g = grid_values();
  int64_t checked = 0;
  for (const int64_t dudx : g)
    for (const int64_t dvdx : g)
      for (const int64_t dudy : g)
        for (const int64_t dvdy : g) {
          const TexelDerivatives d{dudx, dvdx, dudy, dvdy};
          const int32_t iso = lambda_from_derivatives(d);
          for (const bool pow2 : {false, true}) {
            const AnisoLod a = aniso_lod(d, {1, rounding(pow2)});
            ASSERT_EQ(a.probes, 1);
            ASSERT_EQ(a.lambda_q8, iso) << dudx << " " << dvdx << " " << dudy << " " << dvdy;
            const ProbeOffset o = probe_offset(a, 1);
            ASSERT_EQ(o.du_q16, 0);
            ASSERT_EQ(o.dv_q16, 0);
            ++checked;
            const AnisoLod b = aniso_lod(d, {16, rounding(pow2)});
            if (b.px2_q32 == b.py2_q32) {
              ASSERT_EQ(b.probes, 1);
              ASSERT_EQ(b.lambda_q8, iso);
            }
            if (std::has_single_bit(static_cast<unsigned>(b.probes)) && iso != kLodMinusInfinity) {
              ASSERT_EQ(b.lambda_q8, iso - 256 * std::countr_zero(static_cast<unsigned>(b.probes)));
            }
          }
        }
  EXPECT_EQ(checked, 2 * static_cast<int64_t>(g.size() * g.size() * g.size() * g.size()));
}

// With one probe the probe coordinate on every level is the centre's texel_coord, and the average of
// one result is that result (every channel value of both channel ranges).
TEST(AnisoLod, OneProbeCoordinateAndAverageAreTheIdentity) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> s(-2.0f, 3.0f);
  for (int it = 0; it < 200'000; ++it) {
    const float x = s(rng);
    const int size = 1 + static_cast<int>(rng() % kMaxTextureSize);
    const int level = static_cast<int>(rng() % 15);
    const dp::LevelCoord c = dp::texel_coord(x, size);
    const dp::LevelCoord p = dp::probe_texel_coord(c, dp::probe_offset_on_level(probe_offset_q16(rng(), 1, 1), level));
    ASSERT_EQ(p.i0, c.i0);
    ASSERT_EQ(p.f, c.f);
  }
  for (int32_t v = -32640; v <= 32640; ++v) {
    const Texel4 c{v, v / 2, 255 - (v & 255), v & 255};
    ASSERT_EQ(dp::aniso_average(&c, 1), c);
  }
}

// ---------------------------------------------------------------- probes

// Offsets against the exact d (2i - N - 1) / (2 (N + 1)): the ROM fraction errs by <= 2^-17, the
// product is rounded to Q.16 (1/2 LSB), the level shift to Q.8 (1/2 LSB of level L).
TEST(AnisoProbes, OffsetsMatchTheExactPositionsWithinTheStatedBound) {
  std::vector<int64_t> ds = grid_values();
  std::mt19937_64 rng(99);
  for (int k = 0; k < 400; ++k) {
    const int e = static_cast<int>(rng() % 32);
    const auto m = static_cast<int64_t>(rng() >> (64 - e - 1));
    ds.push_back(rng() % 2 ? -m : m);
  }
  for (const int64_t d : ds) {
    const int64_t dc = d < 0 ? -int64_t{derivative_magnitude(d)} : int64_t{derivative_magnitude(d)};
    for (int n = 1; n <= kMaxAniso; ++n) {
      int64_t sum = 0;
      for (int i = 1; i <= n; ++i) {
        const int64_t o = probe_offset_q16(d, n, i);
        sum += o;
        ASSERT_EQ(o, -probe_offset_q16(d, n, n + 1 - i));  // symmetric about the centre
        ASSERT_EQ(o, -probe_offset_q16(-d, n, i));         // odd in d
        ASSERT_LT(std::abs(o), int64_t{1} << 30);
        const long double exact = static_cast<long double>(dc) * (-0.5L + static_cast<long double>(i) / (n + 1));
        const long double bound_q16 = std::fabs(static_cast<long double>(dc)) / 131072.0L + 0.5L;
        const long double err = std::fabs(static_cast<long double>(o) - exact);
        ASSERT_LE(err, bound_q16) << d << " " << n << " " << i;
        for (int level = 0; level < 15; ++level) {
          const long double scale = std::ldexp(1.0L, 8 + level);
          const long double err8 = std::fabs(static_cast<long double>(dp::probe_offset_on_level(o, level)) - exact / scale);
          ASSERT_LE(err8, bound_q16 / scale + 0.5L) << d << " " << n << " " << i << " L " << level;
        }
      }
      ASSERT_EQ(sum, 0);
    }
  }
}

// The probe coordinate on a power-of-two level against the reference u(x - 1/2 + i/(N+1), y):
// s W_L 2^8 - 128 + 2^8 (d / 2^L) (2i - N - 1) / (2 (N + 1)), within the floor of texel_coord
// (< 1 LSB) plus the offset bound.
TEST(AnisoProbes, ProbeTexelCoordinatesMatchTheReference) {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_real_distribution<float> grad(-0.2f, 0.2f);
  long double worst = 0;
  for (int it = 0; it < 200'000; ++it) {
    const int w0 = 1 << (4 + rng() % 8);  // 16..2048
    const float s = unit(rng), t = unit(rng);
    const TexelDerivatives d = derivatives_from_gradients(grad(rng), grad(rng), grad(rng), grad(rng), w0, w0);
    const AnisoLod a = aniso_lod(d, {16, rounding(it % 2 == 1)});
    // A random level, or one of the two levels a trilinear probe at lambda reads.
    const int max_level = std::countr_zero(static_cast<unsigned>(w0));
    const int lambda_level = a.lambda_q8 < 0 ? 0 : std::min(a.lambda_q8 >> 8, max_level);
    const int level = it % 3 == 0 ? static_cast<int>(rng() % static_cast<unsigned>(max_level + 1))
                                  : std::min(lambda_level + it % 3 - 1, max_level);
    const bool trilinear_level = level * 256 >= a.lambda_q8 - 256;  // L >= lambda - 1
    const int wl = w0 >> level;
    const dp::LevelCoord cu = dp::texel_coord(s, wl), cv = dp::texel_coord(t, wl);
    for (int i = 1; i <= a.probes; ++i) {
      const ProbeOffset o = probe_offset(a, i);
      const dp::LevelCoord pu = dp::probe_texel_coord(cu, dp::probe_offset_on_level(o.du_q16, level));
      const dp::LevelCoord pv = dp::probe_texel_coord(cv, dp::probe_offset_on_level(o.dv_q16, level));
      const long double frac = -0.5L + static_cast<long double>(i) / (a.probes + 1);
      const long double scale = std::ldexp(1.0L, 8 + level);
      for (const auto& [p, c, dd, oq16] :
           {std::tuple{pu, s, a.major_du_q16, o.du_q16}, std::tuple{pv, t, a.major_dv_q16, o.dv_q16}}) {
        const long double ref = static_cast<long double>(c) * wl * 256 - 128 + dd * frac / scale;
        const long double bound = 1.0L + (std::fabs(static_cast<long double>(dd)) / 131072.0L + 0.5L) / scale + 0.5L;
        const long double got = static_cast<long double>(p.i0) * 256 + p.f;
        ASSERT_LE(std::fabs(got - ref), bound) << it << " probe " << i << " of " << a.probes;
        ASSERT_LT(p.f, 256u);
        if (trilinear_level) {  // the offset alone: (|d| / 2^L) 2^-9 + 2^-(9 + L) + 1/2 <= 0.57 LSB for |d| / 2^L <= 2N
          const long double off = static_cast<long double>(dp::probe_offset_on_level(oq16, level));
          const long double err = std::fabs(off - dd * frac / scale);
          worst = std::max(worst, err);
          ASSERT_LE(err, 0.57L) << it << " probe " << i << " of " << a.probes << " L " << level;
        }
      }
    }
  }
  std::printf("probe offsets on the trilinear levels: max error %.4Lf Q.8 LSB of the level\n", worst);
}

// The speed-only forms of the offset units (aniso_fast.hpp, used by the golden model's LINEAR probe
// path) equal the plain units: the rounding at every shift 1..62 on and around every tie, both signs;
// the fraction scaling for every probe ROM word against derivatives at and around the clamp and
// random ones; the level offset for every level on ties and random offsets; the coordinate add.
TEST(AnisoProbes, FastOffsetUnitsEqualThePlainUnits) {
  const auto sign_magnitude = [](int64_t x, int k) {  // sgn(x) ((|x| + 2^(k-1)) >> k), written out
    const uint64_t m = x < 0 ? uint64_t{0} - static_cast<uint64_t>(x) : static_cast<uint64_t>(x);
    const auto r = static_cast<int64_t>((m + (uint64_t{1} << (k - 1))) >> k);
    return x < 0 ? -r : r;
  };
  std::mt19937_64 rng(2026);
  for (int k = 1; k <= 62; ++k) {
    const int64_t unit = int64_t{1} << k, half = unit >> 1;
    const int64_t limit = (int64_t{1} << 62) - 1;
    const int64_t q_max = limit / unit;  // q unit <= limit: no overflow below
    for (int64_t j = 0; j < 40; ++j) {
      const int64_t q = j < 20 ? std::min(j, q_max) : static_cast<int64_t>(rng() % static_cast<uint64_t>(q_max + 1));
      for (int64_t delta = -2; delta <= 2; ++delta)
        for (const int64_t sign : {1, -1}) {
          const int64_t x = sign * (q * unit + half + delta);
          if (x > limit || x < -limit) continue;
          ASSERT_EQ(dp::fast::round_half_away_shift(x, k), sign_magnitude(x, k)) << x << " >> " << k;
        }
    }
  }
  std::vector<int64_t> majors = grid_values();
  for (const int64_t m : {int64_t{0}, int64_t{1}, int64_t{kDerivativeClamp} - 1, int64_t{kDerivativeClamp},
                          int64_t{kDerivativeClamp} + 1, int64_t{1} << 40, std::numeric_limits<int64_t>::max()}) {
    majors.push_back(m);
    majors.push_back(-m);
  }
  majors.push_back(std::numeric_limits<int64_t>::min());
  for (int k = 0; k < 2000; ++k) {
    const auto m = static_cast<int64_t>(rng() >> (rng() % 64));
    majors.push_back(k % 2 ? -m : m);
  }
  for (const int64_t d : majors)
    for (int n = 1; n <= kMaxAniso; ++n)
      for (int i = 1; i <= n; ++i) {
        const int32_t q = probe_rom()[static_cast<size_t>(probe_rom_address(n, i))].frac_q16;
        ASSERT_EQ(dp::fast::scale_probe_fraction(dp::fast::clamped_major(d), q), dp::scale_probe_fraction(d, q))
            << d << " N " << n << " i " << i;
      }
  for (int level = 0; level <= 15; ++level)
    for (int k = 0; k < 20000; ++k) {
      const int64_t tie = (static_cast<int64_t>(rng() % (uint64_t{1} << (22 - level))) << (8 + level)) + (int64_t{1} << (7 + level));
      const int64_t o = k % 2 ? tie + static_cast<int64_t>(k % 5) - 2 : static_cast<int64_t>(rng() % (uint64_t{1} << 30));
      for (const int64_t x : {o, -o}) {
        ASSERT_EQ(dp::fast::probe_offset_on_level(x, level), dp::probe_offset_on_level(x, level))
            << x << " L " << level;
        const dp::LevelCoord c{static_cast<int64_t>(rng() % (uint64_t{1} << 40)) - (int64_t{1} << 39),
                               static_cast<uint32_t>(rng() % 256)};
        const dp::LevelCoord want = dp::probe_texel_coord(c, dp::probe_offset_on_level(x, level));
        const dp::LevelCoord got = dp::fast::split_q8(dp::fast::join_q8(c) + dp::fast::probe_offset_on_level(x, level));
        ASSERT_EQ(got.i0, want.i0);
        ASSERT_EQ(got.f, want.f);
      }
    }
}

// The average: each channel between the probes' smallest and largest value, equal probes give that
// value, and the distance to the plain mean is at most 1/2 LSB plus what the weights' deviation from
// 1/N can move it: (max - min) / 2 * sum_i |w_i / 256 - 1/N|.
TEST(AnisoAverage, RoundsTheWeightedMeanAndStaysInRange) {
  std::mt19937 rng(31);
  const auto& rom = probe_rom();
  {
    const std::array<Texel4, 3> p{Texel4{0, 255, 10, -7}, Texel4{255, 0, 10, -8}, Texel4{0, 0, 10, -9}};
    // w = 85, 86, 85: (86 * 255 + 128) >> 8 = 86; (85 * 255 + 128) >> 8 = 85; 10; (-595 - 688 - 765 + 128) >> 8 = -8
    EXPECT_EQ(dp::aniso_average(p.data(), 3), (Texel4{86, 85, 10, -8}));
  }
  for (int it = 0; it < 200'000; ++it) {
    const int n = 1 + static_cast<int>(rng() % kMaxAniso);
    const bool vs16 = it % 3 == 0;
    std::array<Texel4, kMaxAniso> p{};
    for (int i = 0; i < n; ++i)
      for (size_t ch = 0; ch < 4; ++ch)
        p[static_cast<size_t>(i)][ch] =
            vs16 ? static_cast<int32_t>(rng() % 65281) - 32640 : static_cast<int32_t>(rng() % 256);
    const Texel4 got = dp::aniso_average(p.data(), n);
    double dev = 0;
    for (int i = 1; i <= n; ++i)
      dev += std::fabs(rom[static_cast<size_t>(probe_rom_address(n, i))].weight / 256.0 - 1.0 / n);
    for (size_t ch = 0; ch < 4; ++ch) {
      int32_t lo = p[0][ch], hi = p[0][ch];
      double mean = 0;
      for (int i = 0; i < n; ++i) {
        lo = std::min(lo, p[static_cast<size_t>(i)][ch]);
        hi = std::max(hi, p[static_cast<size_t>(i)][ch]);
        mean += p[static_cast<size_t>(i)][ch];
      }
      mean /= n;
      ASSERT_GE(got[ch], lo);
      ASSERT_LE(got[ch], hi);
      ASSERT_LE(std::fabs(got[ch] - mean), 0.5 + (hi - lo) / 2.0 * dev + 1e-9) << n;
    }
    std::array<Texel4, kMaxAniso> same{};
    same.fill(p[0]);
    ASSERT_EQ(dp::aniso_average(same.data(), n), p[0]);
  }
}

// ---------------------------------------------------------------- lengths and degenerate inputs

TEST(AnisoLengths, AxisLengthIsTheExactFloorSquareRoot) {
  EXPECT_EQ(axis_length_q16(0), 0u);
  EXPECT_EQ(axis_length_q16(1), 1u);
  EXPECT_EQ(axis_length_q16(uint64_t{1} << 32), 65536u);  // 1 texel
  const uint64_t c = kDerivativeClamp;
  EXPECT_EQ(axis_length_q16(2 * c * c), 3037000498u);  // floor(sqrt(2) (2^31 - 1))
  std::mt19937_64 rng(3);
  for (int it = 0; it < 1'000'000; ++it) {
    const uint64_t x = rng() >> (1 + rng() % 63);
    const uint64_t r = axis_length_q16(x);
    ASSERT_LE(r * r, x);
    ASSERT_GT((r + 1) * (r + 1), x);
  }
  for (uint64_t r = 1; r < (uint64_t{1} << 31); r = r * 3 + 1)
    for (const uint64_t x : {r * r - 1, r * r, r * r + 1})
      ASSERT_EQ(axis_length_q16(x), x == r * r - 1 ? r - 1 : r);
}

TEST(AnisoLod, DegenerateFloatDerivativesHaveTheDocumentedResults) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const int w = 256;
  // Zero derivatives (also NaN, which the input stage turns into 0): one probe, lambda = -infinity.
  for (const float z : {0.0f, -0.0f, nan}) {
    const AnisoLod a = aniso_lod(derivatives_from_gradients(z, z, z, z, w, w), {16, rounding(false)});
    EXPECT_EQ(a.probes, 1);
    EXPECT_EQ(a.lambda_q8, kLodMinusInfinity);
    EXPECT_TRUE(a.major_x);
    EXPECT_EQ(probe_offset(a, 1).du_q16, 0);
  }
  // Equal axes: one probe, the isotropic lambda (1/64 in s of 256 texels: 4 texels, lambda = 2).
  {
    const AnisoLod a = aniso_lod(derivatives_from_gradients(1 / 64.0f, 0, 0, 1 / 64.0f, w, w), {16, rounding(false)});
    EXPECT_EQ(a.probes, 1);
    EXPECT_EQ(a.lambda_q8, 512);
  }
  // A line footprint (Pmin = 0 < Pmax): maxAniso probes (pow2 mode: rounded up), along x.
  {
    const AnisoLod a = aniso_lod(derivatives_from_gradients(1 / 16.0f, 0, 0, 0, w, w), {6, rounding(false)});
    EXPECT_EQ(a.probes, 6);
    EXPECT_TRUE(a.major_x);
    // Pmax = 16 texels: log2_q8(2^40) - 32 * 256 = 2048; R[6] = round(512 log2 6) = 1324;
    // (2048 - 1324 + 1) >> 1 = 362 (256 log2(16 / 6) = 362.25).
    EXPECT_EQ(a.lambda_q8, 362);
  }
  // Infinite derivatives saturate, then clamp to 2^31 - 1 (32768 texels): Px = Py -> 1 probe, lambda
  // = 256 log2(sqrt(2) (2^31 - 1) / 2^16) = 15.5 levels; +inf and -inf alike.
  for (const float x : {inf, -inf}) {
    const AnisoLod a = aniso_lod(derivatives_from_gradients(x, x, x, -x, w, w), {16, rounding(false)});
    EXPECT_EQ(a.probes, 1);
    EXPECT_EQ(a.lambda_q8, 3968);
    const AnisoLod b = aniso_lod(derivatives_from_gradients(0, 0, x, 0, w, w), {8, rounding(true)});
    EXPECT_FALSE(b.major_x);
    EXPECT_EQ(b.probes, 8);
    EXPECT_EQ(b.major_du_q16, x > 0 ? int64_t{kDerivativeClamp} : -int64_t{kDerivativeClamp});
    EXPECT_EQ(b.lambda_q8, 3840 - 768);  // log2((2^31 - 1) / 2^16 / 8) = 12 levels (- 2^-31 rounds away)
  }
  // maxAniso outside 1..16 is clamped into it.
  const TexelDerivatives line = derivatives_from_gradients(1.0f, 0, 0, 0, w, w);
  EXPECT_EQ(aniso_lod(line, {0, rounding(false)}).probes, 1);
  EXPECT_EQ(aniso_lod(line, {-5, rounding(false)}).probes, 1);
  EXPECT_EQ(aniso_lod(line, {17, rounding(false)}).probes, 16);
  EXPECT_EQ(aniso_lod(line, {1000, rounding(true)}).probes, 16);
  EXPECT_EQ(aniso_lod(line, {5, rounding(true)}).probes, 8);  // round up: the spec's "nearest supported rate"
}

}  // namespace
}  // namespace tfu
