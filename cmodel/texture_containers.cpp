#include "cmodel/texture_containers.hpp"

#include <filesystem>
#include <fstream>
#include <algorithm>
#include <array>
#include <cstring>

#include <sys/stat.h>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/memory_budget.hpp"

namespace tfu {
namespace {

// ---- Magic numbers and header layouts ----
// DDS: "DDS " then DDS_HEADER (124 bytes, DDS_PIXELFORMAT of 32 bytes at offset 72 within it), then
// DDS_HEADER_DXT10 (20 bytes) when the FourCC is "DX10" (Microsoft, "DDS file layout").
constexpr std::array<uint8_t, 4> kDdsMagic{'D', 'D', 'S', ' '};
constexpr size_t kDdsHeaderBytes = 124, kDdsPixelFormatBytes = 32, kDdsDx10Bytes = 20;
constexpr uint32_t kDdsdCaps = 0x1, kDdsdHeight = 0x2, kDdsdWidth = 0x4, kDdsdPixelFormat = 0x1000,
                   kDdsdMipMapCount = 0x20000, kDdsdLinearSize = 0x80000;
constexpr uint32_t kDdpfAlphaPixels = 0x1, kDdpfFourCC = 0x4;
constexpr uint32_t kDdsCapsComplex = 0x8, kDdsCapsTexture = 0x1000, kDdsCapsMipMap = 0x400000;
constexpr uint32_t kDdsCaps2CubeMap = 0x200, kDdsCaps2Volume = 0x200000;
constexpr uint32_t kD3d10ResourceDimensionTexture2D = 3, kDdsResourceMiscTextureCube = 0x4;
constexpr uint32_t kDdsAlphaModeOpaque = 3;  // miscFlags2 bits 0..2 (DDS_ALPHA_MODE_OPAQUE)

// KTX 1.1 (Khronos): 12-byte identifier, then 13 uint32 fields; the endianness field reads
// 0x04030201 in the writer's byte order.
constexpr std::array<uint8_t, 12> kKtxMagic{0xAB, 'K', 'T', 'X', ' ', '1', '1', 0xBB, '\r', '\n', 0x1A, '\n'};
constexpr size_t kKtxHeaderBytes = 64;
constexpr uint32_t kKtxEndianness = 0x04030201;
constexpr uint32_t kGlRed = 0x1903, kGlRg = 0x8227, kGlRgb = 0x1907, kGlRgba = 0x1908;

// ARM .astc (astcenc's astcenccli_image_load_store.cpp "astc_header"): magic 0x5CA1AB13 little
// endian, block x/y/z (one byte each), texels x/y/z (24-bit little endian each).
constexpr std::array<uint8_t, 4> kAstcMagic{0x13, 0xAB, 0xA1, 0x5C};
constexpr size_t kAstcHeaderBytes = 16;

constexpr uint32_t fourcc(char a, char b, char c, char d) {
  return uint32_t(uint8_t(a)) | uint32_t(uint8_t(b)) << 8 | uint32_t(uint8_t(c)) << 16 | uint32_t(uint8_t(d)) << 24;
}

bool starts_with(std::span<const uint8_t> bytes, std::span<const uint8_t> magic) {
  return bytes.size() >= magic.size() && std::equal(magic.begin(), magic.end(), bytes.begin());
}

uint32_t le32(std::span<const uint8_t> b, size_t at) {
  return uint32_t{b[at]} | uint32_t{b[at + 1]} << 8 | uint32_t{b[at + 2]} << 16 | uint32_t{b[at + 3]} << 24;
}
uint32_t byteswap32(uint32_t v) { return (v >> 24) | ((v >> 8) & 0xFF00) | ((v << 8) & 0xFF0000) | (v << 24); }

void put32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

// Levels of a full chain from w x h (down to 1 x 1).
int full_chain_levels(int w, int h) {
  int n = 1;
  for (int s = std::max(w, h); s > 1; s >>= 1) ++n;
  return n;
}

// A FourCC for messages: its characters when printable, else hex.
std::string fourcc_text(uint32_t v) {
  std::string s;
  for (int i = 0; i < 4; ++i) {
    const char c = static_cast<char>(v >> (8 * i));
    if (c < 0x20 || c > 0x7e) return fmt::format("0x{:08x}", v);
    s += c;
  }
  return "'" + s + "'";
}

// Reads a file's levels after its header: `count` levels of `f` from w x h, each preceded by a
// 4-byte size in KTX (`ktx_sizes`, byte order `swap`). Every size is checked before a byte is copied.
class LevelReader {
 public:
  LevelReader(std::span<const uint8_t> bytes, size_t at, std::string where)
      : bytes_(bytes), at_(at), where_(std::move(where)) {}
  [[noreturn]] void fail(const std::string& what) const { throw InputError(fmt::format("{}: {}", where_, what)); }

