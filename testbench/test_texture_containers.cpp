// Block-compressed files and encoders (cmodel/texture_containers.hpp, cmodel/block_encode.hpp):
// round trips of every format through every container that holds it, headers written by hand and
// by outside tools (ARM astcenc, NVIDIA Texture Tools) and read by an outside reader (OpenImageIO),
// every class of bad file (one InputError line naming the file), and the encoders' error floors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include "cmodel/block_encode.hpp"
#include "cmodel/error.hpp"
#include "cmodel/etc2_decode.hpp"
#include "cmodel/memory_budget.hpp"
#include "cmodel/metrics.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/procedural.hpp"
#include "cmodel/temp_paths.hpp"
#include "cmodel/texture_containers.hpp"
#include "testbench/input_error.hpp"
#include "testbench/iterations.hpp"

namespace tfu::test {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<uint8_t>;

const fs::path kData = fs::path(TFU_GOLDEN_DIR) / ".." / "data" / "containers";

Bytes file_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(f), {});
}

// A w x h image of `levels` levels (0: the full chain) of random blocks.
BlockImage random_image(BlockFormat f, int w, int h, int levels, std::mt19937& rng) {
  BlockImage img;
  img.format = f;
  for (int l = 0; levels == 0 ? true : l < levels; ++l) {
    BlockLevel level{w, h, Bytes(block_level_bytes(f, w, h))};
    for (uint8_t& b : level.blocks) b = static_cast<uint8_t>(rng());
    img.levels.push_back(std::move(level));
    if (w == 1 && h == 1) break;
    w = std::max(1, w >> 1), h = std::max(1, h >> 1);
  }
  return img;
}

void expect_same(const BlockImage& a, const BlockImage& b, const std::string& what) {
  EXPECT_EQ(a.format, b.format) << what;
  EXPECT_EQ(a.srgb, b.srgb) << what;
  ASSERT_EQ(a.levels.size(), b.levels.size()) << what;
  for (size_t l = 0; l < a.levels.size(); ++l) {
    EXPECT_EQ(a.levels[l].width, b.levels[l].width) << what << " level " << l;
    EXPECT_EQ(a.levels[l].height, b.levels[l].height) << what << " level " << l;
    EXPECT_EQ(a.levels[l].blocks, b.levels[l].blocks) << what << " level " << l;
  }
}

// The message is one line of at most kMaxMessageChars that names the input.
void expect_one_line_naming(const std::string& message, const std::string& label, const std::string& reason) {
  EXPECT_NE(message, "(no InputError)") << reason;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_LE(message.size(), kMaxMessageChars) << message;
  EXPECT_EQ(message.rfind(label, 0), 0u) << message;
  EXPECT_NE(message.find(reason), std::string::npos) << "want '" << reason << "' in: " << message;
}

void put32(Bytes& b, size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + static_cast<size_t>(i)] = static_cast<uint8_t>(v >> (8 * i));
}

// ---- Round trips ----

TEST(TextureContainers, RoundTripEveryFormatThroughEveryContainerThatHoldsIt) {
  std::mt19937 rng(7);
  int trips = 0;
  for (const BlockFormatInfo& info : kBlockFormats)
    for (const BlockContainer c : {BlockContainer::DDS, BlockContainer::KTX, BlockContainer::ASTC}) {
      if (!container_holds(c, info.format)) continue;
      for (const bool srgb : {false, true}) {
        if (srgb && (info.gl_srgb_internal_format == 0 || c == BlockContainer::ASTC)) continue;
        // Sizes not a multiple of the block, a full chain (one level in .astc).
        BlockImage img = random_image(info.format, 37, 13, c == BlockContainer::ASTC ? 1 : 0, rng);
        img.srgb = srgb;
        const Bytes bytes = serialize_block_image(img, c, "test");
        EXPECT_EQ(container_by_magic(bytes), c);
        expect_same(parse_block_image(bytes, "test"), img,
                    fmt::format("{} in {} srgb {}", info.name, block_container_name(c), srgb));
        ++trips;
      }
    }
  // 9 BC formats x 2 containers + 5 with sRGB x 2; 7 ETC x KTX + 3 sRGB; 14 ASTC x (KTX x 2 + .astc).
  EXPECT_EQ(trips, 9 * 2 + 5 * 2 + 7 + 3 + 14 * 3);
}

