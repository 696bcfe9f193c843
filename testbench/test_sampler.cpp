// Golden sampler: hand-derived values per filter mode and wrap mode, and properties that hold for
// every mode (constant textures, interpolation at texel centres, fixed point vs ideal).
#include <bit>
#include <cmath>
#include <iterator>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "cmodel/datapath.hpp"
#include "cmodel/datapath_fast.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/sampler.hpp"

namespace tfu {
namespace {

Texture one_level(int w, int h, const std::vector<Rgba8>& texels, TexelFormat f = TexelFormat::RGBA8) {
  Texture t;
  t.format = f;
  t.levels.emplace_back(w, h);
  t.levels[0].texels = texels;
  return t;
}

SamplerDescriptor cfg(BaseFilter b, MipMode m = MipMode::None, WrapMode w = WrapMode::Repeat) {
  SamplerDescriptor c;
  c.mode = {b, m};
  c.wrap_s = c.wrap_t = w;
  return c;
}

constexpr int32_t kMag = -256;  // lambda for magnification

// A texel word of four random bytes (one draw of the generator).
Rgba8 random_word(std::mt19937& rng) {
  return std::bit_cast<Rgba8>(static_cast<uint32_t>(rng()));
}

TEST(FilterNames, ParseAndPrint) {
  EXPECT_EQ(filter_mode_from_name("linear-mipmap-linear"), (FilterMode{BaseFilter::Linear, MipMode::Linear}));
  EXPECT_EQ(filter_mode_from_name("Edge_Preserving_Mipmap_Linear"),
            (FilterMode{BaseFilter::EdgePreserving, MipMode::Linear}));
  EXPECT_EQ(filter_mode_name({BaseFilter::Cubic, MipMode::Nearest}), "CUBIC_MIPMAP_NEAREST");
  EXPECT_THROW(filter_mode_from_name("anisotropic"), std::exception);
  EXPECT_EQ(all_filter_modes().size(), 12u);
}

TEST(Wrap, ModesOnIntegerIndices) {
  EXPECT_EQ(wrap_repeat(-1, 4), 3);
  EXPECT_EQ(wrap_repeat(9, 4), 1);
  EXPECT_EQ(wrap_mirrored_repeat(4, 4), 3);
  EXPECT_EQ(wrap_mirrored_repeat(-1, 4), 0);
  EXPECT_EQ(wrap_mirrored_repeat(-5, 4), 3);
  EXPECT_EQ(wrap_mirrored_repeat(8, 4), 0);
  EXPECT_EQ(wrap_clamp_to_edge(-7, 4), 0);
  EXPECT_EQ(wrap_clamp_to_edge(99, 4), 3);
  EXPECT_EQ(wrap_clamp_to_border(4, 4), -1);
  EXPECT_EQ(wrap_clamp_to_border(-1, 4), -1);
  EXPECT_EQ(wrap_clamp_to_border(2, 4), 2);
  EXPECT_EQ(wrap_repeat(int64_t{1} << 40, 3), static_cast<int>((int64_t{1} << 40) % 3));
}

TEST(Nearest, TexelSelectionAndWrap) {
  const Texture t = one_level(2, 1, {{10, 0, 0, 255}, {20, 0, 0, 255}});
  const Sampler rep(t, cfg(BaseFilter::Nearest));
  EXPECT_EQ(rep.sample(0.25f, 0.5f, kMag).r, 10);
  EXPECT_EQ(rep.sample(0.75f, 0.5f, kMag).r, 20);
  EXPECT_EQ(rep.sample(1.25f, 0.5f, kMag).r, 10);
  EXPECT_EQ(rep.sample(-0.25f, 0.5f, kMag).r, 20);
  const Sampler mir(t, cfg(BaseFilter::Nearest, MipMode::None, WrapMode::MirroredRepeat));
  EXPECT_EQ(mir.sample(1.25f, 0.5f, kMag).r, 20);  // u = 2.5 -> i = 2 -> mirrored to 1
  EXPECT_EQ(mir.sample(1.75f, 0.5f, kMag).r, 10);
  SamplerDescriptor b = cfg(BaseFilter::Nearest, MipMode::None, WrapMode::ClampToBorder);
  b.border = {1, 2, 3, 4};
  const Sampler bor(t, b);
  EXPECT_EQ(bor.sample(1.25f, 0.5f, kMag), (Rgba8{1, 2, 3, 4}));
  const Sampler edg(t, cfg(BaseFilter::Nearest, MipMode::None, WrapMode::ClampToEdge));
  EXPECT_EQ(edg.sample(-3.0f, 0.5f, kMag).r, 10);
  // Row 0 of the image is the top: t in [0, 1/H) reads row 0.
  const Texture v = one_level(1, 2, {{5, 0, 0, 255}, {6, 0, 0, 255}});
  const Sampler vs(v, cfg(BaseFilter::Nearest));
  EXPECT_EQ(vs.sample(0.5f, 0.1f, kMag).r, 5);
  EXPECT_EQ(vs.sample(0.5f, 0.9f, kMag).r, 6);
}

TEST(Linear, HandDerivedWeights) {
  const Texture t = one_level(2, 1, {{0, 0, 0, 255}, {255, 0, 0, 255}});
  const Sampler s(t, cfg(BaseFilter::Linear, MipMode::None, WrapMode::ClampToEdge));
  EXPECT_EQ(s.sample(0.25f, 0.5f, kMag).r, 0);     // texel centre
  EXPECT_EQ(s.sample(0.5f, 0.5f, kMag).r, 128);    // 127.5, round half up
  EXPECT_EQ(s.sample(0.375f, 0.5f, kMag).r, 64);   // fu = 64: 255 * 64 / 256 = 63.75 -> 64
  EXPECT_EQ(s.sample(0.75f, 0.5f, kMag).r, 255);
  // 2x2: bilinear of (0, 100, 200, 40) at the centre: (0 + 100 + 200 + 40) / 4 = 85
  const Texture q = one_level(2, 2, {{0, 0, 0, 0}, {100, 0, 0, 0}, {200, 0, 0, 0}, {40, 0, 0, 0}});
  const Sampler sq(q, cfg(BaseFilter::Linear, MipMode::None, WrapMode::ClampToEdge));
  EXPECT_EQ(sq.sample(0.5f, 0.5f, kMag).r, 85);
}

TEST(Trilinear, BlendsLevels) {
  Texture t;
  t.levels.emplace_back(4, 4, Rgba8{0, 0, 0, 0});
  t.levels.emplace_back(2, 2, Rgba8{200, 0, 0, 0});
  t.levels.emplace_back(1, 1, Rgba8{100, 0, 0, 0});
  const Sampler s(t, cfg(BaseFilter::Linear, MipMode::Linear));
  EXPECT_EQ(s.sample(0.3f, 0.6f, 64).r, 50);    // (0 * 192 + 200 * 64 + 128) >> 8 = 50
  EXPECT_EQ(s.sample(0.3f, 0.6f, 384).r, 150);  // levels 1, 2 at 1/2: 150
  EXPECT_EQ(s.sample(0.3f, 0.6f, 9999).r, 100);
  EXPECT_EQ(s.sample(0.3f, 0.6f, -10).r, 0);    // magnification: level 0
  const Sampler n(t, cfg(BaseFilter::Nearest, MipMode::Nearest));
  EXPECT_EQ(n.sample(0.3f, 0.6f, 129).r, 200);
}

TEST(Cubic, CatmullRomHalfwayBetweenTexels) {
  // Step 0,0 | 255,255 along x, sampled half-way between the middle texels (f = 1/2). The ROM
  // (centre sampling, R = 64) answers f = 1/2 with entry 32, which holds the weights at f = 32.5/64:
  // h(1.5078) = -0.0615, h(0.5078) = 0.5518, h(0.4922) = 0.5732, h(1.4922) = -0.0635 (Catmull-Rom),
  // so the result is 255 (0.5732 - 0.0635) = 129.98 -> 130 (not the 127.5 of an exact f = 1/2).
  const Texture t = one_level(4, 1, {{0, 0, 0, 255}, {0, 0, 0, 255}, {255, 0, 0, 255}, {255, 0, 0, 255}});
  const Sampler s(t, cfg(BaseFilter::Cubic, MipMode::None, WrapMode::ClampToEdge));
  EXPECT_EQ(s.sample(0.5f, 0.5f, kMag).r, 130);
  // With corner sampling entry 32 is exactly f = 1/2: 255 (9/16 - 1/16) = 127.5; 8-bit weights
  // (-16, 143, 143, -15 after the sum-preserving rounding) give 127 or 128.
  SamplerDescriptor c = cfg(BaseFilter::Cubic, MipMode::None, WrapMode::ClampToEdge);
  c.cubic_rom.pos = SamplePos::Corner;
  const Sampler sc(t, c);
  EXPECT_NEAR(sc.sample(0.5f, 0.5f, kMag).r, 127.5, 0.5);
  // Overshoot of the negative lobes is clamped: a single bright texel has no negative output.
  const Texture spike = one_level(4, 1, {{0, 0, 0, 255}, {255, 0, 0, 255}, {0, 0, 0, 255}, {0, 0, 0, 255}});
  const Sampler ss(spike, cfg(BaseFilter::Cubic, MipMode::None, WrapMode::Repeat));
  for (float x = 0; x < 1; x += 1.0f / 64) EXPECT_LE(ss.sample(x, 0.5f, kMag).r, 255);
}

Texture random_texture(int w, int h, uint32_t seed, TexelFormat f = TexelFormat::RGBA8) {
  std::mt19937 rng(seed);
  Texture t;
  t.format = f;
  t.levels.emplace_back(w, h);
  for (auto& x : t.levels[0].texels)
    x = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng())};
  return t;
}

