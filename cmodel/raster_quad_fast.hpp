// Speed-only form of the golden renderer's per-pixel interpolation on the four pixels of a quad at
// once (raster.cpp, shade_triangle): the barycentrics, the depth, 1/w and the perspective-correct
// (s, t) of a UV set converted to the FP32 interface coordinates. Plain twin: per pixel,
// RasterTriangle::barycentric's divisions of the edge functions, interpolate_z, interpolate_st and
// to_float_coord (raster.cpp). Equality test: RasterQuadFast.* in testbench/test_raster_quad_fast.cpp
// (random triangles of every shape, every pixel of their quads, helper pixels beyond the horizon
// included, compared bit for bit). Off with the fast-path switch (cmodel/fast_paths.hpp: TFU_PLAIN=1,
// the CLI's --plain).
//
// These are the renderer's real-valued interpolation (as in the plain twin, double precision; the
// datapath starts at the FP32 coordinates), so "the same" means bit for bit the same doubles: every
// value is formed by the same IEEE-754 operations, in the same order, on the same operands, as the
// plain twin forms it (sums start from 0.0 as its loops do, which matters for the sign of a zero),
// two pixels per SSE2 register (SSE2 is part of x86-64; packed double operations round each lane as
// the scalar ones do). 1/w is formed once per pixel and shared by the stages, which the plain twin
// recomputes per stage with the same operations. Elsewhere a portable per-lane loop stands in.
// write_quad (the drawn pixels' colour and depth writes, two per row at once) has the per-pixel
// write loop of shade_triangle as its plain twin; it is checked by the renders with the fast paths
// on and off (PlainPaths.*, RasterQuadFast.WriteQuadEqualsThePerPixelWrites).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>

#include "cmodel/raster.hpp"

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define TFU_RASTER_QUAD_SSE2 1
#endif