  void read_levels(BlockImage& img, int w, int h, int count, bool ktx_sizes, bool swap) {
    // Everything the levels need, summed and checked against the file before anything is allocated.
    size_t need = 0;
    for (int l = 0, lw = w, lh = h; l < count; ++l, lw = std::max(1, lw >> 1), lh = std::max(1, lh >> 1))
      need += block_level_bytes(img.format, lw, lh) + (ktx_sizes ? 4 : 0);
    const size_t have = bytes_.size() - at_;
    if (have < need)
      fail(fmt::format("truncated: {} {}x{} with {} MIP levels needs {} bytes of levels, the file has {}",
                       block_format_name(img.format), w, h, count, need, have));
    if (have > need)
      fail(fmt::format("{} bytes after the last MIP level (a {}x{} {} with {} levels holds {})", have - need, w, h,
                       block_format_name(img.format), count, need));
    img.levels.resize(static_cast<size_t>(count));
    for (int l = 0, lw = w, lh = h; l < count; ++l, lw = std::max(1, lw >> 1), lh = std::max(1, lh >> 1)) {
      const size_t n = block_level_bytes(img.format, lw, lh);
      if (ktx_sizes) {
        uint32_t size = le32(bytes_, at_);
        if (swap) size = byteswap32(size);
        if (size != n)
          fail(fmt::format("level {} imageSize {} where a {}x{} {} level holds {} bytes", l, size, lw, lh,
                           block_format_name(img.format), n));
        at_ += 4;
      }
      BlockLevel& level = img.levels[static_cast<size_t>(l)];
      level.width = lw;
      level.height = lh;
      level.blocks.assign(bytes_.begin() + static_cast<ptrdiff_t>(at_),
                          bytes_.begin() + static_cast<ptrdiff_t>(at_ + n));
      at_ += n;
    }
  }