TEST(TextureContainers, FileDetectedByMagicNotByExtension) {
  std::mt19937 rng(1);
  const TempDir dir("tfu-containers");
  const BlockImage img = random_image(BlockFormat::BC3, 8, 8, 0, rng);
  const Bytes bytes = serialize_block_image(img, BlockContainer::DDS, "test");
  const fs::path p = dir.path() / "looks_like.ktx";
  std::ofstream(p, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  expect_same(read_block_image(p.string()), img, "DDS named .ktx");
}

TEST(TextureContainers, MapsEveryFormatToItsDefaultContainer) {
  for (const BlockFormatInfo& info : kBlockFormats) {
    const BlockContainer c = default_container(info.format);
    EXPECT_TRUE(container_holds(c, info.format)) << info.name;
    EXPECT_EQ(c, info.family == BlockFamily::BC ? BlockContainer::DDS : BlockContainer::KTX) << info.name;
  }
  EXPECT_FALSE(container_holds(BlockContainer::DDS, BlockFormat::ETC2));
  EXPECT_FALSE(container_holds(BlockContainer::ASTC, BlockFormat::BC7));
}

// ---- Headers by hand ----

// A DDS header written field by field from Microsoft's DDS_HEADER / DDS_PIXELFORMAT description.
Bytes hand_dds(uint32_t width, uint32_t height, uint32_t mips, const char fourcc[4], uint32_t pf_flags) {
  Bytes b(128, 0);
  b[0] = 'D', b[1] = 'D', b[2] = 'S', b[3] = ' ';
  put32(b, 4, 124);  // dwSize
  put32(b, 8,
        0x1 | 0x2 | 0x4 | 0x1000 | 0x80000 |
            (mips > 1 ? 0x20000 : 0));  // CAPS HEIGHT WIDTH PIXELFORMAT LINEARSIZE [MIPMAPCOUNT]
  put32(b, 12, height);
  put32(b, 16, width);
  put32(b, 28, mips);
  put32(b, 76, 32);  // ddspf.dwSize
  put32(b, 80, pf_flags);
  for (int i = 0; i < 4; ++i) b[84 + static_cast<size_t>(i)] = static_cast<uint8_t>(fourcc[i]);
  put32(b, 108, 0x1000 | (mips > 1 ? 0x8 | 0x400000 : 0));  // dwCaps: TEXTURE [COMPLEX MIPMAP]
  return b;
}

TEST(TextureContainers, DdsHeaderAsWrittenByHand) {
  std::mt19937 rng(3);
  // 6x5 DXT5 with 3 levels: 2x2 + 1x1 + 1x1 blocks of 16 bytes.
  const BlockImage img = random_image(BlockFormat::BC3, 6, 5, 3, rng);
  Bytes hand = hand_dds(6, 5, 3, "DXT5", 0x4);
  put32(hand, 20, 64);  // dwPitchOrLinearSize: level 0's bytes
  for (const BlockLevel& l : img.levels) hand.insert(hand.end(), l.blocks.begin(), l.blocks.end());
  EXPECT_EQ(serialize_block_image(img, BlockContainer::DDS, "test"), hand);
  expect_same(parse_block_image(hand, "test"), img, "hand DDS");
  // DXT1 with DDPF_ALPHAPIXELS is bc1a; without, bc1; ATI1 / ATI2 are BC4 / BC5.
  Bytes dxt1 = hand_dds(4, 4, 1, "DXT1", 0x4 | 0x1);
  dxt1.resize(dxt1.size() + 8);
  EXPECT_EQ(parse_block_image(dxt1, "t").format, BlockFormat::BC1A);
  put32(dxt1, 80, 0x4);
  EXPECT_EQ(parse_block_image(dxt1, "t").format, BlockFormat::BC1);
  std::memcpy(dxt1.data() + 84, "ATI1", 4);
  EXPECT_EQ(parse_block_image(dxt1, "t").format, BlockFormat::BC4);
  Bytes ati2 = hand_dds(4, 4, 0, "ATI2", 0x4);  // dwMipMapCount 0: one level
  ati2.resize(ati2.size() + 16);
  EXPECT_EQ(parse_block_image(ati2, "t").format, BlockFormat::BC5);
}

TEST(TextureContainers, DdsDx10HeaderCarriesTheDxgiCodes) {
  // DXGI_FORMAT values from Microsoft's dxgiformat.h: BC1_UNORM 71, _SRGB 72, BC2 74/75, BC3 77/78,
  // BC4_UNORM 80, BC4_SNORM 81, BC5_UNORM 83, BC5_SNORM 84, BC7_UNORM 98, _SRGB 99.
  const std::vector<std::tuple<BlockFormat, bool, uint32_t>> want{
      {BlockFormat::BC1, true, 72}, {BlockFormat::BC1A, true, 72}, {BlockFormat::BC2, true, 75},
      {BlockFormat::BC3, true, 78}, {BlockFormat::BC7, false, 98}, {BlockFormat::BC7, true, 99}};
  std::mt19937 rng(5);
  for (const auto& [f, srgb, dxgi] : want) {
    BlockImage img = random_image(f, 4, 4, 1, rng);
    img.srgb = srgb;
    const Bytes b = serialize_block_image(img, BlockContainer::DDS, "t");
    ASSERT_EQ(b.size(), 4 + 124 + 20 + img.levels[0].blocks.size());
    EXPECT_EQ(std::string(b.begin() + 84, b.begin() + 88), "DX10");
    EXPECT_EQ(b[128], dxgi) << block_format_name(f);
    EXPECT_EQ(b[132], 3u);                               // D3D10_RESOURCE_DIMENSION_TEXTURE2D
    EXPECT_EQ(b[140], 1u);                               // arraySize
    EXPECT_EQ(b[144], f == BlockFormat::BC1 ? 3u : 0u);  // DDS_ALPHA_MODE_OPAQUE for bc1
  }
  EXPECT_EQ(block_format_info(BlockFormat::BC4).dxgi_format, 80u);
  EXPECT_EQ(block_format_info(BlockFormat::BC4S).dxgi_format, 81u);
  EXPECT_EQ(block_format_info(BlockFormat::BC5).dxgi_format, 83u);
  EXPECT_EQ(block_format_info(BlockFormat::BC5S).dxgi_format, 84u);
  for (const BlockFormatInfo& i : kBlockFormats) EXPECT_EQ(i.dxgi_format != 0, i.family == BlockFamily::BC) << i.name;
}

TEST(TextureContainers, KtxAndAstcFilesEqualWhatAstcencWrites) {
  // astcenc 4.2 wrote both files from the same image: the same blocks, and our writer must give
  // the same bytes (KTX 1.1 header fields and the .astc header).
  const Bytes ktx = file_bytes(kData / "out6x6.ktx"), astc = file_bytes(kData / "out6x6.astc");
  ASSERT_FALSE(ktx.empty());
  const BlockImage a = parse_block_image(ktx, "ktx"), b = parse_block_image(astc, "astc");
  EXPECT_EQ(a.format, BlockFormat::ASTC_6x6);
  ASSERT_EQ(a.levels.size(), 1u);
  EXPECT_EQ(a.levels[0].width, 16);
  EXPECT_EQ(a.levels[0].height, 12);
  EXPECT_EQ(a.levels[0].blocks.size(), 3u * 2u * 16u);
  expect_same(a, b, "astcenc KTX vs .astc");
  EXPECT_EQ(serialize_block_image(a, BlockContainer::KTX, "t"), ktx);
  EXPECT_EQ(serialize_block_image(b, BlockContainer::ASTC, "t"), astc);
  // Decoded, it is the source image (25.4 dB at astcenc's -fast; random blocks give about 8).
  const Image src = load_image((kData / "src.png").string());
  EXPECT_GT(psnr_db(decode_block_level(a.format, 16, 12, a.levels[0].blocks, {}), src), 24.0);
}

TEST(TextureContainers, ReadsNvcompressDdsWithMipLevels) {
  const BlockImage img = read_block_image((kData / "bc3.dds").string());
  EXPECT_EQ(img.format, BlockFormat::BC3);
  ASSERT_EQ(img.levels.size(), 5u);  // 16x12, 8x6, 4x3, 2x1, 1x1
  EXPECT_EQ(img.levels[3].width, 2);
  EXPECT_EQ(img.levels[3].height, 1);
  const Image src = load_image((kData / "src.png").string());  // 21.7 dB (the source wraps hard in blue)
  EXPECT_GT(psnr_db(decode_block_level(img.format, 16, 12, img.levels[0].blocks, {}), src), 20.0);
}

// OpenImageIO's DDS reader (outside the project) decodes what we write as we do: BC7 is bit-exact
// across decoders; BC1/BC3 within 1 (vendor interpolation, docs/compressed-bc.md).
TEST(TextureContainers, OpenImageIoReadsOurDdsFiles) {
  const TempDir dir("tfu-containers");
  const Image src = make_procedural("zoneplate", 32).texture.levels[0];
  for (const auto& [f, tolerance] : {std::pair{BlockFormat::BC7, 0}, {BlockFormat::BC3, 1}, {BlockFormat::BC1, 1}}) {
    const BlockImage img = encode_block_image(std::span(&src, 1), f, false);
    const Bytes b = serialize_block_image(img, BlockContainer::DDS, "t");
    const fs::path p = dir.path() / fmt::format("{}.dds", block_format_name(f));
    std::ofstream(p, std::ios::binary)
        .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
    auto in = OIIO::ImageInput::open(p.string());
    ASSERT_TRUE(in) << OIIO::geterror();
    const OIIO::ImageSpec spec = in->spec();
    ASSERT_EQ(spec.width, 32);
    ASSERT_EQ(spec.height, 32);
    std::vector<uint8_t> px(static_cast<size_t>(32 * 32 * spec.nchannels));
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, px.data()));
    const Image ours = decode_block_level(f, 32, 32, img.levels[0].blocks, {});
    int worst = 0;
    for (size_t i = 0; i < 32 * 32; ++i) {
      const Rgba8 t = ours.texels[i];
      const int c[4] = {t.r, t.g, t.b, t.a};
      for (int k = 0; k < std::min(spec.nchannels, 4); ++k)
        worst = std::max(worst, std::abs(c[k] - px[i * static_cast<size_t>(spec.nchannels) + static_cast<size_t>(k)]));
    }
    EXPECT_LE(worst, tolerance) << block_format_name(f);
  }
}

