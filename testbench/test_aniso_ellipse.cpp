// The anisotropic LOD unit with the footprint ellipse's axes (AnisoParams::aniso_axes = Ellipse,
// docs/anisotropic.md "Lambda against the angle"): the dot-and-cross unit, the hypot unit and its
// error bound, Pmax'^2, the probe count against n |D|, a hand-derived footprint, perpendicular
// derivatives giving the screen axes' result bit for bit, a long-double reference of the true axes,
// degenerate footprints, and the descriptor field and sampler key.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cmodel/aniso.hpp"
#include "cmodel/bindings.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/error.hpp"
#include "testbench/iterations.hpp"

namespace tfu {
namespace {

constexpr int64_t kOne = int64_t{1} << 16;  // one texel, Q.16

AnisoParams ellipse(int max_aniso, int t = 0, AnisoRounding r = AnisoRounding::Integer) {
  return {max_aniso, r, t, AnisoAxes::Ellipse};
}

// a = (24, -4), b = (32, 3) texels: J = diag(40, 5) R(-theta) with cos = 3/5, sin = 4/5, an 8:1
// ellipse with axes 40 and 5 turned against the screen axes. By hand: A = 592 + 1033 = 1625, E =
// -441, a.b = 768 - 12 = 756, F = 1512, H = sqrt(441^2 + 1512^2) = 1575, Pmax'^2 = (1625 + 1575) / 2
// = 1600, D = 24 * 3 + 4 * 32 = 200 = 40 * 5: N = 1600 / 200 = 8 (an exact tie), lambda = log2(40 /
// 8) = log2 5. The screen axes see Px = sqrt(592) = 24.3, Py = sqrt(1033) = 32.1: N = 2, lambda =
// log2(32.1 / 2) = 4.006.
TEST(AnisoEllipse, HandDerivedPythagoreanFootprint) {
  const TexelDerivatives d{24 * kOne, -4 * kOne, 32 * kOne, 3 * kOne};
  const DotCross dc = aniso_dot_cross(d);
  EXPECT_EQ(dc.dot_q32, int64_t{756} << 32);
  EXPECT_EQ(dc.det_q32, int64_t{200} << 32);
  // All values are integers times 2^32, so the 16-bit mantissas are exact and so is H.
  EXPECT_EQ(aniso_hypot(uint64_t{441} << 32, uint64_t{1512} << 32), AnisoU128{1575} << 32);
  EXPECT_EQ(ellipse_major_len2(uint64_t{592} << 32, uint64_t{1033} << 32, dc.dot_q32), uint64_t{1600} << 32);
  const AnisoLod e = aniso_lod(d, ellipse(16));
  EXPECT_EQ(e.pmax2_q32, uint64_t{1600} << 32);
  EXPECT_EQ(e.det_q32, uint64_t{200} << 32);
  EXPECT_EQ(e.probes, 8);
  EXPECT_NEAR(e.lambda_q8, 256.0 * std::log2(5.0), 1.2);  // 594.4
  EXPECT_FALSE(e.major_x);                                  // the probes stay on the longer vector, b
  EXPECT_EQ(e.major_du_q16, 32 * kOne);
  EXPECT_EQ(e.major_dv_q16, 3 * kOne);
  // The tie and one unit past it; the threshold: n (8 + t) 200 >= 8 * 1600.
  EXPECT_EQ(aniso_probe_count_ellipse(uint64_t{1600} << 32, uint64_t{200} << 32, ellipse(16)), 8);
  EXPECT_EQ(aniso_probe_count_ellipse((uint64_t{1600} << 32) + 1, uint64_t{200} << 32, ellipse(16)), 9);
  EXPECT_EQ(aniso_lod(d, ellipse(16, 1)).probes, 8);  // 7 * 9 * 200 = 12,600 < 12,800
  EXPECT_EQ(aniso_lod(d, ellipse(16, 4)).probes, 6);  // 5 * 12 * 200 < 12,800 <= 6 * 12 * 200
  EXPECT_EQ(aniso_lod(d, ellipse(5)).probes, 5);
  EXPECT_EQ(aniso_lod(d, ellipse(5, 0, AnisoRounding::PowerOfTwo)).probes, 8);
  const AnisoLod s = aniso_lod(d, {16, AnisoRounding::Integer, 0, AnisoAxes::Screen});
  EXPECT_EQ(s.probes, 2);
  EXPECT_EQ(s.pmax2_q32, uint64_t{1033} << 32);
  EXPECT_EQ(s.det_q32, 0u);
  EXPECT_NEAR(s.lambda_q8, 256.0 * std::log2(std::sqrt(1033.0) / 2), 1.2);
}

// H = M + ((h - M') << s) against sqrt(e^2 + f^2): exact when one input is 0, never below max(e, f),
// and |H - sqrt(e^2 + f^2)| < 2.5 * 2^s (truncation of both mantissas, < 2^s each, and the root's
// floor, < 2^s: H - T = dM - eps 2^s - (T - T'), T - T' < sqrt(2) 2^s), which is below 2^-13.6 of
// the result wherever max(e, f) >= 2^15 (then M >= 2^(15 + s)); below that s = 0, the inputs are
// exact and the error (the root's floor) is below 1.
TEST(AnisoEllipse, HypotIsExactOnAnAxisAndWithinItsBound) {
  std::mt19937_64 rng(71);
  const int n = test::iterations(300000);
  double worst = 0;
  for (int i = 0; i < n; ++i) {
    const int se = static_cast<int>(rng() % 64), sf = static_cast<int>(rng() % 65);
    const uint64_t e = (rng() >> se) >> 1;  // < 2^63
    const uint64_t f = sf == 64 ? 0 : rng() >> sf;
    ASSERT_EQ(aniso_hypot(e, 0), AnisoU128{e});
    ASSERT_EQ(aniso_hypot(0, f), AnisoU128{f});
    const AnisoU128 h = aniso_hypot(e, f);
    ASSERT_EQ(aniso_hypot(f, e), h);  // symmetric
    ASSERT_GE(h, AnisoU128{std::max(e, f)});
    const long double t = std::sqrt(static_cast<long double>(e) * e + static_cast<long double>(f) * f);
    const int s = std::max(0, static_cast<int>(std::bit_width(std::max(e, f))) - 16);
    const long double err = std::fabs(static_cast<long double>(h) - t);
    ASSERT_LT(err, 2.5L * std::ldexp(1.0L, s)) << e << " " << f;
    if (std::max(e, f) >= uint64_t{1} << 15) worst = std::max(worst, static_cast<double>(err / t));
  }
  EXPECT_LT(worst, std::ldexp(1.0, -13));
  EXPECT_GT(worst, std::ldexp(1.0, -18));  // the truncation shows: the bound is not vacuous
}

// F = 2 a.b = 0 (perpendicular derivative vectors, e.g. axis-aligned footprints): H = |E| exactly,
// Pmax'^2 = max(Px^2, Py^2) and |D| = Px Py, so n (8 + t) |D| >= 8 Pmax'^2 is n^2 (8 + t)^2 Pmin^2 >=
// 64 Pmax^2: the ellipse axes give the screen axes' AnisoLod bit for bit, at every setting.
TEST(AnisoEllipse, PerpendicularDerivativesGiveTheScreenAxesResultBitForBit) {
  std::mt19937_64 rng(72);
  const int n = test::iterations(200000);
  const auto check = [](const TexelDerivatives& d, const AnisoParams& p, const std::string& what) {
    AnisoParams ps = p;
    ps.aniso_axes = AnisoAxes::Screen;
    const AnisoLod s = aniso_lod(d, ps), e = aniso_lod(d, p);
    EXPECT_EQ(e.probes, s.probes) << what;
    EXPECT_EQ(e.lambda_q8, s.lambda_q8) << what;
    EXPECT_EQ(e.pmax2_q32, s.pmax2_q32) << what;
    EXPECT_EQ(e.major_x, s.major_x) << what;
    EXPECT_EQ(e.major_du_q16, s.major_du_q16) << what;
    EXPECT_EQ(e.major_dv_q16, s.major_dv_q16) << what;
    return e.probes == s.probes && e.lambda_q8 == s.lambda_q8;
  };
  // Axis-aligned: a = (u, 0), b = (0, v) and swapped, every pair of a small grid including 0.
  const int64_t grid[] = {0, 1, 3, 255, kOne, 3 * kOne, 16 * kOne, 17 * kOne, 1000 * kOne, (int64_t{1} << 31) - 1, int64_t{1} << 40};
  for (int64_t u : grid)
    for (int64_t v : grid)
      for (int max_aniso : {1, 4, 16})
        for (int t : {0, 3}) {
          const AnisoParams p = ellipse(max_aniso, t);
          check({u, 0, 0, -v}, p, fmt::format("({}, 0) (0, {})", u, -v));
          check({0, -u, v, 0}, p, fmt::format("(0, {}) ({}, 0)", -u, v));
        }
  // Turned: a = k (p, q), b = l (-q, p), with random signs, magnitudes within the clamp.
  int equal = 0;
  for (int i = 0; i < n; ++i) {
    const int64_t p = static_cast<int64_t>(rng() % 40000) - 20000, q = static_cast<int64_t>(rng() % 40000) - 20000;
    const int64_t k = 1 + static_cast<int64_t>(rng() % 50000), l = 1 + static_cast<int64_t>(rng() % 50000);
    const int64_t sg = rng() % 2 ? 1 : -1;
    TexelDerivatives d{k * p, k * q, -l * q * sg, l * p * sg};
    if (rng() % 2) d = {d.dudy, d.dvdy, d.dudx, d.dvdx};
    const AnisoParams prm = ellipse(1 + static_cast<int>(rng() % 16), static_cast<int>(rng() % 8),
                                    rng() % 2 ? AnisoRounding::PowerOfTwo : AnisoRounding::Integer);
    ASSERT_EQ(aniso_dot_cross(d).dot_q32, 0);
    if (!check(d, prm, fmt::format("{} {} {} {}", d.dudx, d.dvdx, d.dudy, d.dvdy))) break;
    ++equal;
  }
  EXPECT_EQ(equal, n);
}

// Random footprints against the true axes in long double: the singular values of J = [a b],
// Pmax' = sqrt((A + sqrt(E^2 + F^2)) / 2), Pmin' = |D| / Pmax'. N is the smallest n with
// n (1 + t/8) Pmin' >= Pmax' (capped, rounded up with pow2) wherever the ratio is not within 2^-12
// of a step (the hypot's rounding may decide those either way); lambda is within 1.2 LSB (the
// lambda unit's bound) plus 0.02 LSB (Pmax'^2 within 2^-13.6 relative: 128 log2(1 + 2^-13.6)) of
// 256 log2(Pmax' / N).
TEST(AnisoEllipse, ProbeCountAndLambdaMatchTheTrueAxes) {
  std::mt19937_64 rng(73);
  const int n = test::iterations(200000);
  int near_steps = 0;
  double worst = 0;
  for (int i = 0; i < n; ++i) {
    const int shift = 8 + static_cast<int>(rng() % 23);  // |component| up to 2^31
    const auto comp = [&] { return static_cast<int64_t>(rng() >> (64 - shift)) * (rng() % 2 ? 1 : -1); };
    const TexelDerivatives d{comp(), comp(), comp(), comp()};
    const int max_aniso = 1 + static_cast<int>(rng() % 16), t = static_cast<int>(rng() % 8);
    const bool pow2 = rng() % 4 == 0;
    const AnisoLod a = aniso_lod(d, ellipse(max_aniso, t, pow2 ? AnisoRounding::PowerOfTwo : AnisoRounding::Integer));
    const long double ux = d.dudx, vx = d.dvdx, uy = d.dudy, vy = d.dvdy;
    const long double A = ux * ux + vx * vx + uy * uy + vy * vy, E = ux * ux + vx * vx - uy * uy - vy * vy,
                      F = 2 * (ux * uy + vx * vy), D = std::fabs(ux * vy - vx * uy);
    const long double pmax2 = (A + std::sqrt(E * E + F * F)) / 2;
    if (pmax2 < std::ldexp(1.0L, 20)) continue;  // the floor of the halving is below 2^-20 relative
    const long double ratio = D > 0 ? pmax2 / D / (1 + t / 8.0L) : 1e30L;  // Pmax' / ((1 + t/8) Pmin')
    int want = std::min<int>(max_aniso, static_cast<int>(std::min(17.0L, std::max(1.0L, std::ceil(ratio)))));
    if (pow2) want = static_cast<int>(std::bit_ceil(static_cast<unsigned>(want)));
    const long double frac = ratio - std::floor(ratio);
    if (ratio < 17 && (frac < 1.0L / 4096 || frac > 1 - 1.0L / 4096)) {
      ++near_steps;
      continue;
    }
    ASSERT_EQ(a.probes, want) << d.dudx << " " << d.dvdx << " " << d.dudy << " " << d.dvdy << " max " << max_aniso << " t " << t;
    ASSERT_LE(std::fabs(static_cast<long double>(a.pmax2_q32) - pmax2 * 0x1p-32L * 0x1p32L), pmax2 * 0x1p-13L);
    const long double lam = 128 * std::log2(pmax2 / 0x1p32L) - 256 * std::log2(static_cast<long double>(a.probes));
    worst = std::max(worst, static_cast<double>(std::fabs(a.lambda_q8 - lam)));
    ASSERT_LE(std::fabs(a.lambda_q8 - lam), 1.22L) << d.dudx << " " << d.dvdx << " " << d.dudy << " " << d.dvdy;
  }
  EXPECT_LT(near_steps, n / 100);
  EXPECT_GT(worst, 0.5);  // the lambda unit's rounding shows: the bound is not vacuous
}

// Degenerate footprints: zero derivatives give N = 1 and lambda -infinity, as with the screen
// axes; a line (b = 0, b parallel to a, |D| = 0) gives maxAniso, as a zero Pmin does; infinities
// arrive clamped to 2^31 - 1 per component.
TEST(AnisoEllipse, DegenerateFootprintsHaveTheDocumentedResults) {
  const AnisoLod zero = aniso_lod({0, 0, 0, 0}, ellipse(16));
  EXPECT_EQ(zero.probes, 1);
  EXPECT_EQ(zero.lambda_q8, kLodMinusInfinity);
  for (int max_aniso : {1, 5, 16}) {
    const AnisoLod line = aniso_lod({3 * kOne, 4 * kOne, 0, 0}, ellipse(max_aniso));
    EXPECT_EQ(line.probes, max_aniso);
    EXPECT_EQ(line.det_q32, 0u);
    EXPECT_EQ(line.pmax2_q32, uint64_t{25} << 32);  // F = 0: exact
    const AnisoLod par = aniso_lod({3 * kOne, 4 * kOne, -6 * kOne, -8 * kOne}, ellipse(max_aniso));
    EXPECT_EQ(par.probes, max_aniso);
    EXPECT_EQ(par.det_q32, 0u);
    EXPECT_EQ(par.pmax2_q32, uint64_t{125} << 32);  // A = 25 + 100, H = sqrt(75^2 + 100^2) = 125 exactly
    EXPECT_NEAR(par.lambda_q8, 256.0 * std::log2(std::sqrt(125.0) / max_aniso), 1.2);
  }
  // The largest magnitudes: a = (M, M), b = (M, -M), M = 2^31 - 1 (what +-Inf becomes): A = 4 M^2 <
  // 2^64, E = 0, F = 0, Pmax'^2 = 2 M^2, |D| = 2 M^2: round, N = 1.
  const int64_t m = (int64_t{1} << 31) - 1;
  const AnisoLod big = aniso_lod({int64_t{1} << 46, int64_t{1} << 46, int64_t{1} << 46, -(int64_t{1} << 46)}, ellipse(16));
  EXPECT_EQ(big.pmax2_q32, 2 * static_cast<uint64_t>(m) * static_cast<uint64_t>(m));
  EXPECT_EQ(big.det_q32, 2 * static_cast<uint64_t>(m) * static_cast<uint64_t>(m));
  EXPECT_EQ(big.probes, 1);
  // Largest A with D = 0 and F at its largest: a = b = (M, M): A = 4 M^2, F = 4 M^2, H <= A.
  const AnisoLod same = aniso_lod({int64_t{1} << 46, int64_t{1} << 46, int64_t{1} << 46, int64_t{1} << 46}, ellipse(16));
  EXPECT_EQ(same.pmax2_q32, 4 * static_cast<uint64_t>(m) * static_cast<uint64_t>(m));
  EXPECT_EQ(same.probes, 16);
}

// The sampler-descriptor field (word 5, bit 8; reset: screen) and the sampler key aniso_axes.
TEST(AnisoEllipse, DescriptorFieldAndSamplerKey) {
  SamplerDescriptor s;
  EXPECT_EQ(s.aniso_axes, AnisoAxes::Screen);
  s.mode = filter_mode_from_name("LINEAR_MIPMAP_LINEAR");
  s.max_aniso = 8;
  EXPECT_EQ(s.aniso().aniso_axes, AnisoAxes::Screen);
  set_sampler_param(s, "aniso_axes", "ellipse");
  EXPECT_EQ(s.aniso_axes, AnisoAxes::Ellipse);
  EXPECT_EQ(s.aniso().aniso_axes, AnisoAxes::Ellipse);
  EXPECT_EQ(sampler_to_params(s).at("aniso_axes"), "ellipse");
  const auto words = encode(s);
  EXPECT_EQ((words[5] >> 8) & 1u, 1u);
  EXPECT_EQ(decode_sampler_descriptor(words), s);
  set_sampler_param(s, "aniso_axes", "screen");
  EXPECT_EQ(s.aniso_axes, AnisoAxes::Screen);
  EXPECT_THROW(set_sampler_param(s, "aniso_axes", "diagonal"), InputError);
}

}  // namespace
}  // namespace tfu
