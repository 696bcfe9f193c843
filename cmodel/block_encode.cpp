#include "cmodel/block_encode.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cstring>
#include <memory>
#include <stdexcept>

#include <astcenc.h>
#include <fmt/format.h>
#include <squish.h>

#include "cmodel/bc7_decode.hpp"
#include "cmodel/bc_decode.hpp"
#include "cmodel/error.hpp"
#include "cmodel/etc2_decode.hpp"

namespace tfu {
namespace {

int sq(int v) { return v * v; }

// The 4x4 block at (bx, by) of a level, the last column and row repeated past the edges.
std::array<Rgba8, 16> gather_block(const Image& img, int bx, int by) {
  std::array<Rgba8, 16> t{};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      t[static_cast<size_t>(4 * y + x)] =
          img.at(std::min(4 * bx + x, img.width - 1), std::min(4 * by + y, img.height - 1));
  return t;
}

// ---- libsquish: BC1-BC5 ----
int squish_flags(BlockFormat f, int quality) {
  int flags = 0;
  switch (f) {
    case BlockFormat::BC1:
    case BlockFormat::BC1A: flags = squish::kDxt1; break;
    case BlockFormat::BC2: flags = squish::kDxt3; break;
    case BlockFormat::BC3: flags = squish::kDxt5; break;
    case BlockFormat::BC4: flags = squish::kBc4; break;
    default: flags = squish::kBc5; break;
  }
  return flags | (quality < 34   ? squish::kColourRangeFit
                  : quality < 67 ? squish::kColourClusterFit
                                 : squish::kColourIterativeClusterFit);
}

void encode_squish(const Image& img, BlockFormat f, int quality, std::vector<uint8_t>& out) {
  std::vector<uint8_t> rgba(img.texels.size() * 4);
  std::memcpy(rgba.data(), img.texels.data(), rgba.size());
  if (f == BlockFormat::BC1)  // opaque BC1: no texel may select the 3-colour mode's transparent index
    for (size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;
  squish::CompressImage(rgba.data(), img.width, img.height, out.data(), squish_flags(f, quality));
}

// ---- libastcenc: ASTC ----
void check_astc(astcenc_error e, const char* what) {
  if (e != ASTCENC_SUCCESS)
    throw std::runtime_error(fmt::format("libastcenc {}: {}", what, astcenc_get_error_string(e)));
}

struct AstcContextFree {
  void operator()(astcenc_context* c) const { astcenc_context_free(c); }
};

// ---- BC7 mode 6 ----
class BitWriter {
 public:
  explicit BitWriter(uint8_t* out) : out_(out) { std::memset(out_, 0, 16); }
  void put(uint32_t value, int bits) {  // LSB first (BC7: bit 0 is bit 0 of byte 0)
    for (int i = 0; i < bits; ++i, ++pos_)
      if ((value >> i) & 1) out_[pos_ / 8] = static_cast<uint8_t>(out_[pos_ / 8] | (1 << (pos_ % 8)));
  }

 private:
  uint8_t* out_;
  int pos_ = 0;
};

struct Bc7Endpoint {
  std::array<int, 4> q{};  // 7-bit values, R G B A
  int p = 0;
  int value(int c) const { return (q[static_cast<size_t>(c)] << 1) | p; }  // mode 6: 8 bits = q << 1 | p
};

// The 7-bit + p-bit endpoint nearest `target` (the p-bit of least squared error).
Bc7Endpoint quantize_bc7(const std::array<int, 4>& target) {
  Bc7Endpoint best;
  int best_err = INT_MAX;
  for (int p = 0; p < 2; ++p) {
    Bc7Endpoint e;
    e.p = p;
    int err = 0;
    for (int c = 0; c < 4; ++c) {
      e.q[static_cast<size_t>(c)] = std::clamp((target[static_cast<size_t>(c)] - p + 1) >> 1, 0, 127);
      err += sq(e.value(c) - target[static_cast<size_t>(c)]);
    }
    if (err < best_err) best_err = err, best = e;
  }
  return best;
}

// ---- ETC1 modes ----
// Sub-block of texel (x, y): flip 0 splits left | right, flip 1 top / bottom (KDFS "Format RGB ETC2").
int etc_subblock(int flip, int x, int y) { return flip ? (y >= 2) : (x >= 2); }

struct EtcSubblockFit {
  int table = 0, error = INT_MAX;
  std::array<int, 16> index{};  // per texel of the block (only this sub-block's are set)
};

// The 32 index bits of an ETC1-mode block (KDFS: MSBs in bits 31..16, LSBs in 15..0, texels in
// column-major order), each texel's index from the fit of its sub-block.
uint64_t etc_index_bits(int flip, const EtcSubblockFit& f0, const EtcSubblockFit& f1) {
  uint64_t w = 0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const int i = (etc_subblock(flip, x, y) ? f1 : f0).index[static_cast<size_t>(4 * y + x)];
      const int j = 4 * x + y;  // texel order: column-major
      w |= uint64_t(i >> 1) << (16 + j) | uint64_t(i & 1) << j;
    }
  return w;
}

// The table and per-texel modifier indices of least squared error for one sub-block of base colour `base`.
EtcSubblockFit fit_etc_subblock(const Rgba8 t[16], int flip, int sub, const std::array<int, 3>& base) {
  EtcSubblockFit best;
  for (int table = 0; table < 8; ++table) {
    const auto& ab = kEtcModifiers[static_cast<size_t>(table)];
    const int mods[4] = {ab[0], ab[1], -ab[0], -ab[1]};  // pixel index 0..3: +a, +b, -a, -b
    EtcSubblockFit fit;
    fit.table = table;
    fit.error = 0;
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        if (etc_subblock(flip, x, y) != sub) continue;
        const Rgba8& v = t[4 * y + x];
        int best_e = INT_MAX, best_i = 0;
        for (int i = 0; i < 4; ++i) {
          const int e = sq(std::clamp(base[0] + mods[i], 0, 255) - v.r) +
                        sq(std::clamp(base[1] + mods[i], 0, 255) - v.g) +
                        sq(std::clamp(base[2] + mods[i], 0, 255) - v.b);
          if (e < best_e) best_e = e, best_i = i;
        }
        fit.error += best_e;
        fit.index[static_cast<size_t>(4 * y + x)] = best_i;
      }
    if (fit.error < best.error) best = fit;
  }
  return best;
}

void put_be64(uint64_t w, uint8_t* out) {
  for (int i = 0; i < 8; ++i) out[i] = static_cast<uint8_t>(w >> (56 - 8 * i));
}

// ---- EAC ----
// The three EAC channels: ETC2 RGBA8's 8-bit alpha, unsigned R11 and signed R11.
enum class EacKind { Alpha8, R11, R11Signed };

// The decoded value of modifier `mod` (KDFS "Format RGBA ETC2 EAC", "Format R11 EAC" and "Format
// Signed R11 EAC"; the decoder's datapath, cmodel/etc2_decode.hpp). Signed: `base` in -127..127.
int eac_value(EacKind k, int base, int mult, int mod) {
  switch (k) {
    case EacKind::Alpha8: return std::clamp(base + mod * mult, 0, 255);
    case EacKind::R11: return std::clamp(base * 8 + 4 + mod * (mult == 0 ? 1 : mult * 8), 0, 2047);
    case EacKind::R11Signed: break;
  }
  return std::clamp(base * 8 + mod * (mult == 0 ? 1 : mult * 8), -1023, 1023);
}

// floor(a / b) for b > 0 (integer division truncates toward zero).
int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

void encode_eac(const int values[16], EacKind kind, uint8_t out[8]);

// ---- BC4 signed ----
// The eight SNORM8 values of signed BC4 endpoints (r0, r1) as the decoder gives them in the golden
// rule (decode_bc4_snorm8, EXACT): a block with codes 0..7 in texels 0..7, decoded.
std::array<int, 8> bc4_signed_palette(int r0, int r1) {
  uint8_t block[8] = {static_cast<uint8_t>(r0), static_cast<uint8_t>(r1), 0, 0, 0, 0, 0, 0};
  uint64_t codes = 0;
  for (uint64_t c = 0; c < 8; ++c) codes |= c << (3 * c);
  for (int i = 0; i < 6; ++i) block[2 + i] = static_cast<uint8_t>(codes >> (8 * i));
  const std::array<int8_t, 16> v = decode_bc4_snorm8(block, Bc4Interpolation::EXACT);
  std::array<int, 8> p{};
  for (size_t c = 0; c < 8; ++c) p[c] = v[c];
  return p;
}

// ---- ETC2 punch-through alpha ----
// Table and per-texel indices of least squared error for one sub-block of a punch-through block
// whose opaque bit is 0 (KDFS "Format RGB ETC2 with punchthrough alpha", differential mode): index
// 0 is the base colour, 1 base + b, 3 base - b, and 2 transparent black, which every transparent
// texel takes (opaque texels choose among 0, 1, 3).
EtcSubblockFit fit_etc_subblock_transparent(const Rgba8 t[16], const bool opaque[16], int flip, int sub,
                                            const std::array<int, 3>& base) {
  EtcSubblockFit best;
  for (int table = 0; table < 8; ++table) {
    const int b = kEtcModifiers[static_cast<size_t>(table)][1];
    const int mods[4] = {0, b, 0, -b};
    EtcSubblockFit fit;
    fit.table = table;
    fit.error = 0;
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        if (etc_subblock(flip, x, y) != sub) continue;
        const int k = 4 * y + x;
        if (!opaque[k]) {
          fit.index[static_cast<size_t>(k)] = 2;
          continue;
        }
        int best_e = INT_MAX, best_i = 0;
        for (int i : {0, 1, 3}) {
          const int e = sq(std::clamp(base[0] + mods[i], 0, 255) - t[k].r) +
                        sq(std::clamp(base[1] + mods[i], 0, 255) - t[k].g) +
                        sq(std::clamp(base[2] + mods[i], 0, 255) - t[k].b);
          if (e < best_e) best_e = e, best_i = i;
        }
        fit.error += best_e;
        fit.index[static_cast<size_t>(k)] = best_i;
      }
    if (fit.error < best.error) best = fit;
  }
  return best;
}

