// Compression at upload (cmodel/upload_compression.hpp): the rule names, ioquake3's s3tc rule
// (DXT1 when every alpha is 255, else uncompressed; light maps never), block counts of compressed
// MIP chains derived by hand, and a real OpenArena frame compressed as it ships (s3tc, astc6x6):
// the golden model equals both cycle-model engines on every request under both cache
// organizations, and the base textures' memory traffic falls.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>

#include "cmodel/bindings.hpp"
#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/q3_scene.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene_frame.hpp"
#include "cmodel/scene_source.hpp"
#include "cmodel/upload_compression.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/texel_cache.hpp"
#include "testbench/input_error.hpp"
#include "testbench/q3_test_data.hpp"

namespace tfu {
namespace {

// The one-line InputError that `expr` throws contains `text` (or the test fails showing the message).
#define EXPECT_INPUT_ERROR(expr, text)                              \
  do {                                                              \
    const std::string message = input_error([&] { (void)(expr); }); \
    EXPECT_NE(message.find(text), std::string::npos) << message;    \
  } while (false)

// A w x h RGBA8 texture of opaque texels (a smooth pattern) with its box MIP chain.
Texture opaque_texture(int w, int h) {
  Texture t;
  t.levels.emplace_back(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      t.levels[0].at(x, y) = {static_cast<uint8_t>(8 * x), static_cast<uint8_t>(16 * y),
                              static_cast<uint8_t>(4 * (x + y)), 255};
  generate_mipmaps(t, MipMethod::Box);
  return t;
}

size_t block_bytes(const Texture& t) {
  size_t n = 0;
  for (const BlockLevel& l : t.compressed->image.levels) n += l.blocks.size();
  return n;
}

TEST(UploadCompression, NamesAndErrors) {
  EXPECT_EQ(upload_compression_from_name("none").rule, UploadRule::None);
  const UploadCompression s3tc = upload_compression_from_name("s3tc");
  EXPECT_EQ(s3tc.rule, UploadRule::S3tc);
  EXPECT_EQ(s3tc.name(), "s3tc");
  const UploadCompression astc = upload_compression_from_name("astc6x6");
  EXPECT_EQ(astc.rule, UploadRule::Format);
  EXPECT_EQ(astc.format, BlockFormat::ASTC_6x6);
  EXPECT_EQ(astc.name(), "astc6x6");
  EXPECT_INPUT_ERROR(upload_compression_from_name("bc8"), "unknown block-compressed format 'bc8' (did you mean 'bc1'?");
  EXPECT_INPUT_ERROR(upload_compression_from_name("bc4s"),
                     "'bc4s' is a signed format; the unit filters unsigned texels only");
}

// Upload32 (ioquake3 renderergl1/tr_image.c): samples = 4 as soon as one texel's alpha is not 255,
// and only samples == 3 is compressed, to GL_COMPRESSED_RGBA_S3TC_DXT1_EXT.
TEST(UploadCompression, S3tcRuleIsIoquake3s) {
  const UploadCompression s3tc = upload_compression_from_name("s3tc");
  Texture t = opaque_texture(20, 12);
  EXPECT_EQ(upload_block_format(s3tc, t), BlockFormat::BC1A);
  EXPECT_EQ(upload_block_format({}, t), std::nullopt);
  EXPECT_EQ(upload_block_format(upload_compression_from_name("bc7"), t), BlockFormat::BC7);
  t.levels[0].at(19, 11).a = 254;  // one texel of level 0
  EXPECT_EQ(upload_block_format(s3tc, t), std::nullopt);
  EXPECT_EQ(upload_block_format(upload_compression_from_name("astc8x8"), t),
            BlockFormat::ASTC_8x8);  // ASTC keeps alpha
  Texture lower = opaque_texture(20, 12);
  lower.levels[2].at(0, 0).a = 0;  // only level 0 is scanned, as Upload32 scans the image it is given
  EXPECT_EQ(upload_block_format(s3tc, lower), BlockFormat::BC1A);
  const Texture c = compress_texture(opaque_texture(20, 12), BlockFormat::BC1A, "t");
  EXPECT_EQ(upload_block_format(upload_compression_from_name("bc3"), c), std::nullopt);  // compressed already
}

// Block bytes of a 20 x 12 chain (20x12, 10x6, 5x3, 2x1, 1x1), by hand: BC1 8-byte blocks of 4x4:
// 5*3 + 3*2 + 2*1 + 1 + 1 = 25 blocks = 200 bytes; ASTC 6x6 16-byte blocks: 4*2 + 2*1 + 1 + 1 + 1
// = 13 blocks = 208 bytes; the RGBA8 chain holds (240 + 60 + 15 + 2 + 1) * 4 = 1272 bytes.
TEST(UploadCompression, CompressedChainsHoldTheBlocksCountedByHand) {
  const auto src = std::make_shared<const Texture>(opaque_texture(20, 12));
  const auto bc1 = upload_compressed(src, upload_compression_from_name("s3tc"), "t");
  ASSERT_TRUE(bc1->compressed);
  EXPECT_EQ(bc1->compressed->image.format, BlockFormat::BC1A);
  EXPECT_EQ(bc1->levels.size(), 5u);
  EXPECT_EQ(block_bytes(*bc1), 200u);
  // An opaque image through DXT1 keeps alpha 255: libsquish gives no texel the transparent index.
  for (const Image& l : bc1->levels)
    for (const Rgba8& p : l.texels) ASSERT_EQ(p.a, 255);
  const auto astc = upload_compressed(src, upload_compression_from_name("astc6x6"), "t");
  EXPECT_EQ(block_bytes(*astc), 208u);
  // Remembered: the same texture and format give the same object; uncompressed gives the source.
  EXPECT_EQ(upload_compressed(src, upload_compression_from_name("s3tc"), "t"), bc1);
  EXPECT_EQ(upload_compressed(src, {}, "t"), src);
}

// ---- A real frame (Debian openarena-081-maps / -textures; scripts/bootstrap --test installs them) ----

using q3::testdata::checked_game_data;

struct FrameRun {
  Scene scene;
  std::map<std::string, uint64_t> base_bytes;  // memory bytes per base texture (stage 0 names)
  uint64_t base_total = 0, light_total = 0;
  uint64_t decoded_blocks = 0;
  std::set<std::string> compressed;  // base textures held as blocks
};

// aggressor from spawn 0 at 256x144, trilinear base stage: the golden render, then the cycle model
// with both engines (each compared with the golden model on every request) and the given cache
// organization.
FrameRun run_frame(const std::string& compress, rtl::CacheHolds holds) {
  FrameRun out;
  out.scene =
      open_scene({"oa:aggressor:0", 256, 144, checked_game_data().dir()}, upload_compression_from_name(compress));
  for (const Mesh& m : out.scene.meshes)
    if (m.stages.at(0).texture->compressed) out.compressed.insert(m.stages.at(0).spec.source);
  RenderOptions ro;
  ro.trace = true;
  ro.threads = 1;
  const RenderResult r = render_scene(out.scene, ro);
  rtl::UnitConfig u;
  u.cache.holds = holds;
  rtl::SceneSimResult sims[2];
  for (const rtl::UnitEngine e : {rtl::UnitEngine::Recurrence, rtl::UnitEngine::Clocked}) {
    rtl::SceneSimOptions so;
    so.engine = e;
    rtl::SceneSimResult& s = sims[e == rtl::UnitEngine::Clocked];
    s = rtl::simulate_scene(out.scene, r, u, so);
    EXPECT_TRUE(s.mismatch.empty()) << compress << ": " << s.mismatch;
    EXPECT_EQ(s.image.texels, r.image.texels) << compress;
  }
  EXPECT_EQ(sims[0].cycles, sims[1].cycles) << compress;
  EXPECT_EQ(sims[0].stats.json_text(), sims[1].stats.json_text()) << compress;
  for (const auto& [label, v] : sims[0].stats.table("textures")->rows) {
    const std::string name = label.substr(label.find(' ') + 1);
    if (name.find(":lightmap") != std::string::npos) {  // ":lightmap:N", or ":lightmap-shiftK:N" as the game shifts it
      out.light_total += v[4];
    } else {
      out.base_bytes[name] = v[4];
      out.base_total += v[4];
    }
  }
  out.decoded_blocks = sims[0].stats.counter("decoded_blocks");
  return out;
}

TEST(OpenArena, CompressedFramesAsTheyShip) {
  if (!checked_game_data().present()) GTEST_SKIP() << checked_game_data().missing();
  const FrameRun plain = run_frame("none", rtl::CacheHolds::Compressed);
  EXPECT_EQ(plain.decoded_blocks, 0u);
  ASSERT_GE(plain.base_bytes.size(), 10u);

  const FrameRun s3tc = run_frame("s3tc", rtl::CacheHolds::Compressed);
  // The level's textures as ioquake3 uploads them with r_ext_compressed_textures 1: a JPEG has no
  // alpha channel, so every JPEG texture is DXT1; light maps are never compressed.
  int jpeg = 0;
  for (const Mesh& m : s3tc.scene.meshes) {
    const TextureStage& base = m.stages.at(0);
    EXPECT_EQ(base.spec.params.at("compress"), "s3tc");
    const auto level = cached_level(checked_game_data().dir(), "aggressor");
    const auto it = std::find_if(level->textures.begin(), level->textures.end(), [&](const q3::LevelTexture& t) {
      return base.spec.source == "oa:aggressor:texture:" + t.name;
    });
    ASSERT_NE(it, level->textures.end());
    if (it->source.ends_with(".jpg")) {
      ++jpeg;
      ASSERT_TRUE(base.texture->compressed) << it->name;
      EXPECT_EQ(base.texture->compressed->image.format, BlockFormat::BC1A) << it->name;
    }
    EXPECT_FALSE(m.stages.at(1).texture->compressed);
    EXPECT_TRUE(m.stages.at(1).spec.params.empty());
  }
  EXPECT_GE(jpeg, 10);
  EXPECT_NE(s3tc.scene.description.find("textures compressed at upload (s3tc): "), std::string::npos);
  EXPECT_GT(s3tc.decoded_blocks, 0u);

  const FrameRun astc = run_frame("astc6x6", rtl::CacheHolds::Compressed);
  for (const Mesh& m : astc.scene.meshes) {
    ASSERT_TRUE(m.stages.at(0).texture->compressed);
    EXPECT_EQ(m.stages.at(0).texture->compressed->image.format, BlockFormat::ASTC_6x6);
  }
  // The traffic falls. A 64-byte line holds 16 RGBA8 texels, 128 BC1 texels or 144 ASTC 6x6 texels:
  // each missed line brings 8 or 9 times the texels. The frame's base-stage bytes must fall below a
  // quarter (misses of lines that straddle footprints, and textures left uncompressed by the alpha
  // rule, keep it above an eighth); every base texture compressed and read for more than 16 KiB
  // uncompressed reads less than half of those bytes (below that, a few sparse footprints on a small
  // or far texture touch about as many lines either way: e7beam01 from the engine's eye, 9 KiB).
  EXPECT_LT(4 * s3tc.base_total, plain.base_total);
  EXPECT_LT(4 * astc.base_total, plain.base_total);
  for (const FrameRun* run : {&s3tc, &astc})
    for (const auto& [name, bytes] : run->base_bytes)
      if (plain.base_bytes.at(name) > 16384 && run->compressed.contains(name)) {
        EXPECT_LT(2 * bytes, plain.base_bytes.at(name)) << name;
      }

  // Decoded on fill: lines hold the 4x4 RGBA8 tiles of the uncompressed texture, and a fill fetches
  // exactly the one 8-byte BC1 block that covers its tile (docs/texel-cache.md) where the
  // uncompressed miss fetches 64 bytes: the same lines at an eighth of the bytes, so again below a
  // quarter of the uncompressed traffic.
  const FrameRun decoded = run_frame("s3tc", rtl::CacheHolds::Decoded);
  EXPECT_GT(decoded.decoded_blocks, 0u);
  EXPECT_LT(4 * decoded.base_total, plain.base_total);
}

// The trace of a compressed level frame binds its base textures with compress=RULE; loading the
// binding again gives the same compressed texture (one encoding per process).
TEST(OpenArena, CompressedLevelTraceBindings) {
  if (!checked_game_data().present()) GTEST_SKIP() << checked_game_data().missing();
  const Scene s =
      open_scene({"oa:aggressor:0", 64, 36, checked_game_data().dir()}, upload_compression_from_name("s3tc"));
  const TextureStage& base = s.meshes.front().stages.front();
  EXPECT_EQ(base.spec.params.at("compress"), "s3tc");
  const LoadedTexture again = load_texture_spec(base.spec, "trace line 2", {}, checked_game_data().dir());
  EXPECT_EQ(again.texture, base.texture);
  EXPECT_EQ(again.texture->compressed->image.format, BlockFormat::BC1A);
  TextureSpec bad = base.spec;
  bad.params["mipmaps"] = "box";
  EXPECT_INPUT_ERROR(load_texture_spec(bad, "trace line 2", {}, checked_game_data().dir()),
                     "trace line 2: a level's texture takes no key but compress");
  bad.params = {{"compress", "bc9"}};
  EXPECT_INPUT_ERROR(load_texture_spec(bad, "trace line 2", {}, checked_game_data().dir()),
                     "trace line 2: key 'compress': unknown block-compressed format 'bc9'");
  EXPECT_INPUT_ERROR(open_scene({kDefaultScene, 64, 36, {}}, upload_compression_from_name("s3tc")),
                     "--compress s3tc applies to oa: level scenes");
}

}  // namespace
}  // namespace tfu
