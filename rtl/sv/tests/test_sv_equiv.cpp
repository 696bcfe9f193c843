// Equivalence of the SystemVerilog datapath blocks (rtl/sv/, Verilated) with the C++ model they
// implement (cmodel/). Exhaustive where the input space is at most 2^24, otherwise >= 10^6 random
// vectors plus directed corners (docs/sv.md). Every mismatch is counted; the first few are printed.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cmodel/datapath.hpp"
#include "cmodel/kernels.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/rom_dump.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/unorm.hpp"
#include "cmodel/weight_rom.hpp"
#include "rtl/sv/tests/sv_texel.hpp"
#include "testbench/iterations.hpp"
#include "tfu_sv_params.hpp"  // generated: W2_BITS, ACC_BITS of gen/tfu_cubic_pkg.sv

#include "Vtfu_bilinear_lerp.h"
#include "Vtfu_bilinear_top.h"
#include "Vtfu_bilinear_top_l4.h"
#include "Vtfu_cubic_filter.h"
#include "Vtfu_cubic_norm.h"
#include "Vtfu_cubic_weights.h"
#include "Vtfu_level_blend.h"
#include "Vtfu_log2_rom.h"
#include "Vtfu_log2_unit.h"
#include "Vtfu_tile_rom.h"
#include "Vtfu_tile_weight_mul.h"
#include "verilated.h"

