// address_gen on a block-compressed texture: the block coordinates of a footprint (which block of
// the level each tap column and row falls in, and each tap's texel inside its block), formed once
// per footprint for the texel cache's tags, its decoders and its read-out. Used by the timing
// recurrences' LINEAR quad path (rtl/unit_recurrence_linear_quads.cpp), whose cache side is
// rtl/cache_stage_block_squares.cpp; the plain blocks (both engines) still form them tap by tap in
// the cache stage (TexelCache::access_blocks, CacheStage::admit_blocks, read_out_blocks:
// docs/compressed.md, "Where block addresses are computed").
#pragma once

#include <array>
#include <cstdint>

#include "cmodel/descriptors.hpp"
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

// A 2 x 2 footprint whose taps are all inside a block-compressed level, in blocks: `blocks` is its
// tap grid with each column x[i] / block_w and each row y[j] / block_h, `texel[t]` the index inside
// its block (v block_w + u) of tap t, read_out's order: tap t reads block column t & 1, block row
// t >> 1.
struct BlockSquare {
  TapGrid blocks;
  std::array<uint8_t, 4> texel;
};

// The BlockSquare of the 2 x 2 grid `g` of texture `tex` (its taps all inside the level).
[[gnu::always_inline]] inline void block_square(const TextureDescriptor& tex, const TapGrid& g, BlockSquare& s) {
  const BlockFormatInfo& b = tex.block();
  const uint32_t mw = block_reciprocal(b.block_w), mh = block_reciprocal(b.block_h);
  s.blocks = g;
  int in_x[2], in_y[2];
  for (size_t i = 0; i < 2; ++i) {
    const int bx = block_quotient(g.x[i], mw), by = block_quotient(g.y[i], mh);
    s.blocks.x[i] = static_cast<int16_t>(bx);
    s.blocks.y[i] = static_cast<int16_t>(by);
    in_x[i] = g.x[i] - bx * b.block_w;
    in_y[i] = g.y[i] - by * b.block_h;
  }
  for (size_t t = 0; t < 4; ++t)  // read_out's order: tap t = (column t & 1, row t >> 1)
    s.texel[t] = static_cast<uint8_t>(in_y[t >> 1] * b.block_w + in_x[t & 1u]);
}

}  // namespace tfu::rtl
