// AVX form of the renderer's quad interpolation (raster_quad_fast.hpp): a quad's four pixels in one
// 256-bit register, so each of the exact interpolation's divisions (the barycentrics' e_i / area, the
// (s, t) divisions by 1/w) is one `vdivpd` for the quad where the SSE2 form takes two `divpd`.
// Plain twin: the SSE2 form, raster_fast::barycentrics, raster_fast::depth and raster_fast::st, and
// through it the per-pixel plain twin (RasterTriangle::barycentric, interpolate_z, interpolate_st and
// to_float_coord of raster.cpp). Equality test: RasterQuadAvx.* in testbench/test_raster_quad_avx.cpp
// (random triangles of every shape, every pixel of their quads, helper pixels beyond the horizon,
// NaN, infinities and -0 among the inputs, in the four rounding modes and with FTZ/DAZ, against both
// twins bit for bit; skipped only on a CPU without AVX). Chosen once at run time (available():
// __builtin_cpu_supports("avx")); off with the fast-path switch (cmodel/fast_paths.hpp: TFU_PLAIN=1,
// the CLI's --plain), which the caller reads: shade_triangle then runs the per-pixel plain twin.
//
// Bit for bit: every lane is formed by the same IEEE-754 operations, in the same order, on the same
// operands as the SSE2 form and the plain twin (packed double operations round each lane as the
// scalar ones do, under the same MXCSR rounding mode). Only AVX is enabled for these functions
// (`target("avx")`, no FMA), and raster_quad_avx.cpp is compiled with -ffp-contract=off, so no
// a * b + c is contracted; the edge functions are converted to double one by one (`vcvtsi2sd`, as
// the SSE2 form's `cvtsi2sd`). The functions are whole quads' work (they cannot inline into the
// non-AVX caller): the call and the `vzeroupper` at their return are a few cycles against the
// divisions' latency.
#pragma once

#include <array>

#include "cmodel/raster.hpp"
#include "cmodel/raster_quad_fast.hpp"

namespace tfu::raster_avx {

// Whether this CPU and OS run AVX (read once; false on a build for another architecture, where the
// functions below are the SSE2/portable form).
bool available();

// = raster_fast::barycentrics(qe, area, tri, q), then z = raster_fast::depth(q, tri). Only with available().
void barycentrics_depth(const raster_fast::QuadEdges& qe, double area, const RasterTriangle& tri, raster_fast::QuadLanes& q,
                        std::array<double, 4>& z);

// = raster_fast::st(q, tri, set, s, t). Only with available().
void st(const raster_fast::QuadLanes& q, const RasterTriangle& tri, int set, float* s, float* t);

// The (s, t) of every UV set a quad's stages read, formed once before the stages: for each set
// whose bit is in `sets` (bit 0: set 0, bit 1: set 1), s[set], t[set] = raster_fast::st(q, tri, set,
// ...); the other sets' entries are left as they are. The four divisions of two sets issue back to
// back, so the second set's wait overlaps the first stage's sampling instead of following it.
// Only with available().
struct QuadCoords {
  alignas(16) std::array<std::array<float, 4>, 2> s, t;  // [UV set][pixel]
};
void st_sets(const raster_fast::QuadLanes& q, const RasterTriangle& tri, unsigned sets, QuadCoords& c);

}  // namespace tfu::raster_avx
