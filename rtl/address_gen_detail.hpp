// Address-unit pieces shared by the plain address generator (rtl/address_gen.cpp) and its
// per-wrap-pair grids (rtl/address_gen_fixed_grids.cpp). Internal to those two files.
#pragma once

#include <cstdint>

#include "cmodel/aniso.hpp"
#include "cmodel/datapath.hpp"
#include "rtl/unit_ports.hpp"

namespace tfu::rtl::detail {

// The centre's level coordinate (dp::texel_coord), plus an anisotropic probe's offset on the
// level (dp::probe_texel_coord) when there is one.
[[gnu::always_inline]] inline dp::LevelCoord probe_coord(float s, int size, const ProbeLevelOffset* o, int64_t offset_q8) {
  const dp::LevelCoord c = dp::texel_coord(s, size);
  return o ? dp::probe_texel_coord(c, offset_q8) : c;
}

// Grid cells whose column or row lies outside the texture (clamp-to-border: -1) read the border.
inline uint16_t cells_inside(const TapGrid& g) {
  uint16_t out = 0xFFFF;
  for (int i = 0; i < g.cols; ++i)
    if (g.x[static_cast<size_t>(i)] < 0) out = static_cast<uint16_t>(out & ~(0x1111u << i));
  for (int j = 0; j < g.rows; ++j)
    if (g.y[static_cast<size_t>(j)] < 0) out = static_cast<uint16_t>(out & ~(0xFu << (4 * j)));
  return out;
}

}  // namespace tfu::rtl::detail