void encode_own(const Image& img, BlockFormat f, std::vector<uint8_t>& out) {
  const BlockFormatInfo& info = block_format_info(f);
  const int across = blocks_across(f, img.width), down = blocks_down(f, img.height);
  for (int by = 0; by < down; ++by)
    for (int bx = 0; bx < across; ++bx) {
      const std::array<Rgba8, 16> t = gather_block(img, bx, by);
      uint8_t* block = out.data() + (static_cast<size_t>(by) * static_cast<size_t>(across) + static_cast<size_t>(bx)) *
                                        static_cast<size_t>(info.block_bytes);
      int values[16];
      switch (f) {
        case BlockFormat::BC7: encode_bc7_mode6_block(t.data(), block); break;
        case BlockFormat::ETC2: encode_etc1_block(t.data(), block); break;
        case BlockFormat::ETC2A:  // EAC alpha, then the colour (KDFS "Format RGBA ETC2 EAC")
          for (int i = 0; i < 16; ++i) values[i] = t[static_cast<size_t>(i)].a;
          encode_eac_block(values, false, block);
          encode_etc1_block(t.data(), block + 8);
          break;
        case BlockFormat::EAC_R11:
        case BlockFormat::EAC_RG11:  // red, then green
          for (int c = 0; c < info.channels; ++c) {
            for (int i = 0; i < 16; ++i) {
              const int v = c == 0 ? t[static_cast<size_t>(i)].r : t[static_cast<size_t>(i)].g;
              values[i] = (v * 2047 + 127) / 255;
            }
            encode_eac_block(values, true, block + 8 * c);
          }
          break;
        case BlockFormat::ETC2A1: encode_etc2_punchthrough_block(t.data(), block); break;
        case BlockFormat::EAC_R11S:
        case BlockFormat::EAC_RG11S:  // red, then green; 8-bit image bytes as SNORM8, then 11 bits
          for (int c = 0; c < info.channels; ++c) {
            for (int i = 0; i < 16; ++i)
              values[i] = eac11_signed_from_snorm8(
                  snorm8_from_image_byte(c == 0 ? t[static_cast<size_t>(i)].r : t[static_cast<size_t>(i)].g));
            encode_eac_r11_signed_block(values, block + 8 * c);
          }
          break;
        case BlockFormat::BC4S:
        case BlockFormat::BC5S:  // red, then green
          for (int c = 0; c < info.channels; ++c) {
            for (int i = 0; i < 16; ++i)
              values[i] = snorm8_from_image_byte(c == 0 ? t[static_cast<size_t>(i)].r : t[static_cast<size_t>(i)].g);
            encode_bc4_signed_block(values, block + 8 * c);
          }
          break;
        default: throw std::logic_error("encode_own: no own encoder for this format");
      }
    }
}

}  // namespace

