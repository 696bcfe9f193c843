// ETC2 / EAC block decoders (cmodel/etc2_decode.hpp; KDFS 1.3, "ETC2 Compressed Texture Image
// Formats"). Every step is the header's datapath; bit positions are those of the spec's tables.
#include "cmodel/etc2_decode.hpp"

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {
namespace {

// int64bit = 256 (... (256 q0 + q1) ...) + q7: q0 is the most significant byte.
uint64_t block_word(const uint8_t* q) {
  uint64_t w = 0;
  for (int i = 0; i < 8; ++i) w = (w << 8) | q[i];
  return w;
}
int bits(uint64_t w, int hi, int lo) { return static_cast<int>((w >> lo) & ((uint64_t{1} << (hi - lo + 1)) - 1)); }
int bit(uint64_t w, int pos) { return static_cast<int>((w >> pos) & 1); }
// 3-bit two's complement (dR, dG, dB): -4..3.
int sext3(int v) { return v >= 4 ? v - 8 : v; }
int clamp255(int v) { return std::clamp(v, 0, 255); }
int extend4(int v) { return v * 17; }  // (v << 4) | v
int extend5(int v) { return (v << 3) | (v >> 2); }
int extend6(int v) { return (v << 2) | (v >> 4); }
int extend7(int v) { return (v << 1) | (v >> 6); }

// Pixel index of texel (x, y) in the colour word: MSB at bit 16 + j, LSB at bit j, j = 4 x + y.
int colour_index(uint64_t w, int x, int y) {
  const int j = 4 * x + y;
  return (bit(w, 16 + j) << 1) | bit(w, j);
}

struct Rgb {
  int r = 0, g = 0, b = 0;
};
Rgb add_clamped(Rgb c, int d) { return {clamp255(c.r + d), clamp255(c.g + d), clamp255(c.b + d)}; }

// The mode decision of the header ("mode"); bit 33 is the diff bit (the opaque bit for RGB8A1, which
// has no individual mode).
Etc2Mode mode_of(uint64_t w, bool punchthrough) {
  if (!punchthrough && bit(w, 33) == 0) return Etc2Mode::Individual;
  const auto outside = [](int v) { return v < 0 || v > 31; };
  if (outside(bits(w, 63, 59) + sext3(bits(w, 58, 56)))) return Etc2Mode::T;
  if (outside(bits(w, 55, 51) + sext3(bits(w, 50, 48)))) return Etc2Mode::H;
  if (outside(bits(w, 47, 43) + sext3(bits(w, 42, 40)))) return Etc2Mode::Planar;
  return Etc2Mode::Differential;
}

// The colour word's 16 texels. punchthrough: RGB8A1 reading; the opaque bit is bit 33.
void decode_colour(uint64_t w, bool punchthrough, Rgba8 out[16]) {
  const Etc2Mode mode = mode_of(w, punchthrough);
  const bool transparent_index = punchthrough && bit(w, 33) == 0;  // index 10 -> (0, 0, 0, 0)
  const auto put = [out](int x, int y, Rgb c) {
    out[4 * y + x] = {static_cast<uint8_t>(c.r), static_cast<uint8_t>(c.g), static_cast<uint8_t>(c.b), 255};
  };

  if (mode == Etc2Mode::Planar) {  // opaque bit ignored (KDFS: treated as 1)
    const int ro = extend6(bits(w, 62, 57));
    const int go = extend7((bit(w, 56) << 6) | bits(w, 54, 49));
    const int bo = extend6((bit(w, 48) << 5) | (bits(w, 44, 43) << 3) | bits(w, 41, 39));
    const int rh = extend6((bits(w, 38, 34) << 1) | bit(w, 32));
    const int gh = extend7(bits(w, 31, 25));
    const int bh = extend6(bits(w, 24, 19));
    const int rv = extend6(bits(w, 18, 13));
    const int gv = extend7(bits(w, 12, 6));
    const int bv = extend6(bits(w, 5, 0));
    // clamp255((x (H - O) + y (V - O) + 4 O + 2) >> 2): round half up of the plane, then clamp.
    const auto plane = [](int o, int h, int v, int x, int y) {
      return clamp255((x * (h - o) + y * (v - o) + 4 * o + 2) >> 2);
    };
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        put(x, y, {plane(ro, rh, rv, x, y), plane(go, gh, gv, x, y), plane(bo, bh, bv, x, y)});
    return;
  }

  if (mode == Etc2Mode::T || mode == Etc2Mode::H) {
    Rgb paint[4];
    if (mode == Etc2Mode::T) {
      const Rgb base1{extend4((bits(w, 60, 59) << 2) | bits(w, 57, 56)), extend4(bits(w, 55, 52)),
                      extend4(bits(w, 51, 48))};
      const Rgb base2{extend4(bits(w, 47, 44)), extend4(bits(w, 43, 40)), extend4(bits(w, 39, 36))};
      const int d = kEtcDistances[static_cast<size_t>((bits(w, 35, 34) << 1) | bit(w, 32))];
      paint[0] = base1;
      paint[1] = add_clamped(base2, d);
      paint[2] = base2;
      paint[3] = add_clamped(base2, -d);
    } else {
      const Rgb base1{extend4(bits(w, 62, 59)), extend4((bits(w, 58, 56) << 1) | bit(w, 52)),
                      extend4((bit(w, 51) << 3) | bits(w, 49, 47))};
      const Rgb base2{extend4(bits(w, 46, 43)), extend4(bits(w, 42, 39)), extend4(bits(w, 38, 35))};
      const auto value = [](Rgb c) { return (c.r << 16) | (c.g << 8) | c.b; };
      const int index = (bit(w, 34) << 2) | (bit(w, 32) << 1) | (value(base1) >= value(base2) ? 1 : 0);
      const int d = kEtcDistances[static_cast<size_t>(index)];
      paint[0] = add_clamped(base1, d);
      paint[1] = add_clamped(base1, -d);
      paint[2] = add_clamped(base2, d);
      paint[3] = add_clamped(base2, -d);
    }
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        const int i = colour_index(w, x, y);
        if (transparent_index && i == 2)
          out[4 * y + x] = {0, 0, 0, 0};
        else
          put(x, y, paint[i]);
      }
    return;
  }

  // Individual or differential: two subblocks, a base colour and a modifier table each.
  Rgb base[2];
  if (mode == Etc2Mode::Individual) {
    base[0] = {extend4(bits(w, 63, 60)), extend4(bits(w, 55, 52)), extend4(bits(w, 47, 44))};
    base[1] = {extend4(bits(w, 59, 56)), extend4(bits(w, 51, 48)), extend4(bits(w, 43, 40))};
  } else {
    const int r = bits(w, 63, 59), g = bits(w, 55, 51), b = bits(w, 47, 43);
    base[0] = {extend5(r), extend5(g), extend5(b)};
    base[1] = {extend5(r + sext3(bits(w, 58, 56))), extend5(g + sext3(bits(w, 50, 48))),
               extend5(b + sext3(bits(w, 42, 40)))};
  }
  const int table[2] = {bits(w, 39, 37), bits(w, 36, 34)};
  const bool flip = bit(w, 32) == 1;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const int sub = flip ? (y >= 2 ? 1 : 0) : (x >= 2 ? 1 : 0);
      const auto& ab = kEtcModifiers[static_cast<size_t>(table[sub])];
      const int i = colour_index(w, x, y);
      if (transparent_index && i == 2) {
        out[4 * y + x] = {0, 0, 0, 0};
        continue;
      }
      // 00 -> +a, 01 -> +b, 10 -> -a, 11 -> -b; non-opaque punch-through: a = 0.
      const int a = transparent_index ? 0 : ab[0];
      const int m = (i & 1) ? ab[1] : a;
      put(x, y, add_clamped(base[sub], (i & 2) ? -m : m));
    }
}

