// Textures as the texture filter unit sees them: texel formats, MIP level chains, wrap modes.
//
// Texel formats (what a texel word in memory holds; see docs/sampler.md, "Textures"):
//   RGBA8  4 x unorm8 (1.0 <-> 255), 4 bytes/texel
//   L8     1 x unorm8 luminance, 1 byte/texel; fetched as (L, L, L, 255) like GL_LUMINANCE
//   VS16X2 two Strzodka virtual signed 16-bit numbers in one RGBA8 word (4 bytes/texel):
//          channel 0 = psi(R, G), channel 1 = psi(B, A), psi(h, l) = (256 (h - 128) + l) / 32640
//          (cmodel/signed_formats.hpp). The unit filters the 16-bit numerators, never the bytes.
//   SRGBA8 4 x 8 bits, R, G, B sRGB-encoded, A linear (GL_SRGB8_ALPHA8), 4 bytes/texel: the unit
//          decodes R, G, B to linear unorm12 (0..4095) before filtering and encodes the filtered
//          linear value back to 8-bit sRGB at its output (cmodel/srgb.hpp, docs/srgb.md)
// Every level is stored as RGBA8 words (L8 replicated) so that one fetch path serves all formats;
// `format` says how many bytes a texel costs in memory and how a word decodes into channels.
//
// Size rule (GL): level 0 is W x H with 1 <= W, H <= kMaxTextureSize; level n+1 is
// max(1, floor(W_n / 2)) x max(1, floor(H_n / 2)); the chain ends at 1 x 1 (1 + floor(log2(max(W, H)))
// levels). Non-power-of-two sizes follow the same floor rule.
//
// Coordinates: texel (i, j) has its centre at s = (i + 0.5) / W, t = (j + 0.5) / H; row j = 0 is
// the top row of the image file.
#pragma once

#include <array>
#include <cstdint>
#include <climits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cmodel/enum_names.hpp"
#include "cmodel/memory_budget.hpp"
#include "cmodel/srgb.hpp"

namespace tfu {

inline constexpr int kMaxTextureSize = 16384;  // per side; 2^14, so texel coordinates fit 15 bits

struct Rgba8 {
  uint8_t r = 0, g = 0, b = 0, a = 0;
  friend constexpr bool operator==(const Rgba8&, const Rgba8&) = default;
};
static_assert(sizeof(Rgba8) == 4, "a texel word is 4 bytes: R, G, B, A in address order");

enum class TexelFormat { RGBA8, L8, VS16X2, SRGBA8 };
inline constexpr EnumNames<TexelFormat, 4> kTexelFormatNames{"texel format",
                                                             {{{TexelFormat::RGBA8, "rgba8"},
                                                               {TexelFormat::L8, "l8"},
                                                               {TexelFormat::VS16X2, "vs16x2"},
                                                               {TexelFormat::SRGBA8, "srgba8"}}}};
TexelFormat texel_format_from_name(const std::string& name);  // kTexelFormatNames
const char* texel_format_name(TexelFormat f);
constexpr int bytes_per_texel(TexelFormat f) { return f == TexelFormat::L8 ? 1 : 4; }
// Formats whose datapath channels are the texel bytes themselves (0..255): the 8-bit fast paths'.
constexpr bool byte_channels(TexelFormat f) { return f == TexelFormat::RGBA8 || f == TexelFormat::L8; }

// One image level: row-major RGBA8 words, row 0 on top.
struct Image {
  int width = 0, height = 0;
  std::vector<Rgba8> texels;