// ---- Bad files ----

struct BadCase {
  std::string name;
  std::function<void(Bytes&)> mutate;
  std::string reason;
};

TEST(TextureContainers, RefusesEveryKindOfBadHeaderWithOneLine) {
  std::mt19937 rng(11);
  const Bytes dds = serialize_block_image(random_image(BlockFormat::BC1, 16, 16, 0, rng), BlockContainer::DDS, "t");
  BlockImage bc7 = random_image(BlockFormat::BC7, 8, 8, 1, rng);
  bc7.srgb = true;
  const Bytes dx10 = serialize_block_image(bc7, BlockContainer::DDS, "t");
  const Bytes ktx = serialize_block_image(random_image(BlockFormat::ETC2, 16, 8, 0, rng), BlockContainer::KTX, "t");
  const Bytes astc =
      serialize_block_image(random_image(BlockFormat::ASTC_5x4, 11, 9, 1, rng), BlockContainer::ASTC, "t");
  const std::vector<std::pair<const Bytes*, BadCase>> cases{
      {&dds, {"dds header size", [](Bytes& b) { put32(b, 4, 100); }, "header size 100"}},
      {&dds, {"dds pixel format size", [](Bytes& b) { put32(b, 76, 0); }, "pixel format size 0"}},
      {&dds, {"dds unknown fourcc", [](Bytes& b) { std::memcpy(b.data() + 84, "XYZW", 4); }, "FourCC 'XYZW'"}},
      {&dds, {"dds premultiplied", [](Bytes& b) { std::memcpy(b.data() + 84, "DXT2", 4); }, "premultiplied"}},
      {&dds, {"dds uncompressed", [](Bytes& b) { put32(b, 80, 0x40); }, "no FourCC"}},
      {&dds, {"dds zero width", [](Bytes& b) { put32(b, 16, 0); }, "size 0x16"}},
      {&dds, {"dds huge height", [](Bytes& b) { put32(b, 12, 1u << 30); }, "outside 1..16384"}},
      {&dds, {"dds absurd mips", [](Bytes& b) { put32(b, 28, 1000); }, "1000 MIP levels"}},
      {&dds,
       {"dds one mip too many", [](Bytes& b) { put32(b, 28, 6); }, "6 MIP levels where a 16x16 texture has at most 5"}},
      {&dds, {"dds fewer mips than data", [](Bytes& b) { put32(b, 28, 2); }, "bytes after the last MIP level"}},
      {&dds, {"dds width larger than data", [](Bytes& b) { put32(b, 16, 20); }, "truncated"}},
      {&dds, {"dds cube map", [](Bytes& b) { put32(b, 112, 0x200); }, "cube map"}},
      {&dds, {"dds volume", [](Bytes& b) { put32(b, 24, 4); }, "volume"}},
      {&dx10, {"dx10 unknown dxgi", [](Bytes& b) { put32(b, 128, 95); }, "DXGI format 95"}},
      {&dx10, {"dx10 texture 3d", [](Bytes& b) { put32(b, 132, 4); }, "resource dimension 4"}},
      {&dx10, {"dx10 array", [](Bytes& b) { put32(b, 140, 6); }, "array size 6"}},
      {&dx10, {"dx10 truncated header", [](Bytes& b) { b.resize(140); }, "DX10 header needs 148"}},
      {&ktx, {"ktx endianness", [](Bytes& b) { put32(b, 12, 0x12345678); }, "endianness"}},
      {&ktx, {"ktx uncompressed", [](Bytes& b) { put32(b, 16, 0x1401); }, "not a compressed texture"}},
      {&ktx, {"ktx unknown internal format", [](Bytes& b) { put32(b, 28, 0x8058); }, "glInternalFormat 0x8058"}},
      {&ktx, {"ktx 1d", [](Bytes& b) { put32(b, 40, 0); }, "1D texture"}},
      {&ktx, {"ktx zero width", [](Bytes& b) { put32(b, 36, 0); }, "size 0x8"}},
      {&ktx, {"ktx volume", [](Bytes& b) { put32(b, 44, 2); }, "volume"}},
      {&ktx, {"ktx array", [](Bytes& b) { put32(b, 48, 3); }, "3 array elements"}},
      {&ktx, {"ktx cube", [](Bytes& b) { put32(b, 52, 6); }, "6 faces"}},
      {&ktx, {"ktx absurd mips", [](Bytes& b) { put32(b, 56, 0xFFFFFFFF); }, "4294967295 MIP levels"}},
      {&ktx, {"ktx key/value past the end", [](Bytes& b) { put32(b, 60, 1u << 20); }, "key/value data"}},
      {&ktx, {"ktx key/value not a multiple of 4", [](Bytes& b) { put32(b, 60, 2); }, "multiple of 4"}},
      {&ktx, {"ktx wrong image size", [](Bytes& b) { put32(b, 64, 40); }, "level 0 imageSize 40"}},
      {&astc, {"astc 3d footprint", [](Bytes& b) { b[6] = 4; }, "3D texture"}},
      {&astc, {"astc unknown footprint", [](Bytes& b) { b[4] = 7, b[5] = 7; }, "footprint 7x7"}},
      {&astc, {"astc zero height", [](Bytes& b) { b[10] = 0; }, "size 11x0"}},
      {&astc, {"astc larger than data", [](Bytes& b) { b[7] = 200; }, "truncated"}},
  };
  for (const auto& [base, c] : cases) {
    Bytes b = *base;
    c.mutate(b);
    expect_one_line_naming(input_error([&] { parse_block_image(b, "'bad.file'"); }), "'bad.file': ", c.reason);
  }
  // No magic at all.
  expect_one_line_naming(input_error([&] {
                           parse_block_image(Bytes{'P', 'N', 'G', 0}, "'x'");
                         }),
                         "'x': ", "not a DDS, KTX or .astc file");
}