const char* block_encoder_name(BlockFormat f) {
  switch (block_format_info(f).family) {
    case BlockFamily::ASTC: return "libastcenc 4.2";
    case BlockFamily::BC:
      return f == BlockFormat::BC7                              ? "tfu BC7 mode 6"
             : f == BlockFormat::BC4S || f == BlockFormat::BC5S ? "tfu BC4 signed"
                                                                : "libsquish 1.15";
    case BlockFamily::ETC:
      return f == BlockFormat::ETC2     ? "tfu ETC1 modes"
             : f == BlockFormat::ETC2A  ? "tfu ETC1 modes + EAC"
             : f == BlockFormat::ETC2A1 ? "tfu ETC2 differential punch-through"
                                        : "tfu EAC";
  }
  return "none";
}

void encode_bc7_mode6_block(const Rgba8 texels[16], uint8_t out[16]) {
  std::array<int, 4> lo{255, 255, 255, 255}, hi{0, 0, 0, 0};
  for (int i = 0; i < 16; ++i) {
    const int v[4] = {texels[i].r, texels[i].g, texels[i].b, texels[i].a};
    for (size_t c = 0; c < 4; ++c) lo[c] = std::min(lo[c], v[c]), hi[c] = std::max(hi[c], v[c]);
  }
  int best_err = INT_MAX;
  Bc7Endpoint best_e0, best_e1;
  std::array<int, 16> best_idx{};
  for (int orientation = 0; orientation < 8; ++orientation) {  // bit k: channel k + 1 falls as R rises
    std::array<int, 4> a = lo, b = hi;
    for (size_t c = 1; c < 4; ++c)
      if ((orientation >> (c - 1)) & 1) std::swap(a[c], b[c]);
    const Bc7Endpoint e0 = quantize_bc7(a), e1 = quantize_bc7(b);
    std::array<std::array<int, 4>, 16> palette{};
    for (size_t w = 0; w < 16; ++w)
      for (int c = 0; c < 4; ++c)  // ((64 - w) e0 + w e1 + 32) >> 6 (KDFS "BC7", interpolation)
        palette[w][static_cast<size_t>(c)] =
            ((64 - kBc7Weights4[w]) * e0.value(c) + kBc7Weights4[w] * e1.value(c) + 32) >> 6;
    int err = 0;
    std::array<int, 16> idx{};
    for (int i = 0; i < 16; ++i) {
      int be = INT_MAX;
      for (int w = 0; w < 16; ++w) {
        const auto& p = palette[static_cast<size_t>(w)];
        const int e = sq(p[0] - texels[i].r) + sq(p[1] - texels[i].g) + sq(p[2] - texels[i].b) + sq(p[3] - texels[i].a);
        if (e < be) be = e, idx[static_cast<size_t>(i)] = w;
      }
      err += be;
    }
    if (err < best_err) best_err = err, best_e0 = e0, best_e1 = e1, best_idx = idx;
  }
  // Texel 0 is the anchor: its index is stored in 3 bits, so its top bit must be 0. The weights are
  // symmetric (w[15 - i] = 64 - w[i]), so swapping the endpoints and inverting every index decodes alike.
  if (best_idx[0] >= 8) {
    std::swap(best_e0, best_e1);
    for (int& i : best_idx) i = 15 - i;
  }
  BitWriter bits(out);
  bits.put(1u << 6, 7);  // mode 6: six 0 bits, then 1
  for (size_t c = 0; c < 4; ++c) {
    bits.put(static_cast<uint32_t>(best_e0.q[c]), 7);
    bits.put(static_cast<uint32_t>(best_e1.q[c]), 7);
  }
  bits.put(static_cast<uint32_t>(best_e0.p), 1);
  bits.put(static_cast<uint32_t>(best_e1.p), 1);
  for (size_t i = 0; i < 16; ++i) bits.put(static_cast<uint32_t>(best_idx[i]), i == 0 ? 3 : 4);
}

