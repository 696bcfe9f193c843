// Equivalence of the SystemVerilog BC1, BC4 and BC3 decoders (rtl/sv/bc/, Verilated) with the C++
// decoder the unit calls, tfu::decode_block (cmodel/block_formats.hpp; the rules of
// cmodel/bc_decode.hpp). docs/sv-bc.md. Per decoder:
//   * every pair of endpoint codes of the palette: every (a0, a1) of the BC4 / BC3 alpha half with
//     all eight codes read back, every (v0, v1) pair of each BC1 colour channel with all four codes
//     read back (the other fields random, eight draws per pair, alternately BC1 RGB and RGBA);
//   * 10^6 random blocks (seeded), four random texel positions each;
//   * hand-derived palettes (the latency tests);
// all streamed through the pipeline with random bubbles and stalls against a reference pipeline.
// The BC3 decoder is also built with RULE = RULE_TRUNCATE and checked against kBcRulesLibsquish.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "cmodel/bc7_decode.hpp"
#include "cmodel/bc_decode.hpp"
#include "cmodel/block_formats.hpp"
#include "testbench/iterations.hpp"

#include "Vtfu_bc1_decode.h"
#include "Vtfu_bc3_decode.h"
#include "Vtfu_bc3_decode_block.h"
#include "Vtfu_bc3_decode_truncate.h"
#include "Vtfu_bc4_decode.h"
#include "Vtfu_bc7_decode.h"
#include "Vtfu_bc7_decode_block.h"
#include "verilated.h"

