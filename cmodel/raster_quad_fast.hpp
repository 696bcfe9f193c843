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
// On a CPU with AVX the renderer runs raster_quad_avx.hpp's form of barycentrics, depth and st (a
// quad's four lanes in one register), whose plain twin is this SSE2 form (RasterQuadAvx.*).
// write_quad (the drawn pixels' colour and depth writes, two per row at once) has the per-pixel
// write loop of shade_triangle as its plain twin; it is checked by the renders with the fast paths
// on and off (PlainPaths.*, RasterQuadFast.WriteQuadEqualsThePerPixelWrites).
// The quad's coverage and depth tests without a branch per pixel (coverage, step, depth_test) and
// the batch's requests gathered and its texels spread back by the draw mask (gather_requests,
// spread_texels): plain twins, the per-pixel loops of shade_triangle that run with the fast paths
// off (the fill-rule test e_i + bias_i >= 0 on RasterTriangle::edge, `z < depth`, `reqs[n++]` per
// drawn pixel and its inverse); equality tests RasterQuadFast.CoverageEqualsThePerPixelTest,
// StepEqualsTheEdgeFunctions, DepthTestEqualsThePerPixelTest, GatherAndSpreadEqualThePerPixelLoops.
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

// The edge functions of a quad's four pixel centres, edge-major: e[i][k] = RasterTriangle::edge(i)
// at pixel k's centre, so that one SSE2 register holds edge i of a row of the quad (pixels 2r, 2r+1).
struct QuadEdges {
  alignas(16) std::array<std::array<int64_t, 4>, 3> e;
};

// Bit k set: pixel k's centre is covered, e[i][k] + bias[i] >= 0 for the three edges (the fill rule
// of RasterTriangle::covers_point; the image bounds are the caller's). Setup bounds |e| below 2^58,
// so e + bias does not overflow and its sign bit decides: one `movmskpd` of the three sums' OR per
// row of the quad.
inline unsigned coverage(const QuadEdges& q, const std::array<int64_t, 3>& bias) {
#if TFU_RASTER_QUAD_SSE2
  unsigned negative = 0;
  for (size_t r = 0; r < 2; ++r) {
    __m128i any = _mm_setzero_si128();
    for (size_t i = 0; i < 3; ++i)
      any = _mm_or_si128(any, _mm_add_epi64(_mm_load_si128(reinterpret_cast<const __m128i*>(&q.e[i][2 * r])),
                                            _mm_set1_epi64x(bias[i])));
    negative |= static_cast<unsigned>(_mm_movemask_pd(_mm_castsi128_pd(any))) << (2 * r);
  }
  return ~negative & 0xFu;
#else
  unsigned covered = 0;
  for (size_t k = 0; k < 4; ++k)
    if (q.e[0][k] + bias[0] >= 0 && q.e[1][k] + bias[1] >= 0 && q.e[2][k] + bias[2] >= 0) covered |= 1u << k;
  return covered;
#endif
}

// Every edge of every pixel moved by step[i] (the next quad of the row: two pixels' step).
inline void step(QuadEdges& q, const std::array<int64_t, 3>& step) {
#if TFU_RASTER_QUAD_SSE2
  for (size_t i = 0; i < 3; ++i) {
    const __m128i d = _mm_set1_epi64x(step[i]);
    for (size_t r = 0; r < 2; ++r) {
      auto* p = reinterpret_cast<__m128i*>(&q.e[i][2 * r]);
      _mm_store_si128(p, _mm_add_epi64(_mm_load_si128(p), d));
    }
  }
#else
  for (size_t i = 0; i < 3; ++i)
    for (auto& v : q.e[i]) v += step[i];
#endif
}

// The depth test of the covered pixels: bit k set where `covered` has it and z[k] < depth[pixel k]
// (the float widened to double, exactly as the plain comparison promotes it; NaN compares false in
// both). Pixel k is depth[idx0 + (k >> 1) row + (k & 1)]. `inside`: the whole quad lies in the image,
// and each row's two depths are one 8-byte load (an uncovered pixel's is read and masked: it is in
// the image, in the caller's band). Else an uncovered pixel's depth is not read (it may lie outside
// the image): its lane reads pixel 0's, which always exists, and is masked.
inline unsigned depth_test(unsigned covered, const std::array<double, 4>& z, const float* depth, size_t idx0, size_t row,
                           bool inside) {
#if TFU_RASTER_QUAD_SSE2
  __m128 d01, d23;
  if (inside) {
    d01 = _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&depth[idx0])));
    d23 = _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&depth[idx0 + row])));
  } else {
    alignas(16) std::array<float, 4> d;
    for (size_t k = 0; k < 4; ++k) d[k] = depth[(covered >> k & 1u) ? idx0 + (k >> 1) * row + (k & 1) : idx0];
    d01 = _mm_load_ps(d.data());
    d23 = _mm_movehl_ps(d01, d01);
  }
  const __m128d lo = _mm_cmplt_pd(_mm_loadu_pd(&z[0]), _mm_cvtps_pd(d01));
  const __m128d hi = _mm_cmplt_pd(_mm_loadu_pd(&z[2]), _mm_cvtps_pd(d23));
  const auto less = static_cast<unsigned>(_mm_movemask_pd(lo) | _mm_movemask_pd(hi) << 2);
