// The texel cache stage's half of the recurrences' LINEAR quad path on block-compressed textures
// (software speed only, off with TFU_PLAIN=1 or --plain: cmodel/fast_paths.hpp). The plain twins
// are CacheStage::admit_blocks (through TexelCache::access_blocks) and CacheStage::read_out_blocks
// in rtl/cache_stage.cpp, which take any footprint tap by tap; these take the 2 x 2 footprints of a
// LINEAR quad whose taps are all inside the level, with the block coordinates formed once per
// footprint by the quad path (rtl/unit_recurrence_linear_quads.cpp), and must give the same tags,
// memory reads, decoder jobs, statistics and texels. CompressedUnit.LinearQuadPathEqualsThePlainBlocks
// (testbench/test_compressed_unit.cpp) compares the two paths and the clocked blocks on several
// block formats, both cache organizations and random unit configurations.
#include "rtl/cache_stage.hpp"

#include "cmodel/block_formats.hpp"

namespace tfu::rtl {

// admit_blocks of a 2 x 2 footprint. Blocks in the cache: the tags of its blocks' lines
// (access_blocks forms the same block grid), then one decoder job of its four taps and of its
// distinct blocks, the product of its distinct block columns and rows (admit_blocks counts the
// distinct (column, row) pairs of its taps). Decoded on fill: admit_blocks itself (its tags take
// the texel grid, and only its misses do more).
uint64_t CacheStage::admit_block_square(int texture, int stage, int level, const TapGrid& texels, const BlockSquare& s,
                                        uint64_t now, int& bank_cycles) {
  FootprintResult r;
  if (cache_.config().holds == CacheHolds::Decoded)
    return admit_blocks(texture, stage, level, texels, now, bank_cycles, r);
  r = cache_.access_block_grid(texture, level, s.blocks);
  const uint64_t in = lines_in(texture, stage, level, r, now, bank_cycles);
  const int blocks = (s.blocks.x[0] != s.blocks.x[1] ? 2 : 1) * (s.blocks.y[0] != s.blocks.y[1] ? 2 : 1);
  return decode(in, 4, blocks, stat_slot(texture, stage));
}

// read_out_blocks of four 2 x 2 footprints on one level. A footprint's blocks are the 2 x 2
// (column, row) pairs of its block grid at the descriptor's block addresses (texel_address of any
// of their texels); each distinct block of the quad's four footprints is looked up in the memo of
// decoded blocks once and held (decoded_block keeps every held block's texels: a block whose memo
// entry another held block occupies decodes into scratch), and each tap reads its texel.
void CacheStage::read_block_squares(int texture, int level, const std::array<BlockSquare, 4>& s,
                                    std::array<std::array<Rgba8, 4>, 4>& taps) const {
  const TextureDescriptor& d = regs_.textures[static_cast<size_t>(texture)];
  const LevelDescriptor& ld = d.level[static_cast<size_t>(level)];
  const auto block_bytes = static_cast<uint64_t>(d.block().block_bytes);
  std::array<HeldBlock, kHeldBlocks> held;
  size_t n = 0;
  for (size_t k = 0; k < 4; ++k) {
    const TapGrid& b = s[k].blocks;
    const Rgba8* texels[4];  // of the (column i, row j) pair i + 2 j
    for (size_t q = 0; q < 4; ++q) {
      const size_t i = q & 1u, j = q >> 1;
      if ((i == 1 && b.x[1] == b.x[0]) || (j == 1 && b.y[1] == b.y[0])) {  // the same block as pair q - 1 or q - 2
        texels[q] = texels[i == 1 && b.x[1] == b.x[0] ? q - 1 : q - 2];
        continue;
      }
      const uint64_t address =
          ld.address + static_cast<uint64_t>(b.y[j]) * ld.row_pitch + static_cast<uint64_t>(b.x[i]) * block_bytes;
      size_t m = 0;
      while (m < n && held[m].address != address) ++m;
      if (m == n) {
        held[n] = {address, decoded_block(d, address, held.data(), n, scratch_[n].data())};
        ++n;
      }
      texels[q] = held[m].texels;
    }
    for (size_t t = 0; t < 4; ++t) taps[k][t] = texels[t][s[k].texel[t]];
  }
}

}  // namespace tfu::rtl