namespace {

using tfu::BlockDecodeRules;
using tfu::BlockFormat;

constexpr uint64_t kSeed = 0xbc13ULL;
constexpr int64_t kRandomBlocks = tfu::test::iterations(1'000'000);
constexpr int kMaxReports = 8;
constexpr int kLatency = 2;     // clocks from the sampling edge to the result: BC1, BC3, BC4 (docs/sv-bc.md)
constexpr int kLatencyBc7 = 3;  // BC7

struct Mismatches {
  int count = 0;
  void add(const std::string& what) {
    if (++count <= kMaxReports) ADD_FAILURE() << what;
  }
};

// One request: a block (8 or 16 bytes; the rest zero), the texel positions t = 4 y + x of the ports
// (four; the whole-block decoders read texel k on port k), and for the BC1 decoder the format (BC1
// RGBA or RGB).
struct Request {
  std::array<uint8_t, 16> block{};
  std::array<int, 16> index{};
  bool rgba = false;
};

uint32_t word(const tfu::Rgba8& c) {
  return static_cast<uint32_t>(c.r) | static_cast<uint32_t>(c.g) << 8 | static_cast<uint32_t>(c.b) << 16 |
         static_cast<uint32_t>(c.a) << 24;
}

std::string hex(const std::array<uint8_t, 16>& b, int bytes) {
  std::string s;
  for (int i = 0; i < bytes; ++i) s += fmt::format("{:02x}", b[static_cast<size_t>(i)]);
  return s;
}

// A Verilated decoder of `Ports` texels per request: clock, reset, inputs from a Request, the output
// words.
template <class Model, int Ports = 4>
struct Dut {
  VerilatedContext ctx;
  Model m{&ctx};
  Dut() {
    m.clk = 0;
    m.rst_n = 0;
    m.en = 1;
    m.in_valid = 0;
    m.eval();
    tick();
    tick();
    m.rst_n = 1;
  }
  void set(const Request& r) {
    if constexpr (sizeof(m.block) == sizeof(uint64_t)) {
      uint64_t v = 0;
      for (int i = 7; i >= 0; --i) v = (v << 8) | r.block[static_cast<size_t>(i)];
      m.block = v;
    } else {
      for (size_t w = 0; w < 4; ++w)
        m.block[w] = static_cast<uint32_t>(r.block[4 * w]) | static_cast<uint32_t>(r.block[4 * w + 1]) << 8 |
                     static_cast<uint32_t>(r.block[4 * w + 2]) << 16 | static_cast<uint32_t>(r.block[4 * w + 3]) << 24;
    }
    if constexpr (requires { m.texel_index; }) {
      uint32_t idx = 0;
      for (int k = 0; k < 4; ++k) idx |= static_cast<uint32_t>(r.index[static_cast<size_t>(k)] & 15) << (4 * k);
      m.texel_index = static_cast<uint16_t>(idx);
    }
    if constexpr (requires { m.rgba; }) m.rgba = r.rgba;
  }
  uint32_t texel(int k) const { return m.texels[static_cast<size_t>(k)]; }
  void tick() {
    m.clk = 0;
    m.eval();
    m.clk = 1;
    m.eval();
  }
};

// The texels decode_block gives for the ports of a request.
std::array<uint32_t, 16> reference(BlockFormat f, const BlockDecodeRules& rules, const Request& r) {
  std::array<tfu::Rgba8, 16> out{};
  tfu::decode_block(r.rgba && f == BlockFormat::BC1 ? BlockFormat::BC1A : f, r.block.data(), rules, out.data());
  std::array<uint32_t, 16> w{};
  for (size_t k = 0; k < 16; ++k) w[k] = word(out[static_cast<size_t>(r.index[k])]);
  return w;
}

// Streams n requests gen(0..n-1) through the decoder, a quarter of the clocks without a request and
// an eighth stalled (en = 0), and checks every result against a reference pipeline of `latency`
// slots. Returns the number of results checked.
template <class Model, int Ports>
int64_t stream(Dut<Model, Ports>& dut, BlockFormat f, const BlockDecodeRules& rules, int64_t n,
               const std::function<Request(int64_t)>& gen, std::mt19937_64& rng, Mismatches& bad,
               int latency = kLatency) {
  struct Slot {
    bool valid = false;
    Request req;
    std::array<uint32_t, 16> want{};
  };
  std::array<Slot, kLatencyBc7> pipe{};
  const auto last = static_cast<size_t>(latency - 1);
  const int bytes = f == BlockFormat::BC3 || f == BlockFormat::BC7 ? 16 : 8;
  const auto busy = [&] {
    for (size_t i = 0; i <= last; ++i)
      if (pipe[i].valid) return true;
    return false;
  };
  int64_t issued = 0, checked = 0;
  for (int64_t cyc = 0; issued < n || busy(); ++cyc) {
    const bool en = (rng() % 8) != 0;
    const bool valid = issued < n && (rng() % 4) != 0;
    Slot in;
    if (valid) {
      in.valid = true;
      in.req = gen(issued);
      in.want = reference(f, rules, in.req);
    } else {
      in.req.block[0] = static_cast<uint8_t>(rng());  // bubbles carry junk
    }
    dut.set(in.req);
    dut.m.in_valid = valid;
    dut.m.en = en;
    dut.tick();
    if (!en) continue;
    if (valid) ++issued;
    for (size_t i = last; i > 0; --i) pipe[i] = pipe[i - 1];
    pipe[0] = in;
    const Slot& out = pipe[last];
    if (dut.m.out_valid != out.valid) {
      bad.add(fmt::format("cycle {}: out_valid {} expected {}", cyc, dut.m.out_valid, out.valid));
      continue;
    }
    if (!out.valid) continue;
    ++checked;
    for (int k = 0; k < Ports; ++k) {
      const uint32_t got = dut.texel(k), want = out.want[static_cast<size_t>(k)];
      if (got != want)
        bad.add(fmt::format("block {}{} texel {}: sv {:08x} decode_block {:08x}", hex(out.req.block, bytes),
                            out.req.rgba ? " (rgba)" : "", out.req.index[static_cast<size_t>(k)], got, want));
    }
  }
  return checked;
}

// Fills bytes [from, to) of a block with random bits.
void randomize(Request& r, int from, int to, std::mt19937_64& rng) {
  for (int i = from; i < to; ++i) r.block[static_cast<size_t>(i)] = static_cast<uint8_t>(rng());
}

// Every code of a palette read back: codes[t] of the code field (2 or 3 bits, at byte `at`) set to
// t mod 2^bits; request `part` reads the texels 4 part .. 4 part + 3.
void cycle_codes(Request& r, int at, int bits, int part) {
  uint64_t codes = 0;
  for (int t = 0; t < 16; ++t) codes |= static_cast<uint64_t>(t & ((1 << bits) - 1)) << (bits * t);
  for (int i = 0; i < 2 * bits; ++i) r.block[static_cast<size_t>(at + i)] = static_cast<uint8_t>(codes >> (8 * i));
  for (int k = 0; k < 4; ++k) r.index[static_cast<size_t>(k)] = 4 * part + k;
}

// A BC1 colour block (at byte `at`) whose channel (0 R, 1 G, 2 B) holds the field pair p of all
// (v0, v1) pairs of that channel; the other fields random.
void set_channel_pair(Request& r, int at, int ch, int64_t p, std::mt19937_64& rng) {
  const int shift = ch == 0 ? 11 : ch == 1 ? 5 : 0, bits = ch == 1 ? 6 : 5;
  const int mask = ((1 << bits) - 1) << shift;
  const int v0 = static_cast<int>(p >> bits), v1 = static_cast<int>(p & ((1 << bits) - 1));
  const int c0 = (static_cast<int>(rng()) & ~mask & 0xffff) | (v0 << shift);
  const int c1 = (static_cast<int>(rng()) & ~mask & 0xffff) | (v1 << shift);
  r.block[static_cast<size_t>(at)] = static_cast<uint8_t>(c0);
  r.block[static_cast<size_t>(at + 1)] = static_cast<uint8_t>(c0 >> 8);
  r.block[static_cast<size_t>(at + 2)] = static_cast<uint8_t>(c1);
  r.block[static_cast<size_t>(at + 3)] = static_cast<uint8_t>(c1 >> 8);
}

Request random_request(int bytes, std::mt19937_64& rng) {
  Request r;
  randomize(r, 0, bytes, rng);
  for (size_t k = 0; k < 4; ++k) r.index[k] = static_cast<int>(rng() % 16);
  r.rgba = (rng() & 1) != 0;
  return r;
}

// Requests of every channel's every field pair: 8 draws per pair (rgba alternating), 4 codes read back.
constexpr int64_t kColourPairs = 1024 + 4096 + 1024;
constexpr int kDrawsPerPair = 8;
Request colour_pair_request(int at, int64_t i, std::mt19937_64& rng) {
  const int64_t pair = i / kDrawsPerPair;
  const int ch = pair < 1024 ? 0 : pair < 1024 + 4096 ? 1 : 2;
  const int64_t p = ch == 0 ? pair : ch == 1 ? pair - 1024 : pair - 1024 - 4096;
  Request r;
  if (at > 0) randomize(r, 0, at, rng);  // BC3: a random alpha half
  set_channel_pair(r, at, ch, p, rng);
  cycle_codes(r, at + 4, 2, 0);
  r.rgba = (i & 1) != 0;
  return r;
}

// Requests of every alpha endpoint pair: 2 per pair (codes 0..3, 4..7).
Request alpha_pair_request(int64_t i, int bytes, std::mt19937_64& rng) {
  Request r;
  randomize(r, 8, bytes, rng);  // BC3: a random colour half
  r.block[0] = static_cast<uint8_t>(i >> 9);
  r.block[1] = static_cast<uint8_t>(i >> 1);
  cycle_codes(r, 2, 3, static_cast<int>(i & 1));
  return r;
}

// ------------------------------------------------------------------ BC1
TEST(SvBc1Decode, LatencyAndHandDerivedPalette) {
  Dut<Vtfu_bc1_decode> dut;
  // color0 = pure red (R = 31 -> 255), color1 = pure blue (B = 31 -> 255): 4-colour mode;
  // index 2 = (2 * 255 + 0 + 1) / 3 = 170 red, (0 + 255 + 1) / 3 = 85 blue; index 3 the mirror.
  Request r;
  r.block = {0x00, 0xf8, 0x1f, 0x00, 0xe4, 0, 0, 0};  // texels 0..3 take codes 0, 1, 2, 3
  r.index = {0, 1, 2, 3};
  dut.set(r);
  dut.m.in_valid = 1;
  dut.tick();  // edge n: request sampled
  dut.m.in_valid = 0;
  dut.set(Request{});
  EXPECT_EQ(dut.m.out_valid, 0);
  dut.tick();  // n + 1: result on the outputs
  EXPECT_EQ(dut.m.out_valid, 1);
  EXPECT_EQ(dut.texel(0), 0xff0000ffu);
  EXPECT_EQ(dut.texel(1), 0xffff0000u);
  EXPECT_EQ(dut.texel(2), 0xff5500aau);
  EXPECT_EQ(dut.texel(3), 0xffaa0055u);
  dut.tick();
  EXPECT_EQ(dut.m.out_valid, 0);
  // 3-colour mode (color0 <= color1) in BC1 RGBA: index 2 = (255 + 0 + 1) >> 1 = 128, index 3
  // transparent black.
  r.block = {0x1f, 0x00, 0x00, 0xf8, 0xe4, 0, 0, 0};
  r.rgba = true;
  dut.set(r);
  dut.m.in_valid = 1;
  dut.tick();
  dut.tick();
  EXPECT_EQ(dut.m.out_valid, 1);
  EXPECT_EQ(dut.texel(2), 0xff800080u);
  EXPECT_EQ(dut.texel(3), 0x00000000u);
}

TEST(SvBc1Decode, EveryFieldPairOfEveryChannel) {
  Dut<Vtfu_bc1_decode> dut;
  std::mt19937_64 rng(kSeed);
  Mismatches bad;
  const int64_t n = kColourPairs * kDrawsPerPair;
  const int64_t checked = stream(
      dut, BlockFormat::BC1, {}, n, [&](int64_t i) { return colour_pair_request(0, i, rng); }, rng, bad);
  EXPECT_EQ(checked, n);
  EXPECT_EQ(bad.count, 0);
}

TEST(SvBc1Decode, RandomBlocks) {
  Dut<Vtfu_bc1_decode> dut;
  std::mt19937_64 rng(kSeed + 1);
  Mismatches bad;
  const int64_t checked = stream(
      dut, BlockFormat::BC1, {}, kRandomBlocks, [&](int64_t) { return random_request(8, rng); }, rng, bad);
  EXPECT_EQ(checked, kRandomBlocks);
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ BC4
TEST(SvBc4Decode, LatencyAndHandDerivedValues) {
  Dut<Vtfu_bc4_decode> dut;
  // a0 = 255 > a1 = 0: 8 values, value c = round((8 - c) 255 / 7) for c = 2..7: 219 182 146 109 73 36.
  Request r;
  r.block = {255, 0};
  cycle_codes(r, 2, 3, 1);  // texels 4..7: codes 4, 5, 6, 7
  dut.set(r);
  dut.m.in_valid = 1;
  dut.tick();
  dut.m.in_valid = 0;
  EXPECT_EQ(dut.m.out_valid, 0);
  dut.tick();
  EXPECT_EQ(dut.m.out_valid, 1);
  EXPECT_EQ(dut.texel(0), 0xff000000u | 146);
  EXPECT_EQ(dut.texel(1), 0xff000000u | 109);
  EXPECT_EQ(dut.texel(2), 0xff000000u | 73);
  EXPECT_EQ(dut.texel(3), 0xff000000u | 36);
  dut.tick();
  EXPECT_EQ(dut.m.out_valid, 0);
  // a0 = 0 <= a1 = 255: 6 values; codes 4, 5 = round(3 * 255 / 5) = 153, round(4 * 255 / 5) = 204;
  // 6, 7 = 0, 255.
  r.block[0] = 0;
  r.block[1] = 255;
  dut.set(r);
  dut.m.in_valid = 1;
  dut.tick();
  dut.tick();
  EXPECT_EQ(dut.m.out_valid, 1);
  EXPECT_EQ(dut.texel(0), 0xff000000u | 153);
  EXPECT_EQ(dut.texel(1), 0xff000000u | 204);
  EXPECT_EQ(dut.texel(2), 0xff000000u);
  EXPECT_EQ(dut.texel(3), 0xff000000u | 255);
}

TEST(SvBc4Decode, EveryEndpointPairEveryCode) {
  Dut<Vtfu_bc4_decode> dut;
  std::mt19937_64 rng(kSeed + 2);
  Mismatches bad;
  const int64_t n = 2 * 65536;
  const int64_t checked = stream(
      dut, BlockFormat::BC4, {}, n, [&](int64_t i) { return alpha_pair_request(i, 8, rng); }, rng, bad);
  EXPECT_EQ(checked, n);
  EXPECT_EQ(bad.count, 0);
}

TEST(SvBc4Decode, RandomBlocks) {
  Dut<Vtfu_bc4_decode> dut;
  std::mt19937_64 rng(kSeed + 3);
  Mismatches bad;
  const int64_t checked = stream(
      dut, BlockFormat::BC4, {}, kRandomBlocks, [&](int64_t) { return random_request(8, rng); }, rng, bad);
  EXPECT_EQ(checked, kRandomBlocks);
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ BC3
TEST(SvBc3Decode, HandDerivedTexel) {
  Dut<Vtfu_bc3_decode> dut;
  // Alpha: a0 = 0 <= a1 = 255, texel 5 code 5 = round(4 * 255 / 5) = 204. Colour: color0 = blue <
  // color1 = red, yet 4-colour mode (BC3): texel 5 code 2 = (2 * 0 + 255 + 1) / 3 = 85 red,
  // (2 * 255 + 0 + 1) / 3 = 170 blue.
  Request r;
  r.block = {0, 255};
  cycle_codes(r, 2, 3, 1);  // texels 4..7: alpha codes 4..7
  r.block[8] = 0x1f;        // color0 = 0x001f
  r.block[11] = 0xf8;       // color1 = 0xf800
  r.block[13] = 0x08;       // colour codes of texels 4..7 in byte 13: texel 5 takes code 2
  r.index = {5, 5, 5, 5};
  dut.set(r);
  dut.m.in_valid = 1;
  dut.tick();
  dut.tick();
  EXPECT_EQ(dut.m.out_valid, 1);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(dut.texel(k), 0xccaa0055u);
}

TEST(SvBc3Decode, EveryAlphaEndpointPairEveryCode) {
  Dut<Vtfu_bc3_decode> dut;
  std::mt19937_64 rng(kSeed + 4);
  Mismatches bad;
  const int64_t n = 2 * 65536;
  const int64_t checked = stream(
      dut, BlockFormat::BC3, {}, n, [&](int64_t i) { return alpha_pair_request(i, 16, rng); }, rng, bad);
  EXPECT_EQ(checked, n);
  EXPECT_EQ(bad.count, 0);
}

TEST(SvBc3Decode, EveryColourFieldPairOfEveryChannel) {
  Dut<Vtfu_bc3_decode> dut;
  std::mt19937_64 rng(kSeed + 5);
  Mismatches bad;
  const int64_t n = kColourPairs * kDrawsPerPair;
  const int64_t checked = stream(
      dut, BlockFormat::BC3, {}, n, [&](int64_t i) { return colour_pair_request(8, i, rng); }, rng, bad);
  EXPECT_EQ(checked, n);
  EXPECT_EQ(bad.count, 0);
}

TEST(SvBc3Decode, RandomBlocks) {
  Dut<Vtfu_bc3_decode> dut;
  std::mt19937_64 rng(kSeed + 6);
  Mismatches bad;
  const int64_t checked = stream(
      dut, BlockFormat::BC3, {}, kRandomBlocks, [&](int64_t) { return random_request(16, rng); }, rng, bad);
  EXPECT_EQ(checked, kRandomBlocks);
  EXPECT_EQ(bad.count, 0);
}

// The truncating rule (RULE = RULE_TRUNCATE; libsquish 1.15 and Mesa): every alpha pair, every
// colour field pair, random blocks against decode_block with kBcRulesLibsquish.
TEST(SvBc3DecodeTruncate, EveryPairAndRandomBlocksMatchLibsquishRule) {
  Dut<Vtfu_bc3_decode_truncate> dut;
  std::mt19937_64 rng(kSeed + 7);
  Mismatches bad;
  const BlockDecodeRules rules{tfu::kBcRulesLibsquish, false};
  int64_t checked = stream(
      dut, BlockFormat::BC3, rules, 2 * 65536, [&](int64_t i) { return alpha_pair_request(i, 16, rng); }, rng, bad);
  checked += stream(
      dut, BlockFormat::BC3, rules, kColourPairs * kDrawsPerPair,
      [&](int64_t i) { return colour_pair_request(8, i, rng); }, rng, bad);
  checked += stream(
      dut, BlockFormat::BC3, rules, kRandomBlocks, [&](int64_t) { return random_request(16, rng); }, rng, bad);
  EXPECT_EQ(checked, 2 * 65536 + kColourPairs * kDrawsPerPair + kRandomBlocks);
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ BC7
// A random block of mode m (byte 0: m zeros, a one, random bits above), or the reserved byte 0 = 0
// for m = 8; the partition (when the mode has one) set to `partition` when >= 0.
Request bc7_request(int m, int partition, std::mt19937_64& rng) {
  Request r = random_request(16, rng);
  if (m == 8) {
    r.block[0] = 0;
    return r;
  }
  r.block[0] = static_cast<uint8_t>((r.block[0] << (m + 1)) | (1 << m));
  const int pb = tfu::kBc7Modes[static_cast<size_t>(m)].partition_bits;
  if (partition >= 0 && pb > 0) {
    // Bits m + 1 .. m + pb of the block, LSB first.
    for (int k = 0; k < pb; ++k) {
      const int bit = m + 1 + k, byte = bit / 8, sh = bit % 8;
      r.block[static_cast<size_t>(byte)] =
          static_cast<uint8_t>((r.block[static_cast<size_t>(byte)] & ~(1 << sh)) | (((partition >> k) & 1) << sh));
    }
  }
  return r;
}

TEST(SvBc7Decode, LatencyAndHandDerivedMode6) {
  Dut<Vtfu_bc7_decode> dut;
  // Mode 6 (byte 0 = 0x40): one subset, 7-bit colour and alpha + one p-bit per endpoint, 4-bit
  // indices. All endpoint fields and p-bits zero except R1 = 127 and p1 = 1: e0 = 0, R e1 = 255,
  // G, B, A e1 = 1 (the p-bit alone). Index of texel 1 = 15 (weight 64): (255, 1, 1, 1). Texel 0
  // (anchor, 3 bits) = 7, weight 30: R = (30 * 255 + 32) >> 6 = 120, G = B = A = (30 + 32) >> 6 = 0.
  // Layout: mode 7 bits, R0 7 @7, R1 7 @14, G0 @21, G1 @28, B0 @35, B1 @42, A0 @49, A1 @56, p0 @63,
  // p1 @64, indices from @65 (texel 0: 3 bits, then 4 bits each).
  Request r;
  r.block[0] = 0x40;
  const auto set_bits = [&](int at, int width, int value) {
    for (int k = 0; k < width; ++k) {
      const int bit = at + k;
      if ((value >> k) & 1) r.block[static_cast<size_t>(bit / 8)] |= static_cast<uint8_t>(1 << (bit % 8));
    }
  };
  set_bits(14, 7, 127);
  set_bits(64, 1, 1);
  set_bits(65, 3, 7);
  set_bits(68, 4, 15);
  r.index = {0, 1, 2, 1};
  dut.set(r);
  dut.m.in_valid = 1;
  dut.tick();
  dut.m.in_valid = 0;
  dut.tick();
  EXPECT_EQ(dut.m.out_valid, 0);
  dut.tick();
  EXPECT_EQ(dut.m.out_valid, 1);
  EXPECT_EQ(dut.texel(0), 0x00000078u);
  EXPECT_EQ(dut.texel(1), 0x010101ffu);
  EXPECT_EQ(dut.texel(2), 0x00000000u);  // index 0: e0
  dut.tick();
  EXPECT_EQ(dut.m.out_valid, 0);
}

TEST(SvBc7Decode, EveryModeEveryPartitionEveryTexel) {
  Dut<Vtfu_bc7_decode> dut;
  std::mt19937_64 rng(kSeed + 8);
  Mismatches bad;
  // Mode m (0..7, 8 = reserved) x partition (64, or 1 for the modes without) x 16 draws x the 16
  // texels in 4 requests of four positions.
  std::vector<std::pair<int, int>> cases;
  for (int m = 0; m <= 8; ++m) {
    const int parts = m < 8 && tfu::kBc7Modes[static_cast<size_t>(m)].partition_bits > 0 ? 64 : 1;
    for (int p = 0; p < parts; ++p) cases.emplace_back(m, p);
  }
  const int64_t per_case = 16 * 4;
  const int64_t n = static_cast<int64_t>(cases.size()) * per_case;
  Request block;
  const int64_t checked = stream(
      dut, BlockFormat::BC7, {}, n,
      [&](int64_t i) {
        const auto [m, p] = cases[static_cast<size_t>(i / per_case)];
        if (i % 4 == 0) block = bc7_request(m, p, rng);
        Request r = block;
        for (int k = 0; k < 4; ++k) r.index[static_cast<size_t>(k)] = static_cast<int>(4 * (i % 4) + k);
        return r;
      },
      rng, bad, kLatencyBc7);
  EXPECT_EQ(checked, n);
  EXPECT_EQ(bad.count, 0);
}

TEST(SvBc7Decode, RandomBlocksOfEveryMode) {
  Dut<Vtfu_bc7_decode> dut;
  std::mt19937_64 rng(kSeed + 9);
  Mismatches bad;
  // Modes uniform over 0..7 (random bytes would be mode 0 half the time), every 64th block reserved.
  const int64_t checked = stream(
      dut, BlockFormat::BC7, {}, kRandomBlocks,
      [&](int64_t i) { return bc7_request(i % 64 == 63 ? 8 : static_cast<int>(rng() % 8), -1, rng); }, rng, bad,
      kLatencyBc7);
  EXPECT_EQ(checked, kRandomBlocks);
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ whole-block decoders (16 ports)
constexpr int64_t kWholeBlocks = tfu::test::iterations(100'000);

Request whole_block(Request r) {
  for (size_t k = 0; k < 16; ++k) r.index[k] = static_cast<int>(k);
  return r;
}

TEST(SvBc3DecodeBlock, EveryAlphaPairAndRandomBlocksEveryTexel) {
  Dut<Vtfu_bc3_decode_block, 16> dut;
  std::mt19937_64 rng(kSeed + 10);
  Mismatches bad;
  int64_t checked = stream(
      dut, BlockFormat::BC3, {}, 65536, [&](int64_t i) { return whole_block(alpha_pair_request(2 * i, 16, rng)); }, rng,
      bad);
  checked += stream(
      dut, BlockFormat::BC3, {}, kWholeBlocks, [&](int64_t) { return whole_block(random_request(16, rng)); }, rng, bad);
  EXPECT_EQ(checked, 65536 + kWholeBlocks);
  EXPECT_EQ(bad.count, 0);
}

TEST(SvBc7DecodeBlock, EveryModePartitionAndRandomBlocksEveryTexel) {
  Dut<Vtfu_bc7_decode_block, 16> dut;
  std::mt19937_64 rng(kSeed + 11);
  Mismatches bad;
  std::vector<std::pair<int, int>> cases;
  for (int m = 0; m <= 8; ++m) {
    const int parts = m < 8 && tfu::kBc7Modes[static_cast<size_t>(m)].partition_bits > 0 ? 64 : 1;
    for (int p = 0; p < parts; ++p) cases.emplace_back(m, p);
  }
  const int64_t per_case = 16;
  const int64_t n = static_cast<int64_t>(cases.size()) * per_case;
  int64_t checked = stream(
      dut, BlockFormat::BC7, {}, n,
      [&](int64_t i) {
        const auto [m, p] = cases[static_cast<size_t>(i / per_case)];
        return whole_block(bc7_request(m, p, rng));
      },
      rng, bad, kLatencyBc7);
  checked += stream(
      dut, BlockFormat::BC7, {}, kWholeBlocks,
      [&](int64_t i) { return whole_block(bc7_request(i % 64 == 63 ? 8 : static_cast<int>(rng() % 8), -1, rng)); }, rng,
      bad, kLatencyBc7);
  EXPECT_EQ(checked, n + kWholeBlocks);
  EXPECT_EQ(bad.count, 0);
}

}  // namespace