 private:
  std::span<const uint8_t> bytes_;
  size_t at_;
  std::string where_;
};

void check_size(const LevelReader& r, uint64_t w, uint64_t h) {
  if (w < 1 || h < 1 || w > kMaxTextureSize || h > kMaxTextureSize)
    r.fail(fmt::format("size {}x{} outside 1..{} per side", w, h, kMaxTextureSize));
}

int check_mip_count(const LevelReader& r, uint32_t count, int w, int h) {
  const int full = full_chain_levels(w, h);
  if (count > static_cast<uint32_t>(full))
    r.fail(fmt::format("{} MIP levels where a {}x{} texture has at most {}", count, w, h, full));
  return count == 0 ? 1 : static_cast<int>(count);
}

// ---- DDS ----
BlockImage parse_dds(std::span<const uint8_t> b, const std::string& label) {
  LevelReader r(b, 0, label + ": DDS");
  if (b.size() < 4 + kDdsHeaderBytes)
    r.fail(fmt::format("truncated: {} bytes, the header needs {}", b.size(), 4 + kDdsHeaderBytes));
  const size_t h0 = 4;  // DDS_HEADER
  if (le32(b, h0) != kDdsHeaderBytes) r.fail(fmt::format("header size {} (must be {})", le32(b, h0), kDdsHeaderBytes));
  const uint32_t height = le32(b, h0 + 8), width = le32(b, h0 + 12), depth = le32(b, h0 + 20), mips = le32(b, h0 + 24);
  const size_t pf = h0 + 72;  // DDS_PIXELFORMAT
  if (le32(b, pf) != kDdsPixelFormatBytes)
    r.fail(fmt::format("pixel format size {} (must be {})", le32(b, pf), kDdsPixelFormatBytes));
  const uint32_t pf_flags = le32(b, pf + 4), code = le32(b, pf + 8), caps2 = le32(b, h0 + 108);
  if (caps2 & kDdsCaps2CubeMap) r.fail("a cube map, not a 2D texture");
  if (caps2 & kDdsCaps2Volume || depth > 1) r.fail("a volume texture, not a 2D texture");
  if (!(pf_flags & kDdpfFourCC)) r.fail("no FourCC: an uncompressed DDS, not a block-compressed texture");
  check_size(r, width, height);
  BlockImage img;
  size_t at = 4 + kDdsHeaderBytes;
  switch (code) {
    case fourcc('D', 'X', 'T', '1'):
      img.format = pf_flags & kDdpfAlphaPixels ? BlockFormat::BC1A : BlockFormat::BC1;
      break;
    case fourcc('D', 'X', 'T', '3'): img.format = BlockFormat::BC2; break;
    case fourcc('D', 'X', 'T', '5'): img.format = BlockFormat::BC3; break;
    case fourcc('A', 'T', 'I', '1'):
    case fourcc('B', 'C', '4', 'U'): img.format = BlockFormat::BC4; break;
    case fourcc('B', 'C', '4', 'S'): img.format = BlockFormat::BC4S; break;
    case fourcc('A', 'T', 'I', '2'):
    case fourcc('B', 'C', '5', 'U'): img.format = BlockFormat::BC5; break;
    case fourcc('B', 'C', '5', 'S'): img.format = BlockFormat::BC5S; break;
    case fourcc('D', 'X', 'T', '2'):
    case fourcc('D', 'X', 'T', '4'):
      r.fail(fmt::format("FourCC {} (premultiplied alpha) is not supported", fourcc_text(code)));
    case fourcc('D', 'X', '1', '0'): {
      if (b.size() < at + kDdsDx10Bytes)
        r.fail(fmt::format("truncated: {} bytes, the DX10 header needs {}", b.size(), at + kDdsDx10Bytes));
      const uint32_t dxgi = le32(b, at), dimension = le32(b, at + 4), misc = le32(b, at + 8),
                     array_size = le32(b, at + 12), misc2 = le32(b, at + 16);
      if (dimension != kD3d10ResourceDimensionTexture2D)
        r.fail(fmt::format("resource dimension {} (a 2D texture is {})", dimension, kD3d10ResourceDimensionTexture2D));
      if (misc & kDdsResourceMiscTextureCube) r.fail("a cube map, not a 2D texture");
      if (array_size != 1) r.fail(fmt::format("array size {} (one 2D texture is 1)", array_size));
      const BlockFormatInfo* found = nullptr;
      for (const BlockFormatInfo& i : kBlockFormats)
        if (i.dxgi_format != 0 && (dxgi == i.dxgi_format || dxgi == i.dxgi_srgb_format) && !found) found = &i;
      if (!found) r.fail(fmt::format("DXGI format {} is not a supported block-compressed format", dxgi));
      img.format = found->format;
      img.srgb = dxgi == found->dxgi_srgb_format;
      // BC1: DXGI has one code; the alpha mode says whether the file's alpha is meaningful.
      if (img.format == BlockFormat::BC1 && (misc2 & 7) != kDdsAlphaModeOpaque) img.format = BlockFormat::BC1A;
      at += kDdsDx10Bytes;
      break;
    }
    default: r.fail(fmt::format("FourCC {} is not a supported block-compressed format", fourcc_text(code)));
  }
  const int count = check_mip_count(r, mips, static_cast<int>(width), static_cast<int>(height));
  LevelReader levels(b, at, label + ": DDS");
  levels.read_levels(img, static_cast<int>(width), static_cast<int>(height), count, false, false);
  return img;
}

std::vector<uint8_t> write_dds(const BlockImage& img) {
  const BlockFormatInfo& info = block_format_info(img.format);
  const BlockLevel& l0 = img.levels.front();
  // The legacy FourCCs where one exists for the linear format, the DX10 header otherwise.
  uint32_t code = 0;
  switch (img.format) {
    case BlockFormat::BC1:
    case BlockFormat::BC1A: code = fourcc('D', 'X', 'T', '1'); break;
    case BlockFormat::BC2: code = fourcc('D', 'X', 'T', '3'); break;
    case BlockFormat::BC3: code = fourcc('D', 'X', 'T', '5'); break;
    case BlockFormat::BC4: code = fourcc('B', 'C', '4', 'U'); break;
    case BlockFormat::BC4S: code = fourcc('B', 'C', '4', 'S'); break;
    case BlockFormat::BC5: code = fourcc('B', 'C', '5', 'U'); break;
    case BlockFormat::BC5S: code = fourcc('B', 'C', '5', 'S'); break;
    default: break;
  }
  const bool dx10 = img.srgb || code == 0;
  std::vector<uint8_t> out(kDdsMagic.begin(), kDdsMagic.end());
  const uint32_t mip_flags = img.levels.size() > 1 ? kDdsdMipMapCount : 0;
  put32(out, kDdsHeaderBytes);
  put32(out, kDdsdCaps | kDdsdHeight | kDdsdWidth | kDdsdPixelFormat | kDdsdLinearSize | mip_flags);
  put32(out, static_cast<uint32_t>(l0.height));
  put32(out, static_cast<uint32_t>(l0.width));
  put32(out, static_cast<uint32_t>(l0.blocks.size()));  // dwPitchOrLinearSize: level 0's bytes
  put32(out, 0);                                        // dwDepth
  put32(out, static_cast<uint32_t>(img.levels.size()));
  for (int i = 0; i < 11; ++i) put32(out, 0);  // dwReserved1
  put32(out, kDdsPixelFormatBytes);
  put32(out, kDdpfFourCC | (img.format == BlockFormat::BC1A && !dx10 ? kDdpfAlphaPixels : 0));
  put32(out, dx10 ? fourcc('D', 'X', '1', '0') : code);
  for (int i = 0; i < 5; ++i) put32(out, 0);  // RGB bit count and masks
  put32(out, kDdsCapsTexture | (img.levels.size() > 1 ? kDdsCapsComplex | kDdsCapsMipMap : 0));
  for (int i = 0; i < 4; ++i) put32(out, 0);  // dwCaps2..4, dwReserved2
  if (dx10) {
    put32(out, img.srgb ? info.dxgi_srgb_format : info.dxgi_format);
    put32(out, kD3d10ResourceDimensionTexture2D);
    put32(out, 0);  // miscFlag
    put32(out, 1);  // arraySize
    put32(out, img.format == BlockFormat::BC1 ? kDdsAlphaModeOpaque : 0);
  }
  for (const BlockLevel& l : img.levels) out.insert(out.end(), l.blocks.begin(), l.blocks.end());
  return out;
}

// ---- KTX 1.1 ----
BlockImage parse_ktx(std::span<const uint8_t> b, const std::string& label) {
  LevelReader r(b, 0, label + ": KTX");
  if (b.size() < kKtxHeaderBytes)
    r.fail(fmt::format("truncated: {} bytes, the header needs {}", b.size(), kKtxHeaderBytes));
  const uint32_t endianness = le32(b, 12);
  if (endianness != kKtxEndianness && endianness != byteswap32(kKtxEndianness))
    r.fail(fmt::format("endianness field 0x{:08x}", endianness));
  const bool swap = endianness != kKtxEndianness;
  auto field = [&](int i) {
    return swap ? byteswap32(le32(b, 12 + 4 * static_cast<size_t>(i))) : le32(b, 12 + 4 * static_cast<size_t>(i));
  };
  const uint32_t gl_type = field(1), gl_type_size = field(2), gl_format = field(3), internal = field(4);
  const uint32_t width = field(6), height = field(7), depth = field(8), array_elements = field(9), faces = field(10),
                 mips = field(11), kv_bytes = field(12);
  if (gl_type != 0 || gl_format != 0 || gl_type_size > 1)
    r.fail(fmt::format("glType {} glTypeSize {} glFormat {}: not a compressed texture (0, 1, 0)", gl_type, gl_type_size,
                       gl_format));
  const BlockFormatInfo* found = nullptr;
  for (const BlockFormatInfo& i : kBlockFormats)
    if ((internal == i.gl_internal_format ||
         (i.gl_srgb_internal_format != 0 && internal == i.gl_srgb_internal_format)) &&
        !found)
      found = &i;
  if (!found) r.fail(fmt::format("glInternalFormat 0x{:04x} is not a supported block-compressed format", internal));
  if (height == 0) r.fail("pixelHeight 0: a 1D texture, not a 2D texture");
  if (depth > 1) r.fail(fmt::format("pixelDepth {}: a volume texture, not a 2D texture", depth));
  if (array_elements > 1) r.fail(fmt::format("{} array elements (one 2D texture is 0 or 1)", array_elements));
  if (faces != 1) r.fail(fmt::format("{} faces (a 2D texture has 1)", faces));
  check_size(r, width, height);
  const int count = check_mip_count(r, mips, static_cast<int>(width), static_cast<int>(height));
  if (kv_bytes > b.size() - kKtxHeaderBytes)
    r.fail(fmt::format("truncated: {} bytes of key/value data, {} left in the file", kv_bytes,
                       b.size() - kKtxHeaderBytes));
  if (kv_bytes % 4 != 0) r.fail(fmt::format("{} bytes of key/value data (must be a multiple of 4)", kv_bytes));
  BlockImage img;
  img.format = found->format;
  img.srgb = internal == found->gl_srgb_internal_format;
  LevelReader levels(b, kKtxHeaderBytes + kv_bytes, label + ": KTX");
  // Every block is 8 or 16 bytes, so no level needs the 4-byte mipPadding.
  levels.read_levels(img, static_cast<int>(width), static_cast<int>(height), count, true, swap);
  return img;
}

std::vector<uint8_t> write_ktx(const BlockImage& img) {
  const BlockFormatInfo& info = block_format_info(img.format);
  std::vector<uint8_t> out(kKtxMagic.begin(), kKtxMagic.end());
  static constexpr uint32_t kBase[] = {0, kGlRed, kGlRg, kGlRgb, kGlRgba};
  put32(out, kKtxEndianness);
  put32(out, 0);  // glType
  put32(out, 1);  // glTypeSize
  put32(out, 0);  // glFormat
  put32(out, img.srgb ? info.gl_srgb_internal_format : info.gl_internal_format);
  put32(out, kBase[info.channels]);
  put32(out, static_cast<uint32_t>(img.levels.front().width));
  put32(out, static_cast<uint32_t>(img.levels.front().height));
  put32(out, 0);  // pixelDepth
  put32(out, 0);  // numberOfArrayElements
  put32(out, 1);  // numberOfFaces
  put32(out, static_cast<uint32_t>(img.levels.size()));
  put32(out, 0);  // bytesOfKeyValueData
  for (const BlockLevel& l : img.levels) {
    put32(out, static_cast<uint32_t>(l.blocks.size()));
    out.insert(out.end(), l.blocks.begin(), l.blocks.end());
  }
  return out;
}

// ---- ARM .astc ----
uint32_t le24(std::span<const uint8_t> b, size_t at) {
  return uint32_t{b[at]} | uint32_t{b[at + 1]} << 8 | uint32_t{b[at + 2]} << 16;
}

BlockImage parse_astc(std::span<const uint8_t> b, const std::string& label) {
  LevelReader r(b, 0, label + ": .astc");
  if (b.size() < kAstcHeaderBytes)
    r.fail(fmt::format("truncated: {} bytes, the header needs {}", b.size(), kAstcHeaderBytes));
  const int bx = b[4], by = b[5], bz = b[6];
  const uint32_t width = le24(b, 7), height = le24(b, 10), depth = le24(b, 13);
  if (bz != 1 || depth != 1)
    r.fail(fmt::format("block depth {}, texel depth {}: a 3D texture, not a 2D texture", bz, depth));
  const BlockFormatInfo* found = nullptr;
  for (const BlockFormatInfo& i : kBlockFormats)
    if (i.family == BlockFamily::ASTC && i.block_w == bx && i.block_h == by) found = &i;
  if (!found) r.fail(fmt::format("block footprint {}x{} is not an ASTC 2D footprint", bx, by));
  check_size(r, width, height);
  BlockImage img;
  img.format = found->format;
  LevelReader levels(b, kAstcHeaderBytes, label + ": .astc");
  levels.read_levels(img, static_cast<int>(width), static_cast<int>(height), 1, false, false);
  return img;
}

std::vector<uint8_t> write_astc(const BlockImage& img) {
  const BlockFormatInfo& info = block_format_info(img.format);
  std::vector<uint8_t> out(kAstcMagic.begin(), kAstcMagic.end());
  out.push_back(static_cast<uint8_t>(info.block_w));
  out.push_back(static_cast<uint8_t>(info.block_h));
  out.push_back(1);
  for (const uint32_t v :
       {static_cast<uint32_t>(img.levels.front().width), static_cast<uint32_t>(img.levels.front().height), 1u})
    for (int i = 0; i < 3; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
  out.insert(out.end(), img.levels.front().blocks.begin(), img.levels.front().blocks.end());
  return out;
}

}  // namespace

const char* block_container_name(BlockContainer c) { return kBlockContainerNames.name(c); }

const char* container_file_text(BlockContainer c) {
  switch (c) {
    case BlockContainer::DDS: return "a DDS file";
    case BlockContainer::KTX: return "a KTX file";
    case BlockContainer::ASTC: return "an .astc file";
  }
  return "a file";
}

bool container_holds(BlockContainer c, BlockFormat f) {
  switch (c) {
    case BlockContainer::DDS: return block_format_info(f).family == BlockFamily::BC;
    case BlockContainer::KTX: return true;
    case BlockContainer::ASTC: return block_format_info(f).family == BlockFamily::ASTC;
  }
  return false;
}

BlockContainer default_container(BlockFormat f) {
  return block_format_info(f).family == BlockFamily::BC ? BlockContainer::DDS : BlockContainer::KTX;
}

std::optional<BlockContainer> container_by_magic(std::span<const uint8_t> bytes) {
  if (starts_with(bytes, kDdsMagic)) return BlockContainer::DDS;
  if (starts_with(bytes, kKtxMagic)) return BlockContainer::KTX;
  if (starts_with(bytes, kAstcMagic)) return BlockContainer::ASTC;
  return std::nullopt;
}

void validate_block_image(const BlockImage& image, const std::string& label) {
  const BlockFormatInfo& info = block_format_info(image.format);
  if (image.levels.empty()) throw InputError(fmt::format("{}: no MIP levels", label));
  if (image.srgb && info.gl_srgb_internal_format == 0)
    throw InputError(fmt::format("{}: {} has no sRGB variant", label, info.name));
  const int w = image.levels.front().width, h = image.levels.front().height;
  if (w < 1 || h < 1 || w > kMaxTextureSize || h > kMaxTextureSize)
    throw InputError(fmt::format("{}: size {}x{} outside 1..{} per side", label, w, h, kMaxTextureSize));
  if (image.levels.size() > static_cast<size_t>(full_chain_levels(w, h)))
    throw InputError(fmt::format("{}: {} MIP levels where a {}x{} texture has at most {}", label, image.levels.size(),
                                 w, h, full_chain_levels(w, h)));
  for (size_t l = 0, lw = static_cast<size_t>(w), lh = static_cast<size_t>(h); l < image.levels.size();
       ++l, lw = std::max<size_t>(1, lw >> 1), lh = std::max<size_t>(1, lh >> 1)) {
    const BlockLevel& level = image.levels[l];
    if (static_cast<size_t>(level.width) != lw || static_cast<size_t>(level.height) != lh)
      throw InputError(
          fmt::format("{}: level {} is {}x{}, the MIP rule gives {}x{}", label, l, level.width, level.height, lw, lh));
    const size_t want = block_level_bytes(image.format, level.width, level.height);
    if (level.blocks.size() != want)
      throw InputError(fmt::format("{}: level {} holds {} bytes, a {}x{} {} level {}", label, l, level.blocks.size(),
                                   level.width, level.height, info.name, want));
  }
}

BlockImage parse_block_image(std::span<const uint8_t> bytes, const std::string& label) {
  const std::optional<BlockContainer> c = container_by_magic(bytes);
  if (!c) throw InputError(fmt::format("{}: not a DDS, KTX or .astc file (no known magic number)", label));
  BlockImage img;
  switch (*c) {
    case BlockContainer::DDS: img = parse_dds(bytes, label); break;
    case BlockContainer::KTX: img = parse_ktx(bytes, label); break;
    case BlockContainer::ASTC: img = parse_astc(bytes, label); break;
  }
  validate_block_image(img, label);  // what the readers built: a check of the readers themselves
  return img;
}

BlockImage read_block_image(const std::string& path, const std::string& label_in) {
  const std::string label = label_in.empty() ? quoted_path(path) : label_in;
  check_input_file(path, label, kMaxImageBytes);
  struct stat st {};
  const uint64_t size = ::stat(path.c_str(), &st) == 0 ? static_cast<uint64_t>(st.st_size) : 0;
  // The file's bytes and the levels copied out of them, charged before either is allocated (a file
  // that grows meanwhile is bounded by read_input_file's kMaxImageBytes).
  MemoryCharge charge(2 * size, label, "compressed blocks");
  const std::string text = read_input_file(path, label, kMaxImageBytes);
  if (text.size() > size) charge.add(2 * (text.size() - size));
  return parse_block_image(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()), label);
}

std::vector<uint8_t> serialize_block_image(const BlockImage& image, BlockContainer c, const std::string& label) {
  validate_block_image(image, label);
  if (!container_holds(c, image.format))
    throw InputError(
        fmt::format("{}: {} cannot hold {} ({})", label, container_file_text(c), block_format_name(image.format),
                    c == BlockContainer::DDS ? "DDS holds the BC formats" : ".astc holds the ASTC formats"));
  switch (c) {
    case BlockContainer::DDS: return write_dds(image);
    case BlockContainer::KTX: return write_ktx(image);
    case BlockContainer::ASTC:
      if (image.levels.size() != 1)
        throw InputError(fmt::format("{}: an .astc file holds one level, the image has {} (use KTX for MIP levels)",
                                     label, image.levels.size()));
      if (image.srgb) throw InputError(fmt::format("{}: an .astc file has no sRGB flag (use KTX for sRGB)", label));
      return write_astc(image);
  }
  return {};
}

bool is_block_container_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  std::ifstream in(path, std::ios::binary);
  uint8_t head[16] = {};
  in.read(reinterpret_cast<char*>(head), sizeof head);
  return container_by_magic(std::span<const uint8_t>(head, static_cast<size_t>(in.gcount()))).has_value();
}

}  // namespace tfu