TEST(Properties, ConstantTextureGivesConstantInEveryMode) {
  for (TexelFormat f : {TexelFormat::RGBA8, TexelFormat::VS16X2}) {
    Texture t;
    t.format = f;
    t.levels.emplace_back(13, 7, Rgba8{37, 201, 99, 180});
    generate_mipmaps(t, MipMethod::Box);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> coord(-3.0f, 3.0f);
    std::uniform_int_distribution<int32_t> lam(-1024, 5 * 256);
    for (const FilterMode& m : all_filter_modes())
      for (const std::string& k : std::vector<std::string>{"catmull-rom", "bspline", "mitchell", "kaiser", "blackman"}) {
        if (m.base != BaseFilter::Cubic && k != "catmull-rom") continue;
        for (WrapMode w : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge}) {
          SamplerDescriptor c = cfg(m.base, m.mip, w);
          c.kernel = k;
          const Sampler s(t, c);
          for (int i = 0; i < 300; ++i) {
            const Rgba8 v = s.sample(coord(rng), coord(rng), lam(rng));
            ASSERT_EQ(v, (Rgba8{37, 201, 99, 180})) << filter_mode_name(m) << " " << k;
          }
        }
      }
  }
}

TEST(Properties, InterpolatingKernelsReproduceTexelsAtCentres) {
  const Texture t = random_texture(8, 8, 5);
  for (const char* k : {"catmull-rom", "kaiser", "blackman"}) {
    SamplerDescriptor c = cfg(BaseFilter::Cubic);
    c.kernel = k;
    c.cubic_rom.pos = SamplePos::Corner;  // entry 0 holds h(0): exact at f = 0
    const Sampler exact(t, c);
    c.cubic_rom.pos = SamplePos::Centre;  // entry 0 holds h(1/128): within the quantization bound
    const Sampler centre(t, c);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        const float s = (static_cast<float>(x) + 0.5f) / 8, tt = (static_cast<float>(y) + 0.5f) / 8;
        EXPECT_EQ(exact.sample(s, tt, kMag), t.levels[0].at(x, y)) << k;
        const Rgba8 a = centre.sample(s, tt, kMag), b = t.levels[0].at(x, y);
        EXPECT_LE(std::abs(a.r - b.r), 2) << k;
      }
  }
  // B-spline on prefiltered coefficients interpolates: the error comes only from the 8-bit
  // coefficient codes, whose step is (fitted range) / 255. On a smooth texture the range stays near
  // [0, 1] and the error within 1 LSB.
  Texture smooth;
  smooth.levels.emplace_back(16, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const auto v = static_cast<uint8_t>(std::lround(127.5 + 100 * std::sin(0.3 * x) * std::cos(0.2 * y)));
      smooth.levels[0].at(x, y) = {v, static_cast<uint8_t>(255 - v), 128, 255};
    }
  SamplerDescriptor c = cfg(BaseFilter::Cubic, MipMode::None, WrapMode::MirroredRepeat);
  c.kernel = kBsplineInterp;
  c.cubic_rom.pos = SamplePos::Corner;
  const Sampler bi(smooth, c);
  int worst = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const Rgba8 a = bi.sample((static_cast<float>(x) + 0.5f) / 16, (static_cast<float>(y) + 0.5f) / 16, kMag);
      const Rgba8 b = smooth.levels[0].at(x, y);
      worst = std::max({worst, std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
    }
  EXPECT_LE(worst, 1);
  // Without the prefilter the B-spline approximates: it misses the texel values by far more.
  c.kernel = "bspline";
  const Sampler ap(smooth, c);
  int worst_ap = 0;
  for (int x = 0; x < 16; ++x) {
    const Rgba8 a = ap.sample((static_cast<float>(x) + 0.5f) / 16, 0.5f / 16, kMag);
    worst_ap = std::max(worst_ap, std::abs(a.r - smooth.levels[0].at(x, 0).r));
  }
  EXPECT_GE(worst_ap, 5);
}