TEST(TextureContainers, BigEndianKtxReadsAlike) {
  std::mt19937 rng(13);
  const BlockImage img = random_image(BlockFormat::EAC_RG11, 9, 7, 0, rng);
  Bytes b = serialize_block_image(img, BlockContainer::KTX, "t");
  for (size_t at = 12; at < 64; at += 4)
    std::reverse(b.begin() + static_cast<ptrdiff_t>(at), b.begin() + static_cast<ptrdiff_t>(at + 4));
  for (size_t at = 64, l = 0; l < img.levels.size(); at += 4 + img.levels[l].blocks.size(), ++l)
    std::reverse(b.begin() + static_cast<ptrdiff_t>(at), b.begin() + static_cast<ptrdiff_t>(at + 4));
  expect_same(parse_block_image(b, "t"), img, "big-endian KTX");
}

// Every proper prefix of a valid file is refused (truncation anywhere), and one byte more too.
TEST(TextureContainers, EveryTruncationAndEveryExtraByteIsRefused) {
  std::mt19937 rng(17);
  for (const auto& [f, c] : {std::pair{BlockFormat::BC5, BlockContainer::DDS},
                             {BlockFormat::BC7, BlockContainer::DDS},
                             {BlockFormat::ETC2A, BlockContainer::KTX},
                             {BlockFormat::ASTC_12x10, BlockContainer::ASTC}}) {
    BlockImage img = random_image(f, 13, 11, c == BlockContainer::ASTC ? 1 : 0, rng);
    img.srgb = f == BlockFormat::BC7;
    const Bytes b = serialize_block_image(img, c, "t");
    for (size_t n = 0; n < b.size(); ++n) {
      const std::string m = input_error([&] { parse_block_image(std::span(b.data(), n), "'cut'"); });
      ASSERT_EQ(m.rfind("'cut': ", 0), 0u) << n << ": " << m;
      ASSERT_EQ(m.find('\n'), std::string::npos) << m;
    }
    Bytes more = b;
    more.push_back(0);
    expect_one_line_naming(input_error([&] { parse_block_image(more, "'more'"); }),
                           "'more': ", "1 bytes after the last MIP level");
  }
}