void encode_etc1_block(const Rgba8 texels[16], uint8_t out[8]) {
  uint64_t best_word = 0;
  int best_err = INT_MAX;
  for (int flip = 0; flip < 2; ++flip) {
    std::array<std::array<int, 3>, 2> avg{};  // per sub-block, rounded mean of its 8 texels
    for (int sub = 0; sub < 2; ++sub) {
      std::array<int, 3> sum{};
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
          if (etc_subblock(flip, x, y) == sub) {
            const Rgba8& v = texels[4 * y + x];
            sum[0] += v.r, sum[1] += v.g, sum[2] += v.b;
          }
      for (size_t c = 0; c < 3; ++c) avg[static_cast<size_t>(sub)][c] = (sum[c] + 4) / 8;
    }
    for (int differential = 0; differential < 2; ++differential) {
      // Quantized base colours: 4 bits each (individual, expanded x * 17) or 5 bits with a 3-bit
      // signed delta (differential, expanded (x << 3) | (x >> 2)).
      const int levels = differential ? 31 : 15;
      std::array<std::array<int, 3>, 2> q{}, base{};
      for (size_t s = 0; s < 2; ++s)
        for (size_t c = 0; c < 3; ++c) q[s][c] = (avg[s][c] * levels + 127) / 255;
      bool ok = true;
      for (size_t c = 0; c < 3; ++c) ok = ok && (!differential || (q[1][c] - q[0][c] >= -4 && q[1][c] - q[0][c] <= 3));
      if (!ok) continue;
      for (size_t s = 0; s < 2; ++s)
        for (size_t c = 0; c < 3; ++c) base[s][c] = differential ? (q[s][c] << 3) | (q[s][c] >> 2) : q[s][c] * 17;
      const EtcSubblockFit f0 = fit_etc_subblock(texels, flip, 0, base[0]),
                           f1 = fit_etc_subblock(texels, flip, 1, base[1]);
      if (f0.error + f1.error >= best_err) continue;
      best_err = f0.error + f1.error;
      uint64_t w = 0;
      for (size_t c = 0; c < 3; ++c) {
        const int shift =
            59 - 8 * static_cast<int>(c);  // R at 63, G at 55, B at 47 (the field's low bit at shift - 1 / shift)
        if (differential) {
          w |= uint64_t(q[0][c]) << shift;
          w |= uint64_t((q[1][c] - q[0][c]) & 7) << (shift - 3);
        } else {
          w |= uint64_t(q[0][c]) << (shift + 1);
          w |= uint64_t(q[1][c]) << (shift - 3);
        }
      }
      w |= uint64_t(f0.table) << 37 | uint64_t(f1.table) << 34 | uint64_t(differential) << 33 | uint64_t(flip) << 32;
      w |= etc_index_bits(flip, f0, f1);
      best_word = w;
    }
  }
  put_be64(best_word, out);
}