TEST(Properties, FixedPointCloseToIdeal) {
  const Texture base = random_texture(32, 32, 9);
  Texture t = base;
  generate_mipmaps(t, MipMethod::Box);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> coord(0.0f, 1.0f);
  std::uniform_int_distribution<int32_t> lam(-512, 6 * 256);
  for (const FilterMode& m : all_filter_modes()) {
    const Sampler s(t, cfg(m.base, m.mip));
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
      const float x = coord(rng), y = coord(rng);
      const int32_t l = lam(rng);
      const Rgba8 a = s.sample(x, y, l);
      const auto b = s.sample_ideal(x, y, l / 256.0);
      worst = std::max({worst, std::abs(a.r - 255 * b[0]), std::abs(a.g - 255 * b[1]), std::abs(a.b - 255 * b[2])});
    }
    // Bounds: fraction truncation to 8 bits moves a bilinear result by < 1 LSB per level on
    // random data, weights quantized to 8 bits by up to a few LSB for cubics; the edge-preserving
    // filter can pick a different direction near a tie (documented), so it is only checked loosely.
    const double bound = m.base == BaseFilter::Nearest ? (m.mip == MipMode::Linear ? 0.5 + 1e-9 : 0.0)
                         : m.base == BaseFilter::Linear ? 2.5
                         : m.base == BaseFilter::Cubic ? 8.0 : 255.0;
    EXPECT_LE(worst, bound) << filter_mode_name(m);
  }
}