TEST(TextureContainers, FileChecksAndMemoryBudget) {
  const TempDir dir("tfu-containers");
  EXPECT_NE(input_error([&] { read_block_image(dir.path().string()); }).find("is a directory"), std::string::npos);
  EXPECT_NE(input_error([&] { read_block_image((dir.path() / "none.dds").string()); }).find("no such file"),
            std::string::npos);
  const uint64_t budget = memory_budget();
  set_memory_budget(100);
  const std::string m = input_error([&] { read_block_image((kData / "bc3.dds").string()); });
  set_memory_budget(budget);
  EXPECT_NE(m.find("memory budget"), std::string::npos) << m;
  EXPECT_NE(m.find("bc3.dds"), std::string::npos) << m;
}

TEST(TextureContainers, WriterRefusesWhatTheContainerCannotHold) {
  std::mt19937 rng(19);
  const BlockImage etc = random_image(BlockFormat::ETC2, 8, 8, 1, rng);
  EXPECT_NE(
      input_error([&] { serialize_block_image(etc, BlockContainer::DDS, "'o.dds'"); }).find("DDS holds the BC formats"),
      std::string::npos);
  const BlockImage astc = random_image(BlockFormat::ASTC_4x4, 8, 8, 0, rng);
  EXPECT_NE(input_error([&] { serialize_block_image(astc, BlockContainer::ASTC, "'o'"); }).find("holds one level"),
            std::string::npos);
  BlockImage bad = random_image(BlockFormat::BC1, 8, 8, 2, rng);
  bad.levels[1].width = 3;
  EXPECT_NE(input_error([&] { serialize_block_image(bad, BlockContainer::KTX, "'o'"); }).find("level 1 is 3x4"),
            std::string::npos);
  BlockImage srgb4 = random_image(BlockFormat::BC4, 8, 8, 1, rng);
  srgb4.srgb = true;
  EXPECT_NE(input_error([&] { serialize_block_image(srgb4, BlockContainer::DDS, "'o'"); }).find("no sRGB variant"),
            std::string::npos);
}

