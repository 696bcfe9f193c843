// ASTC tables, each generated at compile time from the procedure or formula that defines it in the
// Khronos Data Format Specification 1.4.0, chapter "ASTC Compressed Texture Image Formats" (KDFS
// below; section names quoted). The decoder (cmodel/astc_decode.cpp) reads only these.
//
//   kIseRanges            the 21 integer-sequence-encoding ranges, 2^n, 3 x 2^n, 5 x 2^n levels
//                         ("Integer Sequence Encoding", Table "ASTC range forms"), ascending
//   kTritBlock, kQuintBlock  the 8 packed bits T -> 5 trits and the 7 bits Q -> 3 quints (the
//                         spec's bit manipulations, run on every input once)
//   kEndpointUnquant      ISE value -> 0..255 per range ("Endpoint Unquantization")
//   kWeightUnquant        ISE value -> 0..64 per weight range ("Weight Unquantization")
//   kInfillScale          D = floor((1024 + floor(B / 2)) / (B - 1)) per footprint dimension B
//                         ("Weight Infill")
#pragma once

#include <array>
#include <cstdint>

namespace tfu::astc {

// ---- Integer sequence encoding ranges -------------------------------------------------------------

// One range: levels = (trits ? 3 : quints ? 5 : 1) x 2^bits; at most one of trits, quints is 1.
struct IseRange {
  uint8_t trits = 0, quints = 0, bits = 0;
  int levels = 0;
};
inline constexpr int kIseRangeCount = 21;  // 2^1..2^8 (8), 3 x 2^0..2^6 (7), 5 x 2^0..2^5 (6)

constexpr std::array<IseRange, kIseRangeCount> make_ise_ranges() {
  std::array<IseRange, kIseRangeCount> r{};
  int k = 0;
  for (int n = 1; n <= 8; ++n) r[static_cast<size_t>(k++)] = {0, 0, static_cast<uint8_t>(n), 1 << n};  // n <= 8
  for (int n = 0; n <= 6; ++n) r[static_cast<size_t>(k++)] = {1, 0, static_cast<uint8_t>(n), 3 << n};  // n <= 6
  for (int n = 0; n <= 5; ++n) r[static_cast<size_t>(k++)] = {0, 1, static_cast<uint8_t>(n), 5 << n};  // n <= 5
  for (int i = 1; i < kIseRangeCount; ++i)  // insertion sort by level count (all distinct)
    for (int j = i; j > 0 && r[static_cast<size_t>(j - 1)].levels > r[static_cast<size_t>(j)].levels; --j) {
      const IseRange t = r[static_cast<size_t>(j)];
      r[static_cast<size_t>(j)] = r[static_cast<size_t>(j - 1)];
      r[static_cast<size_t>(j - 1)] = t;
    }
  return r;
}
inline constexpr std::array<IseRange, kIseRangeCount> kIseRanges = make_ise_ranges();
static_assert(kIseRanges[0].levels == 2 && kIseRanges[11].levels == 32 && kIseRanges[20].levels == 256);

// Bits of a sequence of `count` values ("Data Size Determination"):
// ceil(8 count trits / 5) + ceil(7 count quints / 3) + count bits.
constexpr int ise_sequence_bits(int count, int range) {
  const IseRange& r = kIseRanges[static_cast<size_t>(range)];
  return (8 * count * r.trits + 4) / 5 + (7 * count * r.quints + 2) / 3 + count * r.bits;
}

// Weight range of a block mode ("Block Mode", Table "ASTC weight range encodings"): rho = 2..7 with
// P = 0 gives 2, 3, 4, 5, 6, 8 levels and with P = 1 10, 12, 16, 20, 24, 32: the first twelve
// ranges in ascending order, index (rho - 2) + 6 P.
constexpr int weight_range_index(int rho, int p) { return rho - 2 + 6 * p; }
inline constexpr int kWeightRangeCount = 12;
static_assert(kIseRanges[weight_range_index(2, 0)].levels == 2 && kIseRanges[weight_range_index(7, 0)].levels == 8 &&
              kIseRanges[weight_range_index(2, 1)].levels == 10 && kIseRanges[weight_range_index(7, 1)].levels == 32);

// Colour endpoint ranges are at least 0..5 (the legality rule "fewer than ceil(13 C / 5) bits" is
// the size of C values of that range): indices 4..20.
inline constexpr int kMinEndpointRange = 4;
static_assert(kIseRanges[kMinEndpointRange].levels == 6 && kIseRanges[kMinEndpointRange].trits == 1);

// ---- Trit and quint blocks ("Integer Sequence Encoding") ------------------------------------------

// Five trits t0..t4 from the 8 bits T, packed as t0 | t1 << 2 | ... | t4 << 8 (2 bits each).
constexpr uint16_t unpack_trits(uint32_t t) {
  const auto bit = [](uint32_t v, int i) { return (v >> i) & 1u; };
  uint32_t c = 0, t0 = 0, t1 = 0, t2 = 0, t3 = 0, t4 = 0;
  if (((t >> 2) & 7u) == 7u) {  // T[4:2] = 111
    c = (((t >> 5) & 7u) << 2) | (t & 3u);
    t4 = t3 = 2;
  } else {
    c = t & 0x1Fu;
    if (((t >> 5) & 3u) == 3u) {
      t4 = 2;
      t3 = bit(t, 7);
    } else {
      t4 = bit(t, 7);
      t3 = (t >> 5) & 3u;
    }
  }
  if ((c & 3u) == 3u) {
    t2 = 2;
    t1 = bit(c, 4);
    t0 = (bit(c, 3) << 1) | (bit(c, 2) & ~bit(c, 3) & 1u);
  } else if (((c >> 2) & 3u) == 3u) {
    t2 = 2;
    t1 = 2;
    t0 = c & 3u;
  } else {
    t2 = bit(c, 4);
    t1 = (c >> 2) & 3u;
    t0 = (bit(c, 1) << 1) | (bit(c, 0) & ~bit(c, 1) & 1u);
  }
  return static_cast<uint16_t>(t0 | t1 << 2 | t2 << 4 | t3 << 6 | t4 << 8);
}

// Three quints q0..q2 from the 7 bits Q, packed as q0 | q1 << 3 | q2 << 6 (3 bits each).
constexpr uint16_t unpack_quints(uint32_t q) {
  const auto bit = [](uint32_t v, int i) { return (v >> i) & 1u; };
  uint32_t q0 = 0, q1 = 0, q2 = 0;
  if (((q >> 1) & 3u) == 3u && ((q >> 5) & 3u) == 0u) {  // Q[2:1] = 11 and Q[6:5] = 00
    q2 = (bit(q, 0) << 2) | ((bit(q, 4) & ~bit(q, 0) & 1u) << 1) | (bit(q, 3) & ~bit(q, 0) & 1u);
    q1 = q0 = 4;
  } else {
    uint32_t c = 0;
    if (((q >> 1) & 3u) == 3u) {
      q2 = 4;
      c = (((q >> 3) & 3u) << 3) | ((~(q >> 5) & 3u) << 1) | bit(q, 0);  // { Q[4:3], ~Q[6:5], Q[0] }
    } else {
      q2 = (q >> 5) & 3u;
      c = q & 0x1Fu;
    }
    if ((c & 7u) == 5u) {
      q1 = 4;
      q0 = (c >> 3) & 3u;
    } else {
      q1 = (c >> 3) & 3u;
      q0 = c & 7u;
    }
  }
  return static_cast<uint16_t>(q0 | q1 << 3 | q2 << 6);
}

template <size_t N, typename F>
constexpr std::array<uint16_t, N> tabulate(F f) {
  std::array<uint16_t, N> t{};
  for (size_t i = 0; i < N; ++i) t[i] = f(static_cast<uint32_t>(i));
  return t;
}
inline constexpr std::array<uint16_t, 256> kTritBlock = tabulate<256>(unpack_trits);
inline constexpr std::array<uint16_t, 128> kQuintBlock = tabulate<128>(unpack_quints);

// ---- Unquantization ---------------------------------------------------------------------------------

// The trit/quint unquantization inputs of one range: B (as its bit layout) and C; D is the trit or
// quint, A the lowest bit of m replicated.
struct UnquantRow {
  int levels;
  const char* b_layout;  // empty: B = 0
  uint32_t c;
};

// Endpoint rows, KDFS Table "ASTC color unquantization parameters" (9-bit A, B).
inline constexpr std::array<UnquantRow, 11> kEndpointUnquantRows{{{6, "", 204},
                                                                  {10, "", 113},
                                                                  {12, "b000b0bb0", 93},
                                                                  {20, "b0000bb00", 54},
                                                                  {24, "cb000cbcb", 44},
                                                                  {40, "cb0000cbc", 26},
                                                                  {48, "dcb000dcb", 22},
                                                                  {80, "dcb0000dc", 13},
                                                                  {96, "edcb000ed", 11},
                                                                  {160, "edcb0000e", 6},
                                                                  {192, "fedcb000f", 5}}};
// Weight rows, KDFS Table "ASTC weight unquantization parameters" (7-bit A, B).
inline constexpr std::array<UnquantRow, 5> kWeightUnquantRows{
    {{6, "", 50}, {10, "", 28}, {12, "b000b0b", 23}, {20, "b0000b0", 13}, {24, "cb000cb", 11}}};

// The spec's bit-layout string of the B input ("b000b0bb0"): most significant bit first; a letter
// is that bit of the value's low bits m (a = bit 0, b = bit 1, ...), '0' a zero.
constexpr uint32_t layout_bits(const char* pattern, uint32_t m) {
  uint32_t v = 0;
  for (; *pattern != '\0'; ++pattern) v = (v << 1) | (*pattern == '0' ? 0u : (m >> (*pattern - 'a')) & 1u);
  return v;
}

// unq = D C + B; unq ^= A; unq = (A & top) | (unq >> 2), with `width`-bit A and B (9 endpoints, 7 weights).
constexpr uint32_t unquant_abcd(const UnquantRow& row, uint32_t d, uint32_t m, int width) {
  const uint32_t a = (m & 1u) ? (1u << width) - 1u : 0u;
  const uint32_t b = row.b_layout[0] == '\0' ? 0u : layout_bits(row.b_layout, m);
  uint32_t unq = d * row.c + b;
  unq ^= a;
  return (a & (1u << (width - 2))) | (unq >> 2);  // 0x80 for 9 bits, 0x20 for 7 bits
}

// Bit replication of an n-bit value to `width` bits, most significant bit first.
constexpr uint32_t replicate_bits(uint32_t v, int n, int width) {
  uint32_t r = 0;
  for (int got = 0; got < width; got += n) r = (r << n) | v;
  const int excess = ((width + n - 1) / n) * n - width;
  return r >> excess;
}

// kEndpointUnquant[range][v]: ISE value v = (trit or quint) x 2^bits + m -> 0..255. Ranges below
// kMinEndpointRange never carry endpoints and stay 0.
using UnquantTable = std::array<std::array<uint8_t, 256>, kIseRangeCount>;
constexpr UnquantTable make_endpoint_unquant() {
  UnquantTable t{};
  for (int r = kMinEndpointRange; r < kIseRangeCount; ++r) {
    const IseRange& ir = kIseRanges[static_cast<size_t>(r)];
    for (int v = 0; v < ir.levels; ++v) {
      const auto m = static_cast<uint32_t>(v) & ((1u << ir.bits) - 1u), d = static_cast<uint32_t>(v) >> ir.bits;
      uint32_t u = 0;
      if (ir.trits == 0 && ir.quints == 0) {
        u = replicate_bits(static_cast<uint32_t>(v), ir.bits, 8);
      } else {
        for (const UnquantRow& row : kEndpointUnquantRows)
          if (row.levels == ir.levels) u = unquant_abcd(row, d, m, 9);
      }
      t[static_cast<size_t>(r)][static_cast<size_t>(v)] = static_cast<uint8_t>(u);
    }
  }
  return t;
}
inline constexpr UnquantTable kEndpointUnquant = make_endpoint_unquant();

// kWeightUnquant[range][v] -> 0..64: to 0..63 by bit replication (bits only), by the two-entry
// KDFS Table "ASTC weight unquantization values" (trit or quint alone: 0..2 -> 0, 32, 63 and
// 0..4 -> 0, 16, 32, 47, 63) or by the A, B, C, D procedure; then +1 above 32.
using WeightUnquantTable = std::array<std::array<uint8_t, 32>, kWeightRangeCount>;
inline constexpr std::array<uint8_t, 3> kWeightTritOnly{0, 32, 63};
inline constexpr std::array<uint8_t, 5> kWeightQuintOnly{0, 16, 32, 47, 63};
constexpr WeightUnquantTable make_weight_unquant() {
  WeightUnquantTable t{};
  for (int r = 0; r < kWeightRangeCount; ++r) {
    const IseRange& ir = kIseRanges[static_cast<size_t>(r)];
    for (int v = 0; v < ir.levels; ++v) {
      const auto m = static_cast<uint32_t>(v) & ((1u << ir.bits) - 1u), d = static_cast<uint32_t>(v) >> ir.bits;
      uint32_t u = 0;
      if (ir.trits == 0 && ir.quints == 0) {
        u = replicate_bits(static_cast<uint32_t>(v), ir.bits, 6);
      } else if (ir.bits == 0) {
        u = ir.trits ? kWeightTritOnly[d] : kWeightQuintOnly[d];
      } else {
        for (const UnquantRow& row : kWeightUnquantRows)
          if (row.levels == ir.levels) u = unquant_abcd(row, d, m, 7);
      }
      if (u > 32) u += 1;
      t[static_cast<size_t>(r)][static_cast<size_t>(v)] = static_cast<uint8_t>(u);
    }
  }
  return t;
}
inline constexpr WeightUnquantTable kWeightUnquant = make_weight_unquant();

// Spot checks against values printed in the spec's examples and tables.
static_assert(kEndpointUnquant[kMinEndpointRange][0] == 0 && kEndpointUnquant[kMinEndpointRange][1] == 255);
static_assert(kEndpointUnquant[5][1] == 36 && kEndpointUnquant[5][7] == 255);  // 0..7: 001 -> 00100100
static_assert(kWeightUnquant[5][7] == 64 && kWeightUnquant[11][16] == 34);     // 0..7 top, 0..31: 100001 + 1
static_assert(kWeightUnquant[1][1] == 32 && kWeightUnquant[1][2] == 64);       // 0..2 -> 0, 32, 64

// ---- Weight infill ---------------------------------------------------------------------------------

// D = floor((1024 + floor(B / 2)) / (B - 1)) for a footprint dimension B = 2..12 (entries 0, 1 unused).
constexpr std::array<int, 13> make_infill_scale() {
  std::array<int, 13> d{};
  for (int b = 2; b <= 12; ++b) d[static_cast<size_t>(b)] = (1024 + b / 2) / (b - 1);
  return d;
}
inline constexpr std::array<int, 13> kInfillScale = make_infill_scale();

}  // namespace tfu::astc