// EAC fields shared by the alpha, R11 and signed R11 decoders.
struct EacBlock {
  uint64_t w;
  int multiplier() const { return bits(w, 55, 52); }
  const std::array<int, 8>& table() const { return kEacModifiers[static_cast<size_t>(bits(w, 51, 48))]; }
  // Texel (x, y): 3-bit index at bits 47 - 3j .. 45 - 3j, j = 4 x + y.
  int modifier(int x, int y) const {
    return table()[static_cast<size_t>(bits(w, 47 - 3 * (4 * x + y), 45 - 3 * (4 * x + y)))];
  }
};

void check_size(int width, int height) {
  if (width < 1 || height < 1 || width > kMaxTextureSize || height > kMaxTextureSize)
    throw InputError("compressed image size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is outside 1.." + std::to_string(kMaxTextureSize) + " per side");
}
void check_blocks(const EtcFormatInfo& info, int width, int height, std::span<const uint8_t> blocks) {
  check_size(width, height);
  const size_t want = etc_block_count(width, height) * static_cast<size_t>(info.block_bytes);
  if (blocks.size() != want)
    throw InputError(std::string(info.name) + " image " + std::to_string(width) + "x" + std::to_string(height) +
                     " needs " + std::to_string(want) + " bytes of blocks, got " + std::to_string(blocks.size()));
}

