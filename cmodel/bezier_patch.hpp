// Tessellation of Quake III Bezier patches (BSP face type 2).
//
// A patch is a grid of W x H control points (both odd, >= 3), row-major (W points per row, the
// first index along the patch's s direction). It is made of (W-1)/2 x (H-1)/2 biquadratic Bezier
// sub-patches; sub-patch (a, b) uses the 3 x 3 control points C[2b + j][2a + i], i, j in 0..2, and
//   P(u, v) = sum_i sum_j B_i(u) B_j(v) C[2b + j][2a + i],  B_0 = (1 - x)^2, B_1 = 2 x (1 - x), B_2 = x^2
// for u, v in [0, 1]. Every vertex attribute (position, both UV sets, normal, colour) is
// interpolated with the same weights; the normal is renormalised, the colour rounded to nearest.
//
// Fixed subdivision: each sub-patch is cut into L x L quads (L = kPatchSubdivision = 8 unless
// asked otherwise), so the patch becomes one grid of ((W-1)/2 L + 1) x ((H-1)/2 L + 1) vertices
// (neighbouring sub-patches share their edge rows: no cracks inside a patch). Grid vertex (I, J)
// lies in sub-patch a = min(I / L, (W-1)/2 - 1) at u = I / L - a (likewise J, b, v). Quake III
// itself subdivides adaptively (r_subdivisions); a fixed level makes the geometry, and hence the
// request stream, independent of any setting.
//
// Triangles: per grid quad with corners g(I, J), two triangles
//   {g(I, J), g(I+1, J), g(I+1, J+1)} and {g(I, J), g(I+1, J+1), g(I, J+1)}
// (quads row by row, J outer). Degenerate triangles (collinear control rows are common) are kept;
// the rasterizer skips zero-area triangles.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "cmodel/bsp.hpp"

namespace tfu::q3 {

inline constexpr int kPatchSubdivision = 8;  // quads per sub-patch side
inline constexpr int kMaxPatchSubdivision = 64;

struct PatchMesh {
  int grid_width = 0, grid_height = 0;  // vertices per row, rows
  std::vector<Vertex> vertices;         // row-major grid, row J = v direction
  std::vector<std::array<uint32_t, 3>> triangles;  // indices into `vertices`
};

// Quadratic Bernstein weights (B_0, B_1, B_2) at x.
std::array<double, 3> quadratic_bernstein(double x);

// One point of a 3 x 3 biquadratic sub-patch: control[j * 3 + i], i along u.
Vertex evaluate_biquadratic(const std::array<Vertex, 9>& control, double u, double v);

// Tessellates a W x H control grid (checked by the caller: odd sizes, W x H points) at
// `subdivision` quads per sub-patch side (1..kMaxPatchSubdivision).
PatchMesh tessellate_patch(std::span<const Vertex> control, int width, int height, int subdivision = kPatchSubdivision);

}  // namespace tfu::q3