  Image() = default;
  Image(int w, int h, Rgba8 fill = {});
  Rgba8& at(int x, int y) { return texels[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)]; }
  const Rgba8& at(int x, int y) const {
    return texels[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
  }
  bool empty() const { return texels.empty(); }
};

// Four channels as the filter datapath holds them: RGBA8/L8 -> 0..255 each;
// VS16X2 -> c[0], c[1] the signed 16-bit numerators, c[2] = c[3] = 0;
// SRGBA8 -> c[0..2] linear unorm12 0..4095 (the decode ROM), c[3] the alpha byte 0..255.
using Texel4 = std::array<int32_t, 4>;
// Channel range of a format: [lo, hi] (0..255, or -32640..32640 for VS16X2: exactly -1..+1, or
// 0..4095 for SRGBA8's colour channels; its alpha is clamped to 0..255 by encode_texel).
constexpr std::pair<int32_t, int32_t> channel_range(TexelFormat f) {
  if (f == TexelFormat::VS16X2) return {-32640, 32640};
  if (f == TexelFormat::SRGBA8) return {0, srgb::kLinearMax};
  return {0, 255};
}
// Strzodka psi numerator of the byte pair (h, l): 256 (h - 128) + l.
constexpr int32_t vs16_numerator(uint8_t h, uint8_t l) { return 256 * (int32_t{h} - 128) + l; }
constexpr Texel4 decode_texel(Rgba8 w, TexelFormat f) {
  if (f == TexelFormat::VS16X2) return {vs16_numerator(w.r, w.g), vs16_numerator(w.b, w.a), 0, 0};
  if (f == TexelFormat::SRGBA8) return {srgb::decode(w.r), srgb::decode(w.g), srgb::decode(w.b), w.a};
  return {w.r, w.g, w.b, w.a};
}
// Clamps every channel to the format's range and packs the word.
constexpr Rgba8 encode_texel(const Texel4& c, TexelFormat f) {
  const auto [lo, hi] = channel_range(f);
  const auto cl = [lo = lo, hi = hi](int32_t v) { return v < lo ? lo : (v > hi ? hi : v); };
  if (f == TexelFormat::VS16X2) {
    const int32_t v0 = cl(c[0]) + 32768, v1 = cl(c[1]) + 32768;  // offset binary: h = v >> 8
    return {static_cast<uint8_t>(v0 >> 8), static_cast<uint8_t>(v0 & 255), static_cast<uint8_t>(v1 >> 8),
            static_cast<uint8_t>(v1 & 255)};
  }
  if (f == TexelFormat::SRGBA8) {
    const int32_t a = c[3] < 0 ? 0 : (c[3] > 255 ? 255 : c[3]);
    return {srgb::encode(c[0]), srgb::encode(c[1]), srgb::encode(c[2]), static_cast<uint8_t>(a)};
  }
  return {static_cast<uint8_t>(cl(c[0])), static_cast<uint8_t>(cl(c[1])), static_cast<uint8_t>(cl(c[2])),
          static_cast<uint8_t>(cl(c[3]))};
}

// How the driver stores a texture in the texel memory (docs/descriptors.md):
//   Linear : row-major texel rows; each row starts on a 256-byte boundary (row pitch a multiple of 256)
//   Tiled  : square tiles of `tile_bytes` bytes (one cache line each), tiles row-major over the level,
//            texels row-major inside a tile; the tile side is sqrt(tile_bytes / bytes_per_texel)
//            texels (64 bytes: 4x4 RGBA8 or 8x8 L8)
// Every level starts on a 256-byte boundary.
enum class MemoryLayout { Linear, Tiled };
inline constexpr EnumNames<MemoryLayout, 2> kMemoryLayoutNames{
    "memory layout", {{{MemoryLayout::Linear, "linear"}, {MemoryLayout::Tiled, "tiled"}}}};
MemoryLayout memory_layout_from_name(const std::string& name);  // kMemoryLayoutNames
const char* memory_layout_name(MemoryLayout l);
inline constexpr int kMinTileBytes = 64, kMaxTileBytes = 1024;  // 64, 256 or 1024 (powers of 4)
constexpr bool valid_tile_bytes(int b) { return b == 64 || b == 256 || b == 1024; }
// log2 of the tile side in texels: tile_bytes = 2^(2 k) bytes_per_texel.
constexpr int tile_side_log2(int tile_bytes, TexelFormat f) {
  int k = 0;
  while ((bytes_per_texel(f) << (2 * (k + 1))) <= tile_bytes) ++k;
  return k;
}

// Size of level `level` of a W x H texture (GL floor rule).
constexpr int mip_extent(int size0, int level) { return (size0 >> level) > 1 ? size0 >> level : 1; }
int mip_level_count(int width, int height);

struct CompressedLevels;  // cmodel/block_formats.hpp

struct Texture {
  TexelFormat format = TexelFormat::RGBA8;
  std::vector<Image> levels;  // levels[0] is the base; complete chains end at 1 x 1
  // Storage in the texel memory (what the texture descriptor records). Tiled in tiles of one
  // 64-byte cache line unless the driver chooses otherwise.
  MemoryLayout layout = MemoryLayout::Tiled;
  int tile_bytes = 64;
  // The memory budget's charge for the decoded chain (cmodel/memory_budget.hpp), shared by copies;
  // null for textures no input decoded (light maps, built in code).
  std::shared_ptr<MemoryCharge> memory;
  // A block-compressed texture (texture_from_block_image, cmodel/block_formats.hpp): its blocks
  // and decode rules, which texture memory stores; `levels` then hold the decoded texels (RGBA8,
  // decode_block_level of each level) that the golden model samples. Null for every other texture.
  std::shared_ptr<const CompressedLevels> compressed;
  int tile_side() const { return 1 << tile_side_log2(tile_bytes, format); }

