// The AVX form of the renderer's quad interpolation (cmodel/raster_quad_avx.cpp) against its twins,
// bit for bit: the SSE2 form (raster_fast::barycentrics, depth, st of cmodel/raster_quad_fast.hpp)
// and the per-pixel plain twin (the edge functions divided by the area, interpolate_z's sum,
// interpolate_st with its beyond-the-horizon 1/w, to_float_coord's clamp and rounding). Every lane
// of every output (barycentrics, 1/w, depth, (s, t) of both UV sets) on random triangles of every
// shape with quads inside, on and around their edges (helper pixels, some beyond the horizon), and
// on raw quads whose edge functions, area and vertex attributes include NaN, infinities, -0,
// denormals and huge values; in the four IEEE rounding modes and with FTZ/DAZ. Skipped on a CPU
// without AVX (there the renderer runs the SSE2 form).
#if defined(__x86_64__) || defined(__i386__)
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <random>

#include "cmodel/raster.hpp"
#include "cmodel/raster_quad_avx.hpp"
#include "cmodel/raster_quad_fast.hpp"
#include "testbench/fp_environment.hpp"
#include "testbench/iterations.hpp"
#include "testbench/quad_edges.hpp"

// Its own namespace: the unity build compiles this file with test_raster_quad_fast.cpp, whose
// helpers have the same names.
namespace tfu::quad_avx_test {
namespace {

template <typename T>
bool bits_equal(T a, T b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Everything the quad's interpolation produces.
struct QuadResult {
  raster_fast::QuadLanes lanes{};
  std::array<double, 4> z{};
  std::array<std::array<float, 4>, 2> s{}, t{};
};

// The AVX form, (s, t) by st() per set.
QuadResult run_avx(const raster_fast::QuadEdges& qe, double area, const RasterTriangle& tri) {
  QuadResult r;
  raster_avx::barycentrics_depth(qe, area, tri, r.lanes, r.z);
  for (size_t set = 0; set < 2; ++set) raster_avx::st(r.lanes, tri, static_cast<int>(set), r.s[set].data(), r.t[set].data());
  return r;
}

// st_sets (the renderer's call) equals st() per set, bit for bit, for both sets and for each set
// alone, which leaves the other set's entries as they were.
::testing::AssertionResult st_sets_agree(const QuadResult& avx, const RasterTriangle& tri) {
  for (unsigned sets = 1; sets <= 3; ++sets) {
    raster_avx::QuadCoords c;
    for (auto* a : {&c.s, &c.t})
      for (auto& x : *a) x.fill(-2.5f);
    raster_avx::st_sets(avx.lanes, tri, sets, c);
    for (size_t set = 0; set < 2; ++set)
      for (size_t k = 0; k < 4; ++k) {
        const bool asked = (sets >> set & 1u) != 0;
        if (!bits_equal(c.s[set][k], asked ? avx.s[set][k] : -2.5f) || !bits_equal(c.t[set][k], asked ? avx.t[set][k] : -2.5f))
          return ::testing::AssertionFailure() << "sets " << sets << " set " << set << " lane " << k;
      }
  }
  return ::testing::AssertionSuccess();
}

QuadResult run_sse2(const raster_fast::QuadEdges& qe, double area, const RasterTriangle& tri) {
  QuadResult r;
  raster_fast::barycentrics(qe, area, tri, r.lanes);
  r.z = raster_fast::depth(r.lanes, tri);
  for (size_t set = 0; set < 2; ++set) raster_fast::st(r.lanes, tri, static_cast<int>(set), r.s[set].data(), r.t[set].data());
  return r;
}

// The clamp's bounds of to_float_coord, read at run time: GCC assumes round-to-nearest when it
// compiles (no -frounding-math), so where the clamp returns its constant bound it may fold the
// bound's conversion to float, 1e30 -> 1.00000002e30 in every mode. The renderer runs in
// round-to-nearest, where that is the run-time rounding too; in the other modes the operations
// themselves (clamp, then round the double to float) are the reference.
volatile double plain_lo = -1e30, plain_hi = 1e30;

// The per-pixel plain twin (shade_triangle with the fast paths off).
QuadResult run_plain(const raster_fast::QuadEdges& qe, double area, const RasterTriangle& tri) {
  QuadResult r;
  for (size_t k = 0; k < 4; ++k) {
    const std::array<double, 3> b = {static_cast<double>(qe.e[0][k]) / area, static_cast<double>(qe.e[1][k]) / area,
                                     static_cast<double>(qe.e[2][k]) / area};
    for (size_t i = 0; i < 3; ++i) r.lanes.b[i][k] = b[i];
    r.z[k] = b[0] * tri.v[0].z + b[1] * tri.v[1].z + b[2] * tri.v[2].z;
    double inv_w = 0;
    for (size_t i = 0; i < 3; ++i) inv_w += b[i] * tri.v[i].inv_w;
    if (!(inv_w > 0)) inv_w = 1e-6 * std::min({tri.v[0].inv_w, tri.v[1].inv_w, tri.v[2].inv_w});
    r.lanes.inv_w[k] = inv_w;
    for (size_t set = 0; set < 2; ++set) {
      const glm::dvec2 st = interpolate_st(tri, b, static_cast<int>(set));
      const double lo = plain_lo, hi = plain_hi;
      r.s[set][k] = static_cast<float>(std::clamp(st.x, lo, hi));
      r.t[set][k] = static_cast<float>(std::clamp(st.y, lo, hi));
    }
  }
  return r;
}

// Every output lane of `got` has the bits of `want`'s; with `any_nan`, a NaN lane matches any NaN.
::testing::AssertionResult same(const QuadResult& got, const QuadResult& want, bool any_nan = false) {
  const auto eq = [any_nan](auto a, auto b) { return bits_equal(a, b) || (any_nan && std::isnan(a) && std::isnan(b)); };
  for (size_t k = 0; k < 4; ++k) {
    for (size_t i = 0; i < 3; ++i)
      if (!eq(got.lanes.b[i][k], want.lanes.b[i][k]))
        return ::testing::AssertionFailure() << "b" << i << " lane " << k << ": " << got.lanes.b[i][k] << " vs " << want.lanes.b[i][k];
    if (!eq(got.lanes.inv_w[k], want.lanes.inv_w[k]))
      return ::testing::AssertionFailure() << "inv_w lane " << k << ": " << got.lanes.inv_w[k] << " vs " << want.lanes.inv_w[k];
    if (!eq(got.z[k], want.z[k])) return ::testing::AssertionFailure() << "z lane " << k << ": " << got.z[k] << " vs " << want.z[k];
    for (size_t set = 0; set < 2; ++set) {
      if (!eq(got.s[set][k], want.s[set][k]))
        return ::testing::AssertionFailure() << "s set " << set << " lane " << k << ": " << got.s[set][k] << " vs " << want.s[set][k];
      if (!eq(got.t[set][k], want.t[set][k]))
        return ::testing::AssertionFailure() << "t set " << set << " lane " << k << ": " << got.t[set][k] << " vs " << want.t[set][k];
    }
  }
  return ::testing::AssertionSuccess();
}

using test::edges_at;

// A random triangle of one of the shapes (huge, tiny, large, medium, slivers, horizontal and
// vertical edges, vertices on pixel centres) with depths, 1/w (near 1, or over five decades: steep
// perspective) and (s/w, t/w) of both UV sets.
std::optional<RasterTriangle> random_triangle(std::mt19937_64& rng, int n) {
  const double span = n % 4 == 0 ? 1e5 : n % 4 == 1 ? 3.0 : n % 4 == 2 ? 300.0 : 40.0;
  std::uniform_real_distribution<double> pos(-span, span), unit(0.0, 1.0), uv(-50.0, 50.0);
  std::array<ScreenVertex, 3> v;
  for (auto& sv : v) {
    sv.x = 100 + pos(rng), sv.y = 80 + pos(rng);
    sv.z = unit(rng);
    sv.inv_w = n % 2 == 0 ? 0.5 + unit(rng) : std::pow(10.0, -4.0 + 5.0 * unit(rng));
    for (auto& set : sv.uv_w) set = {uv(rng) * sv.inv_w, uv(rng) * sv.inv_w};
  }
  if (n % 5 == 0) v[2].x = v[1].x + 0.01, v[2].y = v[1].y + 0.5 * span;  // a sliver
  if (n % 7 == 0) v[2].y = v[1].y;                                       // a horizontal edge
  if (n % 11 == 0) v[2].x = v[0].x;                                      // a vertical edge
  if (n % 13 == 0)
    for (auto& sv : v) sv.x = std::floor(sv.x) + 0.5, sv.y = std::floor(sv.y) + 0.5;
  std::optional<RasterTriangle> tri = setup_triangle(v, 200, 160);
  if (tri && (tri->xmin > tri->xmax || tri->ymin > tri->ymax)) return std::nullopt;
  return tri;
}

TEST(RasterQuadAvx, EqualsTheSse2FormAndThePlainTwinOnRandomTriangles) {
  if (!raster_avx::available()) GTEST_SKIP() << "no AVX on this CPU";
  std::mt19937_64 rng(20261207);
  const int triangles = test::iterations(1500);
  int64_t quads = 0, beyond_horizon = 0;
  for (int mode = 0; mode < test::FpEnvironment::kCount; ++mode) {
    const test::FpEnvironment env(mode);
    ASSERT_TRUE(env.set()) << mode;
    for (int n = 0; n < triangles; ++n) {
      const auto tri = random_triangle(rng, n);
      if (!tri) continue;
      const double area = static_cast<double>(tri->area);
      // Quads across the bounding box and a margin of 6 pixels around it (far from a steep
      // triangle's edges, 1/w extrapolates through zero).
      for (int trial = 0; trial < 16; ++trial) {
        const int qx = std::uniform_int_distribution<int>(tri->xmin - 6, tri->xmax + 6)(rng) & ~1;
        const int qy = std::uniform_int_distribution<int>(tri->ymin - 6, tri->ymax + 6)(rng) & ~1;
        const raster_fast::QuadEdges qe = edges_at(*tri, qx, qy);
        const QuadResult avx = run_avx(qe, area, *tri);
        ASSERT_TRUE(same(avx, run_sse2(qe, area, *tri))) << "SSE2 form, mode " << mode << " triangle " << n;
        ASSERT_TRUE(st_sets_agree(avx, *tri)) << "mode " << mode << " triangle " << n;
        ASSERT_TRUE(same(avx, run_plain(qe, area, *tri))) << "plain twin, mode " << mode << " triangle " << n;
        for (size_t k = 0; k < 4; ++k) {
          double inv_w = 0;
          for (size_t i = 0; i < 3; ++i) inv_w += avx.lanes.b[i][k] * tri->v[i].inv_w;
          beyond_horizon += !(inv_w > 0);
        }
        ++quads;
      }
    }
  }
  EXPECT_GT(quads, int64_t{test::FpEnvironment::kCount} * triangles * 16 / 2);
  EXPECT_GT(beyond_horizon, 0);
}

// Raw quads: edge functions anywhere in the setup's range (|e| < 2^58, zeros, +-1), any area
// (the setup's positive ones, and 0, negative, tiny, huge and infinite) and vertex attributes drawn
// from the special values (infinities, +-0, denormals, huge): the three forms agree on every lane
// however the divisions and sums come out (NaN from inf - inf, 0 * inf and 0 / 0, infinities from
// overflow, -0, denormals, the horizon fix-up on a NaN 1/w), bit for bit.
// Half the quads also take NaN as an input (an attribute or the area). Then a NaN result matches any
// NaN: where an input NaN (positive) meets a NaN the arithmetic made (x86's default NaN, negative)
// in a sum or product, the result is the first operand's, and the compiler may put either operand
// of a commutative add or multiply first, in the plain twin and in the SSE2 form alike (the source
// does not fix it). The renderer's attributes are finite (clipped vertices), so its NaNs are all
// the default NaN and carry the same bits in either order.
TEST(RasterQuadAvx, EqualsTheSse2FormAndThePlainTwinOnSpecialValues) {
  if (!raster_avx::available()) GTEST_SKIP() << "no AVX on this CPU";
  std::mt19937_64 rng(91);
  constexpr double kInf = std::numeric_limits<double>::infinity(), kNaN = std::numeric_limits<double>::quiet_NaN();
  constexpr double kDenorm = std::numeric_limits<double>::denorm_min();
  const std::array<double, 16> special = {0.0, -0.0, kInf, -kInf, kNaN, kDenorm, -kDenorm, 1e-310, 1e300, -1e300,
                                          1.0, -1.0, 0.5, 1e-6, -3.25, 1e30};
  const std::array<double, 10> areas = {1.0, 65536.0, 3.0, 0.0, -0.0, -7.0, 1e-320, 1e308, kInf, kNaN};
  std::uniform_int_distribution<int64_t> edge(-(int64_t{1} << 58) + 1, (int64_t{1} << 58) - 1), small(-3, 3);
  std::uniform_int_distribution<size_t> pick(0, special.size() - 1);
  std::uniform_real_distribution<double> real(-2.0, 2.0);
  bool nan_inputs = false;
  const auto value = [&] {
    if (rng() % 3 == 0) return real(rng);
    const double x = special[pick(rng)];
    return std::isnan(x) && !nan_inputs ? 0.25 : x;
  };
  const int quads = test::iterations(4000);
  int64_t nan_lanes = 0, inf_lanes = 0, negative_zero_lanes = 0;
  for (int mode = 0; mode < test::FpEnvironment::kCount; ++mode) {
    const test::FpEnvironment env(mode);
    ASSERT_TRUE(env.set()) << mode;
    for (int n = 0; n < quads; ++n) {
      nan_inputs = n % 2 == 1;
      RasterTriangle tri;
      for (auto& v : tri.v) {
        v.z = value(), v.inv_w = value();
        for (auto& set : v.uv_w) set = {value(), value()};
      }
      raster_fast::QuadEdges qe;
      for (auto& e : qe.e)
        for (auto& x : e) x = rng() % 4 == 0 ? small(rng) : edge(rng);
      double area = n % 3 == 0 ? areas[static_cast<size_t>(n / 3) % areas.size()]
                               : std::ldexp(1.0 + static_cast<double>(rng() % 1000), static_cast<int>(rng() % 60));
      if (std::isnan(area) && !nan_inputs) area = 5.0;
      const QuadResult avx = run_avx(qe, area, tri);
      ASSERT_TRUE(same(avx, run_sse2(qe, area, tri), nan_inputs)) << "SSE2 form, mode " << mode << " quad " << n;
      ASSERT_TRUE(st_sets_agree(avx, tri)) << "mode " << mode << " quad " << n;
      ASSERT_TRUE(same(avx, run_plain(qe, area, tri), nan_inputs)) << "plain twin, mode " << mode << " quad " << n;
      for (size_t k = 0; k < 4; ++k)
        for (const double x : {avx.lanes.b[0][k], avx.z[k], static_cast<double>(avx.s[0][k]), static_cast<double>(avx.t[1][k])}) {
          nan_lanes += std::isnan(x);
          inf_lanes += std::isinf(x);
          negative_zero_lanes += x == 0 && std::signbit(x);
        }
    }
  }
  // The sweep reached the special results.
  EXPECT_GT(nan_lanes, 100);
  EXPECT_GT(inf_lanes, 100);
  EXPECT_GT(negative_zero_lanes, 100);
}

}  // namespace
}  // namespace tfu::quad_avx_test
#endif
