// The golden model against the Vulkan specification's texel-filtering bounds
// (testbench/spec_bounds.hpp, docs/sampler.md "Within the spec's bounds"), and the API limits a
// driver of the unit reports (cmodel/api_limits.hpp) against the datapath they come from.
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "cmodel/api_limits.hpp"
#include "cmodel/datapath.hpp"
#include "cmodel/error.hpp"
#include "cmodel/fast_paths.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/sampler.hpp"
#include "testbench/docs_text.hpp"
#include "testbench/iterations.hpp"
#include "testbench/spec_bounds.hpp"
#include "testbench/spec_bounds_case.hpp"

namespace tfu {
namespace {

using spec::Bounds;
using spec::LodInput;
using spec::LodKind;

Texture texture_of_levels(TexelFormat fmt, const std::vector<std::vector<uint8_t>>& levels, int w, int h) {
  Texture tex;
  tex.format = fmt;
  for (size_t l = 0; l < levels.size(); ++l) {
    Image img(mip_extent(w, static_cast<int>(l)), mip_extent(h, static_cast<int>(l)));
    for (size_t k = 0; k < img.texels.size(); ++k) {
      const uint8_t v = levels[l][k % levels[l].size()];
      img.texels[k] = {v, v, v, 255};
    }
    tex.levels.push_back(std::move(img));
  }
  return tex;
}

SamplerDescriptor sampler_of(BaseFilter base, MipMode mip, WrapMode wrap = WrapMode::ClampToEdge) {
  SamplerDescriptor sd;
  sd.mode = {base, mip};
  sd.wrap_s = sd.wrap_t = wrap;
  return sd;
}

LodInput explicit_lod(float lod) {
  LodInput l;
  l.kind = LodKind::Explicit;
  l.lod = lod;
  return l;
}

// ---- The verifier against hand-derived intervals ----

TEST(SpecBounds, LinearSnapsTheSubTexelPositionToEitherNeighbour) {
  // 2 x 1 texture, texels 0 and 255: u - 1/2 = 2 s - 1/2
  const Texture tex = texture_of_levels(TexelFormat::L8, {{0, 255}}, 2, 1);
  const SamplerDescriptor sd = sampler_of(BaseFilter::Linear, MipMode::None);
  // s = 1/2: alpha = 1/2 exactly, 127.5 -> either code
  Bounds b = spec::filter_bounds(tex, sd, 0.5f, 0.5f, explicit_lod(0));
  EXPECT_EQ(b.lo[0], 127);
  EXPECT_EQ(b.hi[0], 128);
  EXPECT_EQ(b.lo[3], 255);
  EXPECT_EQ(b.hi[3], 255);
  // s = 1/2 + 2^-12: alpha between 128/256 and 129/256: 127.5 .. 128.496
  b = spec::filter_bounds(tex, sd, 0.5f + 0x1p-12f, 0.5f, explicit_lod(0));
  EXPECT_EQ(b.lo[0], 127);
  EXPECT_EQ(b.hi[0], 129);
  // at a texel centre (s = 1/4: u - 1/2 = 0) only texel 0
  b = spec::filter_bounds(tex, sd, 0.25f, 0.5f, explicit_lod(0));
  EXPECT_EQ(b.lo[0], 0);
  EXPECT_EQ(b.hi[0], 0);
  // 4 subtexel steps above the centre of texel 0: alpha = 4/256, 3.98 -> 3 .. 4
  b = spec::filter_bounds(tex, sd, 0.25f + 2 * 0x1p-8f, 0.5f, explicit_lod(0));
  EXPECT_EQ(b.lo[0], 3);
  EXPECT_EQ(b.hi[0], 4);
}

TEST(SpecBounds, NearestTakesEitherTexelOnlyWithinOneSubTexelStepOfAnEdge) {
  const Texture tex = texture_of_levels(TexelFormat::L8, {{0, 255}}, 2, 1);
  const SamplerDescriptor sd = sampler_of(BaseFilter::Nearest, MipMode::None);
  Bounds b = spec::filter_bounds(tex, sd, 0.5f, 0.5f, explicit_lod(0));  // u = 1 exactly: texel 1
  EXPECT_EQ(b.lo[0], 255);
  EXPECT_EQ(b.hi[0], 255);
  b = spec::filter_bounds(tex, sd, 0.5f - 0x1p-20f, 0.5f, explicit_lod(0));  // u just below 1: snaps to 1 or 255/256
  EXPECT_EQ(b.lo[0], 0);
  EXPECT_EQ(b.hi[0], 255);
  b = spec::filter_bounds(tex, sd, 0.5f - 0x1p-9f, 0.5f, explicit_lod(0));  // u = 1 - 2^-8: on the grid, texel 0
  EXPECT_EQ(b.lo[0], 0);
  EXPECT_EQ(b.hi[0], 0);
}

TEST(SpecBounds, WrapsFollowTheSpecFormulas) {
  // 3 x 1 texture 10, 20, 30; NEAREST at texel centre i (s = (i + 1/2) / 3)
  const Texture tex = texture_of_levels(TexelFormat::L8, {{10, 20, 30}}, 3, 1);
  const auto at = [&](WrapMode m, int i) {
    SamplerDescriptor sd = sampler_of(BaseFilter::Nearest, MipMode::None, m);
    sd.border = {99, 99, 99, 99};
    const Bounds b = spec::filter_bounds(tex, sd, (static_cast<float>(i) + 0.5f) / 3.0f, 0.5f, explicit_lod(0));
    EXPECT_EQ(b.lo[0], b.hi[0]);
    return b.lo[0];
  };
  // repeat: i mod 3
  EXPECT_EQ(at(WrapMode::Repeat, -1), 30);
  EXPECT_EQ(at(WrapMode::Repeat, 4), 20);
  // mirrored repeat: (size - 1) - mirror((i mod 2 size) - size): -1 -> 0, 3 -> 2, 4 -> 1, 6 -> 0
  EXPECT_EQ(at(WrapMode::MirroredRepeat, -1), 10);
  EXPECT_EQ(at(WrapMode::MirroredRepeat, 3), 30);
  EXPECT_EQ(at(WrapMode::MirroredRepeat, 4), 20);
  EXPECT_EQ(at(WrapMode::MirroredRepeat, 6), 10);
  EXPECT_EQ(at(WrapMode::ClampToEdge, -5), 10);
  EXPECT_EQ(at(WrapMode::ClampToEdge, 7), 30);
  EXPECT_EQ(at(WrapMode::ClampToBorder, -1), 99);
  EXPECT_EQ(at(WrapMode::ClampToBorder, 3), 99);
  EXPECT_EQ(at(WrapMode::ClampToBorder, 2), 30);
}

TEST(SpecBounds, MipLinearTakesTheLodWithinOneStepAndDeltaToEitherNeighbour) {
  // level 0 black, level 1 white; lambda = 1/2 +- 2^-8, delta quantized: k in 127..129
  const Texture tex = texture_of_levels(TexelFormat::L8, {{0}, {255}}, 2, 2);
  const SamplerDescriptor sd = sampler_of(BaseFilter::Linear, MipMode::Linear);
  const Bounds b = spec::filter_bounds(tex, sd, 0.3f, 0.6f, explicit_lod(0.5f));
  EXPECT_EQ(b.lo[0], 126);  // 255 * 127 / 256 = 126.5
  EXPECT_EQ(b.hi[0], 129);  // 255 * 129 / 256 = 128.5
  // a clamp to an exact value leaves no freedom: min_lod = max_lod = 1/4
  SamplerDescriptor c = sd;
  c.lod.min_lod_q8 = c.lod.max_lod_q8 = 64;
  const Bounds e = spec::filter_bounds(tex, c, 0.3f, 0.6f, explicit_lod(7.0f));
  EXPECT_EQ(e.lo[0], 63);  // 255 / 4 = 63.75
  EXPECT_EQ(e.hi[0], 64);
}

TEST(SpecBounds, MipNearestTakesEitherRoundingAtTheHalf) {
  const Texture tex = texture_of_levels(TexelFormat::L8, {{0}, {100}, {255}}, 4, 4);
  const SamplerDescriptor sd = sampler_of(BaseFilter::Nearest, MipMode::Nearest);
  Bounds b = spec::filter_bounds(tex, sd, 0.3f, 0.6f, explicit_lod(1.5f));  // levels 1 or 2
  EXPECT_EQ(b.lo[0], 100);
  EXPECT_EQ(b.hi[0], 255);
  b = spec::filter_bounds(tex, sd, 0.3f, 0.6f, explicit_lod(1.25f));  // level 1 only
  EXPECT_EQ(b.lo[0], 100);
  EXPECT_EQ(b.hi[0], 100);
  b = spec::filter_bounds(tex, sd, 0.3f, 0.6f, explicit_lod(9.0f));  // clamped to q = 2
  EXPECT_EQ(b.lo[0], 255);
  EXPECT_EQ(b.hi[0], 255);
}

TEST(SpecBounds, ScaleFactorSpansMaxAxisToSqrt2TimesTheSum) {
  // 64 x 64, ds/dx = 4 texels, dt/dx = 3 texels: rho_x in [4, 7 sqrt 2]: lambda_base 2 .. 3.307
  Texture tex;
  tex.format = TexelFormat::L8;
  tex.levels.push_back(Image(64, 64));
  LodInput g;
  g.kind = LodKind::Gradients;
  g.dsdx = 4.0f / 64, g.dtdx = 3.0f / 64;
  auto r = spec::lambda_base_range(tex, g);
  EXPECT_NEAR(static_cast<double>(r[0]), 2.0, 1e-9);
  EXPECT_NEAR(static_cast<double>(r[1]), std::log2(7 * std::sqrt(2.0)), 1e-9);
  // the same footprint as a quad: coarse differences
  LodInput q;
  q.kind = LodKind::Quad;
  q.qs = {0.25f, 0.25f + 4.0f / 64, 0.25f, 0.25f + 4.0f / 64};
  q.qt = {0.5f, 0.5f + 3.0f / 64, 0.5f, 0.5f + 3.0f / 64};
  r = spec::lambda_base_range(tex, q);
  EXPECT_NEAR(static_cast<double>(r[0]), 2.0, 1e-9);
  EXPECT_NEAR(static_cast<double>(r[1]), std::log2(7 * std::sqrt(2.0)), 1e-9);
  // the unit's GL vector length sqrt(4^2 + 3^2) = 5 lies inside: lambda = log2 5 = 2.32
  EXPECT_NEAR(lambda_from_gradients(g.dsdx, g.dtdx, 0, 0, 64, 64) / 256.0, std::log2(5.0), 1.0 / 256);
}

// ---- The levels are blended before the one rounding ----

// LINEAR_MIPMAP_LINEAR at delta = 1/4 (min_lod = max_lod = 1/4), alpha = 1/2 on both levels:
// level 0 gives (10 + 11) / 2 = 10.5, level 1 (20 + 21) / 2 = 20.5, and the spec's value is
// 3/4 10.5 + 1/4 20.5 = 13 exactly, so 13 is the only code it admits. The bilinear lerp unit hands
// the blend unit Q.8 results (2688 and 5248, dp::bilinear_lerp_q8), which blends them once:
// (2688 192 + 5248 64 + 2^15) >> 16 = 851,968 / 65,536 = 13. (Rounding each level first, half up to
// 11 and 21, gave (11 192 + 21 64 + 128) >> 8 = 14, one code outside: docs/sampler.md.)
TEST(SpecBounds, LevelsBlendedBeforeTheOneRoundingGiveTheExactValue) {
  const Texture tex = texture_of_levels(TexelFormat::L8, {{0, 10, 11, 0}, {20, 21}, {0}}, 4, 1);
  SamplerDescriptor sd = sampler_of(BaseFilter::Linear, MipMode::Linear);
  sd.lod.min_lod_q8 = sd.lod.max_lod_q8 = 64;
  const Bounds strict = spec::filter_bounds(tex, sd, 0.5f, 0.5f, explicit_lod(3.0f));
  EXPECT_EQ(strict.lo[0], 13);
  EXPECT_EQ(strict.hi[0], 13);
  const std::array<Texel4, 4> l0{Texel4{10, 0, 0, 0}, {11, 0, 0, 0}, {10, 0, 0, 0}, {11, 0, 0, 0}};
  const std::array<Texel4, 4> l1{Texel4{20, 0, 0, 0}, {21, 0, 0, 0}, {20, 0, 0, 0}, {21, 0, 0, 0}};
  EXPECT_EQ(dp::bilinear_lerp_q8(l0, 128, 0)[0], 2688);
  EXPECT_EQ(dp::bilinear_lerp_q8(l1, 128, 0)[0], 5248);
  const bool saved = fast_paths_enabled();
  for (const bool fast : {true, false}) {  // the fast path and the plain datapath
    set_fast_paths(fast);
    const Sampler sm(tex, sd);
    const Texel4 got = decode_texel(sm.sample(0.5f, 0.5f, lambda_explicit(3.0f)), tex.format);
    EXPECT_EQ(got[0], 13) << (fast ? "fast" : "plain");
    EXPECT_TRUE(strict.contains(got));
    const std::vector<SampleRequest> quad(4, SampleRequest{0.5f, 0.5f, lambda_explicit(3.0f)});
    std::vector<Rgba8> out(4);
    sm.sample_batch(quad.data(), quad.size(), out.data());
    for (const Rgba8& c : out) EXPECT_EQ(c.r, 13) << (fast ? "fast batch" : "plain batch");
  }
  set_fast_paths(saved);
}

// ---- The golden model inside the bounds ----

// At least 10^6 requests (quad pixels) of random cases (a tenth under the sanitizers), bias within
// the reported maxSamplerLodBias.
TEST(SpecBounds, GoldenModelInsideOnFuzzedRequests) {
  const int64_t want = tfu::test::iterations(1'000'000);
  std::mt19937_64 rng(20261206);
  std::vector<uint8_t> bytes(2048);
  spec::CaseResult all;
  int64_t cases = 0;
  while (all.checked < want) {
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng());
    fuzz::ByteReader in(bytes.data(), bytes.size());
    const spec::CaseResult r = spec::run_case(in);
    ++cases;
    all.checked += r.checked;
    all.out_of_domain += r.out_of_domain;
    all.outside += r.outside;
    if (all.first.empty()) all.first = r.first;
  }
  std::printf("spec bounds: %lld requests of %lld cases checked (%lld outside the domain), %lld outside the bounds\n",
              static_cast<long long>(all.checked), static_cast<long long>(cases),
              static_cast<long long>(all.out_of_domain), static_cast<long long>(all.outside));
  EXPECT_EQ(all.outside, 0) << all.first;
}

// ---- The API limits against the datapath they come from ----

TEST(ApiLimits, SubTexelPrecisionBitsIsTheAddressFraction) {
  constexpr int b = api_limits::kSubTexelPrecisionBits;
  // s 4 2^b = k + 1/2: texel_coord's u = k - 2^(b-1); the fraction steps by one per 2^-b texel,
  // takes 2^b values, and a quarter step more or less does not change it
  std::set<uint32_t> fractions;
  for (int k = 0; k < 4 << b; ++k) {
    const auto at = [&](double x) { return dp::texel_coord(static_cast<float>(std::ldexp(x, -(b + 2))), 4); };
    const dp::LevelCoord c = at(k + 0.5), lo = at(k + 0.25), hi = at(k + 0.75);
    const int64_t u = k - (1 << (b - 1));
    EXPECT_EQ(c.i0, u >> b);
    EXPECT_EQ(c.f, static_cast<uint32_t>(u & ((1 << b) - 1)));
    EXPECT_EQ(lo.f, c.f);
    EXPECT_EQ(hi.f, c.f);
    fractions.insert(c.f);
  }
  EXPECT_EQ(fractions.size(), size_t{1} << b);
}

TEST(ApiLimits, MipmapPrecisionBitsIsTheLevelBlendWeight) {
  constexpr int b = api_limits::kMipmapPrecisionBits;
  std::set<int> weights;
  for (int k = 0; k < 3 << b; ++k) {
    // an explicit LOD on the 2^-b grid is kept, a quarter step off it is not
    EXPECT_EQ(lambda_explicit(static_cast<float>(std::ldexp(k, -b))), k);
    EXPECT_EQ(lambda_explicit(static_cast<float>(std::ldexp(k + 0.25, -b))), k);
    const LevelPick p = select_levels(k, MipMode::Linear, 4);
    if (k > 0) {
      EXPECT_EQ(p.blend, k & ((1 << b) - 1));
    }
    weights.insert(p.blend);
  }
  EXPECT_EQ(weights.size(), size_t{1} << b);
}

// The longest chain (16384 x 1: kMaxLevels levels), each level one grey (17 l), a footprint of 2^20
// texels per pixel: the spec's lambda is 20 + bias, beyond the last level for any bias the driver
// may pass. The LOD unit's derivatives saturate at 2^kLambdaBaseSaturation texels: a bias of
// -maxSamplerLodBias still reaches the last level, one more level of negative bias does not.
TEST(ApiLimits, MaxSamplerLodBiasIsWhereTheDerivativeClampStillReachesTheLastLevel) {
  ASSERT_EQ(mip_level_count(api_limits::kMaxImageDimension2D, 1), kMaxLevels);
  std::vector<std::vector<uint8_t>> greys;
  for (int l = 0; l < kMaxLevels; ++l) greys.push_back({static_cast<uint8_t>(17 * l)});
  const Texture tex = texture_of_levels(TexelFormat::L8, greys, api_limits::kMaxImageDimension2D, 1);
  const float dsdx = std::ldexp(1.0f, 20) / static_cast<float>(api_limits::kMaxImageDimension2D);
  EXPECT_EQ(lambda_from_gradients(dsdx, 0, 0, 0, tex.width(), 1), api_limits::kLambdaBaseSaturation << kLodFracBits);
  LodInput g;
  g.kind = LodKind::Gradients;
  g.dsdx = dsdx;
  for (const MipMode mip : {MipMode::Nearest, MipMode::Linear}) {
    SamplerDescriptor sd = sampler_of(BaseFilter::Linear, mip);
    const auto inside = [&](int bias_levels) {
      sd.lod.bias_q8 = bias_levels << kLodFracBits;
      const Sampler sm(tex, sd);
      const Texel4 got =
          decode_texel(sm.sample(0.3f, 0.5f, lambda_from_gradients(dsdx, 0, 0, 0, tex.width(), 1)), tex.format);
      return spec::filter_bounds(tex, sd, 0.3f, 0.5f, g).contains(got);
    };
    EXPECT_TRUE(inside(-api_limits::kMaxSamplerLodBias));
    EXPECT_FALSE(inside(-api_limits::kMaxSamplerLodBias - 1));
  }
}

// The positive side: the derivatives' Q.16 resolution. A footprint just under 2^-bias texels per
// pixel lands on level 0 .. 1 after the bias; at +maxSamplerLodBias its quantization stays within
// the LOD accuracy, at +12 levels (2^-12 texels: 16 LSBs of Q.16) it does not.
TEST(ApiLimits, PositiveBiasIsBoundByTheDerivativeResolution) {
  const Texture tex = texture_of_levels(TexelFormat::L8, {{0}, {255}, {255}, {255}}, 8, 8);
  const SamplerDescriptor base = sampler_of(BaseFilter::Linear, MipMode::Linear);
  const auto worst_outside = [&](int bias_levels) {
    SamplerDescriptor sd = base;
    sd.lod.bias_q8 = bias_levels << kLodFracBits;
    const Sampler sm(tex, sd);
    int outside = 0;
    for (int k = 0; k < 1024; ++k) {  // lambda_base from -bias to -bias + 1 in 1/1024 steps
      LodInput g;
      g.kind = LodKind::Gradients;
      g.dsdx = static_cast<float>(std::exp2(-bias_levels + k / 1024.0) / 8);
      const Texel4 got = decode_texel(sm.sample(0.3f, 0.3f, lambda_from_gradients(g.dsdx, 0, 0, 0, 8, 8)), tex.format);
      outside += spec::filter_bounds(tex, sd, 0.3f, 0.3f, g).contains(got) ? 0 : 1;
    }
    return outside;
  };
  EXPECT_EQ(worst_outside(api_limits::kMaxSamplerLodBias), 0);
  EXPECT_GT(worst_outside(12), 0);
}

TEST(ApiLimits, MaxSamplerAnisotropyAndImageDimensionAreTheRegisterRanges) {
  SamplerDescriptor sd = sampler_of(BaseFilter::Linear, MipMode::Linear);
  sd.max_aniso = api_limits::kMaxSamplerAnisotropy;
  EXPECT_NO_THROW(sd.validate());
  sd.max_aniso = api_limits::kMaxSamplerAnisotropy + 1;
  EXPECT_THROW(sd.validate(), InputError);
  Texture tex;
  tex.levels.push_back(Image(api_limits::kMaxImageDimension2D, 1));
  EXPECT_NO_THROW(tex.validate("t"));
  tex.levels[0] = Image(api_limits::kMaxImageDimension2D + 1, 1);
  EXPECT_THROW(tex.validate("t"), InputError);
}

TEST(ApiLimits, TheTableIsPastedInTheSamplerPage) {
  EXPECT_NE(test::docs_text("sampler.md").find(api_limits::limits_markdown()), std::string::npos)
      << "docs/sampler.md, \"API limits\", should hold:\n"
      << api_limits::limits_markdown();
}

}  // namespace
}  // namespace tfu
