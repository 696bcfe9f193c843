// The texel cache stage's half of the recurrences' LINEAR quad path on block-compressed textures
// (software speed only, off with TFU_PLAIN=1 or --plain: cmodel/fast_paths.hpp). The plain twins
// are CacheStage::admit_blocks and CacheStage::read_out_blocks in rtl/cache_stage.cpp, which take
// any footprint tap by tap; these take the 2 x 2 footprints of a LINEAR quad whose taps are all
// inside the level (both with the block coordinates the address generator forms,
// rtl/address_gen_blocks.hpp), four footprints of a level at a time, and must give the same tags,
// memory reads, decoder jobs, statistics and texels. The admission, admit_block_square, is inline
// in rtl/cache_stage.hpp. CompressedUnit.LinearQuadPathEqualsThePlainBlocks
// (testbench/test_compressed_unit.cpp) compares the two paths and the clocked blocks on several
// block formats, both cache organizations and random unit configurations.
#include <cstring>

#include "rtl/cache_stage.hpp"

#include "cmodel/block_formats.hpp"

namespace tfu::rtl {

CacheStage::DecodedLevel& CacheStage::decoded_level(int texture, int level) const {
  DecodedLevel& dl = decoded_levels_[first_readout_[static_cast<size_t>(texture)] + static_cast<size_t>(level)];
  if (dl.texels == nullptr) {
    const TextureDescriptor& d = regs_.textures[static_cast<size_t>(texture)];
    const BlockFormatInfo& b = d.block();
    dl.blocks_across = blocks_across(d.block_format, d.level_width(level));
    const auto blocks = static_cast<size_t>(dl.blocks_across) *
                        static_cast<size_t>(blocks_down(d.block_format, d.level_height(level)));
    dl.texels.reset(new unsigned char[blocks * static_cast<size_t>(b.block_w * b.block_h) * sizeof(Rgba8)]);
    dl.decoded.assign(blocks, 0);
  }
  return dl;
}

// Block (bx, by) of `level`, decoded from the bytes at its address in the descriptor
// (TextureDescriptor::block_address).
void CacheStage::decode_into_level(const TextureDescriptor& d, int level, DecodedLevel& dl, int bx, int by) const {
  const BlockFormatInfo& b = d.block();
  const uint64_t address = d.block_address(level, bx, by);
  std::array<Rgba8, 144> texels;  // up to 12 x 12
  decode_block(d.block_format, memory_.bytes_at(address), d.decode, texels.data());
  const size_t block = static_cast<size_t>(by) * static_cast<size_t>(dl.blocks_across) + static_cast<size_t>(bx);
  const size_t n = static_cast<size_t>(b.block_w * b.block_h);
  std::memcpy(dl.texels.get() + block * n * sizeof(Rgba8), texels.data(), n * sizeof(Rgba8));
  dl.decoded[block] = 1;
}

// read_out_blocks of four 2 x 2 footprints on one level. A footprint's blocks are the 2 x 2
// (column, row) pairs of its block grid at the descriptor's block addresses; each is decoded once
// a run into the level's decoded blocks (decoded_level), and each tap reads its texel there.
void CacheStage::read_block_squares(int texture, int level, const std::array<TapBlocks, 4>& s,
                                    std::array<std::array<Rgba8, 4>, 4>& taps) const {
  const TextureDescriptor& d = regs_.textures[static_cast<size_t>(texture)];
  DecodedLevel& dl = decoded_level(texture, level);
  const int block_w = d.block().block_w;
  const auto block_texels = static_cast<size_t>(block_w * d.block().block_h);
  for (size_t k = 0; k < 4; ++k) {
    const TapGrid& b = s[k].blocks;
    size_t first[4];  // the first texel of the block of the (column i, row j) pair i + 2 j
    for (size_t q = 0; q < 4; ++q) {
      const int bx = b.x[q & 1u], by = b.y[q >> 1];
      const size_t block = static_cast<size_t>(by) * static_cast<size_t>(dl.blocks_across) + static_cast<size_t>(bx);
      if (dl.decoded[block] == 0) [[unlikely]]
        decode_into_level(d, level, dl, bx, by);
      first[q] = block * block_texels;
    }
    for (size_t t = 0; t < 4; ++t)  // tap t: grid cell (t & 1) + 4 (t >> 1)
      std::memcpy(&taps[k][t], dl.texels.get() + (first[t] + texel_in_block(s[k], (t & 1u) + 4 * (t >> 1), block_w)) * sizeof(Rgba8),
                  sizeof(Rgba8));
  }
}

}  // namespace tfu::rtl
