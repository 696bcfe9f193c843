// Port payloads of the texture filter unit's pipeline (rtl/tfu_unit.hpp has the block diagram).
// Field widths are those of the hardware; C++ types are chosen wide enough.
#pragma once

#include <array>
#include <cstdint>

#include "cmodel/direction_rom.hpp"
#include "cmodel/texture.hpp"

namespace tfu::rtl {

// request_fifo -> lod_unit: one 2x2 quad (quad traces) or one pixel (lod / grad traces).
//   id[31:0], npix[2:0] (4 or 1), s[4] t[4] FP32, lod FP32 | dsdx dtdx dsdy dtdy FP32
struct QuadReq {
  uint32_t id = 0;  // index of the first pixel in the trace
  int npix = 4;
  std::array<float, 4> s{}, t{};
  float lod = 0, dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0;
};

// lod_unit -> address_gen: one pixel per cycle.  id, s t FP32, lambda[15:0] (Q.8, before bias/clamp)
struct PixelReq {
  uint32_t id = 0;
  float s = 0, t = 0;
  int32_t lambda = 0;
};

// A texel address: x[13:0] y[13:0] inside the level; border = outside the texture under
// clamp-to-border (the border word, no cache access).
struct Tap {  // trivial (no initialisers): only the first ntaps of a footprint are written and read
  int16_t x, y;  // levels are at most 16384 texels wide: 15 bits, -1 with border
  bool border;
};

// What travels with one level footprint from address_gen to the filter's output, unchanged except
// for the shape (set by kernel_select, widened by the cache-aware probe):
//   id[31:0], fu[7:0] fv[7:0] (fractions in the level), blend[8:0] (weight of level1),
//   two/second (a blending MIPMAP_LINEAR pixel's first/second level), shape[11:0] (edge cross:
//   texels the kernel may use)
struct LevelTag {
  uint32_t id = 0;
  uint32_t fu = 0, fv = 0;
  int blend = 0;
  bool two = false, second = false;
  lee_jen::TexelMask shape = lee_jen::kAllTexels;
  bool emits() const { return !two || second; }    // the filter outputs a pixel for this footprint
  bool holds() const { return two && !second; }    // level0 of a blending pair: kept for the blend
};

// address_gen -> kernel_select -> texel_cache: one level footprint per cycle.
//   tag, level[3:0], ntaps[4:0] (1, 4, T*T <= 16, or 12 for the edge cross: tap k = texel C(k+1)),
//   optional[11:0] (cache-aware: arms to add when their lines are resident)
struct FootprintReq {
  LevelTag tag;
  int level = 0, ntaps = 0;
  std::array<Tap, 16> taps;  // [0, ntaps) valid
  lee_jen::TexelMask optional = 0;
};

// texel_cache -> filter: the footprint's texel words.
struct FilterReq {
  LevelTag tag;
  int ntaps = 0;
  std::array<Rgba8, 16> texels;  // [0, ntaps) valid; zero where an edge shape has no texel
};

// filter -> response: id[31:0], rgba[31:0]
struct Response {
  uint32_t id = 0;
  Rgba8 rgba{};
};

}  // namespace tfu::rtl