// Calls decode(block, x0, y0, nx, ny) for every block: its bytes, its top-left texel (x0, y0) and
// how many of its columns and rows lie inside the image (4, or fewer at the right and bottom edges).
template <typename DecodeBlock>
void for_each_block(const EtcFormatInfo& info, int width, int height, std::span<const uint8_t> blocks,
                    DecodeBlock&& decode) {
  const int bw = (width + kEtcBlockDim - 1) / kEtcBlockDim, bh = (height + kEtcBlockDim - 1) / kEtcBlockDim;
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      const size_t offset = (static_cast<size_t>(by) * static_cast<size_t>(bw) + static_cast<size_t>(bx)) *
                            static_cast<size_t>(info.block_bytes);
      decode(blocks.data() + offset, bx * kEtcBlockDim, by * kEtcBlockDim,
             std::min(kEtcBlockDim, width - bx * kEtcBlockDim), std::min(kEtcBlockDim, height - by * kEtcBlockDim));
    }
}

}  // namespace

Etc2Mode etc2_block_mode(const uint8_t block[8], bool punchthrough) { return mode_of(block_word(block), punchthrough); }

void decode_etc2_rgb_block(const uint8_t block[8], Rgba8 out[16]) { decode_colour(block_word(block), false, out); }
void decode_etc2_rgb8a1_block(const uint8_t block[8], Rgba8 out[16]) { decode_colour(block_word(block), true, out); }

void decode_eac_alpha8_block(const uint8_t block[8], uint8_t out[16]) {
  const EacBlock e{block_word(block)};
  const int base = bits(e.w, 63, 56), m = e.multiplier();
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) out[4 * y + x] = static_cast<uint8_t>(clamp255(base + e.modifier(x, y) * m));
}

void decode_etc2_rgba8_block(const uint8_t block[16], Rgba8 out[16]) {
  decode_colour(block_word(block + 8), false, out);
  uint8_t alpha[16];
  decode_eac_alpha8_block(block, alpha);
  for (int i = 0; i < 16; ++i) out[i].a = alpha[i];
}

void decode_eac_r11_block(const uint8_t block[8], uint16_t out[16]) {
  const EacBlock e{block_word(block)};
  const int base = bits(e.w, 63, 56), m = e.multiplier();
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const int mod = e.modifier(x, y);
      // 8 base + 4 (the spec's base + 0.5), plus 8 modifier m, or modifier alone when m = 0.
      const int v = 8 * base + 4 + (m == 0 ? mod : 8 * mod * m);
      out[4 * y + x] = static_cast<uint16_t>(std::clamp(v, 0, 2047));
    }
}

void decode_eac_r11_signed_block(const uint8_t block[8], int16_t out[16]) {
  const EacBlock e{block_word(block)};
  const int raw = bits(e.w, 63, 56);
  const int base = std::max(raw >= 128 ? raw - 256 : raw, -127);  // -128 is read as -127
  const int m = e.multiplier();
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const int mod = e.modifier(x, y);
      const int v = 8 * base + (m == 0 ? mod : 8 * mod * m);  // no +4 in the signed format
      out[4 * y + x] = static_cast<int16_t>(std::clamp(v, -1023, 1023));
    }
}