void encode_eac_block(const int values[16], bool r11, uint8_t out[8]) {
  encode_eac(values, r11 ? EacKind::R11 : EacKind::Alpha8, out);
}

void encode_eac_r11_signed_block(const int values[16], uint8_t out[8]) { encode_eac(values, EacKind::R11Signed, out); }

namespace {

void encode_eac(const int values[16], EacKind kind, uint8_t out[8]) {
  const bool r11 = kind != EacKind::Alpha8;
  int lo = INT_MAX, hi = INT_MIN;
  for (int i = 0; i < 16; ++i) lo = std::min(lo, values[i]), hi = std::max(hi, values[i]);
  const int unit = r11 ? 8 : 1;  // what one multiplier step moves a modifier of 1
  uint64_t best_word = 0;
  int64_t best_err = INT64_MAX;
  for (int table = 0; table < 16; ++table) {
    const auto& mods = kEacModifiers[static_cast<size_t>(table)];
    const int mmin = *std::min_element(mods.begin(), mods.end()), mmax = *std::max_element(mods.begin(), mods.end());
    const int m0 = (hi - lo + (mmax - mmin) * unit / 2) / ((mmax - mmin) * unit);
    for (int mult = std::max(0, m0 - 1); mult <= std::min(15, m0 + 1); ++mult) {
      // The base that centres the table's range on the block's: (lo + hi) / 2 - (mmin + mmax) / 2 * step.
      const int step = r11 ? (mult == 0 ? 1 : mult * 8) : mult;
      const int centre = (lo + hi) / 2 - (mmin + mmax) * step / 2;
      // R11: 8 base + 4 nearest the centre (unsigned), 8 base nearest it (signed, base -127..127).
      const int base = kind == EacKind::Alpha8 ? std::clamp(centre, 0, 255)
                       : kind == EacKind::R11  ? std::clamp(floor_div(centre, 8), 0, 255)
                                               : std::clamp(floor_div(centre + 4, 8), -127, 127);
      int64_t err = 0;
      uint64_t w = uint64_t(static_cast<uint8_t>(base)) << 56 | uint64_t(mult) << 52 | uint64_t(table) << 48;
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
          const int v = values[4 * y + x];
          int be = INT_MAX, bi = 0;
          for (int i = 0; i < 8; ++i) {
            const int e = sq(eac_value(kind, base, mult, mods[static_cast<size_t>(i)]) - v);
            if (e < be) be = e, bi = i;
          }
          err += be;
          const int j = 4 * x + y;  // 3-bit index at bits 47 - 3j .. 45 - 3j
          w |= uint64_t(bi) << (45 - 3 * j);
        }
      if (err < best_err) best_err = err, best_word = w;
    }
  }
  put_be64(best_word, out);
}

}  // namespace

