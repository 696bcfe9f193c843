// BC1-BC5 decoders: the rules and widths are in bc_decode.hpp; docs/compressed-bc.md.
#include "cmodel/bc_decode.hpp"

#include <fmt/format.h>

#include "cmodel/bc7_decode.hpp"
#include "cmodel/error.hpp"

namespace tfu {

namespace {

// A colour channel of a BC1 block: the two n-bit fields (n = 5 or 6) and their 8-bit widenings.
struct Bc1Channel {
  int v0, v1;  // fields, n bits
  int e0, e1;  // widened, 8 bits
  int bits;    // n
};

// 2/3 e0 + 1/3 e1 by `rule` (index 2 of 4-colour mode; index 3 calls it with the endpoints swapped).
// Widths: at most 3 * 255 + 1 (exact, truncate), 256 * 255 + 128 + 80 * 255 (nvidia, < 2^17),
// 64 * 255 + 32 (amd): all fit an int.
int third_of(const Bc1Channel& c, Bc1Interpolation rule) {
  switch (rule) {
    case Bc1Interpolation::EXACT: return (2 * c.e0 + c.e1 + 1) / 3;
    case Bc1Interpolation::TRUNCATE: return (2 * c.e0 + c.e1) / 3;
    case Bc1Interpolation::NVIDIA:
      if (c.bits == 5) return (2 * c.v0 + c.v1) * 22 / 8;
      {
        const int d = c.e1 - c.e0;                         // -255..255; d / 4 truncates toward zero (C++ division)
        return (256 * c.e0 + d / 4 + 128 + 80 * d) / 256;  // numerator >= 175 e0 + 64 > 0
      }
    case Bc1Interpolation::AMD: return (43 * c.e0 + 21 * c.e1 + 32) >> 6;
  }
  return 0;
}

// (e0 + e1) / 2 by `rule` (index 2 of 3-colour mode).
int half_of(const Bc1Channel& c, Bc1Interpolation rule) {
  switch (rule) {
    case Bc1Interpolation::EXACT:
    case Bc1Interpolation::AMD: return (c.e0 + c.e1 + 1) >> 1;
    case Bc1Interpolation::TRUNCATE: return (c.e0 + c.e1) >> 1;
    case Bc1Interpolation::NVIDIA:
      if (c.bits == 5) return (c.v0 + c.v1) * 33 / 8;
      {
        const int d = c.e1 - c.e0;
        return (256 * c.e0 + d / 4 + 128 + 128 * d) / 256;  // numerator >= 128 e0 + 64 > 0
      }
  }
  return 0;
}

Bc1Channel channel(int color0, int color1, int shift, int bits) {
  const int mask = (1 << bits) - 1;
  const int v0 = (color0 >> shift) & mask, v1 = (color1 >> shift) & mask;
  const auto widen = [bits](int v) { return bits == 5 ? bc_widen5(v) : bc_widen6(v); };
  return {v0, v1, widen(v0), widen(v1), bits};
}

Bc1Channel swapped(const Bc1Channel& c) { return {c.v1, c.v0, c.e1, c.e0, c.bits}; }

uint8_t u8(int v) { return static_cast<uint8_t>(v); }

uint64_t load_le64(const uint8_t* p) {
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

// The 3-bit codes of a BC4 block: bytes 2..7 as a 48-bit little-endian integer, texel t at bits 3t.
uint64_t bc4_codes(const uint8_t* block) { return load_le64(block) >> 16; }
int bc4_code(uint64_t codes, int t) { return static_cast<int>((codes >> (3 * t)) & 7); }

int round_div35(int32_t n) {  // nearest integer to n / 35; n / 35 is never a half (see header)
  return n >= 0 ? (n + 17) / 35 : -((-n + 17) / 35);
}

}  // namespace

std::array<Rgba8, 4> bc1_palette(const uint8_t* block, Bc1Interpolation rule, bool four_colour_only,
                                 bool three_colour_alpha0) {
  const int color0 = block[0] | (block[1] << 8), color1 = block[2] | (block[3] << 8);
  const std::array<Bc1Channel, 3> ch{channel(color0, color1, 11, 5), channel(color0, color1, 5, 6),
                                     channel(color0, color1, 0, 5)};
  std::array<Rgba8, 4> p{};
  p[0] = {u8(ch[0].e0), u8(ch[1].e0), u8(ch[2].e0), 255};
  p[1] = {u8(ch[0].e1), u8(ch[1].e1), u8(ch[2].e1), 255};
  if (four_colour_only || color0 > color1) {
    p[2] = {u8(third_of(ch[0], rule)), u8(third_of(ch[1], rule)), u8(third_of(ch[2], rule)), 255};
    p[3] = {u8(third_of(swapped(ch[0]), rule)), u8(third_of(swapped(ch[1]), rule)), u8(third_of(swapped(ch[2]), rule)),
            255};
  } else {
    p[2] = {u8(half_of(ch[0], rule)), u8(half_of(ch[1], rule)), u8(half_of(ch[2], rule)), 255};
    p[3] = {0, 0, 0, u8(three_colour_alpha0 ? 0 : 255)};
  }
  return p;
}

namespace {

BcBlockTexels bc1_texels(const uint8_t* block, Bc1Interpolation rule, bool four_colour_only, bool alpha0) {
  const std::array<Rgba8, 4> palette = bc1_palette(block, rule, four_colour_only, alpha0);
  const uint32_t codes = block[4] | (block[5] << 8) | (block[6] << 16) | (static_cast<uint32_t>(block[7]) << 24);
  BcBlockTexels out;
  for (int t = 0; t < kBcBlockTexels; ++t) out[t] = palette[(codes >> (2 * t)) & 3];
  return out;
}

}  // namespace

BcBlockTexels decode_bc1_block(const uint8_t* block, bool rgba, Bc1Interpolation rule) {
  return bc1_texels(block, rule, false, rgba);
}

BcBlockTexels decode_bc2_block(const uint8_t* block, Bc1Interpolation rule) {
  BcBlockTexels out = bc1_texels(block + 8, rule, true, false);
  const uint64_t alpha = load_le64(block);
  for (int t = 0; t < kBcBlockTexels; ++t) out[t].a = u8(((alpha >> (4 * t)) & 15) * 17);  // a / 15 exactly
  return out;
}

BcBlockTexels decode_bc3_block(const uint8_t* block, BcRules rules) {
  BcBlockTexels out = bc1_texels(block + 8, rules.colour, true, false);
  const std::array<uint8_t, kBcBlockTexels> alpha = decode_bc4_unorm8(block, rules.alpha);
  for (int t = 0; t < kBcBlockTexels; ++t) out[t].a = alpha[t];
  return out;
}

std::array<int32_t, kBcBlockTexels> decode_bc4_exact(const uint8_t* block, bool is_signed) {
  // Raw endpoints select the mode; the values interpolated are the spec's RED0, RED1 in units of
  // 1/255 (unsigned) or 1/127 (signed, -128 read as -127).
  const int raw0 = is_signed ? static_cast<int8_t>(block[0]) : block[0];
  const int raw1 = is_signed ? static_cast<int8_t>(block[1]) : block[1];
  const int a0 = raw0 < -127 ? -127 : raw0, a1 = raw1 < -127 ? -127 : raw1;
  const int full = is_signed ? 127 : 255, low = is_signed ? -127 : 0;
  const uint64_t codes = bc4_codes(block);
  std::array<int32_t, kBcBlockTexels> out;
  for (int t = 0; t < kBcBlockTexels; ++t) {
    const int code = bc4_code(codes, t);
    int32_t n;
    if (code == 0) {
      n = kBc4ExactScale * a0;
    } else if (code == 1) {
      n = kBc4ExactScale * a1;
    } else if (raw0 > raw1) {  // 8 values: (w0 a0 + w1 a1) / 7, w1 = code - 1
      n = 5 * ((8 - code) * a0 + (code - 1) * a1);
    } else if (code < 6) {  // 6 values: (w0 a0 + w1 a1) / 5, w1 = code - 1
      n = 7 * ((6 - code) * a0 + (code - 1) * a1);
    } else {
      n = kBc4ExactScale * (code == 6 ? low : full);
    }
    out[t] = n;
  }
  return out;
}

namespace {

// The truncating rule on the raw bytes (libsquish, Mesa); C++ division truncates toward zero.
int bc4_truncated(int raw0, int raw1, int code, int low, int full) {
  if (code == 0) return raw0;
  if (code == 1) return raw1;
  if (raw0 > raw1) return ((8 - code) * raw0 + (code - 1) * raw1) / 7;
  if (code < 6) return ((6 - code) * raw0 + (code - 1) * raw1) / 5;
  return code == 6 ? low : full;
}

}  // namespace

std::array<uint8_t, kBcBlockTexels> decode_bc4_unorm8(const uint8_t* block, Bc4Interpolation rule) {
  std::array<uint8_t, kBcBlockTexels> out;
  if (rule == Bc4Interpolation::EXACT) {
    const std::array<int32_t, kBcBlockTexels> n = decode_bc4_exact(block, false);
    for (int t = 0; t < kBcBlockTexels; ++t) out[t] = u8(round_div35(n[t]));
  } else {
    const uint64_t codes = bc4_codes(block);
    for (int t = 0; t < kBcBlockTexels; ++t) out[t] = u8(bc4_truncated(block[0], block[1], bc4_code(codes, t), 0, 255));
  }
  return out;
}

std::array<int8_t, kBcBlockTexels> decode_bc4_snorm8(const uint8_t* block, Bc4Interpolation rule) {
  std::array<int8_t, kBcBlockTexels> out;
  if (rule == Bc4Interpolation::EXACT) {
    const std::array<int32_t, kBcBlockTexels> n = decode_bc4_exact(block, true);
    for (int t = 0; t < kBcBlockTexels; ++t) out[t] = static_cast<int8_t>(round_div35(n[t]));
  } else {
    const int raw0 = static_cast<int8_t>(block[0]), raw1 = static_cast<int8_t>(block[1]);
    const uint64_t codes = bc4_codes(block);
    for (int t = 0; t < kBcBlockTexels; ++t) {
      const int v = bc4_truncated(raw0, raw1, bc4_code(codes, t), -127, 127);
      out[t] = static_cast<int8_t>(v < -127 ? -127 : v);  // -128 and -127 are both -1.0
    }
  }
  return out;
}

namespace {

// One channel of BC4 / BC5 as the byte stored in an Rgba8 (UNORM8, or SNORM8's two's complement).
std::array<uint8_t, kBcBlockTexels> bc4_bytes(const uint8_t* block, bool is_signed, Bc4Interpolation rule) {
  if (!is_signed) return decode_bc4_unorm8(block, rule);
  const std::array<int8_t, kBcBlockTexels> s = decode_bc4_snorm8(block, rule);
  std::array<uint8_t, kBcBlockTexels> out;
  for (int t = 0; t < kBcBlockTexels; ++t) out[t] = static_cast<uint8_t>(s[t]);
  return out;
}

}  // namespace

BcBlockTexels decode_bc4_block(const uint8_t* block, bool is_signed, Bc4Interpolation rule) {
  const std::array<uint8_t, kBcBlockTexels> r = bc4_bytes(block, is_signed, rule);
  BcBlockTexels out;
  for (int t = 0; t < kBcBlockTexels; ++t) out[t] = {r[t], 0, 0, u8(is_signed ? 127 : 255)};
  return out;
}

BcBlockTexels decode_bc5_block(const uint8_t* block, bool is_signed, Bc4Interpolation rule) {
  const std::array<uint8_t, kBcBlockTexels> r = bc4_bytes(block, is_signed, rule);
  const std::array<uint8_t, kBcBlockTexels> g = bc4_bytes(block + 8, is_signed, rule);
  BcBlockTexels out;
  for (int t = 0; t < kBcBlockTexels; ++t) out[t] = {r[t], g[t], 0, u8(is_signed ? 127 : 255)};
  return out;
}

BcBlockTexels decode_bc_block(BcFormat format, const uint8_t* block, BcRules rules) {
  switch (format) {
    case BcFormat::BC1_RGB: return decode_bc1_block(block, false, rules.colour);
    case BcFormat::BC1_RGBA: return decode_bc1_block(block, true, rules.colour);
    case BcFormat::BC2: return decode_bc2_block(block, rules.colour);
    case BcFormat::BC3: return decode_bc3_block(block, rules);
    case BcFormat::BC4_UNORM: return decode_bc4_block(block, false, rules.alpha);
    case BcFormat::BC4_SNORM: return decode_bc4_block(block, true, rules.alpha);
    case BcFormat::BC5_UNORM: return decode_bc5_block(block, false, rules.alpha);
    case BcFormat::BC5_SNORM: return decode_bc5_block(block, true, rules.alpha);
    case BcFormat::BC7: return decode_bc7_block(block);
  }
  return {};
}

size_t bc_image_bytes(BcFormat format, int width, int height) {
  const size_t bx = (static_cast<size_t>(width) + 3) / 4, by = (static_cast<size_t>(height) + 3) / 4;
  return bx * by * static_cast<size_t>(bc_block_bytes(format));
}

std::vector<Rgba8> decode_bc_image(BcFormat format, int width, int height, std::span<const uint8_t> blocks,
                                   BcRules rules) {
  const char* name = kBcFormatNames.name(format);
  if (width <= 0 || height <= 0 || width > (1 << 16) || height > (1 << 16))
    throw InputError(fmt::format("{} image of {} x {} texels: sizes must be 1..65536", name, width, height));
  const size_t need = bc_image_bytes(format, width, height);
  if (blocks.size() != need)
    throw InputError(fmt::format("{} image of {} x {} texels needs {} bytes of blocks, got {}", name, width, height,
                                 need, blocks.size()));
  std::vector<Rgba8> image(static_cast<size_t>(width) * static_cast<size_t>(height));
  const int blocks_x = (width + 3) / 4, bytes = bc_block_bytes(format);
  const uint8_t* block = blocks.data();
  for (int by = 0; by < (height + 3) / 4; ++by) {
    for (int bx = 0; bx < blocks_x; ++bx, block += bytes) {
      const BcBlockTexels texels = decode_bc_block(format, block, rules);
      for (int y = 0; y < kBcBlockDim && 4 * by + y < height; ++y)
        for (int x = 0; x < kBcBlockDim && 4 * bx + x < width; ++x)
          image[static_cast<size_t>(4 * by + y) * static_cast<size_t>(width) + static_cast<size_t>(4 * bx + x)] =
              texels[4 * y + x];
    }
  }
  return image;
}

}  // namespace tfu
