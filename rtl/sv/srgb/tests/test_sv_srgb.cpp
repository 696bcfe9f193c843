// Equivalence of the sRGB texel decode and result encode in SystemVerilog (rtl/sv/srgb/, Verilated)
// with the C++ model (cmodel/srgb.hpp through decode_texel / encode_texel), bit for bit and
// exhaustive over the ROM addresses: every byte in every colour lane, both formats (docs/srgb.md).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "cmodel/srgb.hpp"
#include "cmodel/texture.hpp"
#include "testbench/iterations.hpp"

#include "Vtfu_srgb_texel_decode.h"
#include "Vtfu_srgb_texel_encode.h"
#include "verilated.h"

namespace {

using tfu::Rgba8;
using tfu::Texel4;
using tfu::TexelFormat;

uint32_t word_bits(Rgba8 w) { return w.r | (uint32_t{w.g} << 8) | (uint32_t{w.b} << 16) | (uint32_t{w.a} << 24); }
Texel4 channels(uint64_t c) {
  return {static_cast<int32_t>(c & 4095), static_cast<int32_t>((c >> 12) & 4095),
          static_cast<int32_t>((c >> 24) & 4095), static_cast<int32_t>((c >> 36) & 4095)};
}
uint64_t channel_bits(const Texel4& c) {
  return static_cast<uint64_t>(c[0]) | (static_cast<uint64_t>(c[1]) << 12) | (static_cast<uint64_t>(c[2]) << 24) |
         (static_cast<uint64_t>(c[3]) << 36);
}

TEST(SvSrgb, TexelDecodeEqualsDecodeTexelForEveryByteInEveryLane) {
  VerilatedContext ctx;
  Vtfu_srgb_texel_decode dut(&ctx);
  int mismatches = 0;
  for (const bool srgb : {false, true}) {
    const TexelFormat f = srgb ? TexelFormat::SRGBA8 : TexelFormat::RGBA8;
    for (int v = 0; v < 256; ++v) {
      // Each lane sees every byte; the other lanes hold rotated values.
      const auto b = [v](int k) { return static_cast<uint8_t>((v + 85 * k) & 255); };
      const Rgba8 w{b(0), b(1), b(2), b(3)};
      dut.word = word_bits(w);
      dut.srgb = srgb;
      dut.eval();
      if (channels(dut.c) != tfu::decode_texel(w, f) && ++mismatches <= 8)
        ADD_FAILURE() << "srgb " << srgb << " word " << std::hex << word_bits(w);
    }
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(SvSrgb, ResultEncodeEqualsEncodeTexelForEveryLinearValue) {
  VerilatedContext ctx;
  Vtfu_srgb_texel_encode dut(&ctx);
  int mismatches = 0;
  for (int x = 0; x < 4096; ++x) {
    const Texel4 c{x, (x + 1365) & 4095, (x + 2730) & 4095, x & 255};
    dut.c = channel_bits(c);
    dut.srgb = 1;
    dut.eval();
    if (dut.word != word_bits(tfu::encode_texel(c, TexelFormat::SRGBA8)) && ++mismatches <= 8)
      ADD_FAILURE() << "x " << x;
    const Texel4 p{x & 255, (x >> 4) & 255, (x * 7) & 255, (x >> 2) & 255};  // RGBA8 results: 0..255
    dut.c = channel_bits(p);
    dut.srgb = 0;
    dut.eval();
    if (dut.word != word_bits(tfu::encode_texel(p, TexelFormat::RGBA8)) && ++mismatches <= 8)
      ADD_FAILURE() << "rgba8 " << x;
  }
  EXPECT_EQ(mismatches, 0);
  // Hand-derived: linear 2048 (the midpoint of black and white in linear light) is code 188.
  dut.c = channel_bits({2048, 0, 4095, 77});
  dut.srgb = 1;
  dut.eval();
  EXPECT_EQ(dut.word, word_bits({188, 0, 255, 77}));
}

}  // namespace
