#include "cmodel/bezier_patch.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace tfu::q3 {

std::array<double, 3> quadratic_bernstein(double x) {
  const double y = 1.0 - x;
  return {y * y, 2.0 * x * y, x * x};
}

Vertex evaluate_biquadratic(const std::array<Vertex, 9>& control, double u, double v) {
  const auto bu = quadratic_bernstein(u), bv = quadratic_bernstein(v);
  Vertex out;
  std::array<double, 4> colour{};
  for (size_t j = 0; j < 3; ++j)
    for (size_t i = 0; i < 3; ++i) {
      const double w = bu[i] * bv[j];
      const Vertex& c = control[j * 3 + i];
      out.pos += w * c.pos;
      out.uv0 += w * c.uv0;
      out.uv1 += w * c.uv1;
      out.normal += w * c.normal;
      for (size_t k = 0; k < 4; ++k) colour[k] += w * c.colour[k];
    }
  const double len = glm::length(out.normal);
  if (len > 0) out.normal /= len;
  for (size_t k = 0; k < 4; ++k) out.colour[k] = static_cast<uint8_t>(std::clamp(std::lround(colour[k]), 0L, 255L));
  return out;
}

namespace {

// The 3 x 3 control points of sub-patch (a, b).
std::array<Vertex, 9> sub_patch_control(std::span<const Vertex> control, int width, int a, int b) {
  std::array<Vertex, 9> c;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      c[static_cast<size_t>(j * 3 + i)] = control[static_cast<size_t>((2 * b + j) * width + 2 * a + i)];
  return c;
}

// Sub-patch index and local parameter of grid line `g` (0..subpatches * L).
std::pair<int, double> locate(int g, int subpatches, int subdivision) {
  const int s = std::min(g / subdivision, subpatches - 1);
  return {s, static_cast<double>(g - s * subdivision) / subdivision};
}

}  // namespace

PatchMesh tessellate_patch(std::span<const Vertex> control, int width, int height, int subdivision) {
  assert(width >= 3 && height >= 3 && width % 2 == 1 && height % 2 == 1);
  assert(control.size() == static_cast<size_t>(width) * static_cast<size_t>(height));
  assert(subdivision >= 1 && subdivision <= kMaxPatchSubdivision);
  const int sub_w = (width - 1) / 2, sub_h = (height - 1) / 2;
  PatchMesh m;
  m.grid_width = sub_w * subdivision + 1;
  m.grid_height = sub_h * subdivision + 1;
  m.vertices.reserve(static_cast<size_t>(m.grid_width) * static_cast<size_t>(m.grid_height));
  for (int J = 0; J < m.grid_height; ++J) {
    const auto [b, v] = locate(J, sub_h, subdivision);
    for (int I = 0; I < m.grid_width; ++I) {
      const auto [a, u] = locate(I, sub_w, subdivision);
      m.vertices.push_back(evaluate_biquadratic(sub_patch_control(control, width, a, b), u, v));
    }
  }
  const auto g = [&](int I, int J) { return static_cast<uint32_t>(J * m.grid_width + I); };
  for (int J = 0; J + 1 < m.grid_height; ++J)
    for (int I = 0; I + 1 < m.grid_width; ++I) {
      m.triangles.push_back({g(I, J), g(I + 1, J), g(I + 1, J + 1)});
      m.triangles.push_back({g(I, J), g(I + 1, J + 1), g(I, J + 1)});
    }
  return m;
}

}  // namespace tfu::q3
