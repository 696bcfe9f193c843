// sRGB textures (cmodel/srgb.hpp, docs/srgb.md): the decode and encode ROMs exhaustively against the
// exact transfer functions (std::pow), the SRGBA8 texel format in the golden sampler (hand-derived
// results, alpha as RGBA8's, the plain and fast paths), and the texture key.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "cmodel/bindings.hpp"
#include "cmodel/error.hpp"
#include "cmodel/metrics.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/srgb.hpp"
#include "cmodel/texture.hpp"

namespace tfu {
namespace {

// The exact transfer functions (IEC 61966-2-1), written here with std::pow, independently of the
// ROM generator's Newton roots.
double exact_eotf(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double exact_oetf(double x) { return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055; }

TEST(SrgbRom, DecodeIsTheRoundedExactEotfWithinHalfAnLsbOf12Bits) {
  double max_err = 0.0;
  int worst = -1;
  for (int c = 0; c < 256; ++c) {
    const double exact = exact_eotf(c / 255.0);
    EXPECT_EQ(srgb::kDecodeRom[static_cast<size_t>(c)], static_cast<int>(std::floor(4095.0 * exact + 0.5))) << c;
    const double err = std::abs(srgb::kDecodeRom[static_cast<size_t>(c)] / 4095.0 - exact);
    if (err > max_err) max_err = err, worst = c;
  }
  // docs/srgb.md: 0.4998 LSB of unorm12 (1.22e-4) at code 80, the rounding bound 0.5 LSB.
  EXPECT_LE(max_err * 4095.0, 0.5);
  EXPECT_NEAR(max_err * 4095.0, 0.4998, 0.0001);
  EXPECT_EQ(worst, 80);
}

TEST(SrgbRom, HandDerivedEntries) {
  EXPECT_EQ(srgb::decode(0), 0);
  EXPECT_EQ(srgb::decode(1), 1);      // 4095 / 255 / 12.92 = 1.243
  EXPECT_EQ(srgb::decode(10), 12);    // 10 / 255 = 0.0392 <= 0.04045: 4095 x 0.0392 / 12.92 = 12.43
  EXPECT_EQ(srgb::decode(128), 884);  // ((128 / 255 + 0.055) / 1.055)^2.4 = 0.215861; x 4095 = 883.95
  EXPECT_EQ(srgb::decode(255), 4095);
  EXPECT_EQ(srgb::encode(2048), 188);  // 1.055 (2048 / 4095)^(1 / 2.4) - 0.055 = 0.73544; x 255 = 187.54
  EXPECT_EQ(srgb::encode(0), 0);
  EXPECT_EQ(srgb::encode(4095), 255);
  EXPECT_EQ(srgb::encode(-5), 0);  // the port's clamp
  EXPECT_EQ(srgb::encode(9000), 255);
}

TEST(SrgbRom, TwelveBitsIsTheNarrowestOneToOneDecode) {
  // Distinct decoded values of the 256 codes at each unorm width (rounded exact EOTF).
  const auto distinct = [](int bits) {
    std::set<long> v;
    for (int c = 0; c < 256; ++c) v.insert(std::lround(std::floor(((1 << bits) - 1) * exact_eotf(c / 255.0) + 0.5)));
    return v.size();
  };
  EXPECT_EQ(distinct(8), 183u);  // codes 0..6 all decode to 0 at 8 bits
  EXPECT_EQ(distinct(11), 250u);
  EXPECT_EQ(distinct(12), 256u);
  std::set<int> rom(srgb::kDecodeRom.begin(), srgb::kDecodeRom.end());
  EXPECT_EQ(rom.size(), 256u);
}

TEST(SrgbRom, EncodeIsTheRoundedExactOetfAndInvertsTheDecode) {
  for (int x = 0; x < 4096; ++x) {
    EXPECT_EQ(srgb::kEncodeRom[static_cast<size_t>(x)],
              static_cast<int>(std::floor(255.0 * exact_oetf(x / 4095.0) + 0.5)))
        << x;
    if (x > 0) {
      EXPECT_GE(srgb::kEncodeRom[static_cast<size_t>(x)], srgb::kEncodeRom[static_cast<size_t>(x - 1)]) << x;
    }
  }
  for (int c = 0; c < 256; ++c) EXPECT_EQ(srgb::encode(srgb::decode(static_cast<uint8_t>(c))), c) << c;
}

TEST(SrgbFormat, TexelWordsDecodeColourAndKeepAlpha) {
  EXPECT_EQ(decode_texel({128, 0, 255, 77}, TexelFormat::SRGBA8), (Texel4{884, 0, 4095, 77}));
  EXPECT_EQ(encode_texel({2048, 4095, -3, 300}, TexelFormat::SRGBA8), (Rgba8{188, 255, 0, 255}));
  EXPECT_EQ(bytes_per_texel(TexelFormat::SRGBA8), 4);
  EXPECT_EQ(texel_format_from_name("srgba8"), TexelFormat::SRGBA8);
}

Texture two_texels(TexelFormat f) {  // black | white, alpha 0 | 255
  Texture t;
  t.format = f;
  t.levels.emplace_back(2, 1);
  t.levels[0].texels = {{0, 0, 0, 0}, {255, 255, 255, 255}};
  return t;
}

TEST(SrgbFormat, LinearMidpointOfBlackAndWhite) {
  // Halfway between the two texel centres (s = 0.5): the stored values average to 128, linear
  // light to 2048 of 4095, which is sRGB code 188 (SrgbRom.HandDerivedEntries); alpha 128 in both.
  SamplerDescriptor cfg;
  cfg.mode = filter_mode_from_name("LINEAR");
  cfg.wrap_s = cfg.wrap_t = WrapMode::ClampToEdge;
  const Texture plain = two_texels(TexelFormat::RGBA8), srgb = two_texels(TexelFormat::SRGBA8);
  EXPECT_EQ(Sampler(plain, cfg).sample(0.5f, 0.5f, 0), (Rgba8{128, 128, 128, 128}));
  EXPECT_EQ(Sampler(srgb, cfg).sample(0.5f, 0.5f, 0), (Rgba8{188, 188, 188, 128}));
  // A quarter of the way (s = 3 / 8): the lerp gives 1024 = 4095 x 64 / 256 rounded, code 137.
  EXPECT_EQ(Sampler(srgb, cfg).sample(0.375f, 0.5f, 0), (Rgba8{137, 137, 137, 64}));
}

Texture random_texture(TexelFormat f, int w, int h, unsigned seed) {
  Texture t;
  t.format = f;
  t.levels.emplace_back(w, h);
  std::mt19937 rng(seed);
  for (Rgba8& x : t.levels[0].texels)
    x = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()),
         static_cast<uint8_t>(rng())};
  generate_mipmaps(t, MipMethod::Box);
  return t;
}

// Every mode the format takes: alpha is filtered as RGBA8's (same words of level 0; the MIP levels'
// alpha are box averages of alpha either way), the colour channels differ from the stored-value
// filter, NEAREST (one texel, no blend) returns the stored word, and the ideal path agrees within the
// datapath's rounding.
TEST(SrgbFormat, EveryModeAlphaAsRgba8AndColourFromLinear) {
  const Texture plain = random_texture(TexelFormat::RGBA8, 16, 16, 3),
                srgb = random_texture(TexelFormat::SRGBA8, 16, 16, 3);
  for (size_t l = 0; l < plain.levels.size(); ++l)
    for (size_t i = 0; i < plain.levels[l].texels.size(); ++i)
      ASSERT_EQ(plain.levels[l].texels[i].a, srgb.levels[l].texels[i].a) << l << " " << i;
  Texture codes = srgb;  // the sRGB texture's words filtered as stored
  codes.format = TexelFormat::RGBA8;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> pos(-0.5f, 1.5f);
  for (const FilterMode& m : all_filter_modes()) {
    if (m.base == BaseFilter::EdgePreserving) continue;
    SamplerDescriptor cfg;
    cfg.mode = m;
    cfg.wrap_s = WrapMode::Repeat;
    cfg.wrap_t = WrapMode::MirroredRepeat;
    const Sampler a(plain, cfg), b(srgb, cfg), c(codes, cfg);
    int colour_differs = 0;
    double max_ideal = 0.0;
    for (int k = 0; k < 500; ++k) {
      const float s = pos(rng), t = pos(rng);
      const auto lambda = static_cast<int32_t>(rng() % 1400) - 200;
      const Rgba8 pa = a.sample(s, t, lambda), pb = b.sample(s, t, lambda);
      ASSERT_EQ(pa.a, pb.a) << filter_mode_name(m);
      colour_differs += pa.r != pb.r;
      if (m.base == BaseFilter::Nearest && m.mip != MipMode::Linear) {
        ASSERT_EQ(pb, c.sample(s, t, lambda)) << filter_mode_name(m);  // the stored word
      }
      const std::array<double, 4> ideal = b.sample_ideal(s, t, lambda / 256.0);
      max_ideal = std::max(max_ideal, std::abs(ideal[0] * 255.0 - pb.r));
    }
    if (m.base != BaseFilter::Nearest) {
      EXPECT_GT(colour_differs, 100) << filter_mode_name(m);
    }
    // The ideal's colour is the exact OETF of the exact linear filter. Measured (these 500 samples):
    // NEAREST 0, NEAREST_MIPMAP_LINEAR 0.60, LINEAR 1.72, LINEAR_MIPMAP_NEAREST 2.63 codes (rgba8:
    // 0.50, 1.22, 1.19); CUBIC 10.3 (rgba8 3.53): the datapath's linear error (Q.8 fractions, 8-bit
    // weight ROM) is multiplied by the OETF's slope near black (0.8 sRGB codes per unorm12 step).
    EXPECT_LT(max_ideal, m.base == BaseFilter::Cubic ? 12.0 : 3.0) << filter_mode_name(m);
  }
}

TEST(SrgbFormat, FastPathsEqualThePlainPathThroughTheTableOfModes) {
  const Texture srgb = random_texture(TexelFormat::SRGBA8, 12, 20, 5);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> pos(-0.5f, 1.5f);
  for (const FilterMode& m : all_filter_modes()) {
    if (m.base == BaseFilter::EdgePreserving) continue;
    SamplerDescriptor cfg;
    cfg.mode = m;
    const Sampler smp(srgb, cfg);
    for (int k = 0; k < 200; ++k) {
      const float s = pos(rng), t = pos(rng);
      const auto lambda = static_cast<int32_t>(rng() % 1200) - 100;
      ASSERT_EQ(smp.sample(s, t, lambda), encode_texel(smp.sample_channels(s, t, lambda), TexelFormat::SRGBA8))
          << filter_mode_name(m);
      const SampleRequest r{s, t, lambda};
      Rgba8 batch{};
      smp.sample_batch(&r, 1, &batch);
      ASSERT_EQ(batch, smp.sample(s, t, lambda)) << filter_mode_name(m);
    }
  }
}

TEST(SrgbFormat, EdgePreservingAndBsplineInterpAreRefused) {
  const Texture srgb = random_texture(TexelFormat::SRGBA8, 8, 8, 1);
  SamplerDescriptor cfg;
  cfg.mode = filter_mode_from_name("EDGE_PRESERVING");
  EXPECT_THROW(Sampler(srgb, cfg), InputError);
  cfg.mode = filter_mode_from_name("CUBIC");
  cfg.kernel = kBsplineInterp;
  EXPECT_THROW(Sampler(srgb, cfg), InputError);
}

// The texture key srgb: the format becomes srgba8 and the MIP levels are averaged in linear light.
TEST(SrgbFormat, TextureKeyDeclaresSrgbAndMipmapsAverageInLinear) {
  const LoadedTexture off = load_texture_spec({"proc:checkerboard:16", {}}, "test");
  const LoadedTexture on = load_texture_spec({"proc:checkerboard:16", {{"srgb", "true"}}}, "test");
  EXPECT_EQ(off.texture->format, TexelFormat::RGBA8);
  EXPECT_EQ(on.texture->format, TexelFormat::SRGBA8);
  ASSERT_EQ(on.texture->levels[0].texels, off.texture->levels[0].texels);
  // Level 1 texel of a 2 x 2 block: the box of the decoded codes, encoded.
  const Image& l0 = on.texture->levels[0];
  const Rgba8 got = on.texture->levels[1].at(0, 0);
  int sum = 0;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) sum += srgb::decode(l0.at(x, y).r);
  EXPECT_EQ(got.r, srgb::encode((sum + 2) >> 2));
  EXPECT_THROW(load_texture_spec({"proc:checkerboard:16", {{"srgb", "maybe"}}}, "test"), InputError);
}