// The LINEAR fast path of Sampler::sample and the plain datapath (sample_channels) agree bit for bit.
TEST(Properties, LinearFastPathEqualsPlainPath) {
  Texture t = random_texture(37, 21, 3);
  generate_mipmaps(t, MipMethod::Box);
  std::mt19937 rng(6);
  std::uniform_real_distribution<float> coord(-2.0f, 2.0f);
  std::uniform_int_distribution<int32_t> lam(-512, 7 * 256);
  for (MipMode m : {MipMode::None, MipMode::Nearest, MipMode::Linear})
    for (WrapMode w : {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge, WrapMode::ClampToBorder}) {
      SamplerDescriptor c = cfg(BaseFilter::Linear, m, w);
      c.border = {9, 99, 199, 49};
      const Sampler s(t, c);
      for (int i = 0; i < 5000; ++i) {
        const float x = coord(rng), y = coord(rng);
        const int32_t l = lam(rng);
        ASSERT_EQ(s.sample(x, y, l), encode_texel(s.sample_channels(x, y, l), t.format));
      }
    }
}

// The memoized CUBIC weights are the tile-weight multipliers' results, bit for bit.
TEST(Properties, CubicWeightMemoChangesNothing) {
  Texture t = random_texture(19, 23, 8);
  generate_mipmaps(t, MipMethod::Box);
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> coord(-1.5f, 1.5f);
  std::uniform_int_distribution<int32_t> lam(-512, 6 * 256);
  for (const char* k : {"catmull-rom", "bspline", "blackman", "bspline-interp"})
    for (SamplePos pos : {SamplePos::Centre, SamplePos::Corner}) {
      SamplerDescriptor c = cfg(BaseFilter::Cubic, MipMode::Linear, WrapMode::MirroredRepeat);
      c.kernel = k;
      c.cubic_rom.pos = pos;
      c.cubic_rom.samples = 32;
      const Sampler memo(t, c);
      c.memoize_cubic_weights = false;
      const Sampler direct(t, c);
      for (int i = 0; i < 3000; ++i) {
        const float x = coord(rng), y = coord(rng);
        const int32_t l = lam(rng);
        ASSERT_EQ(memo.sample(x, y, l), direct.sample(x, y, l)) << k;
      }
    }
}

