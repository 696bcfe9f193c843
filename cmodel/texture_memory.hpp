// The texel memory: one byte-addressed image holding every texture of a frame at its descriptor's
// addresses (docs/descriptors.md), as the driver uploads them and as the cycle model's texel cache
// fetches them, line by line, by address.
//
//   allocate     next free address aligned to 256 bytes (addresses start at 0x1000; 0 is never a texture)
//   place        writes a texture's levels in its layout (linear rows or tiles of one cache line) and
//                returns its descriptor; every level and every linear row starts on 256 bytes
//   read_texel   the texel word at (level, x, y) through the descriptor: RGBA8 / VS16X2 4 bytes
//                (R, G, B, A in address order), L8 1 byte fetched as (L, L, L, 255) as GL_LUMINANCE
//   read_texture the texture back from memory (decode; equals what was placed, tested)
//
// Compressed textures (Texture::compressed) are stored as their blocks, whatever the layout field:
// a level is its block rows, blocks row-major within a row (the order every container and
// decoder uses), each block row starting on `align` bytes (the cache line or 256), so that a
// cache line holds line_bytes / block_bytes horizontally adjacent blocks of one block row (4 or 8
// blocks at 64 bytes: 16 x 4 or 32 x 4 texels of a 4x4 format). Why not tiled into squares like
// the texel layout: a block already is a 2D tile (4x4 to 12x12 texels, most of a bilinear
// footprint), ASTC block sides of 5, 6, 10 and 12 texels do not tile a power-of-two line into a
// square, and a row of blocks is what the driver uploads unchanged (no swizzle at load).
// LevelReadout reads uncompressed levels only; the cycle model decodes compressed levels' blocks
// (rtl/cache_stage.hpp).
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "cmodel/descriptors.hpp"
#include "cmodel/texture.hpp"

namespace tfu {

class TextureMemory {
 public:
  static constexpr uint64_t kFirstAddress = 0x1000;
  static constexpr uint64_t kMaxBytes = uint64_t{1} << 32;  // 4 GiB of texels per frame

  // Reserves `bytes` at the next multiple of `align` (a power of two >= kLevelAlign); throws
  // InputError beyond kMaxBytes.
  uint64_t allocate(uint64_t bytes, uint64_t align = kLevelAlign);
  uint64_t end() const { return kFirstAddress + bytes_.size(); }  // first unallocated address
  uint64_t bytes_used() const { return bytes_.size(); }

  Rgba8 read_word(uint64_t address, TexelFormat f) const {
    const uint8_t* p = bytes_.data() + (address - kFirstAddress);
    if (f == TexelFormat::L8) return {p[0], p[0], p[0], 255};
    return {p[0], p[1], p[2], p[3]};
  }
  void write_word(uint64_t address, TexelFormat f, Rgba8 w);
  void write_bytes(uint64_t address, const uint8_t* bytes, size_t n);
  // The bytes [address, address + n) (a cache line fill).
  const uint8_t* bytes_at(uint64_t address) const { return bytes_.data() + (address - kFirstAddress); }

 private:
  std::vector<uint8_t> bytes_;
};

// Writes `tex` (its format, layout and tile size) at fresh addresses and returns its descriptor.
// Levels and linear rows start on multiples of `align` (256, or the cache line when it is longer,
// so that lines never straddle two rows or levels).
TextureDescriptor place_texture(TextureMemory& mem, const Texture& tex, uint64_t align = kLevelAlign);
inline Rgba8 read_texel(const TextureMemory& mem, const TextureDescriptor& d, int level, int x, int y) {
  return mem.read_word(d.texel_address(level, x, y), d.format);
}

// One level of a texture as the texel read-out addresses it: the same address arithmetic as
// TextureDescriptor::texel_address with the level's registers decoded once (a footprint's taps
// share them). The address is separable, offset(x, y) = column(x) + row(y), because a tiled
// address puts the tile column and the column inside the tile in other bits than the row parts:
//   column(x) = (x >> k) << (2k + b) | (x & m) << b      row(y) = (y >> k) pitch + (y & m) << (k + b)
// (b = log2 bytes per texel, k = log2 tile side, m = 2^k - 1); a linear level is the case k = 0
// (column x << b, row y pitch), so one formula serves both layouts without a branch.
class LevelReadout {
 public:
  LevelReadout() = default;
  LevelReadout(const TextureMemory& mem, const TextureDescriptor& d, int level)
      : base_(mem.bytes_at(d.level[static_cast<size_t>(level)].address)),
        pitch_(d.level[static_cast<size_t>(level)].row_pitch),
        l8_(d.format == TexelFormat::L8),
        b_(l8_ ? 0 : 2),
        k_(d.layout == MemoryLayout::Tiled ? d.tile_log2 : 0),
        m_((1 << k_) - 1) {}
  size_t column(int x) const {
    return (static_cast<size_t>(x >> k_) << (2 * k_ + b_)) | (static_cast<size_t>(x & m_) << b_);
  }
  size_t row(int y) const { return static_cast<size_t>(y >> k_) * pitch_ + (static_cast<size_t>(y & m_) << (k_ + b_)); }
  Rgba8 at(size_t offset) const {
    const uint8_t* p = base_ + offset;
    if (l8_) return {p[0], p[0], p[0], 255};
    Rgba8 w;
    std::memcpy(&w, p, sizeof w);  // R, G, B, A in address order
    return w;
  }
  Rgba8 operator()(int x, int y) const { return at(column(x) + row(y)); }

 private:
  const uint8_t* base_ = nullptr;
  size_t pitch_ = 0;
  bool l8_ = false;
  int b_ = 2, k_ = 0, m_ = 0;
};

// Decodes the levels of `d` from memory (format, layout and tile size from the descriptor).
Texture read_texture(const TextureMemory& mem, const TextureDescriptor& d);

}  // namespace tfu
