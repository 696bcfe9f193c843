// Texture file formats through OpenImageIO (PNG, JPEG, TIFF, OpenEXR; stored MIP levels) and a
// randomized fuzz of the scene parser.
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cmodel/error.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/texture.hpp"

namespace tfu {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / fmt::format("tfu_io_{}", ::testing::UnitTest::GetInstance()->random_seed());
  fs::create_directories(d);
  return d / name;
}

Image pattern(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.at(x, y) = {static_cast<uint8_t>(x * 17), static_cast<uint8_t>(y * 29), static_cast<uint8_t>((x + y) * 7), 255};
  return img;
}

TEST(TextureFiles, LosslessFormatsRoundTripExactly) {
  const Image img = pattern(13, 7);  // non-power-of-two
  for (const char* ext : {"png", "tif", "exr"}) {
    const fs::path p = scratch(fmt::format("rt.{}", ext));
    save_image(img, p.string(), true);
    const Texture t = load_texture(p.string());
    ASSERT_EQ(t.levels.size(), 1u) << ext;
    EXPECT_EQ(t.levels[0].texels, img.texels) << ext;
    EXPECT_EQ(t.format, TexelFormat::RGBA8);
  }
}

TEST(TextureFiles, JpegLoadsApproximately) {
  // JPEG has no alpha: write RGB through OpenImageIO directly, then load (A = 255). A smooth
  // gradient, so that chroma subsampling does not dominate.
  Image img(16, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      img.at(x, y) = {static_cast<uint8_t>(x * 8), static_cast<uint8_t>(y * 8), static_cast<uint8_t>(64 + x * 4), 255};
  const fs::path p = scratch("a.jpg");
  auto out = OIIO::ImageOutput::create(p.string());
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(16, 16, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("CompressionQuality", 100);
  ASSERT_TRUE(out->open(p.string(), spec));
  std::vector<uint8_t> rgb;
  for (const Rgba8& t : img.texels) rgb.insert(rgb.end(), {t.r, t.g, t.b});
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, rgb.data()));
  out->close();
  const Texture t = load_texture(p.string());
  int worst = 0;
  for (size_t i = 0; i < img.texels.size(); ++i) {
    worst = std::max({worst, std::abs(t.levels[0].texels[i].r - img.texels[i].r),
                      std::abs(t.levels[0].texels[i].g - img.texels[i].g)});
    EXPECT_EQ(t.levels[0].texels[i].a, 255);
  }
  EXPECT_LE(worst, 24);  // lossy, but the same picture
}

TEST(TextureFiles, StoredMipLevelsAreUsed) {
  // A tiled, MIP-mapped TIFF made the way maketx makes it (ImageBufAlgo::make_texture). Its
  // stored levels come from OpenImageIO's own filter; the loader must return them unchanged.
  const fs::path p = scratch("mip.tx");
  const Image base = pattern(16, 8);
  OIIO::ImageBuf src(OIIO::ImageSpec(16, 8, 4, OIIO::TypeDesc::UINT8), const_cast<Rgba8*>(base.texels.data()));
  OIIO::ImageSpec config;
  config.attribute("maketx:filtername", "box");
  config.attribute("oiio:UnassociatedAlpha", 1);
  ASSERT_TRUE(OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, src, p.string(), config))
      << OIIO::geterror();
  const Texture t = load_texture(p.string());
  ASSERT_EQ(t.levels.size(), 5u);  // 16x8, 8x4, 4x2, 2x1, 1x1
  EXPECT_EQ(t.levels[0].texels, base.texels);
  auto in = OIIO::ImageInput::open(p.string());
  ASSERT_TRUE(in);
  for (int l = 1; l < 5; ++l) {
    ASSERT_TRUE(in->seek_subimage(0, l));
    std::vector<Rgba8> stored(static_cast<size_t>(in->spec().width * in->spec().height));
    ASSERT_TRUE(in->read_image(0, l, 0, 4, OIIO::TypeDesc::UINT8, stored.data()));
    EXPECT_EQ(t.levels[static_cast<size_t>(l)].texels, stored) << "level " << l;
  }
}

TEST(TextureFiles, BadFilesGiveOneLineErrors) {
  const fs::path p = scratch("corrupt.png");
  { std::ofstream(p) << "\x89PNG\r\n garbage"; }
  for (const std::string& f : {p.string(), scratch("missing.png").string()}) {
    try {
      (void)load_texture(f);
      ADD_FAILURE() << "no error for " << f;
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(f), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
  }
}

// Randomized fuzz of the scene parser: mutations of the built-in scenes either parse or raise a
// one-line InputError naming the source; never another exception, never a crash.
TEST(SceneFuzz, MutatedScenesParseOrFailCleanly) {
  std::mt19937 rng(77);
  const std::string alphabet = "{}[]\",:0123456789.-eEtruefalsn \n";
  int parsed = 0, rejected = 0;
  for (int iter = 0; iter < 1500; ++iter) {
    const auto& names = builtin_scene_names();
    // Textures shrunk to 8x8 so that accepted mutations stay fast.
    const std::string src = std::regex_replace(builtin_scene_json(names[rng() % names.size()]),
                                               std::regex("\"size\": [0-9]+"), "\"size\": 8");
    // Mutate a char vector (std::string insert/replace trips a GCC 12 -Wrestrict false positive).
    std::vector<char> buf(src.begin(), src.end());
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const size_t pos = rng() % (buf.size() + 1);
      const auto at = buf.begin() + static_cast<std::ptrdiff_t>(pos);
      switch (rng() % 3) {
        case 0: buf.insert(at, alphabet[rng() % alphabet.size()]); break;
        case 1: if (pos < buf.size()) buf.erase(at, at + static_cast<std::ptrdiff_t>(std::min<size_t>(1 + rng() % 8, buf.size() - pos))); break;
        default: if (pos < buf.size()) *at = alphabet[rng() % alphabet.size()]; break;
      }
    }
    const std::string text(buf.begin(), buf.end());
    try {
      (void)parse_scene(text, "fuzz.json");
      ++parsed;
    } catch (const InputError& e) {
      const std::string m = e.what();
      ASSERT_NE(m.find("fuzz.json"), std::string::npos) << m;
      ASSERT_EQ(m.find('\n'), std::string::npos) << m;
      ++rejected;
    }
  }
  EXPECT_GT(rejected, 100);
  EXPECT_GT(parsed, 10);
}

}  // namespace
}  // namespace tfu