// The 8-bit-word lerp and blend units (used by the LINEAR fast path and the cycle model's filter;
// the lerp in both its SSE2 and its portable 64-bit word form) against the channel datapath + encode: every fraction pair with random words, plus the extreme
// words, and every blend weight.
TEST(Properties, WordLerpAndBlendEqualChannelDatapath) {
  std::mt19937 rng(8);
  const auto word = [&rng] { return random_word(rng); };
  const auto channels = [](Rgba8 w) { return decode_texel(w, TexelFormat::RGBA8); };
  const Rgba8 zero{0, 0, 0, 0}, full{255, 255, 255, 255};
  for (uint32_t fu = 0; fu < 256; ++fu)
    for (uint32_t fv = 0; fv < 256; ++fv) {
      const std::array<Rgba8, 4> w = (fu + fv) % 7 == 0 ? std::array<Rgba8, 4>{full, full, full, full}
                                     : (fu + fv) % 7 == 1 ? std::array<Rgba8, 4>{full, zero, zero, full}
                                                          : std::array<Rgba8, 4>{word(), word(), word(), word()};
      const Rgba8 want = encode_texel(
          dp::bilinear_lerp({channels(w[0]), channels(w[1]), channels(w[2]), channels(w[3])}, fu, fv, TexelFormat::RGBA8),
          TexelFormat::RGBA8);
      ASSERT_EQ(dp::fast::bilinear_lerp8(w[0], w[1], w[2], w[3], fu, fv), want) << fu << "," << fv;
      ASSERT_EQ(dp::fast::bilinear_lerp8_words(w[0], w[1], w[2], w[3], fu, fv), want) << fu << "," << fv;
      // the Q.8 result for the blend unit: the Q.16 sum's bits 8..23, and rounded it is the code
      const std::array<Texel4, 4> c{channels(w[0]), channels(w[1]), channels(w[2]), channels(w[3])};
      const Texel4 q = dp::bilinear_lerp_q8(c, fu, fv);
      const dp::fast::Rgba8q q8 = dp::fast::bilinear_lerp8q(w[0], w[1], w[2], w[3], fu, fv);
      ASSERT_EQ((Texel4{q8.r, q8.g, q8.b, q8.a}), q) << fu << "," << fv;
      ASSERT_EQ(dp::round_level(q), dp::bilinear_lerp(c, fu, fv, TexelFormat::RGBA8)) << fu << "," << fv;
      const auto fu_ = static_cast<int64_t>(fu), fv_ = static_cast<int64_t>(fv);
      const int64_t sum = c[0][0] * (256 - fu_) * (256 - fv_) + c[1][0] * fu_ * (256 - fv_) + c[2][0] * (256 - fu_) * fv_ +
                          c[3][0] * fu_ * fv_;
      ASSERT_EQ(q[0], sum >> 8) << fu << "," << fv;
    }
  for (int f = 0; f <= 256; ++f)
    for (int k = 0; k < 64; ++k) {
      const Rgba8 a = k == 0 ? full : word(), b = k == 0 ? zero : word();
      ASSERT_EQ(dp::fast::level_blend8(a, b, f),
                encode_texel(dp::level_blend_codes(channels(a), channels(b), f), TexelFormat::RGBA8))
          << f;
      // codes: the blend of one rounding of codes, (c0 (256 - f) + c1 f + 128) >> 8
      for (size_t ch = 0; ch < 4; ++ch)
        ASSERT_EQ(dp::level_blend_codes(channels(a), channels(b), f)[ch],
                  (channels(a)[ch] * (256 - f) + channels(b)[ch] * f + 128) >> 8);
      // Q.8 inputs (random level results 0..255 x 256, and the extremes)
      const auto q16 = [&](int i) { return static_cast<uint16_t>(k == 0 ? (i == 0 ? 0xFF00 : 0) : rng() % 65281); };
      const dp::fast::Rgba8q p{q16(0), q16(0), q16(0), q16(0)}, r{q16(1), q16(1), q16(1), q16(1)};
      const Texel4 pc{p.r, p.g, p.b, p.a}, rc{r.r, r.g, r.b, r.a};
      ASSERT_EQ(dp::fast::level_blend8q(p, r, f), encode_texel(dp::level_blend(pc, rc, f), TexelFormat::RGBA8)) << f;
      for (size_t ch = 0; ch < 4; ++ch)
        ASSERT_EQ(dp::level_blend(pc, rc, f)[ch], (int64_t{pc[ch]} * (256 - f) + int64_t{rc[ch]} * f + 32768) >> 16);
    }
}

// The 4-lane lerp-and-blend unit (batches and the recurrences' quads that blend) against the
// scalar Q.8 units, lane by lane: every fraction pair, every blend weight 0..255 across the lanes,
// random words and the extreme words.
TEST(Properties, QuadLerpBlendEqualsScalarUnits) {
  std::mt19937 rng(10);
  const auto word = [&rng] { return random_word(rng); };
  const Rgba8 zero{0, 0, 0, 0}, full{255, 255, 255, 255}, mixed{255, 0, 255, 0};
  for (uint32_t fu = 0; fu < 256; ++fu)
    for (uint32_t fv = 0; fv < 256; ++fv) {
      dp::fast::Quad8 q0, q1;
      q0.fu = {fu, fv, 255 - fu, fu};
      q0.fv = {fv, fu, fv, 255 - fv};
      q1.fu = {fv, 255 - fu, fu, 255 - fv};
      q1.fv = {fu, fv, 255 - fv, fu};
      for (size_t k = 0; k < 4; ++k) {
        const uint32_t sel = (fu + fv + static_cast<uint32_t>(k)) % 8;
        for (dp::fast::Quad8* q : {&q0, &q1}) {
          q->a[k] = sel == 0 ? full : sel == 1 ? zero : sel == 2 ? mixed : word();
          q->b[k] = sel == 0 ? full : sel == 1 ? full : sel == 2 ? zero : word();
          q->c[k] = sel == 0 ? full : sel == 1 ? zero : sel == 2 ? full : word();
          q->d[k] = sel == 0 ? full : sel == 1 ? full : sel == 2 ? mixed : word();
        }
      }
      const std::array<int, 4> f{static_cast<int>(fu), static_cast<int>(fv), static_cast<int>(255 - fu), (static_cast<int>(fu + fv) * 7) & 255};
      std::array<Rgba8, 4> out;
      dp::fast::bilinear_blend8x4(q0, q1, f, out.data());
      for (size_t k = 0; k < 4; ++k)
        ASSERT_EQ(out[k], dp::fast::level_blend8q(dp::fast::bilinear_lerp8q(q0.a[k], q0.b[k], q0.c[k], q0.d[k], q0.fu[k], q0.fv[k]),
                                                  dp::fast::bilinear_lerp8q(q1.a[k], q1.b[k], q1.c[k], q1.d[k], q1.fu[k], q1.fv[k]), f[k]))
            << "lane " << k << " at " << q0.fu[k] << "," << q0.fv[k] << " blend " << f[k];
    }
}