namespace {

using tfu::Texel4;

constexpr uint64_t kSeed = 0x7f0dULL;
constexpr int kRandomVectors = tfu::test::iterations(1'000'000);  // testbench/iterations.hpp
constexpr int kMaxReports = 8;

// Counts mismatches and reports the first few.
struct Mismatches {
  int count = 0;
  void add(const std::string& what) {
    if (++count <= kMaxReports) ADD_FAILURE() << what;
  }
};

// The default CUBIC ROM of SamplerDescriptor (what tfu_svgen generates).
const tfu::TileWeightRom& default_rom() {
  static const tfu::SamplerDescriptor cfg;
  static const tfu::TileWeightRom rom(tfu::FilterKernel::by_name(cfg.kernel), cfg.cubic_rom);
  return rom;
}

int64_t sext(uint64_t v, int bits) {
  const uint64_t m = uint64_t{1} << (bits - 1);
  v &= (bits == 64) ? ~uint64_t{0} : ((uint64_t{1} << bits) - 1);
  return static_cast<int64_t>((v ^ m) - m);
}

// Bits [lsb, lsb + width) of a wide Verilator signal (width <= 32).
template <std::size_t N>
uint32_t field(const VlWide<N>& w, int lsb, int width) {
  uint64_t v = w[static_cast<std::size_t>(lsb / 32)];
  if (static_cast<std::size_t>(lsb / 32 + 1) < N) v |= uint64_t{w[static_cast<std::size_t>(lsb / 32 + 1)]} << 32;
  return static_cast<uint32_t>((v >> (lsb % 32)) & ((uint64_t{1} << width) - 1));
}

using tfu::svtest::pack;
using tfu::svtest::str;
using tfu::svtest::unpack;
Texel4 random_texel(std::mt19937_64& rng) { return unpack(static_cast<uint32_t>(rng())); }

// ------------------------------------------------------------------ ROMs (every address)
TEST(SvRom, TileRomEveryAddressMatchesTileWeightRom) {
  VerilatedContext ctx;
  Vtfu_tile_rom m{&ctx};
  const auto& rom = default_rom();
  const unsigned bits = rom.spec().bits;
  const int word = static_cast<int>(bits) + 1;
  ASSERT_EQ(rom.taps(), 4);
  ASSERT_EQ(rom.entries(), 64);
  Mismatches bad;
  for (int a = 0; a < rom.entries(); ++a) {
    m.addr = static_cast<uint8_t>(a);
    m.eval();
    for (int t = 0; t < rom.taps(); ++t) {
      const auto got = static_cast<uint32_t>((m.row >> (word * t)) & ((uint64_t{1} << word) - 1));
      const uint32_t want = tfu::tile_word_bits(rom.row(a)[static_cast<size_t>(t)], bits);
      if (got != want) bad.add(fmt::format("addr {} tap {}: sv {:#x} c++ {:#x}", a, t, got, want));
    }
  }
  EXPECT_EQ(bad.count, 0);
}

TEST(SvRom, Log2RomEveryAddressMatchesLog2Rom) {
  VerilatedContext ctx;
  Vtfu_log2_rom m{&ctx};
  const auto& rom = tfu::log2_rom();
  Mismatches bad;
  for (uint32_t a = 0; a < rom.size(); ++a) {
    m.addr = static_cast<uint16_t>(a);
    m.eval();
    if (m.data != rom[a]) bad.add(fmt::format("addr {}: sv {} c++ {}", a, m.data, rom[a]));
  }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ log2 unit
TEST(SvLog2Unit, MatchesLog2Q8) {
  VerilatedContext ctx;
  Vtfu_log2_unit m{&ctx};
  Mismatches bad;
  int64_t n = 0;
  const auto check = [&](uint64_t x) {
    m.x = x;
    m.eval();
    const int64_t got = sext(m.log2_q8, 16);
    const int32_t want = tfu::log2_q8(x);
    if (got != want) bad.add(fmt::format("x = {:#x}: sv {} c++ {}", x, got, want));
    ++n;
  };
  // Exhaustive below 2^20 (covers every e < 9 case, where the index is x shifted left).
  for (uint64_t x = 0; x < (uint64_t{1} << 20); ++x) check(x);
  // Every power of two and its neighbours, all-ones prefixes.
  for (int e = 0; e < 64; ++e) {
    const uint64_t p = uint64_t{1} << e;
    for (const uint64_t x : {p, p - 1, p + 1, p | (p >> 1), p | (p - 1), ~uint64_t{0} >> (63 - e)}) check(x);
  }
  // Random values with a random leading-one position (uniform in e, then uniform below it).
  std::mt19937_64 rng(kSeed);
  for (int k = 0; k < kRandomVectors; ++k) {
    const int e = static_cast<int>(rng() % 64);
    const uint64_t x = (rng() >> (63 - e)) | (uint64_t{1} << e);
    check(x);
  }
  EXPECT_EQ(bad.count, 0) << "of " << n << " vectors";
}

// ------------------------------------------------------------------ tile-weight multiplier
TEST(SvTileWeightMul, AllSignMagnitudePairs) {
  VerilatedContext ctx;
  Vtfu_tile_weight_mul m{&ctx};
  constexpr unsigned kBits = 8;
  Mismatches bad;
  for (uint32_t x = 0; x < 512; ++x)
    for (uint32_t y = 0; y < 512; ++y) {
      m.wx = static_cast<uint16_t>(x);
      m.wy = static_cast<uint16_t>(y);
      m.eval();
      const auto sv = [](uint32_t w) {
        const auto mag = static_cast<int32_t>(w & 255);
        return (w & 256) ? -mag : mag;
      };
      const int64_t got = sext(m.w, 9);
      const int32_t want = tfu::tile_weight_multiply(sv(x), sv(y), kBits);
      if (got != want) bad.add(fmt::format("wx {:#x} wy {:#x}: sv {} c++ {}", x, y, got, want));
    }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ cubic weights (all fu, fv)
TEST(SvCubicWeights, AllFractionPairsMatchTileWeights2d) {
  VerilatedContext ctx;
  Vtfu_cubic_weights m{&ctx};
  const auto& rom = default_rom();
  Mismatches bad;
  std::array<int32_t, 16> w2{};
  for (uint32_t fu = 0; fu < 256; ++fu)
    for (uint32_t fv = 0; fv < 256; ++fv) {
      m.fu = static_cast<uint8_t>(fu);
      m.fv = static_cast<uint8_t>(fv);
      m.eval();
      tfu::dp::tile_weights_2d(rom, tfu::RomRecon::Nearest, fu, fv, w2);
      for (int k = 0; k < 16; ++k) {
        const int64_t got = sext(field(m.w, tfu::sv::kW2Bits * k, tfu::sv::kW2Bits), tfu::sv::kW2Bits);
        if (got != w2[static_cast<size_t>(k)])
          bad.add(fmt::format("fu {} fv {} tap {}: sv {} c++ {}", fu, fv, k, got, w2[static_cast<size_t>(k)]));
      }
    }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ cubic normalisation
// The CUBIC output stage of Sampler::sample_level_filter (cmodel/sampler.cpp), M = 255:
// clamp(floor_div(2 acc + M, 2 M), 0, 255), floor_div rounding towards -infinity.
int32_t cubic_norm_ref(int64_t acc) {
  const int64_t a = 2 * acc + 255, b = 510;
  const int64_t q = a >= 0 ? a / b : -((-a + b - 1) / b);
  return static_cast<int32_t>(q < 0 ? 0 : (q > 255 ? 255 : q));
}

TEST(SvCubicNorm, EveryAccumulatorValue) {
  VerilatedContext ctx;
  Vtfu_cubic_norm m{&ctx};
  const int bits = tfu::sv::kAccBits;
  ASSERT_LE(bits, 24);
  Mismatches bad;
  for (int64_t acc = -(int64_t{1} << (bits - 1)); acc < (int64_t{1} << (bits - 1)); ++acc) {
    m.acc = static_cast<uint32_t>(acc) & ((uint32_t{1} << bits) - 1);
    m.eval();
    const int32_t want = cubic_norm_ref(acc);
    if (m.c != want) bad.add(fmt::format("acc {}: sv {} c++ {}", acc, m.c, want));
  }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ cubic filter
// Reference: the CUBIC datapath of the golden sampler for a 4x4 footprint (tile_weights_2d,
// filter_tiled_acc's sum c w, the output normalisation above).
Texel4 cubic_ref(const std::array<Texel4, 16>& t, uint32_t fu, uint32_t fv) {
  std::array<int32_t, 16> w2{};
  tfu::dp::tile_weights_2d(default_rom(), tfu::RomRecon::Nearest, fu, fv, w2);
  Texel4 out{};
  for (size_t ch = 0; ch < 4; ++ch) {
    int64_t acc = 0;
    for (size_t k = 0; k < 16; ++k) acc += int64_t{t[k][ch]} * w2[k];
    out[ch] = cubic_norm_ref(acc);
  }
  return out;
}

struct CubicDut {
  VerilatedContext ctx;
  Vtfu_cubic_filter m{&ctx};
  Texel4 run(const std::array<Texel4, 16>& t, uint32_t fu, uint32_t fv) {
    for (size_t k = 0; k < 16; ++k) m.texels[k] = pack(t[k]);
    m.fu = static_cast<uint8_t>(fu);
    m.fv = static_cast<uint8_t>(fv);
    m.eval();
    return unpack(m.c);
  }
};

TEST(SvCubicFilter, RandomAndCornersMatchSamplerDatapath) {
  CubicDut dut;
  Mismatches bad;
  const auto check = [&](const std::array<Texel4, 16>& t, uint32_t fu, uint32_t fv) {
    const Texel4 got = dut.run(t, fu, fv), want = cubic_ref(t, fu, fv);
    if (got != want) bad.add(fmt::format("fu {} fv {} t0 {}: sv {} c++ {}", fu, fv, str(t[0]), str(got), str(want)));
  };
  std::mt19937_64 rng(kSeed + 1);
  std::array<Texel4, 16> t{};
  // Directed: constant textures (0, 255, random) at every fraction pair on a grid incl. 0 and 255.
  for (const int v : {0, 255, 1, 128, 254}) {
    t.fill({v, v, v, v});
    for (uint32_t fu = 0; fu < 256; fu += 5)
      for (uint32_t fv = 0; fv < 256; fv += 5) check(t, fu, fv);
    for (const uint32_t f : {0u, 255u, 3u, 4u, 252u}) check(t, f, 255u - f);
  }
  // Directed: checkerboards and single bright / dark taps (maximise the negative lobes).
  for (uint32_t fu : {0u, 64u, 128u, 191u, 255u})
    for (uint32_t fv : {0u, 64u, 128u, 191u, 255u}) {
      for (size_t k = 0; k < 16; ++k) t[k] = ((k + k / 4) % 2) ? Texel4{255, 0, 255, 0} : Texel4{0, 255, 0, 255};
      check(t, fu, fv);
      for (size_t hot = 0; hot < 16; ++hot) {
        t.fill({0, 255, 0, 255});
        t[hot] = {255, 0, 255, 0};
        check(t, fu, fv);
      }
    }
  // Random: uniform texels, and texels near 0/255 (exercises the clamp).
  for (int k = 0; k < kRandomVectors; ++k) {
    const bool extreme = (k & 3) == 0;
    for (auto& c : t) {
      c = random_texel(rng);
      if (extreme)
        for (auto& ch : c) ch = (ch & 1) ? 255 - (ch >> 6) : (ch >> 6);
    }
    check(t, static_cast<uint32_t>(rng() & 255), static_cast<uint32_t>(rng() & 255));
  }
  EXPECT_EQ(bad.count, 0);
}

// Ties the block to the golden Sampler itself: a 4x4 rgba8 texture, CUBIC, clamp-to-edge,
// s = (384 + fu) / 1024 puts i0 = 1 and the fraction fu, so the footprint is the whole texture.
TEST(SvCubicFilter, MatchesGoldenSampler) {
  CubicDut dut;
  std::mt19937_64 rng(kSeed + 2);
  tfu::SamplerDescriptor cfg;
  cfg.mode = tfu::filter_mode_from_name("cubic");
  cfg.wrap_s = cfg.wrap_t = tfu::WrapMode::ClampToEdge;
  Mismatches bad;
  for (int tex = 0; tex < 40; ++tex) {
    tfu::Texture texture;
    texture.levels.emplace_back(4, 4);
    std::array<Texel4, 16> t{};
    for (size_t k = 0; k < 16; ++k) {
      t[k] = random_texel(rng);
      if (tex % 4 == 0)
        for (auto& ch : t[k]) ch = (ch & 1) ? 255 : 0;
      texture.levels[0].texels[k] = {static_cast<uint8_t>(t[k][0]), static_cast<uint8_t>(t[k][1]),
                                     static_cast<uint8_t>(t[k][2]), static_cast<uint8_t>(t[k][3])};
    }
    const tfu::Sampler sampler(texture, cfg);
    for (int k = 0; k < 500; ++k) {
      const auto fu = static_cast<uint32_t>(rng() & 255), fv = static_cast<uint32_t>(rng() & 255);
      const tfu::Rgba8 g = sampler.sample(static_cast<float>(384 + fu) / 1024.0f, static_cast<float>(384 + fv) / 1024.0f, -256);
      const Texel4 want{g.r, g.g, g.b, g.a};
      const Texel4 got = dut.run(t, fu, fv);
      if (got != want) bad.add(fmt::format("texture {} fu {} fv {}: sv {} sampler {}", tex, fu, fv, str(got), str(want)));
    }
  }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ bilinear lerp
struct BilinearDut {
  VerilatedContext ctx;
  Vtfu_bilinear_lerp m{&ctx};
  Texel4 run(const std::array<Texel4, 4>& c, uint32_t fu, uint32_t fv) {
    m.c00 = pack(c[0]);
    m.c10 = pack(c[1]);
    m.c01 = pack(c[2]);
    m.c11 = pack(c[3]);
    m.fu = static_cast<uint8_t>(fu);
    m.fv = static_cast<uint8_t>(fv);
    m.eval();
    return unpack(m.c);
  }
};

TEST(SvBilinearLerp, RandomAndCornersMatchDatapath) {
  BilinearDut dut;
  Mismatches bad;
  const auto check = [&](const std::array<Texel4, 4>& c, uint32_t fu, uint32_t fv) {
    const Texel4 got = dut.run(c, fu, fv);
    const Texel4 want = tfu::dp::bilinear_lerp(c, fu, fv, tfu::TexelFormat::RGBA8);
    if (got != want)
      bad.add(fmt::format("c {} {} {} {} fu {} fv {}: sv {} c++ {}", str(c[0]), str(c[1]), str(c[2]), str(c[3]), fu,
                          fv, str(got), str(want)));
  };
  // Directed: all-equal inputs and every 0/255 corner pattern at every (fu, fv) pair.
  for (const int v : {0, 255, 1, 127, 128, 254}) {
    const Texel4 tv{v, v, v, v};
    for (uint32_t fu = 0; fu < 256; ++fu)
      for (uint32_t fv = 0; fv < 256; ++fv) check({tv, tv, tv, tv}, fu, fv);
  }
  for (int pattern = 0; pattern < 16; ++pattern) {
    std::array<Texel4, 4> c{};
    for (size_t k = 0; k < 4; ++k) {
      const int v = (pattern >> k) & 1 ? 255 : 0;
      c[k] = {v, 255 - v, v, 255 - v};
    }
    for (uint32_t fu = 0; fu < 256; ++fu)
      for (uint32_t fv = 0; fv < 256; ++fv) check(c, fu, fv);
  }
  std::mt19937_64 rng(kSeed + 3);
  std::array<Texel4, 4> c{};
  for (int k = 0; k < kRandomVectors; ++k) {
    for (auto& t : c) t = random_texel(rng);
    uint32_t fu = static_cast<uint32_t>(rng() & 255), fv = static_cast<uint32_t>(rng() & 255);
    if ((k & 15) == 0) fu = (k & 16) ? 0u : 255u;
    if ((k & 15) == 1) fv = (k & 16) ? 0u : 255u;
    check(c, fu, fv);
  }
  EXPECT_EQ(bad.count, 0);
}

// Ties the block to the golden Sampler: a 2x2 rgba8 texture, LINEAR, clamp-to-edge,
// s = (128 + fu) / 512 gives i0 = 0 and the fraction fu.
TEST(SvBilinearLerp, MatchesGoldenSampler) {
  BilinearDut dut;
  std::mt19937_64 rng(kSeed + 4);
  tfu::SamplerDescriptor cfg;
  cfg.mode = tfu::filter_mode_from_name("linear");
  cfg.wrap_s = cfg.wrap_t = tfu::WrapMode::ClampToEdge;
  Mismatches bad;
  for (int tex = 0; tex < 40; ++tex) {
    tfu::Texture texture;
    texture.levels.emplace_back(2, 2);
    std::array<Texel4, 4> c{};
    for (size_t k = 0; k < 4; ++k) {
      c[k] = random_texel(rng);
      texture.levels[0].texels[k] = {static_cast<uint8_t>(c[k][0]), static_cast<uint8_t>(c[k][1]),
                                     static_cast<uint8_t>(c[k][2]), static_cast<uint8_t>(c[k][3])};
    }
    const tfu::Sampler sampler(texture, cfg);
    for (int k = 0; k < 2000; ++k) {
      const auto fu = static_cast<uint32_t>(rng() & 255), fv = static_cast<uint32_t>(rng() & 255);
      const tfu::Rgba8 g = sampler.sample(static_cast<float>(128 + fu) / 512.0f, static_cast<float>(128 + fv) / 512.0f, -256);
      const Texel4 want{g.r, g.g, g.b, g.a};
      const Texel4 got = dut.run(c, fu, fv);
      if (got != want) bad.add(fmt::format("texture {} fu {} fv {}: sv {} sampler {}", tex, fu, fv, str(got), str(want)));
    }
  }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ trilinear blend
// Q.8 channels, four 16-bit fields of a 64-bit port (channel k in bits [16k+15:16k]).
uint64_t pack_q8(const Texel4& q) {
  uint64_t w = 0;
  for (size_t ch = 0; ch < 4; ++ch) w |= uint64_t{static_cast<uint16_t>(q[ch])} << (16 * ch);
  return w;
}
Texel4 unpack_q8(uint64_t w) {
  Texel4 q{};
  for (size_t ch = 0; ch < 4; ++ch) q[ch] = static_cast<int32_t>((w >> (16 * ch)) & 0xFFFF);
  return q;
}

// Codes entering as code << 8 (NEAREST, CUBIC, EDGE_PRESERVING levels), exhaustively: 2^24 (c0, c1,
// f) triples, the four channels taking four different (c0, c1) pairs per evaluation.
TEST(SvLevelBlend, ExhaustiveOverCodesC0C1F) {
  VerilatedContext ctx;
  Vtfu_level_blend m{&ctx};
  Mismatches bad;
  for (uint32_t f = 0; f < 256; ++f) {
    m.f = static_cast<uint8_t>(f);
    for (uint32_t p = 0; p < 65536; p += 4) {
      Texel4 c0{}, c1{};
      for (size_t ch = 0; ch < 4; ++ch) {
        c0[ch] = static_cast<int32_t>((p + ch) >> 8);
        c1[ch] = static_cast<int32_t>((p + ch) & 255);
      }
      m.c0 = pack_q8(tfu::dp::level_q8(c0));
      m.c1 = pack_q8(tfu::dp::level_q8(c1));
      m.eval();
      const Texel4 got = unpack(m.c), want = tfu::dp::level_blend_codes(c0, c1, static_cast<int>(f));
      if (got != want) bad.add(fmt::format("c0 {} c1 {} f {}: sv {} c++ {}", str(c0), str(c1), f, str(got), str(want)));
    }
  }
  EXPECT_EQ(bad.count, 0);
}

// Q.8 level results (the bilinear lerp unit's, 0..65280): random channels, the extremes, every f.
TEST(SvLevelBlend, RandomQ8LevelResults) {
  VerilatedContext ctx;
  Vtfu_level_blend m{&ctx};
  std::mt19937_64 rng(kSeed + 7);
  Mismatches bad;
  for (int i = 0; i < kRandomVectors; ++i) {
    Texel4 c0{}, c1{};
    for (size_t ch = 0; ch < 4; ++ch) {
      const uint64_t r = rng();
      const auto q8 = [](uint64_t x) { return static_cast<int32_t>(x % 65281); };
      c0[ch] = i < 256 ? (ch & 1u ? 65280 : 0) : q8(r);
      c1[ch] = i < 256 ? (ch & 1u ? 0 : 65280) : q8(r >> 32);
    }
    const int f = i & 255;
    m.c0 = pack_q8(c0);
    m.c1 = pack_q8(c1);
    m.f = static_cast<uint8_t>(f);
    m.eval();
    const Texel4 got = unpack(m.c), want = tfu::dp::level_blend(c0, c1, f);
    if (got != want) bad.add(fmt::format("c0 {} c1 {} f {}: sv {} c++ {}", str(c0), str(c1), f, str(got), str(want)));
  }
  EXPECT_EQ(bad.count, 0);
}

// ------------------------------------------------------------------ pipelined bilinear top
// The top at each offered depth (parameter CUT_V of tfu_bilinear_top): latency 3 and 4 clocks.
template <class Model, int Latency>
struct TopDut {
  static constexpr int kLatency = Latency;
  VerilatedContext ctx;
  Model m{&ctx};
  TopDut() {
    m.clk = 0;
    m.rst_n = 0;
    m.en = 1;
    m.in_valid = 0;
    m.eval();
    tick();
    tick();
    m.rst_n = 1;
  }
  void set(const std::array<Texel4, 4>& c, uint32_t fu, uint32_t fv) {
    m.c00 = pack(c[0]);
    m.c10 = pack(c[1]);
    m.c01 = pack(c[2]);
    m.c11 = pack(c[3]);
    m.fu = static_cast<uint8_t>(fu);
    m.fv = static_cast<uint8_t>(fv);
  }
  void tick() {  // one rising edge
    m.clk = 0;
    m.eval();
    m.clk = 1;
    m.eval();
  }
};

template <class Dut>
void latency_is_exact() {
  Dut dut;
  const std::array<Texel4, 4> c{Texel4{10, 20, 30, 40}, Texel4{200, 100, 0, 255}, Texel4{1, 2, 3, 4}, Texel4{9, 9, 9, 9}};
  dut.set(c, 77, 200);
  dut.m.in_valid = 1;
  dut.tick();  // edge n: request sampled
  dut.m.in_valid = 0;
  dut.set({}, 0, 0);
  EXPECT_EQ(dut.m.out_valid, 0);
  for (int k = 1; k < Dut::kLatency - 1; ++k) {
    dut.tick();  // n + k
    EXPECT_EQ(dut.m.out_valid, 0);
  }
  dut.tick();  // n + kLatency - 1: result on the outputs
  EXPECT_EQ(dut.m.out_valid, 1);
  EXPECT_EQ(unpack(dut.m.c), tfu::dp::bilinear_lerp(c, 77, 200, tfu::TexelFormat::RGBA8));
  EXPECT_EQ(unpack_q8(dut.m.q), tfu::dp::bilinear_lerp_q8(c, 77, 200));
  dut.tick();
  EXPECT_EQ(dut.m.out_valid, 0);
}

template <class Dut>
void random_stream_with_stalls_matches_datapath() {
  Dut dut;
  std::mt19937_64 rng(kSeed + 5);
  struct Slot {
    bool valid = false;
    Texel4 c{}, q{};
  };
  std::array<Slot, Dut::kLatency> pipe{};  // reference pipeline: S1, S2, ...
  constexpr size_t kLast = Dut::kLatency - 1;
  Mismatches bad;
  int results = 0;
  for (int cyc = 0; cyc < kRandomVectors; ++cyc) {
    std::array<Texel4, 4> c{};
    for (auto& t : c) t = random_texel(rng);
    const auto fu = static_cast<uint32_t>(rng() & 255), fv = static_cast<uint32_t>(rng() & 255);
    const bool valid = (rng() % 4) != 0, en = (rng() % 8) != 0;
    dut.set(c, fu, fv);
    dut.m.in_valid = valid;
    dut.m.en = en;
    dut.tick();
    if (en) {
      for (size_t k = kLast; k > 0; --k) pipe[k] = pipe[k - 1];
      pipe[0] = {valid, tfu::dp::bilinear_lerp(c, fu, fv, tfu::TexelFormat::RGBA8), tfu::dp::bilinear_lerp_q8(c, fu, fv)};
    }
    if (dut.m.out_valid != pipe[kLast].valid) {
      bad.add(fmt::format("cycle {}: out_valid {} expected {}", cyc, dut.m.out_valid, pipe[kLast].valid));
    } else if (pipe[kLast].valid) {
      ++results;
      if (unpack(dut.m.c) != pipe[kLast].c || unpack_q8(dut.m.q) != pipe[kLast].q)
        bad.add(fmt::format("cycle {}: sv {} q {} c++ {} q {}", cyc, str(unpack(dut.m.c)), str(unpack_q8(dut.m.q)),
                            str(pipe[kLast].c), str(pipe[kLast].q)));
    }
  }
  EXPECT_GT(results, kRandomVectors / 2);
  EXPECT_EQ(bad.count, 0);
}

using Top3 = TopDut<Vtfu_bilinear_top, 3>;
using Top4 = TopDut<Vtfu_bilinear_top_l4, 4>;

TEST(SvBilinearTop, LatencyIsThreeClocks) { latency_is_exact<Top3>(); }
TEST(SvBilinearTop, RandomStreamWithStallsMatchesDatapath) { random_stream_with_stalls_matches_datapath<Top3>(); }
TEST(SvBilinearTopL4, LatencyIsFourClocks) { latency_is_exact<Top4>(); }
TEST(SvBilinearTopL4, RandomStreamWithStallsMatchesDatapath) { random_stream_with_stalls_matches_datapath<Top4>(); }

}  // namespace