#else
  (void)inside;
  std::array<float, 4> d;
  for (size_t k = 0; k < 4; ++k) d[k] = depth[(covered >> k & 1u) ? idx0 + (k >> 1) * row + (k & 1) : idx0];
  unsigned less = 0;
  for (size_t k = 0; k < 4; ++k) less |= static_cast<unsigned>(z[k] < d[k]) << k;
#endif
  return less & covered;
}

// The drawn pixels' requests in pixel order, reqs[0..n), n returned (the plain `if (mask >> k & 1)
// reqs[n++] = ...`): every pixel's request is stored at reqs[n] and n counts the drawn ones, so a
// pixel not drawn is overwritten by the next drawn one or left beyond n (unread). n <= k at pixel k,
// so nothing is written beyond reqs[3].
inline size_t gather_requests(unsigned mask, const float* s, const float* t, int32_t lambda, SampleRequest* reqs) {
  if (mask == 0xFu) {  // every pixel drawn (most quads): request k is pixel k's, no index to form
    for (size_t k = 0; k < 4; ++k) reqs[k] = {s[k], t[k], lambda};
    return 4;
  }
  size_t n = 0;
  for (size_t k = 0; k < 4; ++k) {
    reqs[n] = {s[k], t[k], lambda};
    n += mask >> k & 1u;
  }
  return n;
}

// The inverse: texel[0..n) holds the drawn pixels' texels in pixel order; afterwards texel[k] is
// pixel k's where it is drawn and 0 elsewhere (the plain `for (k = 4; k-- > 0;) texel[k] = mask >> k & 1
// ? texel[--n] : Rgba8{}`), by a table of the source slot of every lane (4: zero).
inline void spread_texels(unsigned mask, std::array<Rgba8, 4>& texel) {
  static constexpr std::array<std::array<uint8_t, 4>, 16> kSource = [] {
    std::array<std::array<uint8_t, 4>, 16> table{};
    for (unsigned m = 0; m < 16; ++m) {
      uint8_t n = 0;
      for (size_t k = 0; k < 4; ++k) table[m][k] = (m >> k & 1u) ? n++ : uint8_t{4};
    }
    return table;
  }();
  std::array<Rgba8, 5> src{};
  std::memcpy(src.data(), texel.data(), sizeof texel);
  const auto& from = kSource[mask & 0xFu];
  for (size_t k = 0; k < 4; ++k) texel[k] = src[from[k]];
}

// Per-pixel values of one quad, pixel k in lane k (pixel order of raster.hpp).
// 32-byte aligned: one AVX register a row (raster_quad_avx.cpp).
struct QuadLanes {
  alignas(32) std::array<std::array<double, 4>, 3> b;  // b[i][k]: barycentric i of pixel k
  alignas(32) std::array<double, 4> inv_w;              // sum b_i / w_i, made positive (interpolate_st)
};

// b[i][k] = e[i][k] / area (RasterTriangle::barycentric at pixel k's centre, whose edge functions
// `qe` holds) and inv_w; the four helper-pixel lanes are formed as the covered ones.
inline void barycentrics(const QuadEdges& qe, double area, const RasterTriangle& tri, QuadLanes& q) {
  const auto& e = qe.e;
#if TFU_RASTER_QUAD_SSE2
  const __m128d a = _mm_set1_pd(area);
  for (size_t i = 0; i < 3; ++i)
    for (size_t k = 0; k < 4; k += 2)
      _mm_store_pd(&q.b[i][k], _mm_div_pd(_mm_set_pd(static_cast<double>(e[i][k + 1]), static_cast<double>(e[i][k])), a));
  int positive = 0xF;  // bit k: pixel k has inv_w > 0 (cmpgt_pd is false for NaN, where `!(v > 0)` is true)
  for (size_t k = 0; k < 4; k += 2) {
    __m128d iw = _mm_setzero_pd();
    for (size_t i = 0; i < 3; ++i) iw = _mm_add_pd(iw, _mm_mul_pd(_mm_load_pd(&q.b[i][k]), _mm_set1_pd(tri.v[i].inv_w)));
    _mm_store_pd(&q.inv_w[k], iw);
    positive &= _mm_movemask_pd(_mm_cmpgt_pd(iw, _mm_setzero_pd())) << k | (k == 0 ? 0xC : 0x3);
  }
  if (positive == 0xF) return;  // no lane beyond the horizon: the loop below would change nothing
#else
  for (size_t k = 0; k < 4; ++k) {
    for (size_t i = 0; i < 3; ++i) q.b[i][k] = static_cast<double>(e[i][k]) / area;
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
