// Angle dependence of the anisotropic LOD unit (docs/anisotropic.md, "Lambda against the angle of
// the major axis"): an elliptical footprint of fixed axes turned through 0..359 degrees in 1-degree
// steps. Turned in texture space (both derivative vectors together) the unit's exact squared
// lengths keep lambda within the Q.16 rounding and the log2 unit's error: the stated goal, at most
// 0.1 level at 16:1, holds. Turned against the screen axes (the tunnel's case) the EXT spec's Px
// and Py are not the ellipse's axes, and lambda moves by 3.5 levels at 16:1: the goal does not hold
// for the spec's formula, exact or not (scripts/aniso-tunnel plots both). With the footprint
// ellipse's true axes (aniso_axes ellipse) it holds against the screen axes as well.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cmodel/aniso.hpp"
#include "cmodel/lod.hpp"

namespace tfu {
namespace {

constexpr int kTextureSize = 1024;

// Footprint with the major axis (the x derivative, Pmax = ratio * pmin texels) at `deg` degrees in
// texture space and the minor (y) axis perpendicular to it, through the unit's input stage.
TexelDerivatives turned_footprint(double deg, double ratio, double pmin_texels) {
  const double a = deg * std::numbers::pi / 180.0, c = std::cos(a), s = std::sin(a);
  const double pmax = ratio * pmin_texels;
  const auto g = [](double texels) { return static_cast<float>(texels / kTextureSize); };
  return derivatives_from_gradients(g(pmax * c), g(pmax * s), g(-pmin_texels * s), g(pmin_texels * c), kTextureSize,
                                    kTextureSize);
}

// The ellipse with axes Pmax (along u) and Pmin (along v) seen with its major axis at `deg` degrees
// against the screen axes: J = diag(Pmax, Pmin) R(-deg), so (du/dx, dv/dx) = (Pmax cos, -Pmin sin)
// and (du/dy, dv/dy) = (Pmax sin, Pmin cos).
TexelDerivatives screen_turned_footprint(double deg, double ratio, double pmin_texels) {
  const double a = deg * std::numbers::pi / 180.0, c = std::cos(a), s = std::sin(a);
  const double pmax = ratio * pmin_texels;
  const auto g = [](double texels) { return static_cast<float>(texels / kTextureSize); };
  return derivatives_from_gradients(g(pmax * c), g(-pmin_texels * s), g(pmax * s), g(pmin_texels * c), kTextureSize,
                                    kTextureSize);
}

struct Range {
  int32_t lo = INT32_MAX, hi = INT32_MIN;
  int n_lo = 99, n_hi = 0;
};

Range over_angles(double ratio, double pmin, const AnisoParams& p, bool screen = false) {
  Range r;
  for (int deg = 0; deg < 360; ++deg) {
    const AnisoLod a = aniso_lod(screen ? screen_turned_footprint(deg, ratio, pmin) : turned_footprint(deg, ratio, pmin), p);
    r.lo = std::min(r.lo, a.lambda_q8);
    r.hi = std::max(r.hi, a.lambda_q8);
    r.n_lo = std::min(r.n_lo, a.probes);
    r.n_hi = std::max(r.n_hi, a.probes);
  }
  return r;
}

// The goal: at 16:1 (maxAniso 16) lambda varies by at most 0.1 level (25.6 LSB of Q.8) over the
// 360 angles, at footprints from a quarter texel to 8 texels wide, N = 16 at every angle, and lambda
// within the unit's 1.2-LSB bound plus the input rounding of log2(Pmax / 16) = log2(Pmin).
TEST(AnisoAngle, LambdaVariesAtMostATenthOfALevelAt16To1InTextureSpace) {
  for (double pmin : {0.25, 1.0, 1.7, 8.0}) {
    const Range r = over_angles(16.0, pmin, {16, AnisoRounding::Integer, 0});
    const std::string what = fmt::format("Pmin {} texels: lambda {}..{} / 256", pmin, r.lo, r.hi);
    EXPECT_LE(r.hi - r.lo, 25) << what;
    EXPECT_LE(r.hi - r.lo, 3) << what;  // measured: 2 LSB at most (the log2 unit and Q.16 rounding)
    EXPECT_EQ(r.n_lo, 16) << what;
    EXPECT_EQ(r.n_hi, 16) << what;
    const double want = 256.0 * std::log2(pmin);
    EXPECT_LE(std::fabs(r.lo - want), 2.0) << what;
    EXPECT_LE(std::fabs(r.hi - want), 2.0) << what;
  }
}

// 4:1 with maxAniso 4, and power-of-two rounding (N = 16 and 4 are powers of two already): the same.
TEST(AnisoAngle, LambdaVariesAtMostATenthOfALevelAt4To1AndWithPow2) {
  for (double pmin : {0.5, 2.0}) {
    for (const auto& [ratio, max_aniso] : {std::pair{4.0, 4}, std::pair{16.0, 16}}) {
      const Range r = over_angles(ratio, pmin, {max_aniso, AnisoRounding::PowerOfTwo, 0});
      EXPECT_LE(r.hi - r.lo, 3) << ratio << " " << pmin;
      EXPECT_EQ(r.n_lo, max_aniso) << ratio << " " << pmin;
      EXPECT_EQ(r.n_hi, max_aniso) << ratio << " " << pmin;
    }
  }
}

// At an exact integer ratio below maxAniso the spec's ceil(Pmax / Pmin) sits on a tie: the Q.16
// rounding of the derivatives decides between k and k + 1 probes by angle, and lambda steps by
// log2((k + 1) / k) (0.32 level at 4:1). A threshold t >= 1 moves the step away from the tie.
TEST(AnisoAngle, ExactIntegerRatioIsATieThatTheThresholdRemoves) {
  const Range spec = over_angles(4.0, 2.0, {16, AnisoRounding::Integer, 0});
  EXPECT_EQ(spec.n_lo, 4);
  EXPECT_EQ(spec.n_hi, 5);  // some angles round up past the tie
  EXPECT_GE(spec.hi - spec.lo, 80);  // 256 log2(5/4) = 82.4
  const Range thr = over_angles(4.0, 2.0, {16, AnisoRounding::Integer, 1});
  EXPECT_EQ(thr.n_lo, 4);
  EXPECT_EQ(thr.n_hi, 4);  // ceil(4 / 1.125) = 4 with a margin
  EXPECT_LE(thr.hi - thr.lo, 3);
}

// Against the screen axes Px^2 = Pmax^2 cos^2 + Pmin^2 sin^2 and Py^2 = Pmax^2 sin^2 + Pmin^2 cos^2:
// at 0 degrees Px = 16, Py = 1 (N = 16, lambda = log2(16 / 16) = 0); at 45 degrees Px = Py =
// sqrt(128.5) (the spec sees a round footprint: N = 1, lambda = log2(sqrt(128.5)) = 3.5028 levels,
// 896.7 / 256). The threshold 1 keeps the 45-degree case off the tie Px = Py that the Q.16
// rounding of the turned derivatives could break either way.
TEST(AnisoAngle, TurnedAgainstTheScreenAxesTheSpecsLambdaMovesBy3Point5LevelsAt16To1) {
  const AnisoParams p{16, AnisoRounding::Integer, 1};
  const AnisoLod at0 = aniso_lod(screen_turned_footprint(0, 16, 1.0), p);
  EXPECT_EQ(at0.probes, 15);  // ceil(16 / 1.125) = 15 with the threshold
  const AnisoLod spec0 = aniso_lod(screen_turned_footprint(0, 16, 1.0), {16, AnisoRounding::Integer, 0});
  EXPECT_EQ(spec0.probes, 16);
  EXPECT_LE(std::abs(spec0.lambda_q8), 2);
  const AnisoLod at45 = aniso_lod(screen_turned_footprint(45, 16, 1.0), p);
  EXPECT_EQ(at45.probes, 1);
  EXPECT_NEAR(at45.lambda_q8, 256.0 * 0.5 * std::log2(128.5), 2.0);
  const Range r = over_angles(16.0, 1.0, {16, AnisoRounding::Integer, 0}, true);
  // Without the threshold the rounding puts 45 degrees just off the tie (N = 2, lambda 2.5 levels):
  // measured 726 / 256 = 2.84 levels over the angles; far from the goal of 0.1 either way.
  EXPECT_GE(r.hi - r.lo, 256 * 5 / 2);
  EXPECT_LE(r.hi - r.lo, 256 * 3.51 + 2);
  EXPECT_LE(r.n_lo, 2);
  EXPECT_EQ(r.n_hi, 16);
  const Range rt = over_angles(16.0, 1.0, p, true);
  EXPECT_GE(rt.hi - rt.lo, 256 * 3.4);  // with the threshold: 0 .. 3.50 levels
  EXPECT_EQ(rt.n_lo, 1);
}

// The ellipse's true axes (aniso_axes ellipse) against the screen axes: the goal, at most 0.1 level
// (25.6 LSB) over the 360 angles at 16:1 (maxAniso 16) and 4:1 (maxAniso 4), footprints a quarter
// texel to 8 texels wide, N = maxAniso at every angle and lambda within 2 LSB of log2(Pmax / N).
// Measured: 0 LSB at every width (the Q.16 rounding of the turned derivatives moves Pmax'^2 and |D|
// by far less than the log2 unit's step). At 4:1 with maxAniso 16 the ratio sits on the tie N = 4
// or 5 as in texture space, and the threshold 1 removes it.
TEST(AnisoAngle, EllipseAxesVaryAtMostATenthOfALevelTurnedAgainstTheScreenAxes) {
  for (double pmin : {0.25, 1.0, 1.7, 8.0})
    for (const auto& [ratio, max_aniso, t] : {std::tuple{16.0, 16, 0}, std::tuple{4.0, 4, 0}, std::tuple{4.0, 16, 1}}) {
      const Range r = over_angles(ratio, pmin, {max_aniso, AnisoRounding::Integer, t, AnisoAxes::Ellipse}, true);
      const std::string what = fmt::format("{}:1 max {} t {} Pmin {} texels: lambda {}..{} / 256", ratio, max_aniso, t, pmin, r.lo, r.hi);
      EXPECT_LE(r.hi - r.lo, 25) << what;
      EXPECT_LE(r.hi - r.lo, 3) << what;
      EXPECT_EQ(r.n_lo, std::min(max_aniso, static_cast<int>(ratio))) << what;
      EXPECT_EQ(r.n_hi, std::min(max_aniso, static_cast<int>(ratio))) << what;
      const double want = 256.0 * std::log2(ratio * pmin / r.n_lo);
      EXPECT_LE(std::fabs(r.lo - want), 2.0) << what;
      EXPECT_LE(std::fabs(r.hi - want), 2.0) << what;
    }
  // Without the threshold, 4:1 at maxAniso 16 is the integer-ratio tie: N 4 or 5 by angle.
  const Range tie = over_angles(4.0, 2.0, {16, AnisoRounding::Integer, 0, AnisoAxes::Ellipse}, true);
  EXPECT_EQ(tie.n_lo, 4);
  EXPECT_EQ(tie.n_hi, 5);
}

// 45 degrees against the screen axes at 16:1, Pmin = 1 texel: a = (16 cos 45, -sin 45), b = (16 sin
// 45, cos 45). By hand: A = 2 (128 + 1/2) = 257, E = 0, F = 2 (128 - 1/2) = 255, H = 255, Pmax'^2 =
// 256, |D| = 16: N = 16 (Pmax'^2 = 16 |D|, to the Q.16 rounding; maxAniso 16 caps it either way) and
// lambda = log2(16 / 16) = log2(Pmin) = 0; the screen axes see Px = Py (N = 1 or 2, lambda 2.5 to
// 3.5 levels). 30 degrees at 8:1, Pmin = 2, maxAniso 8 (the cap keeps N off the tie 8 or 9): N = 8,
// lambda = log2 2 = 256 / 256.
TEST(AnisoAngle, EllipseAxesHandValuesAt45And30Degrees) {
  const AnisoParams p{16, AnisoRounding::Integer, 0, AnisoAxes::Ellipse};
  const AnisoLod at45 = aniso_lod(screen_turned_footprint(45, 16, 1.0), p);
  EXPECT_EQ(at45.probes, 16);
  EXPECT_LE(std::abs(at45.lambda_q8), 3);
  EXPECT_NEAR(static_cast<double>(at45.pmax2_q32) / 0x1p32, 256.0, 256.0 / 4096);
  EXPECT_NEAR(static_cast<double>(at45.det_q32) / 0x1p32, 16.0, 16.0 / 4096);
  const AnisoLod spec45 = aniso_lod(screen_turned_footprint(45, 16, 1.0), {16, AnisoRounding::Integer, 0});
  EXPECT_LE(spec45.probes, 2);
  EXPECT_GE(spec45.lambda_q8, 256 * 5 / 2);
  const AnisoLod at30 = aniso_lod(screen_turned_footprint(30, 8, 2.0), {8, AnisoRounding::Integer, 0, AnisoAxes::Ellipse});
  EXPECT_EQ(at30.probes, 8);
  EXPECT_LE(std::abs(at30.lambda_q8 - 256), 3);
}

}  // namespace
}  // namespace tfu
