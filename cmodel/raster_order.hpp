// The rasterizer's traversal order and the distribution of screen tiles over texture filter units:
// the order in which a frame's shaded quads reach the units (full text in docs/renderer.md, "Raster
// order", and docs/cycle-model.md).
//
//   scanline        today's order: bands of kBandRows rows top to bottom; within a band the triangles in
//                   scene order, each triangle's quads row by row (left to right) inside the band
//   tiled:N         N x N-pixel screen tiles in row order; within a tile the triangles in scene order,
//                   each triangle's quads row by row inside the tile (Hakura & Gupta 1997, "tiled
//                   rasterization"); N even, 2..256
//   morton:N        as tiled:N, each triangle's quads inside the tile in Morton (Z) order of their quad
//                   coordinates: x bit 0, y bit 0, x bit 1, ... (N a power of two, 2..256)
//
// Every order shades the same quads with the same masks: a pixel lies in one band or tile, and the
// triangles covering it are drawn in scene order in each, so the depth test sees the same sequence.
// Only the order of the trace (and so of the units' requests) changes.
//
// Units (rtl/scene_sim.hpp) take screen tiles of T x T pixels:
//   round-robin:T   tile k of the row-major tile sequence goes to unit k mod units (the default, T = 32)
//   bands:T         the tile rows are dealt in contiguous horizontal bands, unit u taking rows
//                   [u R / units, (u+1) R / units) of the R tile rows
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cmodel/enum_names.hpp"

namespace tfu {

enum class RasterTraversal { Scanline, Tiled, Morton };
inline constexpr EnumNames<RasterTraversal, 3> kRasterTraversalNames{"raster order",
                                                                     {{{RasterTraversal::Scanline, "scanline"},
                                                                       {RasterTraversal::Tiled, "tiled"},
                                                                       {RasterTraversal::Morton, "morton"}}}};

inline constexpr int kMaxRasterTile = 256;  // pixels per side of a raster or unit tile

struct RasterOrder {
  RasterTraversal traversal = RasterTraversal::Scanline;
  int tile = 0;  // pixels per side (tiled, morton); 0 for scanline
  bool operator==(const RasterOrder&) const = default;
};

// "scanline", "tiled:N", "morton:N" (InputError naming the input otherwise).
RasterOrder raster_order_from_name(const std::string& name);
std::string raster_order_name(const RasterOrder& order);

// One shaded quad as the rasterizer produced it: the triangle (index in setup order, i.e. scene
// order), its top-left pixel, and the position of the record in the scanline sequence.
struct QuadPlace {
  uint32_t triangle = 0;
  int x = 0, y = 0;
};

// The permutation that puts quads recorded in scanline order into `order`: element i of the result
// is the index (into `quads`) of the i-th quad of the new sequence. Records of one quad (its stages)
// keep their relative order. Identity for scanline.
std::vector<size_t> raster_sequence(const RasterOrder& order, const std::vector<QuadPlace>& quads);

// The rank of quad (qx, qy) (quad coordinates, i.e. pixel / 2, inside a tile) in the tile's order.
uint32_t quad_rank_in_tile(const RasterOrder& order, int qx, int qy);

enum class UnitDistribution { RoundRobin, Bands };
inline constexpr EnumNames<UnitDistribution, 2> kUnitDistributionNames{
    "unit distribution", {{{UnitDistribution::RoundRobin, "round-robin"}, {UnitDistribution::Bands, "bands"}}}};

struct UnitTiles {
  UnitDistribution distribution = UnitDistribution::RoundRobin;
  int tile = 32;  // pixels per side of a screen tile
  bool operator==(const UnitTiles&) const = default;
};

// "round-robin:T", "bands:T"; a bare name takes T = 32.
UnitTiles unit_tiles_from_name(const std::string& name);
std::string unit_tiles_name(const UnitTiles& t);

// The unit (0..units-1) that draws the quad with top-left pixel (x, y) of a width x height screen.
int unit_of_quad(const UnitTiles& t, int units, int width, int height, int x, int y);

}  // namespace tfu