size_t etc_block_count(int width, int height) {
  return static_cast<size_t>((width + kEtcBlockDim - 1) / kEtcBlockDim) *
         static_cast<size_t>((height + kEtcBlockDim - 1) / kEtcBlockDim);
}

std::vector<Rgba8> decode_etc_image(EtcFormat f, int width, int height, std::span<const uint8_t> blocks) {
  const EtcFormatInfo& info = etc_format_info(f);
  if (info.is_signed)
    throw InputError(std::string(info.name) +
                     " has no RGBA8 form (signed 11-bit channels); decode it as 11-bit values");
  check_blocks(info, width, height, blocks);
  std::vector<Rgba8> image(static_cast<size_t>(width) * static_cast<size_t>(height));
  for_each_block(info, width, height, blocks, [&](const uint8_t* b, int x0, int y0, int nx, int ny) {
    Rgba8 texels[16];
    if (info.eac11) {
      uint16_t r[16], g[16] = {};
      decode_eac_r11_block(b, r);
      if (info.channels == 2) decode_eac_r11_block(b + 8, g);
      for (int i = 0; i < 16; ++i)
        texels[i] = {eac11_to_unorm8(r[i]), info.channels == 2 ? eac11_to_unorm8(g[i]) : uint8_t{0}, 0, 255};
    } else if (info.block_bytes == 16) {
      decode_etc2_rgba8_block(b, texels);
    } else if (info.channels == 4) {
      decode_etc2_rgb8a1_block(b, texels);
    } else {
      decode_etc2_rgb_block(b, texels);
    }
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        image[static_cast<size_t>(y0 + y) * static_cast<size_t>(width) + static_cast<size_t>(x0 + x)] =
            texels[4 * y + x];
  });
  return image;
}

std::vector<int16_t> decode_eac11_image(EtcFormat f, int width, int height, std::span<const uint8_t> blocks) {
  const EtcFormatInfo& info = etc_format_info(f);
  if (!info.eac11) throw InputError(std::string(info.name) + " is not an 11-bit EAC format");
  check_blocks(info, width, height, blocks);
  const auto channels = static_cast<size_t>(info.channels);
  std::vector<int16_t> image(static_cast<size_t>(width) * static_cast<size_t>(height) * channels);
  for_each_block(info, width, height, blocks, [&](const uint8_t* b, int x0, int y0, int nx, int ny) {
    int16_t values[2][16];
    for (size_t c = 0; c < channels; ++c) {
      if (info.is_signed) {
        decode_eac_r11_signed_block(b + 8 * c, values[c]);
      } else {
        uint16_t u[16];
        decode_eac_r11_block(b + 8 * c, u);
        for (int i = 0; i < 16; ++i) values[c][i] = static_cast<int16_t>(u[i]);
      }
    }
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        for (size_t c = 0; c < channels; ++c)
          image[(static_cast<size_t>(y0 + y) * static_cast<size_t>(width) + static_cast<size_t>(x0 + x)) * channels +
                c] = values[c][4 * y + x];
  });
  return image;
}

std::string etc_formats_markdown() {
  std::string md =
      "| model name | GL internal format | bytes / 4x4 block | decodes to | sRGB |\n"
      "|---|---|---|---|---|\n";
  for (const EtcFormatInfo& f : kEtcFormats) {
    std::string to;
    if (f.eac11)
      to = std::to_string(f.channels) + " x 11-bit " + (f.is_signed ? "signed" : "unsigned");
    else if (f.channels == 3)
      to = "RGB8, alpha 255";
    else if (f.block_bytes == 8)
      to = "RGB8, alpha 0 or 255";
    else
      to = "RGBA8";
    md += fmt::format("| `{}` | `{}` | {} | {} | {} |\n", f.name, f.gl_name, f.block_bytes, to, f.srgb ? "yes" : "no");
  }
  return md;
}

}  // namespace tfu
