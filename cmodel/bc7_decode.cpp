// BC7 decoder: the block layout and rules are in bc7_decode.hpp; docs/compressed-bc.md.
#include "cmodel/bc7_decode.hpp"

#include <string_view>
#include <utility>

namespace tfu {

namespace {

// The one partition table: the spec's "Partition table for 2-subset BPTC" and "... 3-subset BPTC",
// 16 texels per partition (t = 4 y + x), the subset of each texel as a digit, and each subset's anchor
// texel (the spec's tables "BPTC anchor index values for the second subset of two-subset
// partitioning", "... second subset of three-subset ...", "... third subset of three-subset ...", and
// texel 0 for subset 0) written as a letter instead: A = subset 0, B = subset 1, C = subset 2.
// Generated once from the spec's text (KhronosGroup/DataFormat bptc.txt): the bold anchor marks in the
// spec's partition tables disagree with its anchor index tables at two places (2-subset partition 35
// marks texel 2, the table says 8; 3-subset partition 1 also marks texel 15); the index tables win
// (D3D11, Mesa and every decoder use them; docs/compressed-bc.md).
constexpr std::array<std::string_view, 64> kPartitions2{
    "A01100110011001B", "A00100010001000B", "A11101110111011B", "A00100110011011B",  // 0-3
    "A00000010001001B", "A01101110111111B", "A00100110111111B", "A00000010011011B",  // 4-7
    "A00000000001001B", "A01101111111111B", "A00000010111111B", "A00000000001011B",  // 8-11
    "A00101111111111B", "A00000001111111B", "A00011111111111B", "A00000000000111B",  // 12-15
    "A00010001110111B", "A1B1000100000000", "A0000000B0001110", "A1B1001100010000",  // 16-19
    "A0B1000100000000", "A0001000B1001110", "A0000000B0001100", "A11100110011000B",  // 20-23
    "A0B1000100010000", "A0001000B0001100", "A1B0011001100110", "A0B1011001101100",  // 24-27
    "A0010111B1101000", "A0001111B1110000", "A1B1000110001110", "A0B1100110011100",  // 28-31
    "A10101010101010B", "A00011110000111B", "A10110B001011010", "A0110011B1001100",  // 32-35
    "A0B1110000111100", "A1010101B0101010", "A11010010110100B", "A10110101010010B",  // 36-39
    "A1B1001111001110", "A0010011B1001000", "A0B1001001001100", "A0B1101111011100",  // 40-43
    "A1B0100110010110", "A01111001100001B", "A11001101001100B", "A00001B001100000",  // 44-47
    "A10011B001000000", "A0B0011100100000", "A00000B001110010", "A0000100B1100100",  // 48-51
    "A11011001001001B", "A01101101100100B", "A1B0001110011100", "A0B1100111000110",  // 52-55
    "A11011001100100B", "A11000110011100B", "A11111101000000B", "A00110001110011B",  // 56-59
    "A00011110011001B", "A0B1001111110000", "A0B0001011101110", "A10001000111011B",  // 60-63
};
constexpr std::array<std::string_view, 64> kPartitions3{
    "A01B00110221222C", "A00B0011C2112221", "A0002001C211221B", "A22C00220011011B",  // 0-3
    "A0000000B122112C", "A01B00110022002C", "A02C00221111111B", "A0110011C211221B",  // 4-7
    "A0000000B111222C", "A0001111B111222C", "A00011B12222222C", "A01200B20012001C",  // 8-11
    "A11201B20112011C", "A1220B220122012C", "A01B01121122122C", "A01B2001C2002220",  // 12-15
    "A00B00110112112C", "A11B0011C0012200", "A0001122B122112C", "A02C00220022111B",  // 16-19
    "A11B01110222022C", "A00B0001C2212221", "A00000B10122012C", "A0001100C2B02210",  // 20-23
    "A12C0B2200110000", "A0120012B122222C", "A11012C1B2210110", "A00001B012C11221",  // 24-27
    "A0221102B102002C", "A1100B102002222C", "A011012201C2001B", "A0002000C211222B",  // 28-31
    "A0000002B122122C", "A22C00220012001B", "A01B00120022022C", "A1200B2001C00120",  // 32-35
    "A00011B122C20000", "A1201201C0B20120", "A1202012BC010120", "A011220011C2001B",  // 36-39
    "A01111C22200001B", "A10B01012222222C", "A0000000C121212B", "A0221B220022112C",  // 40-43
    "A02C00110022001B", "A22012C10220122B", "A10122C22222010B", "A0002121C121212B",  // 44-47
    "A10B01010101222C", "A22C01110222011B", "A0021B120002111C", "A0002B122112211C",  // 48-51
    "A2220B110111022C", "A0021112B112000C", "A1100B100110222C", "A000000021B2211C",  // 52-55
    "A1100B102222222C", "A022001100B1002C", "A0221122B122002C", "A000000000002B1C",  // 56-59
    "A00C00010002000B", "A22212220222B22C", "A10B22222222222C", "A11B2011C2012220",  // 60-63
};

struct PartitionTable {
  std::array<std::array<uint8_t, 16>, 64> subset{};
  std::array<std::array<uint8_t, 3>, 64> anchor{};
};

// Subset and anchor of every texel from the marked table; any malformed row stops compilation.
constexpr PartitionTable derive(const std::array<std::string_view, 64>& rows, int subsets) {
  PartitionTable t;
  for (int p = 0; p < 64; ++p) {
    if (rows[p].size() != 16) throw "a partition row has 16 texels";
    std::array<int, 3> anchors{0, 0, 0};
    for (int i = 0; i < 16; ++i) {
      const char c = rows[p][i];
      const bool is_anchor = c >= 'A' && c <= 'C';
      const int s = is_anchor ? c - 'A' : c - '0';
      if (s < 0 || s >= subsets) throw "a subset digit or anchor letter out of range";
      t.subset[p][i] = static_cast<uint8_t>(s);
      if (is_anchor) {
        ++anchors[s];
        t.anchor[p][s] = static_cast<uint8_t>(i);
      }
    }
    for (int s = 0; s < subsets; ++s)
      if (anchors[s] != 1) throw "one anchor per subset";
    if (t.anchor[p][0] != 0) throw "subset 0's anchor is texel 0";
  }
  return t;
}

constexpr PartitionTable kTable2 = derive(kPartitions2, 2);
constexpr PartitionTable kTable3 = derive(kPartitions3, 3);

// The block as a little-endian 128-bit integer, read from bit 0 up.
class BitReader {
 public:
  explicit BitReader(const uint8_t* block) {
    for (int i = 7; i >= 0; --i) {
      lo_ = (lo_ << 8) | block[i];
      hi_ = (hi_ << 8) | block[8 + i];
    }
  }
  int read(int bits) {  // bits <= 8
    int v = 0;
    for (int i = 0; i < bits; ++i, ++pos_) {
      const uint64_t word = pos_ < 64 ? lo_ : hi_;
      v |= static_cast<int>((word >> (pos_ & 63)) & 1) << i;
    }
    return v;
  }
  int position() const { return pos_; }

