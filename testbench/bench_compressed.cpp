// tfu_bench_compressed: decode speed of the compressed-texture decoders (Google Benchmark, one
// thread), side by side with the outside decoder on the same blocks; items are texels.
//   * ASTC: a 256x256 procedural RGBA image encoded once by libastcenc 4.2.0 (ASTCENC_PRE_FAST) at
//     4x4, 6x6, 8x8 and 12x12, decoded whole by decode_astc_image (BM_AstcDecode) and by
//     astcenc_decompress_image to ASTCENC_TYPE_U8 (BM_AstcencDecode). Target: ASTC 8x8 >= 10 M texels/s.
//   * BC1 and BC3: the same image encoded once by libsquish 1.15 (block_encode.hpp, cluster fit),
//     decoded whole by decode_block_level, the dispatch every model calls (BM_BcDecode), and by
//     squish::DecompressImage to RGBA8 (BM_SquishDecode). Target: BC1 >= 50 M texels/s. The golden
//     decoder rounds the interpolated colours to nearest (the spec), libsquish truncates: the same
//     work, one LSB apart on some texels (docs/compressed-bc.md).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <squish.h>

#include "cmodel/astc_decode.hpp"
#include "cmodel/block_encode.hpp"
#include "cmodel/block_formats.hpp"
#include "testbench/astc_reference.hpp"

namespace {

constexpr int kSize = 256;
constexpr std::array<tfu::AstcFootprint, 4> kBenchFootprints{{{4, 4}, {6, 6}, {8, 8}, {12, 12}}};

// Gradients, rings and hash noise in all four channels (what the decode tests encode, larger).
std::vector<uint8_t> procedural_image() {
  std::vector<uint8_t> px(static_cast<size_t>(kSize * kSize * 4));
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const uint32_t n = (static_cast<uint32_t>(x) * 73856093u) ^ (static_cast<uint32_t>(y) * 19349663u);
      const int noise = static_cast<int>((n >> 7) & 31) - 16;
      const int ring = ((x - kSize / 2) * (x - kSize / 2) + (y - kSize / 2) * (y - kSize / 2)) / 8 % 64;
      uint8_t* p = &px[static_cast<size_t>((y * kSize + x) * 4)];
      p[0] = static_cast<uint8_t>(std::clamp(x + noise, 0, 255));
      p[1] = static_cast<uint8_t>(std::clamp(y + ring, 0, 255));
      p[2] = static_cast<uint8_t>(std::clamp(128 + ring * 2 - noise, 0, 255));
      p[3] = static_cast<uint8_t>(std::clamp(255 - (x + y) / 2, 0, 255));
    }
  return px;
}

// The encoded image of footprint i (encoded on first use, kept).
const std::vector<uint8_t>& encoded(size_t i) {
  static std::array<std::vector<uint8_t>, kBenchFootprints.size()> cache;
  std::vector<uint8_t>& data = cache[i];
  if (data.empty()) {
    const tfu::AstcFootprint f = kBenchFootprints[i];
    std::vector<uint8_t> src = procedural_image();
    void* slice = src.data();
    astcenc_image img{kSize, kSize, 1, ASTCENC_TYPE_U8, &slice};
    data.resize(static_cast<size_t>((kSize + f.w - 1) / f.w) * static_cast<size_t>((kSize + f.h - 1) / f.h) *
                tfu::kAstcBlockBytes);
    astcenc_context* ctx = tfu::test::astcenc_ctx(f.w, f.h, false, true);
    tfu::test::astcenc_check(
        astcenc_compress_image(ctx, &img, &tfu::test::kAstcencIdentity, data.data(), data.size(), 0),
        "astcenc_compress_image");
    tfu::test::astcenc_check(astcenc_compress_reset(ctx), "astcenc_compress_reset");
  }
  return data;
}