// The 4-lane lerp unit (sample_batch's LINEAR path) against the scalar one, lane by lane: every
// fraction pair in every lane (the four lanes get (fu, fv), (fv, fu), (255 - fu, fv) and
// (fu, 255 - fv)), with random words, and the extreme words that drive the 16-bit lanes' sums to
// their ends.
TEST(Properties, QuadLerpEqualsScalarLerp) {
  std::mt19937 rng(9);
  const auto word = [&rng] { return random_word(rng); };
  const Rgba8 zero{0, 0, 0, 0}, full{255, 255, 255, 255}, mixed{255, 0, 255, 0};
  for (uint32_t fu = 0; fu < 256; ++fu)
    for (uint32_t fv = 0; fv < 256; ++fv) {
      dp::fast::Quad8 q;
      q.fu = {fu, fv, 255 - fu, fu};
      q.fv = {fv, fu, fv, 255 - fv};
      for (size_t k = 0; k < 4; ++k) {
        const uint32_t sel = (fu + fv + static_cast<uint32_t>(k)) % 8;
        q.a[k] = sel == 0 ? full : sel == 1 ? zero : sel == 2 ? mixed : word();
        q.b[k] = sel == 0 ? full : sel == 1 ? full : sel == 2 ? zero : word();
        q.c[k] = sel == 0 ? full : sel == 1 ? zero : sel == 2 ? full : word();
        q.d[k] = sel == 0 ? full : sel == 1 ? full : sel == 2 ? mixed : word();
      }
      std::array<Rgba8, 4> out;
      dp::fast::bilinear_lerp8x4(q, out.data());
      for (size_t k = 0; k < 4; ++k)
        ASSERT_EQ(out[k], dp::fast::bilinear_lerp8(q.a[k], q.b[k], q.c[k], q.d[k], q.fu[k], q.fv[k]))
            << "lane " << k << " at " << q.fu[k] << "," << q.fv[k];
    }
}

// Sample_batch returns sample() of every request, in order, and writes nothing past out[n - 1]:
// every base filter and MIP mode, all 16 wrap pairs, a power-of-two RGBA8, an NPOT L8 and a VS16X2
// texture (no batch fast path: the loop over sample()), batch sizes around the 4-lane groups, and
// random float bit patterns (NaN, infinities, denormals, huge values) and extreme lambdas.
TEST(Properties, BatchEqualsSample) {
  std::mt19937 rng(33);
  std::uniform_real_distribution<float> coord(-2.5f, 2.5f);
  std::uniform_int_distribution<int32_t> lam(-512, 9 * 256);
  const float specials[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::denorm_min(),
                            -1e-40f, 0.0f, -0.0f, std::numeric_limits<float>::max(), -1e20f, 65536.0f, 0.5f, 1.0f};
  const auto request_coord = [&] {
    const uint32_t r = rng() % 8;
    if (r == 0) return std::bit_cast<float>(static_cast<uint32_t>(rng()));
    if (r == 1) return specials[rng() % std::size(specials)];
    return coord(rng);
  };
  const auto request_lambda = [&] {
    const uint32_t r = rng() % 16;
    return r == 0 ? std::numeric_limits<int32_t>::min() : r == 1 ? std::numeric_limits<int32_t>::max() : lam(rng);
  };
  const WrapMode wraps[] = {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge, WrapMode::ClampToBorder};
  const size_t sizes[] = {0, 1, 3, 4, 5, 257};
  for (const auto& [w, h, f] : {std::tuple{32, 16, TexelFormat::RGBA8}, std::tuple{37, 21, TexelFormat::L8},
                                std::tuple{16, 8, TexelFormat::VS16X2}}) {
    Texture t = random_texture(w, h, 5, f);
    generate_mipmaps(t, MipMethod::Box);
    for (BaseFilter b : {BaseFilter::Nearest, BaseFilter::Linear, BaseFilter::Cubic, BaseFilter::EdgePreserving})
      for (MipMode m : {MipMode::None, MipMode::Nearest, MipMode::Linear})
        for (WrapMode ws : wraps)
          for (WrapMode wt : wraps) {
            SamplerDescriptor c = cfg(b, m);
            c.wrap_s = ws;
            c.wrap_t = wt;
            c.border = {9, 99, 199, 49};
            const Sampler smp(t, c);
            for (size_t n : sizes) {
              std::vector<SampleRequest> req(n);
              for (SampleRequest& r : req) r = {request_coord(), request_coord(), request_lambda()};
              const Rgba8 sentinel{1, 2, 3, 4};
              std::vector<Rgba8> out(n + 4, sentinel);
              smp.sample_batch(req.data(), n, out.data());
              for (size_t i = 0; i < n; ++i)
                ASSERT_EQ(out[i], smp.sample(req[i].s, req[i].t, req[i].lambda_q8))
                    << filter_mode_name(c.mode) << " " << wrap_mode_name(ws) << "/" << wrap_mode_name(wt) << " "
                    << w << "x" << h << " batch " << n << " request " << i << " at (" << req[i].s << ", "
                    << req[i].t << ", " << req[i].lambda_q8 << ")";
              for (size_t i = n; i < out.size(); ++i) ASSERT_EQ(out[i], sentinel) << "wrote past the batch";
            }
          }
  }
}