namespace tfu::raster_fast {

// Per-pixel values of one quad, pixel k in lane k (pixel order of raster.hpp).
struct QuadLanes {
  alignas(16) std::array<std::array<double, 4>, 3> b;  // b[i][k]: barycentric i of pixel k
  alignas(16) std::array<double, 4> inv_w;              // sum b_i / w_i, made positive (interpolate_st)
};

// b[i][k] = e[k][i] / area (RasterTriangle::barycentric at pixel k's centre, whose edge functions
// `e` holds) and inv_w; the four helper-pixel lanes are formed as the covered ones.
inline void barycentrics(const std::array<std::array<int64_t, 3>, 4>& e, double area, const RasterTriangle& tri, QuadLanes& q) {
#if TFU_RASTER_QUAD_SSE2
  const __m128d a = _mm_set1_pd(area);
  for (size_t i = 0; i < 3; ++i)
    for (size_t k = 0; k < 4; k += 2)
      _mm_store_pd(&q.b[i][k], _mm_div_pd(_mm_set_pd(static_cast<double>(e[k + 1][i]), static_cast<double>(e[k][i])), a));
  for (size_t k = 0; k < 4; k += 2) {
    __m128d iw = _mm_setzero_pd();
    for (size_t i = 0; i < 3; ++i) iw = _mm_add_pd(iw, _mm_mul_pd(_mm_load_pd(&q.b[i][k]), _mm_set1_pd(tri.v[i].inv_w)));
    _mm_store_pd(&q.inv_w[k], iw);
  }
#else
  for (size_t k = 0; k < 4; ++k) {
    for (size_t i = 0; i < 3; ++i) q.b[i][k] = static_cast<double>(e[k][i]) / area;
    double iw = 0;
    for (size_t i = 0; i < 3; ++i) iw += q.b[i][k] * tri.v[i].inv_w;
    q.inv_w[k] = iw;
  }
#endif
  // A helper pixel extrapolated beyond the horizon (as interpolate_st).
  for (size_t k = 0; k < 4; ++k)
    if (!(q.inv_w[k] > 0)) q.inv_w[k] = 1e-6 * std::min({tri.v[0].inv_w, tri.v[1].inv_w, tri.v[2].inv_w});
}

// = interpolate_z(tri, b of pixel k): b0 z0 + b1 z1 + b2 z2.
inline std::array<double, 4> depth(const QuadLanes& q, const RasterTriangle& tri) {
  std::array<double, 4> z;
#if TFU_RASTER_QUAD_SSE2
  for (size_t k = 0; k < 4; k += 2) {
    __m128d acc = _mm_mul_pd(_mm_load_pd(&q.b[0][k]), _mm_set1_pd(tri.v[0].z));
    acc = _mm_add_pd(acc, _mm_mul_pd(_mm_load_pd(&q.b[1][k]), _mm_set1_pd(tri.v[1].z)));
    acc = _mm_add_pd(acc, _mm_mul_pd(_mm_load_pd(&q.b[2][k]), _mm_set1_pd(tri.v[2].z)));
    _mm_storeu_pd(&z[k], acc);
  }
#else
  for (size_t k = 0; k < 4; ++k) z[k] = q.b[0][k] * tri.v[0].z + q.b[1][k] * tri.v[1].z + q.b[2][k] * tri.v[2].z;
#endif
  return z;
}

// s[k], t[k] = to_float_coord of interpolate_st(tri, b of pixel k, set): (sum b_i s_i/w_i) / (1/w),
// clamped to [-1e30, 1e30] (std::clamp, a NaN passes through) and rounded to FP32.
inline void st(const QuadLanes& q, const RasterTriangle& tri, int set, float* s, float* t) {
  const auto uv = static_cast<size_t>(set);
#if TFU_RASTER_QUAD_SSE2
  // std::clamp(v, lo, hi) = v < lo ? lo : (hi < v ? hi : v); _mm_min_pd(a, b) = a < b ? a : b and
  // _mm_max_pd(a, b) = a > b ? a : b, so max(lo, min(hi, v)) is the same for every v, NaN and -0 included.
  const __m128d lo = _mm_set1_pd(-1e30), hi = _mm_set1_pd(1e30);
  const auto to_float = [&](__m128d v) { return _mm_cvtpd_ps(_mm_max_pd(lo, _mm_min_pd(hi, v))); };
  __m128 sf[2], tf[2];
  for (size_t k = 0; k < 4; k += 2) {
    __m128d s_w = _mm_setzero_pd(), t_w = _mm_setzero_pd();
    for (size_t i = 0; i < 3; ++i) {
      const __m128d bi = _mm_load_pd(&q.b[i][k]);
      s_w = _mm_add_pd(s_w, _mm_mul_pd(bi, _mm_set1_pd(tri.v[i].uv_w[uv].x)));
      t_w = _mm_add_pd(t_w, _mm_mul_pd(bi, _mm_set1_pd(tri.v[i].uv_w[uv].y)));
    }
    const __m128d iw = _mm_load_pd(&q.inv_w[k]);
    sf[k / 2] = to_float(_mm_div_pd(s_w, iw));
    tf[k / 2] = to_float(_mm_div_pd(t_w, iw));
  }
  // One 16-byte store each (two 8-byte stores read back as 16 bytes stall store forwarding).
  _mm_storeu_ps(s, _mm_movelh_ps(sf[0], sf[1]));
  _mm_storeu_ps(t, _mm_movelh_ps(tf[0], tf[1]));
#else
  for (size_t k = 0; k < 4; ++k) {
    double s_w = 0, t_w = 0;
    for (size_t i = 0; i < 3; ++i) {
      s_w += q.b[i][k] * tri.v[i].uv_w[uv].x;
      t_w += q.b[i][k] * tri.v[i].uv_w[uv].y;
    }
    s[k] = static_cast<float>(std::clamp(s_w / q.inv_w[k], -1e30, 1e30));
    t[k] = static_cast<float>(std::clamp(t_w / q.inv_w[k], -1e30, 1e30));
  }
#endif
}

// The drawn pixels' writes of a quad: for each pixel k in `mask`, image[row k] = colour[k] and
// depth[row k] = static_cast<float>(z[k]) (the plain twin: shade_triangle's per-pixel loop, which
// this replaces when no other per-pixel output is kept). A row of the quad with both pixels drawn
// takes one 8-byte store of two colours and one of two depths; cvtpd2ps rounds each lane to FP32 as
// cvtsd2ss does (the same rounding mode, MXCSR), so the depths are the same bits. `idx0` is the
// index of the quad's pixel (0, 0), `row` the image width.
inline void write_quad(unsigned mask, const std::array<Rgba8, 4>& colour, const std::array<double, 4>& z, size_t idx0,
                       size_t row, Rgba8* image, float* depth) {
  for (size_t r = 0; r < 2; ++r) {
    const unsigned m = mask >> (2 * r) & 3u;
    if (m == 0) continue;
    const size_t idx = idx0 + r * row;
    if (m == 3u) {
      std::memcpy(&image[idx], &colour[2 * r], 2 * sizeof(Rgba8));
#if TFU_RASTER_QUAD_SSE2
      _mm_storel_pi(reinterpret_cast<__m64*>(&depth[idx]), _mm_cvtpd_ps(_mm_loadu_pd(&z[2 * r])));
#else
      depth[idx] = static_cast<float>(z[2 * r]);
      depth[idx + 1] = static_cast<float>(z[2 * r + 1]);
#endif
    } else {
      const size_t k = m == 1u ? 0 : 1;
      image[idx + k] = colour[2 * r + k];
      depth[idx + k] = static_cast<float>(z[2 * r + k]);
    }
  }
}

}  // namespace tfu::raster_fast
