// ASTC LDR 2D decoder: the steps and their widths are listed in cmodel/astc_decode.hpp; each
// function below names the KDFS 1.4.0 section it implements. docs/compressed-astc.md.
#include "cmodel/astc_decode.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>

#include "cmodel/astc_tables.hpp"
#include "cmodel/error.hpp"

namespace tfu {

namespace {

using astc::IseRange;
using astc::kIseRanges;

// ---- The 128-bit block ("Block Layout": little-endian, bit 0 the lowest bit of byte 0) ------------

struct Bits128 {
  uint64_t lo = 0, hi = 0;
};

Bits128 load_block(const uint8_t* b) {
  Bits128 r;
  for (int i = 7; i >= 0; --i) {
    r.lo = (r.lo << 8) | b[i];
    r.hi = (r.hi << 8) | b[8 + i];
  }
  return r;
}

// Bits [pos, pos + n) as an unsigned number, n <= 32; bits at or above 128 read as 0.
inline uint32_t get_bits(const Bits128& b, int pos, int n) {
  if (pos >= 128) return 0;
  const uint64_t v = pos >= 64 ? b.hi >> (pos - 64) : pos == 0 ? b.lo : (b.lo >> pos) | (b.hi << (64 - pos));
  return static_cast<uint32_t>(v & ((uint64_t{1} << n) - 1));
}

// b >> n, n in 0..127.
inline Bits128 shift_right(const Bits128& b, int n) {
  if (n == 0) return b;
  if (n >= 64) return {b.hi >> (n - 64), 0};
  return {(b.lo >> n) | (b.hi << (64 - n)), b.hi >> n};
}

// The low n bits of b (n in 0..128), the rest 0: a sequence's bits with its unused tail reading 0.
inline Bits128 low_bits(const Bits128& b, int n) {
  if (n >= 128) return b;
  if (n >= 64) return {b.lo, n == 64 ? 0 : b.hi & ((uint64_t{1} << (n - 64)) - 1)};
  return {n == 0 ? 0 : b.lo & ((uint64_t{1} << n) - 1), 0};
}

inline uint64_t reverse64(uint64_t x) {
  x = ((x >> 1) & 0x5555555555555555ull) | ((x & 0x5555555555555555ull) << 1);
  x = ((x >> 2) & 0x3333333333333333ull) | ((x & 0x3333333333333333ull) << 2);
  x = ((x >> 4) & 0x0F0F0F0F0F0F0F0Full) | ((x & 0x0F0F0F0F0F0F0F0Full) << 4);
  return __builtin_bswap64(x);
}

// "Weight Decoding": the weight stream's bit n is block bit 127 - n.
inline Bits128 reverse128(const Bits128& b) { return {reverse64(b.hi), reverse64(b.lo)}; }

// ---- Integer sequence decoding ("Integer Sequence Encoding") ---------------------------------------

// `count` values of `range` from the bit string s, bit 0 first; bits past the sequence must be 0
// in s (a final partial trit or quint block reads its missing high bits as 0).
void decode_ise(const Bits128& s, int count, int range, uint8_t* out) {
  const IseRange& r = kIseRanges[static_cast<size_t>(range)];
  const int n = r.bits;
  if (r.trits) {
    // One block of 5 values, 8 + 5n bits: m0 T[1:0] m1 T[3:2] m2 T[4] m3 T[6:5] m4 T[7].
    for (int i = 0, pos = 0; i < count; i += 5, pos += 8 + 5 * n) {
      std::array<uint32_t, 5> m{};
      uint32_t t = 0;
      int p = pos;
      m[0] = get_bits(s, p, n), p += n, t |= get_bits(s, p, 2), p += 2;
      m[1] = get_bits(s, p, n), p += n, t |= get_bits(s, p, 2) << 2, p += 2;
      m[2] = get_bits(s, p, n), p += n, t |= get_bits(s, p, 1) << 4, p += 1;
      m[3] = get_bits(s, p, n), p += n, t |= get_bits(s, p, 2) << 5, p += 2;
      m[4] = get_bits(s, p, n), p += n, t |= get_bits(s, p, 1) << 7;
      const uint32_t trits = astc::kTritBlock[t];
      for (int k = 0; k < 5 && i + k < count; ++k)
        out[i + k] = static_cast<uint8_t>((((trits >> (2 * k)) & 3u) << n) | m[static_cast<size_t>(k)]);
    }
  } else if (r.quints) {
    // One block of 3 values, 7 + 3n bits: m0 Q[2:0] m1 Q[4:3] m2 Q[6:5].
    for (int i = 0, pos = 0; i < count; i += 3, pos += 7 + 3 * n) {
      std::array<uint32_t, 3> m{};
      uint32_t q = 0;
      int p = pos;
      m[0] = get_bits(s, p, n), p += n, q |= get_bits(s, p, 3), p += 3;
      m[1] = get_bits(s, p, n), p += n, q |= get_bits(s, p, 2) << 3, p += 2;
      m[2] = get_bits(s, p, n), p += n, q |= get_bits(s, p, 2) << 5;
      const uint32_t quints = astc::kQuintBlock[q];
      for (int k = 0; k < 3 && i + k < count; ++k)
        out[i + k] = static_cast<uint8_t>((((quints >> (3 * k)) & 7u) << n) | m[static_cast<size_t>(k)]);
    }
  } else {
    for (int i = 0; i < count; ++i) out[i] = static_cast<uint8_t>(get_bits(s, i * n, n));
  }
}

// ---- Block mode ("Block Mode", Table "ASTC 2D block mode layout") ----------------------------------

struct BlockMode {
  bool reserved = false;
  int w = 0, h = 0, rho = 0, p = 0;
  bool dual = false;
};

BlockMode decode_block_mode(uint32_t m) {
  const auto f = [m](int lo, int n) { return static_cast<int>((m >> lo) & ((1u << n) - 1u)); };
  BlockMode r;
  r.p = f(9, 1);
  r.dual = f(10, 1) != 0;
  const int a = f(5, 2), b = f(7, 2);
  if (f(0, 2) != 0) {  // rows 1-5: rho2 rho1 in bits 1, 0
    r.rho = (f(1, 1) << 2) | (f(0, 1) << 1) | f(4, 1);
    switch (f(2, 2)) {
      case 0: r.w = b + 4, r.h = a + 2; break;
      case 1: r.w = b + 8, r.h = a + 2; break;
      case 2: r.w = a + 2, r.h = b + 8; break;
      default:
        if (f(8, 1) == 0) {
          r.w = a + 2, r.h = f(7, 1) + 6;
        } else {
          r.w = f(7, 1) + 2, r.h = a + 2;
        }
    }
    return r;
  }
  r.rho = (f(3, 1) << 2) | (f(2, 1) << 1) | f(4, 1);  // rows 6-10: rho2 rho1 in bits 3, 2
  if (f(2, 2) == 0) {                                 // bits [3:0] = 0000: reserved
    r.reserved = true;
    return r;
  }
  switch (b) {
    case 0: r.w = 12, r.h = a + 2; break;
    case 1: r.w = a + 2, r.h = 12; break;
    case 2:  // W + 6, H + 6 with H in bits 10:9: no dual plane, low precision
      r.w = a + 6, r.h = f(9, 2) + 6;
      r.p = 0;
      r.dual = false;
      break;
    default:
      if (a == 0) {
        r.w = 6, r.h = 10;
      } else if (a == 1) {
        r.w = 10, r.h = 6;
      } else {  // 1 1 1 x x x x 0 0 other than the void extent
        r.reserved = true;
      }
  }
  return r;
}

// ---- Configuration -------------------------------------------------------------------------------

AstcBlockConfig read_config(const Bits128& blk, int block_w, int block_h) {
  AstcBlockConfig c;
  const uint32_t mode = get_bits(blk, 0, 11);
  if ((mode & 0x1FFu) == 0x1FCu) {  // "Void-Extent Blocks", 2D layout
    c.void_extent = true;
    for (int ch = 0; ch < 4; ++ch)
      c.void_color[static_cast<size_t>(ch)] = static_cast<uint16_t>(get_bits(blk, 64 + 16 * ch, 16));
    const uint32_t min_s = get_bits(blk, 12, 13), max_s = get_bits(blk, 25, 13);
    const uint32_t min_t = get_bits(blk, 38, 13), max_t = get_bits(blk, 51, 13);
    const bool all_ones = min_s == 0x1FFF && max_s == 0x1FFF && min_t == 0x1FFF && max_t == 0x1FFF;
    if (get_bits(blk, 10, 2) != 3) {
      c.illegal = AstcIllegal::VoidExtentReservedBits;
    } else if (!all_ones && (min_s >= max_s || min_t >= max_t)) {
      c.illegal = AstcIllegal::VoidExtentCoordinates;
    } else if (get_bits(blk, 9, 1) != 0) {
      c.illegal = AstcIllegal::VoidExtentHdr;
    }
    return c;
  }
  const BlockMode bm = decode_block_mode(mode);
  if (bm.reserved) {
    c.illegal = AstcIllegal::ReservedBlockMode;
    return c;
  }
  c.grid_w = bm.w, c.grid_h = bm.h, c.dual_plane = bm.dual;
  c.weight_range = astc::weight_range_index(bm.rho, bm.p);
  c.partitions = static_cast<int>(get_bits(blk, 11, 2)) + 1;
  const int weight_count = bm.w * bm.h * (bm.dual ? 2 : 1);
  if (weight_count > 64) {
    c.illegal = AstcIllegal::TooManyWeights;
    return c;
  }
  c.weight_bits = astc::ise_sequence_bits(weight_count, c.weight_range);
  if (c.weight_bits < 24 || c.weight_bits > 96) {
    c.illegal = AstcIllegal::WeightBitsOutOfRange;
    return c;
  }
  if (bm.w > block_w || bm.h > block_h) {
    c.illegal = AstcIllegal::GridExceedsFootprint;
    return c;
  }
  if (bm.dual && c.partitions == 4) {
    c.illegal = AstcIllegal::DualPlaneFourPartitions;
    return c;
  }
  // "Color Endpoint Mode" and "Data Size Determination".
  int config_bits = 17, extra_cem_bits = 0;
  if (c.partitions == 1) {
    c.cem[0] = static_cast<int>(get_bits(blk, 13, 4));
  } else {
    c.partition_seed = static_cast<int>(get_bits(blk, 13, 10));
    const uint32_t field = get_bits(blk, 23, 6);
    const uint32_t selector = field & 3u;
    if (selector == 0) {  // one 4-bit CEM in bits [28:25] for every partition
      for (int i = 0; i < c.partitions; ++i) c.cem[static_cast<size_t>(i)] = static_cast<int>(field >> 2);
      config_bits = 29;
    } else {  // class bits C_i, then the 2-bit M_i, the high part just below the weights
      extra_cem_bits = 3 * c.partitions - 4;
      const uint32_t combined =
          (field >> 2) | (get_bits(blk, 128 - c.weight_bits - extra_cem_bits, extra_cem_bits) << 4);
      for (int i = 0; i < c.partitions; ++i) {
        const int cls = static_cast<int>(selector) - 1 + static_cast<int>((combined >> i) & 1u);
        const int low = static_cast<int>((combined >> (c.partitions + 2 * i)) & 3u);
        c.cem[static_cast<size_t>(i)] = (cls << 2) | low;
      }
      config_bits = 25 + 3 * c.partitions;
    }
  }
  if (bm.dual) {
    config_bits += 2;
    c.ccs = static_cast<int>(get_bits(blk, 128 - c.weight_bits - extra_cem_bits - 2, 2));
  }
  for (int i = 0; i < c.partitions; ++i) c.endpoint_values += 2 * ((c.cem[static_cast<size_t>(i)] >> 2) + 1);
  if (c.endpoint_values > 18) {
    c.illegal = AstcIllegal::TooManyEndpointValues;
    return c;
  }
  const int remaining = 128 - config_bits - c.weight_bits;
  if (remaining < (13 * c.endpoint_values + 4) / 5) {
    c.illegal = AstcIllegal::TooFewEndpointBits;
    return c;
  }
  // The largest range whose sequence of C values fits the remaining bits (0..5 always does now).
  c.endpoint_range = astc::kIseRangeCount - 1;
  while (astc::ise_sequence_bits(c.endpoint_values, c.endpoint_range) > remaining) --c.endpoint_range;
  return c;
}

// ---- Endpoints ("LDR Endpoint Decoding") ----------------------------------------------------------

using Color = std::array<int, 4>;  // R, G, B, A

void bit_transfer_signed(int& a, int& b) {
  b >>= 1;
  b |= a & 0x80;
  a >>= 1;
  a &= 0x3F;
  if ((a & 0x20) != 0) a -= 0x40;
}

Color blue_contract(int r, int g, int b, int a) { return {(r + b) >> 1, (g + b) >> 1, b, a}; }

void clamp_unorm8(Color& c) {
  for (int& x : c) x = x < 0 ? 0 : x > 255 ? 255 : x;
}

// e0, e1 (0..255 each) of one partition from its unquantized values v; false for an HDR mode.
bool decode_endpoints(int cem, const uint8_t* vals, Color& e0, Color& e1) {
  std::array<int, 8> v{};
  for (int i = 0; i < 2 * ((cem >> 2) + 1); ++i) v[static_cast<size_t>(i)] = vals[i];
  switch (cem) {
    case 0:  // luminance, direct
      e0 = {v[0], v[0], v[0], 0xFF};
      e1 = {v[1], v[1], v[1], 0xFF};
      return true;
    case 1: {  // luminance, base + offset
      const int l0 = (v[0] >> 2) | (v[1] & 0xC0);
      const int l1 = std::min(l0 + (v[1] & 0x3F), 0xFF);
      e0 = {l0, l0, l0, 0xFF};
      e1 = {l1, l1, l1, 0xFF};
      return true;
    }
    case 4:  // luminance + alpha, direct
      e0 = {v[0], v[0], v[0], v[2]};
      e1 = {v[1], v[1], v[1], v[3]};
      return true;
    case 5:  // luminance + alpha, base + offset
      bit_transfer_signed(v[1], v[0]);
      bit_transfer_signed(v[3], v[2]);
      e0 = {v[0], v[0], v[0], v[2]};
      e1 = {v[0] + v[1], v[0] + v[1], v[0] + v[1], v[2] + v[3]};
      clamp_unorm8(e0);
      clamp_unorm8(e1);
      return true;
    case 6:  // RGB, base + scale
      e0 = {(v[0] * v[3]) >> 8, (v[1] * v[3]) >> 8, (v[2] * v[3]) >> 8, 0xFF};
      e1 = {v[0], v[1], v[2], 0xFF};
      return true;
    case 8:     // RGB, direct
    case 12: {  // RGBA, direct
      const int a0 = cem == 12 ? v[6] : 0xFF, a1 = cem == 12 ? v[7] : 0xFF;
      if (v[1] + v[3] + v[5] >= v[0] + v[2] + v[4]) {
        e0 = {v[0], v[2], v[4], a0};
        e1 = {v[1], v[3], v[5], a1};
      } else {
        e0 = blue_contract(v[1], v[3], v[5], a1);
        e1 = blue_contract(v[0], v[2], v[4], a0);
      }
      return true;
    }
    case 9:     // RGB, base + offset
    case 13: {  // RGBA, base + offset
      bit_transfer_signed(v[1], v[0]);
      bit_transfer_signed(v[3], v[2]);
      bit_transfer_signed(v[5], v[4]);
      if (cem == 13) bit_transfer_signed(v[7], v[6]);
      const int a0 = cem == 13 ? v[6] : 0xFF, a1 = cem == 13 ? v[6] + v[7] : 0xFF;
      if (v[1] + v[3] + v[5] >= 0) {
        e0 = {v[0], v[2], v[4], a0};
        e1 = {v[0] + v[1], v[2] + v[3], v[4] + v[5], a1};
      } else {
        e0 = blue_contract(v[0] + v[1], v[2] + v[3], v[4] + v[5], a1);
        e1 = blue_contract(v[0], v[2], v[4], a0);
      }
      clamp_unorm8(e0);
      clamp_unorm8(e1);
      return true;
    }
    case 10:  // RGB, base + scale, plus two alphas
      e0 = {(v[0] * v[3]) >> 8, (v[1] * v[3]) >> 8, (v[2] * v[3]) >> 8, v[4]};
      e1 = {v[0], v[1], v[2], v[5]};
      return true;
    default:  // 2, 3, 7, 11, 14, 15: HDR endpoint modes, the error colour in LDR operation modes
      return false;
  }
}

// ---- Partition pattern ("Partition Pattern Generation") ------------------------------------------

uint32_t hash52(uint32_t p) {
  p ^= p >> 15;
  p -= p << 17;
  p += p << 7;
  p += p << 4;
  p ^= p >> 5;
  p += p << 16;
  p ^= p >> 7;
  p ^= p >> 3;
  p ^= p << 6;
  p ^= p >> 17;
  return p;
}

// select_partition(seed, x, y, z = 0, partitioncount, small_block) with the per-block part (hash,
// squared and shifted seeds) computed once. All sums modulo 2^32; only their low 6 bits are used.
class PartitionSelector {
 public:
  PartitionSelector(int seed, int count, bool small_block) : count_(count), shift_xy_(small_block ? 1 : 0) {
    const auto s = static_cast<uint32_t>(seed) + static_cast<uint32_t>(count - 1) * 1024u;
    rnum_ = hash52(s);
    std::array<uint32_t, 9> sd{};  // seed1..seed8 (index 1..8); seed9..12 only multiply z = 0
    for (int i = 1; i <= 8; ++i) sd[static_cast<size_t>(i)] = (rnum_ >> (4 * (i - 1))) & 0xFu;
    for (uint32_t& x : sd) x *= x;
    int sh1 = 0, sh2 = 0;
    if (s & 1u) {
      sh1 = (s & 2u) ? 4 : 5;
      sh2 = count == 3 ? 6 : 5;
    } else {
      sh1 = count == 3 ? 6 : 5;
      sh2 = (s & 2u) ? 4 : 5;
    }
    for (int i = 1; i <= 8; ++i) sd[static_cast<size_t>(i)] >>= (i % 2 == 1) ? sh1 : sh2;
    for (int i = 0; i < 8; ++i) mul_[static_cast<size_t>(i)] = sd[static_cast<size_t>(i + 1)];
  }
  int at(int x, int y) const {
    const auto ux = static_cast<uint32_t>(x) << shift_xy_, uy = static_cast<uint32_t>(y) << shift_xy_;
    const uint32_t a = (mul_[0] * ux + mul_[1] * uy + (rnum_ >> 14)) & 0x3Fu;
    const uint32_t b = (mul_[2] * ux + mul_[3] * uy + (rnum_ >> 10)) & 0x3Fu;
    uint32_t c = (mul_[4] * ux + mul_[5] * uy + (rnum_ >> 6)) & 0x3Fu;
    uint32_t d = (mul_[6] * ux + mul_[7] * uy + (rnum_ >> 2)) & 0x3Fu;
    if (count_ < 4) d = 0;
    if (count_ < 3) c = 0;
    if (a >= b && a >= c && a >= d) return 0;
    if (b >= c && b >= d) return 1;
    if (c >= d) return 2;
    return 3;
  }