// Random bytes after a valid magic: never anything but a valid image or one InputError line.
TEST(TextureContainers, RandomHeadersNeverCrash) {
  std::mt19937 rng(23);
  std::mt19937 blocks(29);
  const std::vector<Bytes> bases{
      serialize_block_image(random_image(BlockFormat::BC2, 8, 4, 0, blocks), BlockContainer::DDS, "t"),
      serialize_block_image(random_image(BlockFormat::EAC_R11, 8, 4, 0, blocks), BlockContainer::KTX, "t"),
      serialize_block_image(random_image(BlockFormat::ASTC_8x5, 8, 4, 1, blocks), BlockContainer::ASTC, "t")};
  int refused = 0, read = 0;
  for (int i = 0; i < iterations(3000); ++i) {
    Bytes b = bases[static_cast<size_t>(i) % bases.size()];
    const int flips = 1 + static_cast<int>(rng() % 3);
    for (int k = 0; k < flips; ++k)
      b[4 + rng() % std::min<size_t>(b.size() - 4, 150)] ^= static_cast<uint8_t>(1u << (rng() % 8));
    try {
      const BlockImage img = parse_block_image(b, "'r'");
      validate_block_image(img, "r");
      ++read;
    } catch (const InputError& e) {
      ASSERT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(read, 0);  // flips in reserved fields and block bytes keep a valid file
}

// ---- Encoders ----

double encoded_psnr(const Image& src, BlockFormat f, int quality = 60) {
  const BlockImage img = encode_block_image(std::span(&src, 1), f, false, BlockEncodeOptions{quality});
  const Image back = decode_block_level(f, src.width, src.height, img.levels[0].blocks, {});
  // One- and two-channel formats: compare the channels they hold.
  const int channels = block_format_info(f).channels;
  if (channels >= 3) return psnr_db(back, src);
  Image want = src;
  for (Rgba8& t : want.texels) t = Rgba8{t.r, channels == 2 ? t.g : uint8_t{0}, 0, 255};
  return psnr_db(back, want);
}

// PSNR floors (RGB, dB) on a 61x45 noise texture (partial blocks at both edges), measured with
// these encoders (docs/compressed-files.md, "Encoders") and set a little below.
Image crop_61x45(const std::string& name) {
  {
    Image s = make_procedural(name, 64).texture.levels[0];
    Image c(61, 45);
    for (int y = 0; y < 45; ++y)
      for (int x = 0; x < 61; ++x) c.at(x, y) = s.at(x, y);
    return c;
  }
}

// Measured (RGB PSNR, quality 60): noise / zoneplate, 61x45 crops of the 64x64 procedurals.
//   bc1 41.08 / 24.05, bc2 and bc3 41.08 / 23.98 (libsquish cluster fit); bc4 51.54 / 33.85 and
//   bc5 49.64 / 30.84 (R, RG); bc7 50.35 / 35.59 (own, mode 6); etc2 34.99 / 24.51 (own, ETC1 modes);
//   eac_r11 51.66 / 35.46, eac_rg11 49.71 / 32.45 (own); astc 4x4 54.98 / 45.26, 6x6 47.06 / 29.49,
//   8x8 43.38 / 21.67, 12x12 36.55 / 14.31 (libastcenc). The floors are these less 0.5 dB: the
//   encoders are deterministic, so a drop means a changed encoder (or library).
TEST(BlockEncode, PsnrFloorsPerFormat) {
  struct Floor {
    BlockFormat format;
    double noise, zoneplate;
  };
  const std::vector<Floor> floors{
      {BlockFormat::BC1, 40.5, 23.5},      {BlockFormat::BC1A, 40.5, 23.5},     {BlockFormat::BC2, 40.5, 23.4},
      {BlockFormat::BC3, 40.5, 23.4},      {BlockFormat::BC4, 51.0, 33.3},      {BlockFormat::BC5, 49.1, 30.3},
      {BlockFormat::BC7, 49.8, 35.0},      {BlockFormat::ETC2, 34.4, 24.0},     {BlockFormat::ETC2A, 34.4, 24.0},
      {BlockFormat::EAC_R11, 51.1, 34.9},  {BlockFormat::EAC_RG11, 49.2, 31.9}, {BlockFormat::ASTC_4x4, 54.4, 44.7},
      {BlockFormat::ASTC_6x6, 46.5, 28.9}, {BlockFormat::ASTC_8x8, 42.8, 21.1}, {BlockFormat::ASTC_12x12, 36.0, 13.8}};
  const Image noise = crop_61x45("noise"), zoneplate = crop_61x45("zoneplate");
  for (const Floor& f : floors) {
    EXPECT_GE(encoded_psnr(noise, f.format), f.noise) << block_format_name(f.format);
    EXPECT_GE(encoded_psnr(zoneplate, f.format), f.zoneplate) << block_format_name(f.format);
  }
}

// Alpha survives the formats that hold it: the largest alpha error on a ramp of alpha.
TEST(BlockEncode, AlphaErrorBounded) {
  Image src = crop_61x45("zoneplate");
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < src.width; ++x) src.at(x, y).a = static_cast<uint8_t>((x * 255) / (src.width - 1));
  // BC2 stores 4-bit alpha (error <= 8.5 -> 9 with rounding); BC3 and ETC2 RGBA (EAC) have an alpha
  // block of their own: within 8 on this ramp of 4.25 per texel. BC7 mode 6 and ASTC share the
  // indices of colour and alpha (mode 6) or trade them in the encoder's search: measured 13 and 10.
  for (const auto& [f, bound] : {std::pair{BlockFormat::BC2, 9},
                                 {BlockFormat::BC3, 8},
                                 {BlockFormat::ETC2A, 8},
                                 {BlockFormat::BC7, 13},
                                 {BlockFormat::ASTC_4x4, 10}}) {
    const BlockImage img = encode_block_image(std::span(&src, 1), f, false);
    const Image back = decode_block_level(f, src.width, src.height, img.levels[0].blocks, {});
    int worst = 0;
    for (size_t i = 0; i < src.texels.size(); ++i)
      worst = std::max(worst, std::abs(back.texels[i].a - src.texels[i].a));
    EXPECT_LE(worst, bound) << block_format_name(f);
  }
}

// Constant blocks: BC7 mode 6 within 1 (the p-bit is shared by the channels of an endpoint), EAC
// alpha exact (multiplier 0), EAC R11 within 1 in 8 bits, ETC1 modes within the 5-bit base's
// quantization plus the smallest modifier (4 + 2 = 6 is an upper bound).
TEST(BlockEncode, ConstantBlocks) {
  std::mt19937 rng(31);
  for (int n = 0; n < iterations(2000); ++n) {
    const Rgba8 c{static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()),
                  static_cast<uint8_t>(rng())};
    Rgba8 t[16];
    std::fill(std::begin(t), std::end(t), c);
    Rgba8 out[16];
    uint8_t block[16];
    encode_bc7_mode6_block(t, block);
    decode_block(BlockFormat::BC7, block, {}, out);
    for (const Rgba8& o : out)
      ASSERT_TRUE(std::abs(o.r - c.r) <= 1 && std::abs(o.g - c.g) <= 1 && std::abs(o.b - c.b) <= 1 &&
                  std::abs(o.a - c.a) <= 1);
    int alpha[16];
    std::fill(std::begin(alpha), std::end(alpha), c.a);
    encode_eac_block(alpha, false, block);
    uint8_t a8[16];
    decode_eac_alpha8_block(block, a8);
    for (const uint8_t a : a8) ASSERT_EQ(a, c.a);
    int r11[16];
    std::fill(std::begin(r11), std::end(r11), (c.r * 2047 + 127) / 255);
    encode_eac_block(r11, true, block);
    uint16_t v11[16];
    decode_eac_r11_block(block, v11);
    for (const uint16_t v : v11) ASSERT_LE(std::abs(eac11_to_unorm8(v) - c.r), 1);
    encode_etc1_block(t, block);
    decode_block(BlockFormat::ETC2, block, {}, out);
    for (const Rgba8& o : out)
      ASSERT_TRUE(std::abs(o.r - c.r) <= 6 && std::abs(o.g - c.g) <= 6 && std::abs(o.b - c.b) <= 6) << n;
  }
}