 private:
  uint64_t lo_ = 0, hi_ = 0;
  int pos_ = 0;
};

// A w-bit endpoint value widened to 8 bits by replicating its top bits (4 <= w <= 8).
int widen(int v, int w) { return w == 8 ? v : (v << (8 - w)) | (v >> (2 * w - 8)); }

int weight(int bits, int index) {
  return bits == 2 ? kBc7Weights2[index] : bits == 3 ? kBc7Weights3[index] : kBc7Weights4[index];
}

int interpolate(int e0, int e1, int w) { return ((64 - w) * e0 + w * e1 + 32) >> 6; }

}  // namespace

int bc7_mode(const uint8_t* block) {
  for (int m = 0; m < 8; ++m)
    if ((block[0] >> m) & 1) return m;
  return -1;
}

int bc7_subset(int subsets, int partition, int texel) {
  if (subsets == 1) return 0;
  return (subsets == 2 ? kTable2 : kTable3).subset[partition][texel];
}

int bc7_anchor(int subsets, int partition, int subset) {
  if (subsets == 1 || subset == 0) return 0;
  return (subsets == 2 ? kTable2 : kTable3).anchor[partition][subset];
}

BcBlockTexels decode_bc7_block(const uint8_t* block) {
  BcBlockTexels out{};
  const int mode = bc7_mode(block);
  if (mode < 0) return out;  // reserved: (0, 0, 0, 0)
  const Bc7Mode& m = kBc7Modes[mode];
  BitReader bits(block);
  bits.read(mode + 1);
  const int partition = bits.read(m.partition_bits);
  const int rotation = bits.read(m.rotation_bits);
  const int index_sel = bits.read(m.index_sel_bits);

  // Endpoint fields [channel][subset][endpoint], channel 3 = alpha.
  std::array<std::array<std::array<int, 2>, 3>, 4> e{};
  for (int c = 0; c < 4; ++c) {
    const int w = c < 3 ? m.colour_bits : m.alpha_bits;
    for (int s = 0; s < m.subsets; ++s)
      for (int i = 0; i < 2; ++i) e[c][s][i] = bits.read(w);
  }
  std::array<std::array<int, 2>, 3> pbit{};
  for (int s = 0; s < m.subsets; ++s) {
    if (m.endpoint_pbits) {
      pbit[s][0] = bits.read(1);
      pbit[s][1] = bits.read(1);
    }
  }
  if (m.shared_pbits)
    for (int s = 0; s < m.subsets; ++s) pbit[s][0] = pbit[s][1] = bits.read(1);
  const bool has_pbit = m.endpoint_pbits || m.shared_pbits;
  for (int c = 0; c < 4; ++c) {
    const int w = c < 3 ? m.colour_bits : m.alpha_bits;
    for (int s = 0; s < m.subsets; ++s)
      for (int i = 0; i < 2; ++i) {
        if (w == 0) {
          e[c][s][i] = 255;
        } else if (has_pbit) {
          e[c][s][i] = widen((e[c][s][i] << 1) | pbit[s][i], w + 1);
        } else {
          e[c][s][i] = widen(e[c][s][i], w);
        }
      }
  }

  // Indices: primary, then secondary; an anchor texel's index has one bit less (its top bit is 0).
  std::array<int, kBcBlockTexels> index1{}, index2{};
  for (int t = 0; t < kBcBlockTexels; ++t) {
    const int s = bc7_subset(m.subsets, partition, t);
    index1[t] = bits.read(m.index_bits - (bc7_anchor(m.subsets, partition, s) == t ? 1 : 0));
  }
  if (m.index2_bits)
    for (int t = 0; t < kBcBlockTexels; ++t) index2[t] = bits.read(m.index2_bits - (t == 0 ? 1 : 0));

  for (int t = 0; t < kBcBlockTexels; ++t) {
    const int s = bc7_subset(m.subsets, partition, t);
    int colour_w, alpha_w;
    if (m.index2_bits == 0) {
      colour_w = alpha_w = weight(m.index_bits, index1[t]);
    } else if (index_sel) {
      colour_w = weight(m.index2_bits, index2[t]);
      alpha_w = weight(m.index_bits, index1[t]);
    } else {
      colour_w = weight(m.index_bits, index1[t]);
      alpha_w = weight(m.index2_bits, index2[t]);
    }
    std::array<int, 4> c{};
    for (int ch = 0; ch < 3; ++ch) c[ch] = interpolate(e[ch][s][0], e[ch][s][1], colour_w);
    c[3] = interpolate(e[3][s][0], e[3][s][1], alpha_w);
    if (rotation) std::swap(c[3], c[rotation - 1]);
    out[t] = {static_cast<uint8_t>(c[0]), static_cast<uint8_t>(c[1]), static_cast<uint8_t>(c[2]),
              static_cast<uint8_t>(c[3])};
  }
  return out;
}

}  // namespace tfu