// Sample_batch's LINEAR groups against the plain datapath (encode_texel of sample_channels), as the
// renderer issues them: a quad's covered pixels, 1..4 requests sharing the quad's lambda (the
// partial groups' masked lanes, the one level pick for a group), then groups of 4 + 1..4 and
// requests with lambdas of their own (each lane's own levels, some blending and some not); every
// MIP mode, all 16 wrap pairs, RGBA8 on a power-of-two extent, L8 on another, and SRGBA8 (no batch
// fast path); lambdas across the magnification, blended and clamped ranges; coordinates including
// random float bit patterns. Nothing past out[n - 1] is written.
TEST(Properties, BatchQuadsEqualPlainPath) {
  std::mt19937 rng(34);
  std::uniform_real_distribution<float> coord(-2.5f, 2.5f);
  std::uniform_int_distribution<int32_t> lam(-512, 7 * 256);
  const auto request_coord = [&] {
    return rng() % 8 == 0 ? std::bit_cast<float>(static_cast<uint32_t>(rng())) : coord(rng);
  };
  const WrapMode wraps[] = {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge, WrapMode::ClampToBorder};
  size_t blended = 0, partial = 0;
  for (const auto& [w, h, f] : {std::tuple{32, 16, TexelFormat::RGBA8}, std::tuple{37, 21, TexelFormat::L8},
                                std::tuple{16, 16, TexelFormat::SRGBA8}}) {
    Texture t = random_texture(w, h, 35, f);
    generate_mipmaps(t, MipMethod::Box);
    for (MipMode m : {MipMode::None, MipMode::Nearest, MipMode::Linear})
      for (WrapMode ws : wraps)
        for (WrapMode wt : wraps) {
          SamplerDescriptor c = cfg(BaseFilter::Linear, m);
          c.wrap_s = ws;
          c.wrap_t = wt;
          c.border = {9, 99, 199, 49};
          const Sampler smp(t, c);
          for (int round = 0; round < 24; ++round)
            for (size_t n = 1; n <= 8; ++n) {
              const bool quad_lambda = round % 2 == 0;  // one lambda per group of 4, else one per request
              std::vector<SampleRequest> req(n);
              int32_t l = lam(rng);
              for (size_t i = 0; i < n; ++i) {
                if (!quad_lambda || i % 4 == 0) l = lam(rng);
                req[i] = {request_coord(), request_coord(), l};
              }
              const Rgba8 sentinel{1, 2, 3, 4};
              std::vector<Rgba8> out(n + 4, sentinel);
              smp.sample_batch(req.data(), n, out.data());
              for (size_t i = 0; i < n; ++i) {
                ASSERT_EQ(out[i], encode_texel(smp.sample_channels(req[i].s, req[i].t, req[i].lambda_q8), f))
                    << filter_mode_name(c.mode) << " " << wrap_mode_name(ws) << "/" << wrap_mode_name(wt) << " " << w
                    << "x" << h << " batch " << n << " request " << i << " at (" << req[i].s << ", " << req[i].t
                    << ", " << req[i].lambda_q8 << ")";
                const LevelPick p = select_levels(lambda_bias_clamp(req[i].lambda_q8, c.lod), m, t.max_level());
                blended += p.blend != 0;
              }
              partial += n % 4 != 0;
              for (size_t i = n; i < out.size(); ++i) ASSERT_EQ(out[i], sentinel) << "wrote past the batch";
            }
        }
  }
  EXPECT_GT(blended, 1000u);  // the blend unit's lanes were exercised
  EXPECT_GT(partial, 1000u);
}

