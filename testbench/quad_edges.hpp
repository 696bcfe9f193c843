// The edge functions of a quad's four pixel centres straight from RasterTriangle::edge: the
// reference the renderer's quad forms are checked against (test_raster_quad_fast.cpp,
// test_raster_quad_avx.cpp), where the renderer steps them quad by quad.
#pragma once

#include "cmodel/raster.hpp"
#include "cmodel/raster_quad_fast.hpp"

namespace tfu::test {

// e[i][k] = tri.edge(i) at the centre of pixel k of the quad whose pixel (0, 0) is (qx, qy).
inline raster_fast::QuadEdges edges_at(const RasterTriangle& tri, int qx, int qy) {
  raster_fast::QuadEdges q;
  for (size_t k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i)
      q.e[static_cast<size_t>(i)][k] = tri.edge(i, RasterTriangle::centre(qx + static_cast<int>(k & 1)),
                                                RasterTriangle::centre(qy + static_cast<int>(k >> 1)));
  return q;
}

}  // namespace tfu::test
