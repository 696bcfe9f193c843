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
  for (int l = 0; l < d.levels; ++l) {
    Image img(d.level_width(l), d.level_height(l));
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) img.at(x, y) = read_texel(mem, d, l, x, y);
    tex.levels.push_back(std::move(img));
  }
  return tex;
}

}  // namespace tfu