// Every fast path of Sampler::sample (LINEAR, CUBIC and EDGE_PRESERVING, each specialized per pair
// of wrap modes and for MIP-mapping) agrees bit for bit with the plain datapath (sample_channels),
// on power-of-two and other extents, over random requests: ordinary coordinates, and random float
// bit patterns (huge, tiny, denormal, infinite, NaN) for the address generator's uncommon cases.
TEST(Properties, FastPathsEqualPlainPath) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> coord(-2.5f, 2.5f);
  std::uniform_int_distribution<int32_t> lam(-512, 9 * 256);
  const auto request_coord = [&] {
    return rng() % 4 == 0 ? std::bit_cast<float>(static_cast<uint32_t>(rng())) : coord(rng);
  };
  struct Case {
    BaseFilter base;
    const char* kernel;
    EdgeShape shape;
  };
  const Case cases[] = {{BaseFilter::Linear, "catmull-rom", EdgeShape::Cross},
                        {BaseFilter::Cubic, "catmull-rom", EdgeShape::Cross},
                        {BaseFilter::Cubic, "bspline", EdgeShape::Cross},
                        {BaseFilter::Cubic, "bspline-interp", EdgeShape::Cross},
                        {BaseFilter::EdgePreserving, "catmull-rom", EdgeShape::Cross},
                        {BaseFilter::EdgePreserving, "catmull-rom", EdgeShape::Static}};
  const WrapMode wraps[] = {WrapMode::Repeat, WrapMode::MirroredRepeat, WrapMode::ClampToEdge, WrapMode::ClampToBorder};
  for (const auto& [w, h, f] : {std::tuple{32, 16, TexelFormat::RGBA8}, std::tuple{37, 21, TexelFormat::L8}}) {
    Texture t = random_texture(w, h, 17, f);
    generate_mipmaps(t, MipMethod::Box);
    for (const Case& k : cases)
      for (MipMode m : {MipMode::None, MipMode::Nearest, MipMode::Linear})
        for (WrapMode ws : wraps)
          for (WrapMode wt : wraps) {
            SamplerDescriptor c = cfg(k.base, m);
            c.wrap_s = ws;
            c.wrap_t = wt;
            c.kernel = k.kernel;
            c.edge_shape = k.shape;
            c.border = {9, 99, 199, 49};
            const Sampler s(t, c);
            for (int i = 0; i < 400; ++i) {
              const float x = request_coord(), y = request_coord();
              const int32_t l = lam(rng);
              ASSERT_EQ(s.sample(x, y, l), encode_texel(s.sample_channels(x, y, l), t.format))
                  << filter_mode_name(c.mode) << " " << k.kernel << " " << wrap_mode_name(ws) << "/"
                  << wrap_mode_name(wt) << " " << w << "x" << h << " at (" << x << ", " << y << ")";
            }
          }
  }
}

TEST(Vs16, FiltersSignedNumerators) {
  // Two texels -1 and +1 in channel 0: halfway gives 0 exactly (bytes 128, 0).
  Texture t;
  t.format = TexelFormat::VS16X2;
  t.levels.emplace_back(2, 1);
  t.levels[0].texels = {encode_texel({-32640, 100, 0, 0}, TexelFormat::VS16X2),
                        encode_texel({32640, 300, 0, 0}, TexelFormat::VS16X2)};
  const Sampler s(t, cfg(BaseFilter::Linear, MipMode::None, WrapMode::ClampToEdge));
  const Texel4 v = s.sample_channels(0.5f, 0.5f, kMag);
  EXPECT_EQ(v[0], 0);
  EXPECT_EQ(v[1], 200);
  EXPECT_EQ(decode_texel(s.sample(0.5f, 0.5f, kMag), TexelFormat::VS16X2)[1], 200);
}

TEST(Config, RejectsBadSettings) {
  const Texture t = random_texture(4, 4, 1);
  SamplerDescriptor c = cfg(BaseFilter::Cubic);
  c.kernel = "no-such-kernel";
  EXPECT_THROW(Sampler(t, c), std::exception);
  c = cfg(BaseFilter::Linear);
  c.max_aniso = 17;
  EXPECT_THROW(Sampler(t, c), std::exception);
  c = cfg(BaseFilter::Linear);
  c.lod.min_lod_q8 = 2 * 256;
  c.lod.max_lod_q8 = 256;
  EXPECT_THROW(Sampler(t, c), std::exception);
  Texture big;
  big.levels.emplace_back(kMaxTextureSize + 1, 1);
  EXPECT_THROW(Sampler(big, cfg(BaseFilter::Linear)), std::exception);
}

}  // namespace
}  // namespace tfu
