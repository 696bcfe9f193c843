// Port payloads of the texture filter unit's pipeline (rtl/tfu_unit.hpp has the block diagram).
// Field widths are those of the hardware; C++ types are chosen wide enough.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "cmodel/aniso.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/direction_rom.hpp"
#include "cmodel/texture.hpp"

namespace tfu::rtl {

// The descriptor indices a request names and the material stage it belongs to:
//   texture[11:0] (texture descriptor), sampler[7:0] (sampler descriptor), stage[1:0] (statistics)
struct RequestTag {
  uint16_t texture = 0;
  uint8_t sampler = 0;
  uint8_t stage = 0;
};

// The statistics slot of a request (its texture descriptor and material stage): the blocks count
// per slot, and the per-stage and per-texture statistics are sums of slots (rtl/unit_stats.hpp).
inline constexpr size_t kStatStages = 4;  // stage[1:0]
constexpr size_t stat_slot(int texture, int stage) {
  return kStatStages * static_cast<size_t>(texture) + static_cast<size_t>(stage);
}
constexpr size_t stat_slot(const RequestTag& r) { return stat_slot(r.texture, r.stage); }
constexpr size_t stat_slots(size_t textures) { return kStatStages * textures; }

// request_fifo -> lod_unit: one 2x2 quad (quad traces) or one pixel (lod / grad traces).
//   id[31:0], descriptor indices, npix[2:0] (4 or 1), s[4] t[4] FP32, lod FP32 | dsdx dtdx dsdy dtdy FP32
struct QuadReq {
  uint32_t id = 0;  // index of the first pixel in the trace
  RequestTag req;
  int npix = 4;
  std::array<float, 4> s{}, t{};
  float lod = 0, dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0;
};

// lod_unit -> address_gen: one pixel per cycle.  id, descriptor indices, s t FP32, lambda[15:0]
// (Q.8, before bias/clamp), and the anisotropic footprint (cmodel/aniso.hpp AnisoLod): probes[4:0]
// (N, 1..16; 1 for isotropic samplers and lod traces) and the major derivative vector
// major_du[31:0] major_dv[31:0] (Q.16 level-0 texels, sign + 31-bit clamped magnitude), the step
// the probes are spread along (probe i at offset probe_offset_q16(major, N, i))
struct PixelReq {
  uint32_t id = 0;
  RequestTag req;
  float s = 0, t = 0;
  int32_t lambda_q8 = 0;
  int probes = 1;
  int64_t major_du_q16 = 0, major_dv_q16 = 0;
};

// An anisotropic probe's offset on one level (dp::probe_offset_on_level): Q.8 texels of the level,
// inside the address generator.
struct ProbeLevelOffset {
  int64_t du_q8 = 0, dv_q8 = 0;
};

// The taps of one footprint as the address generator sends them, the columns and rows of a grid
// (the cache forms the tap addresses):
//   x[4] {x[13:0]}, y[4] {y[13:0]}  wrapped coordinates inside the level; -1 = outside the texture
//                                   under clamp-to-border (the border word, no cache access)
//   cols[2:0] rows[2:0]             1 (NEAREST), 2 (LINEAR), T <= 4 (CUBIC), 4 (edge cross)
//   used[15:0]                      grid cells (bit 4 j + i = tap (x[i], y[j])) that read the cache
struct TapGrid {
  std::array<int16_t, 4> x, y;  // levels are at most 16384 texels wide: 15 bits, -1 with border
  int cols, rows;
  uint16_t used;
};

// The same footprint in blocks, on a block-compressed level (address_gen forms it beside the
// texel grid: block_grid, rtl/address_gen_blocks.hpp; not written on other textures):
//   blocks            the tap grid in blocks: column i is the block column x[i] / block_w, row j
//                     the block row y[j] / block_h (below 2^14 / 4: at most 12 bits; -1, a border
//                     column or row, stays -1), cols, rows and used those of the texel grid
//   u[4] v[4] {[3:0]} the texel column x[i] mod block_w and row y[j] mod block_h inside the block
// Tap (x[i], y[j]) is texel v[j] block_w + u[i] (row-major) of block (blocks.x[i], blocks.y[j]).
struct TapBlocks {
  TapGrid blocks;
  std::array<uint8_t, 4> u, v;
};

// Grid cells of a full cols x rows square (LINEAR, CUBIC, NEAREST): kSquareCells[cols][rows].
inline constexpr auto kSquareCells = [] {
  std::array<std::array<uint16_t, 5>, 5> t{};
  for (uint32_t c = 0; c <= 4; ++c)
    for (uint32_t r = 0; r <= 4; ++r)
      for (uint32_t j = 0; j < r; ++j) t[c][r] = static_cast<uint16_t>(t[c][r] | (((1u << c) - 1u) << (4 * j)));
  return t;
}();
constexpr uint16_t square_cells(int cols, int rows) {
  return kSquareCells[static_cast<size_t>(cols)][static_cast<size_t>(rows)];
}

// The edge cross on the 4x4 grid of columns and rows -1..2 (lee_jen::grid_col, grid_row): texel
// C(k+1) of Lee & Jen Eq. 4 is cell kCrossCell[k] (the corners are not used); the C order is
// row-major over the grid.
inline constexpr std::array<uint8_t, lee_jen::kTexels> kCrossCell = [] {
  static_assert(lee_jen::kGridSide == 4);
  std::array<uint8_t, lee_jen::kTexels> c{};
  for (int n = 1; n <= lee_jen::kTexels; ++n)
    c[static_cast<size_t>(n - 1)] = static_cast<uint8_t>(4 * lee_jen::grid_row(n) + lee_jen::grid_col(n));
  return c;
}();
// Grid cells of the cross texels in a shape mask (bit k = C(k+1)): two 64-entry tables.
inline constexpr auto kCrossCellsOf6 = [] {
  std::array<std::array<uint16_t, 64>, 2> t{};
  for (size_t half = 0; half < 2; ++half)
    for (uint32_t m = 0; m < 64; ++m)
      for (size_t b = 0; b < 6; ++b)
        if ((m >> b) & 1u) t[half][m] = static_cast<uint16_t>(t[half][m] | (1u << kCrossCell[6 * half + b]));
  return t;
}();
constexpr uint16_t cross_cells(lee_jen::TexelMask shape) {
  return static_cast<uint16_t>(kCrossCellsOf6[0][shape & 63u] | kCrossCellsOf6[1][(shape >> 6) & 63u]);
}

// What travels with one level footprint from address_gen to the filter's output, unchanged except
// for the shape (set by kernel_select, widened by the cache-aware probe):
//   id[31:0], descriptor indices, base[1:0] (the sampler's base filter: routes the footprint to
//   the filter or the edge datapath), format[1:0] (the texture's texel format, for unpack),
//   fu[7:0] fv[7:0] (fractions in the level), blend[8:0] (weight of level1), blends (the pixel
//   blends two levels: *_MIPMAP_LINEAR), is_level1 (this footprint is the pixel's level1, its
//   second; else level0), shape[11:0] (edge cross: texels the kernel may use), probes[4:0]
//   probe[3:0] (an anisotropic pixel's probe count N and this
//   footprint's probe i - 1: the datapath accumulates the probes and answers at the last one)
// (address_gen::footprint writes every field into the reused output register: keep it in step.)
struct LevelTag {
  uint32_t id = 0;
  RequestTag req;
  BaseFilter base = BaseFilter::Linear;
  TexelFormat format = TexelFormat::RGBA8;
  uint32_t fu = 0, fv = 0;
  int blend = 0;
  bool blends = false, is_level1 = false;
  lee_jen::TexelMask shape = lee_jen::kAllTexels;
  uint8_t probes = 1, probe = 0;
  bool last_level() const { return !blends || is_level1; }  // a probe's result is complete after this footprint
  bool emits() const { return last_level() && probe + 1 == probes; }  // the datapath outputs a pixel
  bool holds() const { return blends && !is_level1; }                 // level0 of a blending pair: kept for the blend
};

// Kernel shapes of one pixel's edge footprints, [2 probe + k] for probe 0..N-1 and level0 / level1
// (k = 0 / 1): what the golden model takes for cache-aware shapes (Sampler::sample_edge_masks).
using ProbeShapes = std::array<lee_jen::TexelMask, 2 * kMaxAniso>;

// address_gen -> kernel_select -> texel_cache: one level footprint per cycle.
//   tag, level[3:0], grid (its `used` cells: those inside the texture; the edge shape narrows
//   them at the cache), cross (the edge cross: 12 taps in C order, else cols x rows row-major),
//   optional[11:0] (cache-aware: arms to add when their lines are resident), and on a
//   block-compressed texture blocks (the grid in blocks and each tap's texel in its block: what
//   the cache stage's tags, decoders and read-out take on such a texture)
struct FootprintReq {
  LevelTag tag;
  int level = 0;
  bool cross = false;
  TapGrid grid;
  TapBlocks blocks;
  lee_jen::TexelMask optional = 0;
  int ntaps() const { return cross ? lee_jen::kTexels : grid.cols * grid.rows; }
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