  int width() const { return levels.front().width; }
  int height() const { return levels.front().height; }
  int max_level() const { return static_cast<int>(levels.size()) - 1; }
  // Throws InputError (naming `what`) if the size is outside 1..kMaxTextureSize or a stored level
  // does not follow the floor rule.
  void validate(const std::string& what) const;
};

// ---- Wrap modes (one function each; GL 4.6 Sec. 8.14.2) ----
enum class WrapMode { Repeat, MirroredRepeat, ClampToEdge, ClampToBorder };
inline constexpr EnumNames<WrapMode, 4> kWrapModeNames{"wrap mode",
                                                        {{{WrapMode::Repeat, "repeat"},
                                                          {WrapMode::MirroredRepeat, "mirrored-repeat"},
                                                          {WrapMode::ClampToEdge, "clamp-to-edge"},
                                                          {WrapMode::ClampToBorder, "clamp-to-border"}}}};
WrapMode wrap_mode_from_name(const std::string& name);  // kWrapModeNames
const char* wrap_mode_name(WrapMode m);
const std::vector<std::string>& wrap_mode_names();

// Map an integer texel index i (any int) onto [0, size) for the wrap modes that address memory;
// for ClampToBorder the result is -1 when the texel lies outside (the border colour is used).
// Coordinates are int64 because repeat keeps any integer meaningful (fixed_coord.hpp saturates at
// 2^46 / 2^F texels).
constexpr int wrap_repeat(int64_t i, int size) {
  if ((size & (size - 1)) == 0) return static_cast<int>(i & (size - 1));  // power of two: the low bits
  int r;
  if (i >= INT32_MIN && i <= INT32_MAX) {
    r = static_cast<int32_t>(i) % size;  // 32-bit divide when it fits (most coordinates)
  } else {
    r = static_cast<int>(i % size);
  }
  return r < 0 ? r + size : r;
}
constexpr int wrap_mirrored_repeat(int64_t i, int size) {
  // GL mirror: period 2 size, the second half reversed.
  const int p = wrap_repeat(i, 2 * size);
  return p < size ? p : 2 * size - 1 - p;
}
constexpr int wrap_clamp_to_edge(int64_t i, int size) {
  return i < 0 ? 0 : (i >= size ? size - 1 : static_cast<int>(i));
}
constexpr int wrap_clamp_to_border(int64_t i, int size) {
  return (i < 0 || i >= size) ? -1 : static_cast<int>(i);
}
constexpr int wrap_index(WrapMode m, int64_t i, int size) {
  if (static_cast<uint64_t>(i) < static_cast<uint64_t>(size)) return static_cast<int>(i);  // inside: every mode agrees
  switch (m) {
    case WrapMode::Repeat: return wrap_repeat(i, size);
    case WrapMode::MirroredRepeat: return wrap_mirrored_repeat(i, size);
    case WrapMode::ClampToEdge: return wrap_clamp_to_edge(i, size);
    case WrapMode::ClampToBorder: return wrap_clamp_to_border(i, size);
  }
  return 0;
}

// Wrap n consecutive texel indices start, start + 1, ... (the taps of one filter row or column):
// the first through wrap_index, the rest by stepping for repeat (no divider per tap).
inline void wrap_run(WrapMode m, int64_t start, int n, int size, int* out) {
  out[0] = wrap_index(m, start, size);
  for (int k = 1; k < n; ++k) {
    if (m == WrapMode::Repeat) {
      out[k] = out[k - 1] + 1 == size ? 0 : out[k - 1] + 1;
    } else {
      out[k] = wrap_index(m, start + k, size);
    }
  }
}

// ---- File I/O through OpenImageIO (unassociated alpha on read and write) ----
// Loads any format OpenImageIO reads (PNG, JPEG, TIFF, OpenEXR, ...). Stored MIP levels (e.g. a
// tiled TIFF written by maketx) are kept as they are; otherwise the texture has one level.
// 1 channel -> L8, 2 channels -> (L, L, L, A) RGBA8, 3 -> RGB with A = 255, 4 -> RGBA8; other
// pixel types are converted to 8 bits by OpenImageIO (floats clamped to [0, 1] and rounded).
// A directory is read as the MIP chain `tfu mipmap --out DIR` writes (level_00.png, level_01.png,
// ...), so that edge-preserving or Gaussian MIP-maps made once can be a scene's texture.
// Throws InputError naming the file on any failure.
Texture load_texture(const std::string& path);
// Writes one level. Refuses to overwrite an existing file unless `overwrite`. (The tools write
// through OutputFiles, cmodel/output_files.hpp, which calls write_image_file.)
void save_image(const Image& img, const std::string& path, bool overwrite);
// Writes one level into `file_path` in the format that `type_path`'s extension names (OutputFiles
// writes a temporary file first). Checks every step, close included; InputError on failure.
void write_image_file(const Image& img, const std::string& type_path, const std::string& file_path);
// Whether OpenImageIO has a writer for `type_path`'s extension.
bool image_writer_exists(const std::string& type_path);
// Loads one plain image (first level) for comparisons.
Image load_image(const std::string& path);

}  // namespace tfu