void encode_bc4_signed_block(const int values[16], uint8_t out[8]) {
  int lo = INT_MAX, hi = INT_MIN;
  for (int i = 0; i < 16; ++i) lo = std::min(lo, values[i]), hi = std::max(hi, values[i]);
  // Both orders of the extremes: (hi, lo) is the eight-value mode (red0 > red1, six interpolants),
  // (lo, hi) the six-value mode (four interpolants, then -1.0 and 1.0), which wins when the block
  // holds -127 or 127 beside values in a narrower range. Equal extremes: every texel code 0.
  int best_err = INT_MAX;
  uint64_t best = 0;
  for (const auto& [r0, r1] : {std::pair{hi, lo}, std::pair{lo, hi}}) {
    const std::array<int, 8> palette = bc4_signed_palette(r0, r1);
    int err = 0;
    uint64_t w = uint64_t(static_cast<uint8_t>(r0)) | uint64_t(static_cast<uint8_t>(r1)) << 8;
    for (int t = 0; t < 16; ++t) {
      int be = INT_MAX, bc = 0;
      for (int c = 0; c < 8; ++c) {
        const int e = sq(palette[static_cast<size_t>(c)] - values[t]);
        if (e < be) be = e, bc = c;
      }
      err += be;
      w |= uint64_t(bc) << (16 + 3 * t);  // texel t's code: bits 3t..3t+2 of bytes 2..7, little-endian
    }
    if (err < best_err) best_err = err, best = w;
  }
  for (int i = 0; i < 8; ++i) out[i] = static_cast<uint8_t>(best >> (8 * i));
}

void encode_etc2_punchthrough_block(const Rgba8 texels[16], uint8_t out[8]) {
  bool opaque[16];
  bool all_opaque = true;
  for (int i = 0; i < 16; ++i) {
    opaque[i] = texels[i].a >= 128;
    all_opaque = all_opaque && opaque[i];
  }
  uint64_t best_word = 0;
  int best_err = INT_MAX;
  for (int flip = 0; flip < 2; ++flip) {
    // Per sub-block, the rounded mean of its opaque texels on the 5-bit grid; a sub-block without
    // one takes the other's, and the second is moved into the 3-bit delta's reach (-4..3).
    std::array<std::array<int, 3>, 2> q{};
    std::array<int, 2> count{};
    for (int sub = 0; sub < 2; ++sub) {
      std::array<int, 3> sum{};
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
          if (etc_subblock(flip, x, y) == sub && opaque[4 * y + x]) {
            const Rgba8& v = texels[4 * y + x];
            sum[0] += v.r, sum[1] += v.g, sum[2] += v.b;
            ++count[static_cast<size_t>(sub)];
          }
      const int n = count[static_cast<size_t>(sub)];
      for (size_t c = 0; c < 3; ++c)
        q[static_cast<size_t>(sub)][c] = n == 0 ? 0 : ((2 * sum[c] + n) / (2 * n) * 31 + 127) / 255;
    }
    if (count[0] == 0) q[0] = q[1];
    if (count[1] == 0) q[1] = q[0];
    std::array<std::array<int, 3>, 2> base{};
    for (size_t c = 0; c < 3; ++c) {
      q[1][c] = q[0][c] + std::clamp(q[1][c] - q[0][c], -4, 3);
      for (size_t s = 0; s < 2; ++s) base[s][c] = (q[s][c] << 3) | (q[s][c] >> 2);
    }
    const EtcSubblockFit f0 = all_opaque ? fit_etc_subblock(texels, flip, 0, base[0])
                                         : fit_etc_subblock_transparent(texels, opaque, flip, 0, base[0]);
    const EtcSubblockFit f1 = all_opaque ? fit_etc_subblock(texels, flip, 1, base[1])
                                         : fit_etc_subblock_transparent(texels, opaque, flip, 1, base[1]);
    if (f0.error + f1.error >= best_err) continue;
    best_err = f0.error + f1.error;
    uint64_t w = 0;
    for (size_t c = 0; c < 3; ++c) {
      const int shift = 59 - 8 * static_cast<int>(c);  // R at 63-59, G at 55-51, B at 47-43; deltas below
      w |= uint64_t(q[0][c]) << shift;
      w |= uint64_t((q[1][c] - q[0][c]) & 7) << (shift - 3);
    }
    // Bit 33 is the opaque bit: 1, every texel opaque (the ETC2 RGB differential block); 0, index 2
    // is transparent and indices 0 and 2 have modifier 0.
    w |= uint64_t(f0.table) << 37 | uint64_t(f1.table) << 34 | uint64_t(all_opaque) << 33 | uint64_t(flip) << 32;
    w |= etc_index_bits(flip, f0, f1);
    best_word = w;
  }
  put_be64(best_word, out);
}