TEST(BlockEncode, DeterministicWithMipLevelsAndPartialBlocks) {
  Texture tex = make_procedural("checkerboard", 40).texture;
  generate_mipmaps(tex, MipMethod::Box);
  for (const BlockFormat f :
       {BlockFormat::BC3, BlockFormat::BC7, BlockFormat::ETC2A, BlockFormat::EAC_RG11, BlockFormat::ASTC_5x4}) {
    const BlockImage a = encode_block_image(tex.levels, f, false), b = encode_block_image(tex.levels, f, false);
    expect_same(a, b, block_format_name(f));
    validate_block_image(a, "encoded");  // 40x40 .. 1x1: every level's size and bytes
    EXPECT_EQ(a.levels.size(), 6u);
  }
}

TEST(BlockEncode, RefusesWhatItCannotEncode) {
  const Image src(8, 8);
  EXPECT_NE(
      input_error([&] { encode_block_image(std::span(&src, 1), BlockFormat::BC5, true); }).find("no sRGB variant"),
      std::string::npos);
  EXPECT_NE(input_error([&] {
              encode_block_image(std::span(&src, 1), BlockFormat::BC1, false, {101});
            }).find("outside 0..100"),
            std::string::npos);
  // sRGB ASTC: libastcenc's sRGB profile, decoded with the sRGB rule.
  const Image z = crop_61x45("zoneplate");
  const BlockImage s = encode_block_image(std::span(&z, 1), BlockFormat::ASTC_4x4, true);
  EXPECT_TRUE(s.srgb);
  EXPECT_GT(psnr_db(decode_block_level(s.format, z.width, z.height, s.levels[0].blocks, {.srgb = true}), z), 40.0);
}

}  // namespace
}  // namespace tfu::test
