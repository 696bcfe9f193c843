// The package of the BC1/BC3/BC4 decoders (rtl/sv/bc/, docs/sv-bc.md), written by tfu_svgen into
// gen/tfu_bc_pkg.sv. The decoders divide by 3 (BC1 thirds), 7 and 5 (BC4 sevenths and fifths); in
// hardware each division is a multiply by a reciprocal and a shift, floor(x / d) = (x M) >> K for
// every numerator x the decoder can form. The constants are not typed by hand: bc_divider() finds
// the smallest K (and M = ceil(2^K / d)) exact over the numerator range, and bc_pkg_sv() then checks
// the palette the SystemVerilog computes with them (the formulas of rtl/sv/bc/tfu_bc1_palette.sv and
// tfu_bc4_palette.sv, written out here once more) against the C++ decoder, bc1_palette() and
// decode_bc4_unorm8() (cmodel/bc_decode.hpp), for every pair of endpoint codes and both rules the
// blocks implement (EXACT, TRUNCATE). Any disagreement stops the generator (the build fails).
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "cmodel/bc_decode.hpp"

namespace tfu::svgen {

struct BcDivider {
  int d = 0;                     // divisor
  int x_max = 0;                 // largest numerator
  int mul = 0;                   // M
  int shift = 0;                 // K
  int mul_bits = 0, x_bits = 0;  // widths of M and of x
};

inline int bc_bit_width(int v) {
  int b = 0;
  while ((v >> b) != 0) ++b;
  return b;
}

// Smallest K with floor(x ceil(2^K / d) / 2^K) == floor(x / d) for every x in 0..x_max.
inline BcDivider bc_divider(int d, int x_max) {
  for (int k = 0; k < 30; ++k) {
    const int64_t m = ((int64_t{1} << k) + d - 1) / d;
    bool ok = true;
    for (int64_t x = 0; x <= x_max && ok; ++x) ok = ((x * m) >> k) == x / d;
    if (ok) return {d, x_max, static_cast<int>(m), k, bc_bit_width(static_cast<int>(m)), bc_bit_width(x_max)};
  }
  throw std::runtime_error(fmt::format("no reciprocal for division by {} up to {}", d, x_max));
}

// The rounding bias the SV adds before each division, per rule (the C++ rules of bc_decode.hpp:
// EXACT rounds to nearest, TRUNCATE floors).
inline int bc1_third_bias(Bc1Interpolation r) { return r == Bc1Interpolation::EXACT ? 1 : 0; }  // (2 e0 + e1 + b) / 3
inline int bc1_half_bias(Bc1Interpolation r) { return r == Bc1Interpolation::EXACT ? 1 : 0; }   // (e0 + e1 + b) >> 1
inline int bc4_seventh_bias(Bc4Interpolation r) {
  return r == Bc4Interpolation::EXACT ? 3 : 0;
}  // round(s / 7) = (s + 3) / 7
inline int bc4_fifth_bias(Bc4Interpolation r) {
  return r == Bc4Interpolation::EXACT ? 2 : 0;
}  // round(s / 5) = (s + 2) / 5

inline int bc_div(const BcDivider& v, int x) {
  if (x < 0 || x > v.x_max) throw std::runtime_error(fmt::format("numerator {} outside 0..{}", x, v.x_max));
  return static_cast<int>((int64_t{x} * v.mul) >> v.shift);
}

// The SV's BC1 channel interpolants (index 2 and 3 of 4-colour mode, index 2 of 3-colour mode)
// against bc1_palette() for every pair of n-bit fields of the channel at bit `shift` of a colour
// (the other fields zero, so the mode is that of the pair).
inline void check_bc1_channel(const BcDivider& div3, int shift, int bits, Bc1Interpolation rule) {
  const int byte_of_channel = shift == 11 ? 0 : shift == 5 ? 1 : 2;
  for (int v0 = 0; v0 < (1 << bits); ++v0)
    for (int v1 = 0; v1 < (1 << bits); ++v1)
      for (const bool four_only : {false, true}) {
        const int c0 = v0 << shift, c1 = v1 << shift;
        const std::array<uint8_t, 4> block{static_cast<uint8_t>(c0), static_cast<uint8_t>(c0 >> 8),
                                           static_cast<uint8_t>(c1), static_cast<uint8_t>(c1 >> 8)};
        const std::array<Rgba8, 4> p = bc1_palette(block.data(), rule, four_only, false);
        const auto ch = [byte_of_channel](const Rgba8& c) {
          return byte_of_channel == 0 ? c.r : byte_of_channel == 1 ? c.g : c.b;
        };
        const int e0 = bits == 5 ? bc_widen5(v0) : bc_widen6(v0), e1 = bits == 5 ? bc_widen5(v1) : bc_widen6(v1);
        int want2, want3;
        if (four_only || c0 > c1) {
          want2 = bc_div(div3, 2 * e0 + e1 + bc1_third_bias(rule));
          want3 = bc_div(div3, e0 + 2 * e1 + bc1_third_bias(rule));
        } else {
          want2 = (e0 + e1 + bc1_half_bias(rule)) >> 1;
          want3 = 0;
        }
        if (ch(p[0]) != e0 || ch(p[1]) != e1 || ch(p[2]) != want2 || ch(p[3]) != want3)
          throw std::runtime_error(
              fmt::format("BC1 {} channel at bit {}: fields {}, {}: the SV formula gives {} {} {} {}, "
                          "bc1_palette {} {} {} {}",
                          kBc1InterpolationNames.name(rule), shift, v0, v1, e0, e1, want2, want3, ch(p[0]), ch(p[1]),
                          ch(p[2]), ch(p[3])));
      }
}

// The SV's BC4 palette against decode_bc4_unorm8() for every endpoint pair and code.
inline void check_bc4(const BcDivider& div7, const BcDivider& div5, Bc4Interpolation rule) {
  // Texel t takes code t & 7: the 48 code bits are the 16 codes 0..7, 0..7.
  uint64_t codes = 0;
  for (int t = 0; t < kBcBlockTexels; ++t) codes |= static_cast<uint64_t>(t & 7) << (3 * t);
  for (int a0 = 0; a0 < 256; ++a0)
    for (int a1 = 0; a1 < 256; ++a1) {
      std::array<uint8_t, 8> block{static_cast<uint8_t>(a0), static_cast<uint8_t>(a1)};
      for (int k = 0; k < 6; ++k) block[static_cast<size_t>(2 + k)] = static_cast<uint8_t>(codes >> (8 * k));
      const std::array<uint8_t, kBcBlockTexels> got = decode_bc4_unorm8(block.data(), rule);
      for (int c = 0; c < 8; ++c) {
        int want;
        if (c < 2)
          want = c == 0 ? a0 : a1;
        else if (a0 > a1)
          want = bc_div(div7, (8 - c) * a0 + (c - 1) * a1 + bc4_seventh_bias(rule));
        else if (c < 6)
          want = bc_div(div5, (6 - c) * a0 + (c - 1) * a1 + bc4_fifth_bias(rule));
        else
          want = c == 6 ? 0 : 255;
        if (got[static_cast<size_t>(c)] != want)
          throw std::runtime_error(
              fmt::format("BC4 {}: endpoints {}, {} code {}: the SV formula gives {}, "
                          "decode_bc4_unorm8 {}",
                          kBc4InterpolationNames.name(rule), a0, a1, c, want, got[static_cast<size_t>(c)]));
      }
    }
}

// gen/tfu_bc_pkg.sv. `banner`: the generated-file banner of the generator.
inline std::string bc_pkg_sv(const char* banner) {
  // Numerator ranges: the largest sum of weighted 8-bit endpoints plus the largest bias.
  const BcDivider div3 = bc_divider(3, 3 * 255 + bc1_third_bias(Bc1Interpolation::EXACT));
  const BcDivider div7 = bc_divider(7, 7 * 255 + bc4_seventh_bias(Bc4Interpolation::EXACT));
  const BcDivider div5 = bc_divider(5, 5 * 255 + bc4_fifth_bias(Bc4Interpolation::EXACT));
  for (const Bc1Interpolation r : {Bc1Interpolation::EXACT, Bc1Interpolation::TRUNCATE}) {
    check_bc1_channel(div3, 11, 5, r);
    check_bc1_channel(div3, 5, 6, r);
    check_bc1_channel(div3, 0, 5, r);
  }
  for (const Bc4Interpolation r : {Bc4Interpolation::EXACT, Bc4Interpolation::TRUNCATE}) check_bc4(div7, div5, r);
  const auto div = [](const char* name, const BcDivider& v) {
    return fmt::format(
        "  // floor(x / {}) = (x * {}_MUL) >> {}_SHIFT for x in 0..{} ({} bits)\n"
        "  localparam int {}_MUL = {};\n  localparam int {}_SHIFT = {};\n  localparam int {}_X_BITS = {};\n",
        v.d, name, name, v.x_max, v.x_bits, name, v.mul, name, v.shift, name, v.x_bits);
  };
  std::string s = banner;
  s += "// Constants of the BC1/BC3/BC4 decoders (rtl/sv/bc/; rtl/sv/bc/svgen_bc.hpp derives the\n"
       "// reciprocals and checks the palettes they give against cmodel/bc_decode.cpp for every pair of\n"
       "// endpoint codes, both rules).\n"
       "// Not every consumer uses every constant: UNUSEDPARAM is waived for this package only.\n"
       "/* verilator lint_off UNUSEDPARAM */\n"
       "package tfu_bc_pkg;\n";
  s += fmt::format(
      "  // Interpolation rules (the parameter RULE of the decoders): tfu::Bc1Interpolation and\n"
      "  // tfu::Bc4Interpolation. EXACT rounds to nearest (the spec's value of the widened endpoints);\n"
      "  // TRUNCATE floors (libsquish 1.15, Mesa).\n"
      "  localparam int RULE_EXACT = {};\n  localparam int RULE_TRUNCATE = {};\n",
      static_cast<int>(Bc1Interpolation::EXACT), static_cast<int>(Bc1Interpolation::TRUNCATE));
  if (static_cast<int>(Bc4Interpolation::EXACT) != static_cast<int>(Bc1Interpolation::EXACT) ||
      static_cast<int>(Bc4Interpolation::TRUNCATE) != static_cast<int>(Bc1Interpolation::TRUNCATE))
    throw std::runtime_error("Bc1Interpolation and Bc4Interpolation number EXACT and TRUNCATE differently");
  s += fmt::format(
      "  // Rounding biases added to the numerator before the division, per rule (EXACT, TRUNCATE)\n"
      "  localparam int BC1_THIRD_BIAS_EXACT = {};\n  localparam int BC1_THIRD_BIAS_TRUNCATE = {};\n"
      "  localparam int BC1_HALF_BIAS_EXACT = {};\n  localparam int BC1_HALF_BIAS_TRUNCATE = {};\n"
      "  localparam int BC4_SEVENTH_BIAS_EXACT = {};\n  localparam int BC4_SEVENTH_BIAS_TRUNCATE = {};\n"
      "  localparam int BC4_FIFTH_BIAS_EXACT = {};\n  localparam int BC4_FIFTH_BIAS_TRUNCATE = {};\n",
      bc1_third_bias(Bc1Interpolation::EXACT), bc1_third_bias(Bc1Interpolation::TRUNCATE),
      bc1_half_bias(Bc1Interpolation::EXACT), bc1_half_bias(Bc1Interpolation::TRUNCATE),
      bc4_seventh_bias(Bc4Interpolation::EXACT), bc4_seventh_bias(Bc4Interpolation::TRUNCATE),
      bc4_fifth_bias(Bc4Interpolation::EXACT), bc4_fifth_bias(Bc4Interpolation::TRUNCATE));
  s += div("DIV3", div3) + div("DIV7", div7) + div("DIV5", div5);
  s += "endpackage\n/* verilator lint_on UNUSEDPARAM */\n";
  return s;
}

}  // namespace tfu::svgen