// A ground plane seen at a grazing angle (minification up to many texels per pixel), one stage.
Scene srgb_plane(std::shared_ptr<const Texture> tex) {
  Scene s;
  s.width = 64;
  s.height = 48;
  s.camera.position = {0, 1, 0};
  s.camera.look_at = {0, 1, -1};
  s.camera.fov_y_deg = 90;
  s.camera.near_plane = 0.1;
  s.camera.far_plane = 100;
  Mesh m = make_quad_mesh({glm::dvec3{-4, 0, -1.5}, {4, 0, -1.5}, {4, 0, -30}, {-4, 0, -30}},
                          {glm::dvec2{0, 0}, {8, 0}, {8, 28}, {0, 28}});
  TextureStage st;
  st.spec.source = "test";
  st.texture = std::move(tex);
  st.sampler.mode = FilterMode{BaseFilter::Linear, MipMode::Linear};
  m.stages.push_back(std::move(st));
  s.meshes.push_back(std::move(m));
  return s;
}

// The surface truth of an srgba8 stage integrates in linear light: a constant texture's truth is its
// colour; on a noise texture the linear-light filter is closer to that truth than the filter of the
// stored codes (which darkens every average: codes 0 and 255 average to 128, light to code 188).
TEST(SrgbFormat, SurfaceTruthInLinearLightAndTheLinearFilterCloserToIt) {
  RenderOptions o;
  o.ground_truth = true;
  o.filter = FilterMode{BaseFilter::Linear, MipMode::Linear};
  Texture flat;
  flat.format = TexelFormat::SRGBA8;
  flat.levels.emplace_back(8, 8, Rgba8{100, 150, 200, 255});
  generate_mipmaps(flat, MipMethod::Box);
  const RenderResult c = render_scene(srgb_plane(std::make_shared<const Texture>(flat)), o);
  int drawn = 0;
  for (size_t i = 0; i < c.image.texels.size(); ++i)
    if (c.image.texels[i] == Rgba8{100, 150, 200, 255}) {
      ++drawn;
      EXPECT_EQ(c.surface_truth.texels[i], (Rgba8{100, 150, 200, 255})) << i;
    }
  EXPECT_GT(drawn, 500);
  Texture noise = random_texture(TexelFormat::SRGBA8, 64, 64, 21);
  for (Image& l : noise.levels)
    for (Rgba8& t : l.texels) t.a = 255;
  Texture codes = random_texture(TexelFormat::RGBA8, 64, 64, 21);  // the same level 0, box MIPs of codes
  for (Image& l : codes.levels)
    for (Rgba8& t : l.texels) t.a = 255;
  ASSERT_EQ(noise.levels[0].texels, codes.levels[0].texels);
  const RenderResult lin = render_scene(srgb_plane(std::make_shared<const Texture>(noise)), o);
  const RenderResult cod = render_scene(srgb_plane(std::make_shared<const Texture>(codes)), o);
  const double p_lin = psnr_db(lin.image, lin.surface_truth), p_cod = psnr_db(cod.image, lin.surface_truth);
  EXPECT_GT(p_lin, p_cod + 6.0) << p_lin << " " << p_cod;
}

}  // namespace
}  // namespace tfu