BlockImage encode_block_image(std::span<const Image> levels, BlockFormat f, bool srgb,
                              const BlockEncodeOptions& options) {
  const BlockFormatInfo& info = block_format_info(f);
  if (srgb && info.gl_srgb_internal_format == 0) throw InputError(fmt::format("{} has no sRGB variant", info.name));
  if (levels.empty()) throw InputError(fmt::format("{}: no levels to encode", info.name));
  if (options.quality < 0 || options.quality > 100)
    throw InputError(fmt::format("encoder quality {} outside 0..100", options.quality));
  BlockImage out;
  out.format = f;
  out.srgb = srgb;
  std::unique_ptr<astcenc_context, AstcContextFree> astc;
  if (info.family == BlockFamily::ASTC) {
    astcenc_config config{};
    check_astc(
        astcenc_config_init(srgb ? ASTCENC_PRF_LDR_SRGB : ASTCENC_PRF_LDR, static_cast<unsigned>(info.block_w),
                            static_cast<unsigned>(info.block_h), 1, static_cast<float>(options.quality), 0, &config),
        "config");
    astcenc_context* ctx = nullptr;
    check_astc(astcenc_context_alloc(&config, 1, &ctx), "context");
    astc.reset(ctx);
  }
  for (const Image& img : levels) {
    if (img.width < 1 || img.height < 1 || img.width > kMaxTextureSize || img.height > kMaxTextureSize ||
        img.texels.size() != static_cast<size_t>(img.width) * static_cast<size_t>(img.height))
      throw InputError(fmt::format("{}: level of size {}x{} cannot be encoded", info.name, img.width, img.height));
    BlockLevel level;
    level.width = img.width;
    level.height = img.height;
    level.blocks.assign(block_level_bytes(f, img.width, img.height), 0);
    if (info.family == BlockFamily::ASTC) {
      void* data = const_cast<Rgba8*>(img.texels.data());  // astcenc_image is not const; it only reads
      astcenc_image image{static_cast<unsigned>(img.width), static_cast<unsigned>(img.height), 1, ASTCENC_TYPE_U8,
                          &data};
      const astcenc_swizzle swizzle{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};
      check_astc(astcenc_compress_image(astc.get(), &image, &swizzle, level.blocks.data(), level.blocks.size(), 0),
                 "compress");
      check_astc(astcenc_compress_reset(astc.get()), "reset");
    } else if (f == BlockFormat::BC7 || f == BlockFormat::BC4S || f == BlockFormat::BC5S ||
               info.family == BlockFamily::ETC) {
      encode_own(img, f, level.blocks);
    } else {
      encode_squish(img, f, options.quality, level.blocks);
    }
    out.levels.push_back(std::move(level));
  }
  return out;
}

}  // namespace tfu
