// The quad texture environment and display ramp (cmodel/texenv_quad.hpp) against their plain twins,
// combine_stage and display_ramp one pixel at a time: exhaustive over every byte pair (and, for
// decal, every texel alpha) in every channel position, every environment and RGB scale; every byte
// through every display shift; random quads.
#include <gtest/gtest.h>

#include <random>

#include "cmodel/texenv_quad.hpp"
#include "testbench/iterations.hpp"

namespace tfu {
namespace {

constexpr std::array<TexEnv, 4> kEnvs{TexEnv::Replace, TexEnv::Modulate, TexEnv::Add, TexEnv::Decal};
constexpr std::array<int, 3> kScales{1, 2, 4};

// Pixel (p, s, a) of the sweep: every channel position sees every (previous, texel) byte pair as p
// and s run over 0..255 (R: (p, s), G: (s, p), B: (~p, ~s), A: (p, s)); the texel's alpha is `a`.
std::pair<Rgba8, Rgba8> sweep_pixel(uint32_t p, uint32_t s, uint32_t a) {
  const auto b = [](uint32_t v) { return static_cast<uint8_t>(v & 255u); };
  return {{b(p), b(s), b(~p), b(p)}, {b(s), b(p), b(~s), b(a)}};
}

// Runs `n` sweep pixels (index i -> (p, s, a)) four at a time through both forms; counts mismatches.
// Under the sanitizers every tenth quad (test::kIterationDivisor).
template <class PixelOf>
int64_t sweep(int64_t n, StageCombine c, PixelOf pixel_of) {
  int64_t mismatches = 0;
  for (int64_t i = 0; i < n; i += 4 * test::kIterationDivisor) {
    texenv_quad::Quad colour, texel, plain;
    for (size_t k = 0; k < 4; ++k) {
      std::tie(colour[k], texel[k]) = pixel_of(i + static_cast<int64_t>(k));
      plain[k] = combine_stage(colour[k], texel[k], c);
    }
    texenv_quad::combine(colour, texel, c);
    mismatches += colour != plain;
  }
  return mismatches;
}

TEST(TexEnvQuad, EveryBytePairEqualsCombineStage) {
  for (TexEnv env : kEnvs) {
    if (env == TexEnv::Decal) continue;  // depends on the texel's alpha too: the next test
    for (int scale : kScales) {
      const int64_t bad = sweep(65536, {env, scale}, [](int64_t i) {
        const auto u = static_cast<uint32_t>(i);
        return sweep_pixel(u >> 8, u & 255u, u & 255u);
      });
      EXPECT_EQ(bad, 0) << "environment " << static_cast<int>(env) << " scale " << scale;
    }
  }
}

TEST(TexEnvQuad, DecalEveryByteTripleEqualsCombineStage) {
  // (previous, texel, texel alpha): 2^24 pixels per scale.
  for (int scale : kScales) {
    const int64_t bad = sweep(int64_t{1} << 24, {TexEnv::Decal, scale}, [](int64_t i) {
      const auto u = static_cast<uint32_t>(i);
      return sweep_pixel(u >> 16, (u >> 8) & 255u, u & 255u);
    });
    EXPECT_EQ(bad, 0) << "decal scale " << scale;
  }
}

TEST(TexEnvQuad, HandDerivedValues) {
  // modulate: round(200 * 100 / 255) = round(78.43) = 78; round(128 * 128 / 255) = round(64.25) = 64;
  // 255 x = x. Scale 2 on R, G, B only: min(255, 2 * 78) = 156, alpha round(255 * 51 / 255) = 51.
  texenv_quad::Quad c{Rgba8{200, 128, 255, 255}, Rgba8{0, 1, 2, 3}, Rgba8{10, 20, 30, 40}, Rgba8{255, 255, 255, 255}};
  texenv_quad::Quad t{Rgba8{100, 128, 77, 51}, Rgba8{255, 255, 255, 255}, Rgba8{0, 0, 0, 0}, Rgba8{200, 130, 1, 0}};
  texenv_quad::combine(c, t, {TexEnv::Modulate, 2});
  EXPECT_EQ(c[0], (Rgba8{156, 128, 154, 51}));
  EXPECT_EQ(c[1], (Rgba8{0, 2, 4, 3}));
  EXPECT_EQ(c[2], (Rgba8{0, 0, 0, 0}));
  EXPECT_EQ(c[3], (Rgba8{255, 255, 2, 0}));
  // add saturates: min(255, 200 + 100) = 255, 20 + 30 = 50; alpha multiplies: round(255 * 128 / 255) = 128.
  // decal with As = 51: round((100 * 204 + 0 * 51) / 255) = 80, round((0 * 204 + 255 * 51) / 255) = 51.
  texenv_quad::Quad a{Rgba8{200, 20, 0, 255}, Rgba8{100, 0, 0, 77}, Rgba8{}, Rgba8{}};
  texenv_quad::Quad s{Rgba8{100, 30, 0, 128}, Rgba8{0, 255, 0, 51}, Rgba8{}, Rgba8{}};
  texenv_quad::Quad d = a;
  texenv_quad::combine(a, s, {TexEnv::Add, 1});
  EXPECT_EQ(a[0], (Rgba8{255, 50, 0, 128}));
  texenv_quad::combine(d, s, {TexEnv::Decal, 1});
  EXPECT_EQ(d[1], (Rgba8{80, 51, 0, 77}));
  // display ramp, shift 2: min(255, 4 v) on R, G, B; alpha kept.
  texenv_quad::Quad r{Rgba8{63, 64, 0, 7}, Rgba8{1, 2, 3, 200}, Rgba8{255, 100, 50, 1}, Rgba8{}};
  texenv_quad::display_ramp(r, 2);
  EXPECT_EQ(r[0], (Rgba8{252, 255, 0, 7}));
  EXPECT_EQ(r[1], (Rgba8{4, 8, 12, 200}));
  EXPECT_EQ(r[2], (Rgba8{255, 255, 200, 1}));
}

TEST(TexEnvQuad, EveryByteEqualsDisplayRamp) {
  for (int shift = 0; shift <= kMaxDisplayShift; ++shift) {
    int bad = 0;
    for (uint32_t v = 0; v < 256; v += 4) {
      texenv_quad::Quad q, plain;
      for (uint32_t k = 0; k < 4; ++k) {
        const auto b = static_cast<uint8_t>(v + k), nb = static_cast<uint8_t>(255u - v - k);
        q[k] = {b, nb, b, nb};
        plain[k] = display_ramp(q[k], shift);
      }
      texenv_quad::display_ramp(q, shift);
      bad += q != plain;
    }
    EXPECT_EQ(bad, 0) << "shift " << shift;
  }
}

TEST(TexEnvQuad, RandomQuadsEqualThePlainForms) {
  std::mt19937 rng(20261207);
  std::uniform_int_distribution<int> byte(0, 255), pick(0, 3), scale(0, 2), shift(0, kMaxDisplayShift);
  const int n = test::iterations(200000);
  int bad = 0;
  for (int i = 0; i < n; ++i) {
    texenv_quad::Quad c, t, plain;
    for (size_t k = 0; k < 4; ++k) {
      c[k] = {static_cast<uint8_t>(byte(rng)), static_cast<uint8_t>(byte(rng)), static_cast<uint8_t>(byte(rng)), static_cast<uint8_t>(byte(rng))};
      t[k] = {static_cast<uint8_t>(byte(rng)), static_cast<uint8_t>(byte(rng)), static_cast<uint8_t>(byte(rng)), static_cast<uint8_t>(byte(rng))};
    }
    const StageCombine sc{kEnvs[static_cast<size_t>(pick(rng))], kScales[static_cast<size_t>(scale(rng))]};
    const int sh = shift(rng);
    for (size_t k = 0; k < 4; ++k) plain[k] = display_ramp(combine_stage(c[k], t[k], sc), sh);
    texenv_quad::combine(c, t, sc);
    texenv_quad::display_ramp(c, sh);
    bad += c != plain;
  }
  EXPECT_EQ(bad, 0);
}

}  // namespace
}  // namespace tfu
