#include "cmodel/texture_memory.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {

uint64_t TextureMemory::allocate(uint64_t bytes, uint64_t align) {
  const uint64_t at = (end() + align - 1) / align * align;
  const uint64_t size = at + bytes - kFirstAddress;
  if (bytes > kMaxBytes || size > kMaxBytes)
    throw InputError(fmt::format("texel memory: {} more bytes exceed the frame's {} GiB", bytes, kMaxBytes >> 30));
  bytes_.resize(size);
  return at;
}

void TextureMemory::write_word(uint64_t address, TexelFormat f, Rgba8 w) {
  uint8_t* p = bytes_.data() + (address - kFirstAddress);
  if (f == TexelFormat::L8) {
    p[0] = w.r;
    return;
  }
  p[0] = w.r;
  p[1] = w.g;
  p[2] = w.b;
  p[3] = w.a;
}

void TextureMemory::write_bytes(uint64_t address, const uint8_t* bytes, size_t n) {
  std::memcpy(bytes_.data() + (address - kFirstAddress), bytes, n);
}

TextureDescriptor place_texture(TextureMemory& mem, const Texture& tex, uint64_t align) {
  tex.validate("texture");
  align = std::max(align, kLevelAlign);
  TextureDescriptor d;
  d.format = tex.format;
  d.width = tex.width();
  d.height = tex.height();
  d.levels = static_cast<int>(tex.levels.size());
  d.layout = tex.layout;
  d.tile_log2 = tile_side_log2(tex.tile_bytes, tex.format);
  if (tex.compressed) {  // block rows, each starting on `align` (lines never straddle two block rows)
    const BlockImage& image = tex.compressed->image;
    d.compressed = true;
    d.block_format = image.format;
    d.decode = tex.compressed->rules;
    const auto bb = static_cast<uint64_t>(d.block().block_bytes);
    for (int l = 0; l < d.levels; ++l) {
      const BlockLevel& bl = image.levels[static_cast<size_t>(l)];
      LevelDescriptor& ld = d.level[static_cast<size_t>(l)];
      const int across = blocks_across(image.format, bl.width), down = blocks_down(image.format, bl.height);
      const uint64_t row_bytes = static_cast<uint64_t>(across) * bb;
      ld.row_pitch = static_cast<uint32_t>((row_bytes + align - 1) / align * align);
      ld.address = mem.allocate(d.level_bytes(l), align);
      for (int by = 0; by < down; ++by)
        mem.write_bytes(ld.address + static_cast<uint64_t>(by) * ld.row_pitch,
                        bl.blocks.data() + static_cast<size_t>(by) * row_bytes, static_cast<size_t>(row_bytes));
    }
    d.validate("placed texture");
    return d;
  }
  const auto bpt = static_cast<uint64_t>(bytes_per_texel(tex.format));
  for (int l = 0; l < d.levels; ++l) {
    const Image& img = tex.levels[static_cast<size_t>(l)];
    LevelDescriptor& ld = d.level[static_cast<size_t>(l)];
    if (d.layout == MemoryLayout::Linear) {
      ld.row_pitch = static_cast<uint32_t>((static_cast<uint64_t>(img.width) * bpt + align - 1) / align * align);
    } else {
      const uint64_t tiles_per_row = static_cast<uint64_t>((img.width + d.tile_side() - 1) >> d.tile_log2);
      ld.row_pitch = static_cast<uint32_t>((tiles_per_row * static_cast<uint64_t>(d.tile_bytes()) + align - 1) / align * align);
    }
    ld.address = mem.allocate(d.level_bytes(l), align);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) mem.write_word(d.texel_address(l, x, y), d.format, img.at(x, y));
  }
  d.validate("placed texture");
  return d;
}

Texture read_texture(const TextureMemory& mem, const TextureDescriptor& d) {
  Texture tex;
  tex.format = d.format;
  tex.layout = d.layout;
  tex.tile_bytes = d.layout == MemoryLayout::Tiled ? d.tile_bytes() : 64;
  if (d.compressed) {  // the blocks back, decoded as the unit decodes them
    BlockImage image;
    image.format = d.block_format;
    image.srgb = d.decode.srgb;
    const auto bb = static_cast<size_t>(d.block().block_bytes);
    for (int l = 0; l < d.levels; ++l) {
      BlockLevel bl;
      bl.width = d.level_width(l);
      bl.height = d.level_height(l);
      const auto across = static_cast<size_t>(blocks_across(d.block_format, bl.width));
      for (int by = 0; by < blocks_down(d.block_format, bl.height); ++by) {
        const uint8_t* row = mem.bytes_at(d.level[static_cast<size_t>(l)].address +
                                          static_cast<uint64_t>(by) * d.level[static_cast<size_t>(l)].row_pitch);
        bl.blocks.insert(bl.blocks.end(), row, row + across * bb);
      }
      image.levels.push_back(std::move(bl));
    }
    Texture t = texture_from_block_image(image, d.decode, "texture read back", d.layout, tex.tile_bytes);
    return t;
  }
  for (int l = 0; l < d.levels; ++l) {
    Image img(d.level_width(l), d.level_height(l));
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) img.at(x, y) = read_texel(mem, d, l, x, y);
    tex.levels.push_back(std::move(img));
  }
  return tex;
}

}  // namespace tfu
