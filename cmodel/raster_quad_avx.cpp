// AVX form of the renderer's quad interpolation. Plain twin: raster_fast::barycentrics, depth and st
// (cmodel/raster_quad_fast.hpp, SSE2), and the per-pixel interpolation of raster.cpp. Equality test:
// RasterQuadAvx.* (testbench/test_raster_quad_avx.cpp). See raster_quad_avx.hpp. This file is
// compiled with -ffp-contract=off and outside the unity batches (cmodel/CMakeLists.txt); only the
// functions marked TFU_AVX use AVX instructions.
#include "cmodel/raster_quad_avx.hpp"

#include <algorithm>

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define TFU_RASTER_QUAD_AVX 1
#define TFU_AVX __attribute__((target("avx")))
#endif

namespace tfu::raster_avx {

#if TFU_RASTER_QUAD_AVX

bool available() {
  static const bool avx = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx") != 0;
  }();
  return avx;
}

// The edge functions of edge i, pixel k in lane k, each converted by `vcvtsi2sd` (as static_cast).
TFU_AVX static inline __m256d edge_lanes(const std::array<int64_t, 4>& e) {
  return _mm256_set_pd(static_cast<double>(e[3]), static_cast<double>(e[2]), static_cast<double>(e[1]), static_cast<double>(e[0]));
}

TFU_AVX void barycentrics_depth(const raster_fast::QuadEdges& qe, double area, const RasterTriangle& tri, raster_fast::QuadLanes& q,
                                std::array<double, 4>& z) {
  const __m256d a = _mm256_set1_pd(area);
  __m256d b[3];
  for (size_t i = 0; i < 3; ++i) {
    b[i] = _mm256_div_pd(edge_lanes(qe.e[i]), a);
    _mm256_store_pd(q.b[i].data(), b[i]);
  }
  // inv_w = ((0 + b0 / w0) + b1 / w1) + b2 / w2, as interpolate_st's loop.
  __m256d iw = _mm256_setzero_pd();
  for (size_t i = 0; i < 3; ++i) iw = _mm256_add_pd(iw, _mm256_mul_pd(b[i], _mm256_set1_pd(tri.v[i].inv_w)));
  _mm256_store_pd(q.inv_w.data(), iw);
  // A helper pixel extrapolated beyond the horizon (not positive, or NaN: _CMP_GT_OS is false for
  // NaN, and signals on it as the SSE2 form's cmpltpd does).
  if (_mm256_movemask_pd(_mm256_cmp_pd(iw, _mm256_setzero_pd(), _CMP_GT_OS)) != 0xF)
    for (size_t k = 0; k < 4; ++k)
      if (!(q.inv_w[k] > 0)) q.inv_w[k] = 1e-6 * std::min({tri.v[0].inv_w, tri.v[1].inv_w, tri.v[2].inv_w});
  // z = (b0 z0 + b1 z1) + b2 z2 (interpolate_z).
  __m256d acc = _mm256_mul_pd(b[0], _mm256_set1_pd(tri.v[0].z));
  acc = _mm256_add_pd(acc, _mm256_mul_pd(b[1], _mm256_set1_pd(tri.v[1].z)));
  acc = _mm256_add_pd(acc, _mm256_mul_pd(b[2], _mm256_set1_pd(tri.v[2].z)));
  _mm256_storeu_pd(z.data(), acc);
}

// The body of st() and st_sets(), inlined into both.
[[gnu::always_inline]] TFU_AVX static inline void st_avx(const raster_fast::QuadLanes& q, const RasterTriangle& tri, size_t uv, float* s,
                                                        float* t) {
  // s/w and t/w from 0.0 (interpolate_st's sums), divided by 1/w, clamped as std::clamp(v, -1e30,
  // 1e30) = max(lo, min(hi, v)) (vminpd/vmaxpd return their second operand for NaN, as minpd/maxpd)
  // and rounded to FP32 by `vcvtpd2ps` (each lane as cvtsd2ss, MXCSR's rounding mode).
  __m256d s_w = _mm256_setzero_pd(), t_w = _mm256_setzero_pd();
  for (size_t i = 0; i < 3; ++i) {
    const __m256d bi = _mm256_load_pd(q.b[i].data());
    s_w = _mm256_add_pd(s_w, _mm256_mul_pd(bi, _mm256_set1_pd(tri.v[i].uv_w[uv].x)));
    t_w = _mm256_add_pd(t_w, _mm256_mul_pd(bi, _mm256_set1_pd(tri.v[i].uv_w[uv].y)));
  }
  const __m256d iw = _mm256_load_pd(q.inv_w.data());
  const __m256d lo = _mm256_set1_pd(-1e30), hi = _mm256_set1_pd(1e30);
  _mm_storeu_ps(s, _mm256_cvtpd_ps(_mm256_max_pd(lo, _mm256_min_pd(hi, _mm256_div_pd(s_w, iw)))));
  _mm_storeu_ps(t, _mm256_cvtpd_ps(_mm256_max_pd(lo, _mm256_min_pd(hi, _mm256_div_pd(t_w, iw)))));
}

TFU_AVX void st(const raster_fast::QuadLanes& q, const RasterTriangle& tri, int set, float* s, float* t) {
  st_avx(q, tri, static_cast<size_t>(set), s, t);
}

TFU_AVX void st_sets(const raster_fast::QuadLanes& q, const RasterTriangle& tri, unsigned sets, QuadCoords& c) {
  for (size_t set = 0; set < 2; ++set)
    if (sets >> set & 1u) st_avx(q, tri, set, c.s[set].data(), c.t[set].data());
}

#else

bool available() { return false; }

void barycentrics_depth(const raster_fast::QuadEdges& qe, double area, const RasterTriangle& tri, raster_fast::QuadLanes& q,
                        std::array<double, 4>& z) {
  raster_fast::barycentrics(qe, area, tri, q);
  z = raster_fast::depth(q, tri);
}

void st(const raster_fast::QuadLanes& q, const RasterTriangle& tri, int set, float* s, float* t) { raster_fast::st(q, tri, set, s, t); }

void st_sets(const raster_fast::QuadLanes& q, const RasterTriangle& tri, unsigned sets, QuadCoords& c) {
  for (size_t set = 0; set < 2; ++set)
    if (sets >> set & 1u) raster_fast::st(q, tri, static_cast<int>(set), c.s[set].data(), c.t[set].data());
}

#endif

}  // namespace tfu::raster_avx