void BM_AstcDecode(benchmark::State& state) {
  const auto i = static_cast<size_t>(state.range(0));
  const tfu::AstcFootprint f = kBenchFootprints[i];
  const std::vector<uint8_t>& data = encoded(i);
  for (auto _ : state) {
    tfu::Image img = tfu::decode_astc_image(data.data(), data.size(), kSize, kSize, f.w, f.h, false);
    benchmark::DoNotOptimize(img.texels.data());
  }
  state.SetItemsProcessed(state.iterations() * kSize * kSize);
  state.SetLabel(std::to_string(f.w) + "x" + std::to_string(f.h));
}

void BM_AstcencDecode(benchmark::State& state) {
  const auto i = static_cast<size_t>(state.range(0));
  const tfu::AstcFootprint f = kBenchFootprints[i];
  const std::vector<uint8_t>& data = encoded(i);
  tfu::test::astcenc_ctx(f.w, f.h, false, false);  // context set-up outside the timing
  for (auto _ : state) {
    std::vector<tfu::Rgba8> out =
        tfu::test::astcenc_decode_image(data.data(), data.size(), kSize, kSize, f.w, f.h, false);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * kSize * kSize);
  state.SetLabel(std::to_string(f.w) + "x" + std::to_string(f.h));
}

// ---- BC1 and BC3 against libsquish ----
constexpr std::array<tfu::BlockFormat, 2> kBenchBcFormats{tfu::BlockFormat::BC1, tfu::BlockFormat::BC3};

const tfu::BlockLevel& bc_encoded(size_t i) {
  static std::array<tfu::BlockImage, kBenchBcFormats.size()> cache;
  tfu::BlockImage& image = cache[i];
  if (image.levels.empty()) {
    const std::vector<uint8_t> px = procedural_image();
    tfu::Image level(kSize, kSize);
    for (size_t t = 0; t < level.texels.size(); ++t)
      level.texels[t] = {px[4 * t], px[4 * t + 1], px[4 * t + 2], px[4 * t + 3]};
    image = tfu::encode_block_image(std::span<const tfu::Image>(&level, 1), kBenchBcFormats[i], false);
  }
  return image.levels.front();
}

void BM_BcDecode(benchmark::State& state) {
  const auto i = static_cast<size_t>(state.range(0));
  const tfu::BlockLevel& level = bc_encoded(i);
  for (auto _ : state) {
    tfu::Image img = tfu::decode_block_level(kBenchBcFormats[i], kSize, kSize, level.blocks, tfu::BlockDecodeRules{});
    benchmark::DoNotOptimize(img.texels.data());
  }
  state.SetItemsProcessed(state.iterations() * kSize * kSize);
  state.SetLabel(tfu::block_format_name(kBenchBcFormats[i]));
}

void BM_SquishDecode(benchmark::State& state) {
  const auto i = static_cast<size_t>(state.range(0));
  const tfu::BlockLevel& level = bc_encoded(i);
  const int flags = kBenchBcFormats[i] == tfu::BlockFormat::BC1 ? squish::kDxt1 : squish::kDxt5;
  std::vector<uint8_t> rgba(static_cast<size_t>(kSize * kSize * 4));
  for (auto _ : state) {
    squish::DecompressImage(rgba.data(), kSize, kSize, level.blocks.data(), flags);
    benchmark::DoNotOptimize(rgba.data());
  }
  state.SetItemsProcessed(state.iterations() * kSize * kSize);
  state.SetLabel(tfu::block_format_name(kBenchBcFormats[i]));
}

BENCHMARK(BM_BcDecode)->DenseRange(0, static_cast<int>(kBenchBcFormats.size()) - 1);
BENCHMARK(BM_SquishDecode)->DenseRange(0, static_cast<int>(kBenchBcFormats.size()) - 1);
BENCHMARK(BM_AstcDecode)->DenseRange(0, static_cast<int>(kBenchFootprints.size()) - 1);
BENCHMARK(BM_AstcencDecode)->DenseRange(0, static_cast<int>(kBenchFootprints.size()) - 1);

}  // namespace

BENCHMARK_MAIN();