 private:
  int count_;
  int shift_xy_;
  uint32_t rnum_ = 0;
  std::array<uint32_t, 8> mul_{};
};

// ---- Output ("Weight Application", LDR endpoint modes) --------------------------------------------

void fill(Rgba8* out, int n, Rgba8 c) {
  for (int i = 0; i < n; ++i) out[i] = c;
}

}  // namespace

const char* astc_illegal_name(AstcIllegal why) {
  switch (why) {
    case AstcIllegal::None: return "none";
    case AstcIllegal::ReservedBlockMode: return "reserved block mode";
    case AstcIllegal::VoidExtentReservedBits: return "void extent with reserved bits not 1";
    case AstcIllegal::VoidExtentHdr: return "HDR void extent in an LDR operation mode";
    case AstcIllegal::VoidExtentCoordinates: return "void extent with min >= max";
    case AstcIllegal::TooManyWeights: return "more than 64 weights";
    case AstcIllegal::WeightBitsOutOfRange: return "weight bits outside 24..96";
    case AstcIllegal::GridExceedsFootprint: return "weight grid larger than the footprint";
    case AstcIllegal::DualPlaneFourPartitions: return "dual plane with 4 partitions";
    case AstcIllegal::TooManyEndpointValues: return "more than 18 endpoint values";
    case AstcIllegal::TooFewEndpointBits: return "fewer than ceil(13 C / 5) endpoint bits";
  }
  return "?";
}

AstcBlockConfig astc_block_config(const uint8_t block[kAstcBlockBytes], int block_w, int block_h) {
  return read_config(load_block(block), block_w, block_h);
}

void decode_astc_block(const uint8_t block[kAstcBlockBytes], int block_w, int block_h, bool srgb, Rgba8* out) {
  if (!is_astc_footprint(block_w, block_h))
    throw InputError(fmt::format("ASTC footprint {}x{} is not one of the 14 2D footprints", block_w, block_h));
  const int texels = block_w * block_h;
  const Bits128 blk = load_block(block);
  const AstcBlockConfig c = read_config(blk, block_w, block_h);
  if (c.illegal != AstcIllegal::None) return fill(out, texels, kAstcErrorColor);

  // Void extent: the stored UNORM16 colour takes the interpolator output's path.
  if (c.void_extent) {
    std::array<uint8_t, 4> v{};
    for (size_t ch = 0; ch < 4; ++ch)
      v[ch] = srgb ? static_cast<uint8_t>(c.void_color[ch] >> 8) : astc_unorm16_to_unorm8(c.void_color[ch]);
    return fill(out, texels, Rgba8{v[0], v[1], v[2], v[3]});
  }

  // Endpoints: C values from bit 17 (one partition) or 29, unquantized, then per partition.
  std::array<uint8_t, 18> ev{};
  const int ep_start = c.partitions == 1 ? 17 : 29;
  decode_ise(low_bits(shift_right(blk, ep_start), astc::ise_sequence_bits(c.endpoint_values, c.endpoint_range)),
             c.endpoint_values, c.endpoint_range, ev.data());
  const auto& eq = astc::kEndpointUnquant[static_cast<size_t>(c.endpoint_range)];
  for (int i = 0; i < c.endpoint_values; ++i) ev[static_cast<size_t>(i)] = eq[ev[static_cast<size_t>(i)]];
  // 16-bit endpoints C0, C1 ("Weight Application"): linear e * 257, sRGB (e << 8) | 0x80.
  std::array<std::array<int, 4>, 4> c0{}, c1{};
  std::array<bool, 4> hdr{};
  for (int p = 0, at = 0; p < c.partitions; ++p) {
    const int cem = c.cem[static_cast<size_t>(p)];
    Color e0{}, e1{};
    hdr[static_cast<size_t>(p)] = !decode_endpoints(cem, ev.data() + at, e0, e1);
    at += 2 * ((cem >> 2) + 1);
    for (size_t ch = 0; ch < 4; ++ch) {
      c0[static_cast<size_t>(p)][ch] = srgb ? (e0[ch] << 8) | 0x80 : e0[ch] * 257;
      c1[static_cast<size_t>(p)][ch] = srgb ? (e1[ch] << 8) | 0x80 : e1[ch] * 257;
    }
  }

  // Weights: from bit 127 down, plane 0 and plane 1 interleaved, unquantized to 0..64. Each plane
  // is padded with zeros past W x H: infill reads index js + 1 + (jt + 1) W with zero fractions at
  // the grid's last row and column.
  const int planes = c.dual_plane ? 2 : 1;
  const int grid = c.grid_w * c.grid_h;
  std::array<uint8_t, 64> wv{};
  decode_ise(low_bits(reverse128(blk), c.weight_bits), grid * planes, c.weight_range, wv.data());
  const auto& wq = astc::kWeightUnquant[static_cast<size_t>(c.weight_range)];
  std::array<std::array<int, 64 + 16>, 2> pw{};
  for (int k = 0; k < grid; ++k)
    for (int pl = 0; pl < planes; ++pl)
      pw[static_cast<size_t>(pl)][static_cast<size_t>(k)] = wq[wv[static_cast<size_t>(k * planes + pl)]];

  // Weight infill ("Weight Infill"): per column and row, gs = (Ds bs (W - 1) + 32) >> 6, Q4.4.
  std::array<int, 12> gs{}, gt{};
  for (int x = 0; x < block_w; ++x)
    gs[static_cast<size_t>(x)] = (astc::kInfillScale[static_cast<size_t>(block_w)] * x * (c.grid_w - 1) + 32) >> 6;
  for (int y = 0; y < block_h; ++y)
    gt[static_cast<size_t>(y)] = (astc::kInfillScale[static_cast<size_t>(block_h)] * y * (c.grid_h - 1) + 32) >> 6;

  const PartitionSelector part(c.partition_seed, c.partitions, texels < 31);
  for (int y = 0; y < block_h; ++y) {
    const int jt = gt[static_cast<size_t>(y)] >> 4, ft = gt[static_cast<size_t>(y)] & 0xF;
    for (int x = 0; x < block_w; ++x) {
      const int js = gs[static_cast<size_t>(x)] >> 4, fs = gs[static_cast<size_t>(x)] & 0xF;
      const int w11 = (fs * ft + 8) >> 4, w10 = ft - w11, w01 = fs - w11, w00 = 16 - fs - ft + w11;
      const auto v0 = static_cast<size_t>(js + jt * c.grid_w), gw = static_cast<size_t>(c.grid_w);
      std::array<int, 2> wt{};
      for (size_t pl = 0; pl < static_cast<size_t>(planes); ++pl) {
        const auto& q = pw[pl];
        wt[pl] = (q[v0] * w00 + q[v0 + 1] * w01 + q[v0 + gw] * w10 + q[v0 + gw + 1] * w11 + 8) >> 4;
      }
      const auto p = static_cast<size_t>(c.partitions > 1 ? part.at(x, y) : 0);
      Rgba8& o = out[y * block_w + x];
      if (hdr[p]) {
        o = kAstcErrorColor;
        continue;
      }
      std::array<uint8_t, 4> r{};
      for (size_t ch = 0; ch < 4; ++ch) {
        const int i = c.dual_plane && static_cast<int>(ch) == c.ccs ? wt[1] : wt[0];
        const auto cc = static_cast<uint32_t>((c0[p][ch] * (64 - i) + c1[p][ch] * i + 32) >> 6);  // UNORM16
        r[ch] = srgb ? static_cast<uint8_t>(cc >> 8) : astc_unorm16_to_unorm8(cc);
      }
      o = Rgba8{r[0], r[1], r[2], r[3]};
    }
  }
}

Image decode_astc_image(const uint8_t* data, size_t size, int width, int height, int block_w, int block_h, bool srgb) {
  if (!is_astc_footprint(block_w, block_h))
    throw InputError(fmt::format("ASTC footprint {}x{} is not one of the 14 2D footprints", block_w, block_h));
  if (width < 1 || width > 65536 || height < 1 || height > 65536)
    throw InputError(fmt::format("ASTC image size {}x{} is not within 1..65536", width, height));
  const size_t bx = static_cast<size_t>((width + block_w - 1) / block_w);
  const size_t by = static_cast<size_t>((height + block_h - 1) / block_h);
  if (size != bx * by * kAstcBlockBytes)
    throw InputError(fmt::format("ASTC {}x{} image with {}x{} blocks needs {} bytes ({} x {} blocks), got {}", width,
                                 height, block_w, block_h, bx * by * kAstcBlockBytes, bx, by, size));
  Image img;
  img.width = width;
  img.height = height;
  img.texels.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
  std::array<Rgba8, kAstcMaxTexels> tile{};
  for (size_t j = 0; j < by; ++j)
    for (size_t i = 0; i < bx; ++i) {
      decode_astc_block(data + (j * bx + i) * kAstcBlockBytes, block_w, block_h, srgb, tile.data());
      const int x0 = static_cast<int>(i) * block_w, y0 = static_cast<int>(j) * block_h;
      for (int y = 0; y < block_h && y0 + y < height; ++y)
        for (int x = 0; x < block_w && x0 + x < width; ++x)
          img.at(x0 + x, y0 + y) = tile[static_cast<size_t>(y * block_w + x)];
    }
  return img;
}

}  // namespace tfu
