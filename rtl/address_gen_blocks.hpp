// address_gen on a block-compressed texture: the block coordinates of a footprint (which block of
// the level each tap column and row falls in, and each tap's texel inside its block), formed once
// per footprint beside its texel grid (TapBlocks, rtl/unit_ports.hpp) by block_grid, the one
// function that forms them: AddressGen::footprint calls it for every footprint of both engines'
// plain blocks (every filter mode, the edge cross, anisotropic probes), the timing recurrences'
// LINEAR quad path (rtl/unit_recurrence_linear_quads.cpp) for its 2 x 2 footprints. The texel cache
// stage takes them as formed: its tags on a level of compressed lines (TexelCache::access,
// line_of, resident take block coordinates there), its decoder jobs' distinct blocks and its
// read-out's block addresses (TextureDescriptor::block_address) and texels in the block
// (CacheStage::admit_blocks, read_out_blocks; the quad path's admit_block_square,
// read_block_squares). docs/compressed.md, "Where block addresses are computed".
#pragma once

#include <array>
#include <cstdint>

#include "cmodel/block_formats.hpp"
#include "rtl/unit_ports.hpp"

namespace tfu::rtl {

// floor(x / d) for a texel coordinate 0 <= x < 2^14 (kMaxTextureSize) and a block side 1 <= d <= 16,
// by multiplication: (x m) >> 18 with m = block_reciprocal(d) = ceil(2^18 / d) (a 14 x 18-bit
// product; m is a register of the texture's block format). With m d = 2^18 + e, 0 <= e < d:
// x m / 2^18 = x / d + x e / (d 2^18), and x e < 2^14 d <= 2^18 keeps the excess below 1 / d, so
// the floor is x / d's (CompressedUnit.BlockQuotientByMultiplicationIsExact: every x and d).
constexpr uint32_t block_reciprocal(int d) {
  return ((uint32_t{1} << 18) + static_cast<uint32_t>(d) - 1) / static_cast<uint32_t>(d);
}
constexpr int block_quotient(int x, uint32_t m) { return static_cast<int>((static_cast<uint32_t>(x) * m) >> 18); }
// The reciprocals of the block sides 0..16 (0 unused), a table indexed by the side: the register
// value the descriptor's block format selects.
inline constexpr auto kBlockReciprocals = [] {
  std::array<uint32_t, 17> m{};
  for (int d = 1; d <= 16; ++d) m[static_cast<size_t>(d)] = block_reciprocal(d);
  return m;
}();

// The TapBlocks of the tap grid `g` on a level of blocks `b` (its columns [0, cols) and rows
// [0, rows) are formed; a border column or row, -1, stays -1 with texel 0). Per column: the block
// column q = (x m_w) >> 18 and the texel column u = x - q block_w (a 12 x 4-bit product and a
// subtraction); per row the same with block_h.
[[gnu::always_inline]] inline void block_grid(const BlockFormatInfo& b, const TapGrid& g, TapBlocks& out) {
  const uint32_t mw = kBlockReciprocals[static_cast<size_t>(b.block_w)];
  const uint32_t mh = kBlockReciprocals[static_cast<size_t>(b.block_h)];
  out.blocks = g;
  const auto split = [](int x, uint32_t m, int side, int16_t& block, uint8_t& in_block) {
    const int q = block_quotient(x < 0 ? 0 : x, m);
    block = static_cast<int16_t>(x < 0 ? -1 : q);
    in_block = static_cast<uint8_t>(x < 0 ? 0 : x - q * side);
  };
  for (size_t i = 0; i < static_cast<size_t>(g.cols); ++i) split(g.x[i], mw, b.block_w, out.blocks.x[i], out.u[i]);
  for (size_t j = 0; j < static_cast<size_t>(g.rows); ++j) split(g.y[j], mh, b.block_h, out.blocks.y[j], out.v[j]);
}

// The texel of grid cell `cell` (4 j + i) inside its block: v[j] block_w + u[i], row-major (what
// decode_block writes).
inline size_t texel_in_block(const TapBlocks& t, size_t cell, int block_w) {
  return static_cast<size_t>(t.v[cell >> 2] * block_w + t.u[cell & 3u]);
}

}  // namespace tfu::rtl
