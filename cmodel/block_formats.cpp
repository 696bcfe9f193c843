#include "cmodel/block_formats.hpp"

#include <memory>

#include <fmt/format.h>

#include "cmodel/astc_decode.hpp"
#include "cmodel/etc2_decode.hpp"

namespace tfu {

namespace {

BcFormat bc_format(BlockFormat f) {
  switch (f) {
    case BlockFormat::BC1: return BcFormat::BC1_RGB;
    case BlockFormat::BC1A: return BcFormat::BC1_RGBA;
    case BlockFormat::BC2: return BcFormat::BC2;
    case BlockFormat::BC3: return BcFormat::BC3;
    case BlockFormat::BC4: return BcFormat::BC4_UNORM;
    case BlockFormat::BC4S: return BcFormat::BC4_SNORM;
    case BlockFormat::BC5: return BcFormat::BC5_UNORM;
    case BlockFormat::BC5S: return BcFormat::BC5_SNORM;
    default: return BcFormat::BC7;
  }
}

void decode_etc(BlockFormat f, const uint8_t* block, Rgba8* out) {
  switch (f) {
    case BlockFormat::ETC2: return decode_etc2_rgb_block(block, out);
    case BlockFormat::ETC2A1: return decode_etc2_rgb8a1_block(block, out);
    case BlockFormat::ETC2A: return decode_etc2_rgba8_block(block, out);
    default: break;
  }
  const bool is_signed = block_format_info(f).is_signed;
  const int channels = block_format_info(f).channels;
  for (int i = 0; i < kEtcBlockTexels; ++i) out[i] = Rgba8{0, 0, 0, static_cast<uint8_t>(is_signed ? 127 : 255)};
  for (int c = 0; c < channels; ++c) {  // RG11: two R11 blocks, red then green (KDFS "Format RG11 EAC")
    const uint8_t* half = block + 8 * c;
    uint8_t v8[kEtcBlockTexels];
    if (is_signed) {
      int16_t v[kEtcBlockTexels];
      decode_eac_r11_signed_block(half, v);
      for (int i = 0; i < kEtcBlockTexels; ++i) v8[i] = static_cast<uint8_t>(eac11_signed_to_snorm8(v[i]));
    } else {
      uint16_t v[kEtcBlockTexels];
      decode_eac_r11_block(half, v);
      for (int i = 0; i < kEtcBlockTexels; ++i) v8[i] = eac11_to_unorm8(v[i]);
    }
    for (int i = 0; i < kEtcBlockTexels; ++i) (c == 0 ? out[i].r : out[i].g) = v8[i];
  }
}

}  // namespace

BlockFormat block_format_from_name(const std::string& name) { return kBlockFormatNames.from_name(name); }
const char* block_format_name(BlockFormat f) { return kBlockFormatNames.name(f); }

size_t block_level_bytes(BlockFormat f, int width, int height) {
  return static_cast<size_t>(blocks_across(f, width)) * static_cast<size_t>(blocks_down(f, height)) *
         static_cast<size_t>(block_format_info(f).block_bytes);
}

void decode_block(BlockFormat f, const uint8_t* block, const BlockDecodeRules& rules, Rgba8* out) {
  const BlockFormatInfo& info = block_format_info(f);
  switch (info.family) {
    case BlockFamily::BC: {
      const BcBlockTexels t = decode_bc_block(bc_format(f), block, rules.bc);
      for (int i = 0; i < kBcBlockTexels; ++i) out[i] = t[static_cast<size_t>(i)];
      return;
    }
    case BlockFamily::ETC: return decode_etc(f, block, out);
    case BlockFamily::ASTC: return decode_astc_block(block, info.block_w, info.block_h, rules.srgb, out);
  }
}

Image decode_block_level(BlockFormat f, int width, int height, std::span<const uint8_t> blocks, const BlockDecodeRules& rules,
                         const std::string& what) {
  const BlockFormatInfo& info = block_format_info(f);
  if (width < 1 || height < 1 || width > kMaxTextureSize || height > kMaxTextureSize)
    throw InputError(fmt::format("{}: size {}x{} outside 1..{} per side", what, width, height, kMaxTextureSize));
  const size_t want = block_level_bytes(f, width, height);
  if (blocks.size() != want)
    throw InputError(fmt::format("{}: {} bytes where a {}x{} {} level holds {}", what, blocks.size(), width, height, info.name, want));
  Image img(width, height);
  std::vector<Rgba8> texels(static_cast<size_t>(info.block_w * info.block_h));
  const int across = blocks_across(f, width), down = blocks_down(f, height);
  for (int by = 0; by < down; ++by)
    for (int bx = 0; bx < across; ++bx) {
      const size_t offset = (static_cast<size_t>(by) * static_cast<size_t>(across) + static_cast<size_t>(bx)) *
                            static_cast<size_t>(info.block_bytes);
      decode_block(f, blocks.data() + offset, rules, texels.data());
      for (int y = 0; y < info.block_h && by * info.block_h + y < height; ++y)
        for (int x = 0; x < info.block_w && bx * info.block_w + x < width; ++x)
          img.at(bx * info.block_w + x, by * info.block_h + y) = texels[static_cast<size_t>(y * info.block_w + x)];
    }
  return img;
}

Texture texture_from_block_image(const BlockImage& image, const BlockDecodeRules& rules, const std::string& what,
                                 MemoryLayout layout, int tile_bytes) {
  if (!unit_filterable(image.format))
    throw InputError(fmt::format("{}: {} is a signed format; the unit filters unsigned texels only", what,
                                 block_format_name(image.format)));
  if (image.levels.empty()) throw InputError(fmt::format("{}: no levels", what));
  auto c = std::make_shared<CompressedLevels>();
  c->image = image;
  c->rules = rules;
  c->rules.srgb = image.srgb;
  Texture tex;
  tex.format = TexelFormat::RGBA8;
  tex.layout = layout;
  tex.tile_bytes = tile_bytes;
  for (size_t l = 0; l < image.levels.size(); ++l) {
    const BlockLevel& bl = image.levels[l];
    tex.levels.push_back(decode_block_level(image.format, bl.width, bl.height, bl.blocks, c->rules,
                                            fmt::format("{} level {}", what, l)));
  }
  tex.validate(what);
  tex.compressed = std::move(c);
  return tex;
}

}  // namespace tfu
