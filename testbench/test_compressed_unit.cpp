// Block-compressed textures through both models: texture_from_block_image (levels decoded by the
// one decoder; signed formats refused), the descriptor fields and texture memory (blocks stored
// and read back, block addresses), and the cycle model against the golden model bit for bit on
// every request: every unsigned block format, all 12 filter modes and anisotropic probes, both
// cache organizations (cache.holds), interleaved with an uncompressed texture, in both engines;
// the decoder statistics; the recurrences' LINEAR quad path on compressed textures against the
// plain path and the clocked blocks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include <astcenc.h>

#include "cmodel/block_formats.hpp"
#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/mipmap.hpp"
#include "rtl/address_gen.hpp"
#include "rtl/address_gen_blocks.hpp"
#include "rtl/engine_compare.hpp"
#include "rtl/golden_compare.hpp"
#include "rtl/texel_cache.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_recurrence_linear_quads.hpp"
#include "testbench/astc_reference.hpp"
#include "testbench/iterations.hpp"

namespace tfu::rtl {
namespace {

// ASTC blocks of a w x h RGBA8 image by libastcenc's encoder (random ASTC bits are mostly illegal
// encodings, which decode to the error colour: a uniform texture).
std::vector<uint8_t> astc_encode(const Image& img, const BlockFormatInfo& info) {
  astcenc_context* ctx = test::astcenc_ctx(info.block_w, info.block_h, false, true);
  std::vector<Rgba8> texels = img.texels;
  void* planes[1] = {texels.data()};
  astcenc_image image{static_cast<unsigned>(img.width), static_cast<unsigned>(img.height), 1, ASTCENC_TYPE_U8, planes};
  std::vector<uint8_t> out(block_level_bytes(info.format, img.width, img.height));
  test::astcenc_check(astcenc_compress_image(ctx, &image, &test::kAstcencIdentity, out.data(), out.size(), 0),
                      "compress");
  test::astcenc_check(astcenc_compress_reset(ctx), "reset");
  return out;
}

// A compressed image of `levels` levels of a w x h texture: random blocks for BC and ETC (every bit
// pattern is a valid block), libastcenc-encoded random-walk texels for ASTC.
BlockImage random_block_image(BlockFormat f, int w, int h, int levels, std::mt19937& rng) {
  const BlockFormatInfo& info = block_format_info(f);
  BlockImage image;
  image.format = f;
  for (int l = 0; l < levels; ++l) {
    BlockLevel bl;
    bl.width = mip_extent(w, l);
    bl.height = mip_extent(h, l);
    if (info.family == BlockFamily::ASTC) {
      Image img(bl.width, bl.height);
      int v = static_cast<int>(rng() % 256);
      for (Rgba8& t : img.texels) {
        v = (v + static_cast<int>(rng() % 61) - 30) & 255;
        t = {static_cast<uint8_t>(v), static_cast<uint8_t>(rng()), static_cast<uint8_t>(255 - v),
             static_cast<uint8_t>(rng() | 128)};
      }
      bl.blocks = astc_encode(img, info);
    } else {
      bl.blocks.resize(block_level_bytes(f, bl.width, bl.height));
      for (uint8_t& b : bl.blocks) b = static_cast<uint8_t>(rng());
    }
    image.levels.push_back(std::move(bl));
  }
  return image;
}

std::vector<BlockFormat> unsigned_formats() {
  std::vector<BlockFormat> v;
  for (const BlockFormatInfo& i : kBlockFormats)
    if (unit_filterable(i.format)) v.push_back(i.format);
  return v;
}

TEST(CompressedTexture, LevelsAreTheDecodedBlocksAndSignedFormatsAreRefused) {
  std::mt19937 rng(3);
  for (const BlockFormat f : {BlockFormat::BC1, BlockFormat::BC7, BlockFormat::ETC2A, BlockFormat::ASTC_6x5}) {
    const BlockImage image = random_block_image(f, 21, 13, 3, rng);  // partial edge blocks, a short chain
    const BlockDecodeRules rules{kBcRulesMesa, false};
    const Texture t = texture_from_block_image(image, rules);
    ASSERT_EQ(t.levels.size(), 3u);
    ASSERT_NE(t.compressed, nullptr);
    EXPECT_EQ(t.format, TexelFormat::RGBA8);
    for (size_t l = 0; l < 3; ++l) {
      const Image want =
          decode_block_level(f, image.levels[l].width, image.levels[l].height, image.levels[l].blocks, rules);
      EXPECT_EQ(t.levels[l].texels, want.texels) << block_format_name(f) << " level " << l;
    }
    // Texture memory stores the blocks: read back, the same blocks and texels; a texel's address
    // is its block's, block rows row_pitch apart.
    TextureMemory mem;
    const TextureDescriptor d = place_texture(mem, t, 64);
    EXPECT_TRUE(d.compressed);
    EXPECT_EQ(d.block_format, f);
    EXPECT_EQ(d.decode, rules);
    const Texture back = read_texture(mem, d);
    ASSERT_NE(back.compressed, nullptr);
    for (size_t l = 0; l < 3; ++l) {
      EXPECT_EQ(back.compressed->image.levels[l].blocks, image.levels[l].blocks) << l;
      EXPECT_EQ(back.levels[l].texels, t.levels[l].texels) << l;
    }
    const BlockFormatInfo& info = block_format_info(f);
    EXPECT_EQ(d.level[1].row_pitch % 64, 0u);
    EXPECT_GE(d.level[0].row_pitch, static_cast<uint32_t>(blocks_across(f, 21) * info.block_bytes));
    EXPECT_EQ(d.texel_address(0, 2 * info.block_w + 1, info.block_h + 2),
              d.level[0].address + d.level[0].row_pitch + 2u * static_cast<uint64_t>(info.block_bytes));
    EXPECT_EQ(std::memcmp(mem.bytes_at(d.texel_address(1, info.block_w, 0)),
                          image.levels[1].blocks.data() + info.block_bytes, static_cast<size_t>(info.block_bytes)),
              0);
  }
  BlockImage signed_image = random_block_image(BlockFormat::BC5S, 8, 8, 1, rng);
  EXPECT_THROW(texture_from_block_image(signed_image, {}), InputError);
  signed_image.format = BlockFormat::EAC_R11S;
  EXPECT_THROW(texture_from_block_image(signed_image, {}), InputError);
  BlockImage wrong = random_block_image(BlockFormat::BC3, 8, 8, 2, rng);
  wrong.levels[1].blocks.pop_back();
  EXPECT_THROW(texture_from_block_image(wrong, {}), InputError);
}

TEST(CompressedTexture, DescriptorFieldsRoundTrip) {
  for (const BlockFormat f : unsigned_formats())
    for (const bool srgb : {false, true}) {
      TextureDescriptor d;
      d.width = 40;
      d.height = 24;
      d.compressed = true;
      d.block_format = f;
      d.decode = {{Bc1Interpolation::AMD, Bc4Interpolation::TRUNCATE}, srgb};
      d.level[0] = {0x1000, 256};
      const auto w = encode(d);
      EXPECT_EQ((w[0] >> 12) & 31u, 1u + static_cast<uint32_t>(f));  // 1 + its row of kBlockFormats
      const TextureDescriptor back = decode_texture_descriptor(w);
      EXPECT_EQ(back, d) << block_format_name(f);
      d.validate("compressed");
    }
  TextureDescriptor plain;  // an uncompressed descriptor's words are what they were: the new fields 0
  EXPECT_EQ(encode(plain)[0] >> 12, 0u);
  std::array<uint32_t, kTextureDescriptorWords> w{};
  w[0] = 31u << 12;  // past the table
  EXPECT_THROW(decode_texture_descriptor(w), InputError);
  TextureDescriptor s;
  s.compressed = true;
  s.block_format = BlockFormat::BC4S;
  s.level[0] = {0x1000, 256};
  EXPECT_THROW(s.validate("signed"), InputError);
}

// A compressed level's lines (cache.holds compressed) are its block bytes over the line size, for
// every block (the tags take block coordinates: texel (x, y) is in block (x / block_w, y /
// block_h)), format and line size; decoded lines tile the level in squares of line_bytes / 4
// texels, above every memory line, and a fill's blocks are those covering the tile.
TEST(CompressedCache, LineOfEveryTexelIsItsBlockAddressOverTheLineSize) {
  std::mt19937 rng(9);
  for (const BlockFormat f :
       {BlockFormat::BC1, BlockFormat::BC3, BlockFormat::ETC2, BlockFormat::ASTC_5x5, BlockFormat::ASTC_12x10})
    for (const int line : {64, 256, 1024}) {
      TextureMemory mem;
      const Texture t = texture_from_block_image(random_block_image(f, 70, 45, 3, rng), {});
      const std::vector<TextureDescriptor> d{place_texture(mem, t, static_cast<uint64_t>(line))};
      TexelCacheConfig c;
      c.line_bytes = line;
      c.capacity_bytes = 4 * line;
      c.ways = 4;
      const TexelCache blocks(c, d);
      c.holds = CacheHolds::Decoded;
      const TexelCache decoded(c, d);
      const BlockFormatInfo& info = block_format_info(f);
      const int side = line == 64 ? 4 : line == 256 ? 8 : 16;
      for (int l = 0; l < 3; ++l)
        for (int y = 0; y < d[0].level_height(l); ++y)
          for (int x = 0; x < d[0].level_width(l); ++x) {
            ASSERT_EQ(blocks.line_of(0, l, x / info.block_w, y / info.block_h),
                      d[0].texel_address(l, x, y) / static_cast<uint64_t>(line))
                << block_format_name(f) << " line " << line << " level " << l << " " << x << "," << y;
            const uint64_t v = decoded.line_of(0, l, x, y);
            ASSERT_GE(v, (uint64_t{1} << 41) / static_cast<uint64_t>(line));
            ASSERT_EQ(decoded.line_of(0, l, x / side * side, y / side * side), v);
            int texels = 0;
            const int n = decoded.fill_blocks(0, l, v, texels);
            const int x0 = x / side * side, y0 = y / side * side;
            const int x1 = std::min(x0 + side, d[0].level_width(l)) - 1,
                      y1 = std::min(y0 + side, d[0].level_height(l)) - 1;
            ASSERT_EQ(texels, (x1 - x0 + 1) * (y1 - y0 + 1));
            ASSERT_EQ(n, (x1 / info.block_w - x0 / info.block_w + 1) * (y1 / info.block_h - y0 / info.block_h + 1));
          }
    }
}

// The 32-byte sectors of compressed lines: a tap's sector is its block's byte address mod the line
// size / 32 (cache.holds compressed), or its texel's offset in the decoded RGBA8 tile / 32
// (decoded); random grids of taps (given to the tags in blocks under cache.holds compressed, as the
// address generator forms them), lookups and hits against that reference (a fully associative
// cache larger than the level: a line hits iff an earlier footprint read it).
TEST(CompressedCache, SectorsOfRandomFootprints) {
  std::mt19937 rng(17);
  for (const BlockFormat f : {BlockFormat::BC1, BlockFormat::BC3, BlockFormat::ASTC_12x10})
    for (const int line : {64, 256})
      for (const CacheHolds holds : {CacheHolds::Compressed, CacheHolds::Decoded}) {
        TextureMemory mem;
        const Texture t = texture_from_block_image(random_block_image(f, 70, 45, 1, rng), {});
        const std::vector<TextureDescriptor> d{place_texture(mem, t, static_cast<uint64_t>(line))};
        TexelCacheConfig c;
        c.line_bytes = line;
        c.capacity_bytes = 1024 * line;
        c.ways = 0;
        c.holds = holds;
        TexelCache cache(c, d);
        const int side = line == 64 ? 4 : 8;  // the decoded tile
        std::vector<uint64_t> seen;
        for (int n = 0; n < tfu::test::iterations(300); ++n) {
          TapGrid g{};
          g.cols = 1 + static_cast<int>(rng() % 4);
          g.rows = 1 + static_cast<int>(rng() % 4);
          const int x0 = static_cast<int>(rng() % 67), y0 = static_cast<int>(rng() % 42);
          for (int i = 0; i < g.cols; ++i) g.x[static_cast<size_t>(i)] = static_cast<int16_t>(x0 + i);
          for (int j = 0; j < g.rows; ++j) g.y[static_cast<size_t>(j)] = static_cast<int16_t>(y0 + j);
          g.used = square_cells(g.cols, g.rows);
          std::vector<std::pair<uint64_t, int>> sectors;
          std::vector<uint64_t> lines;
          for (int cell = 0; cell < 16; ++cell) {
            if (!((g.used >> cell) & 1)) continue;
            const int x = g.x[static_cast<size_t>(cell & 3)], y = g.y[static_cast<size_t>(cell >> 2)];
            const BlockFormatInfo& info = block_format_info(f);
            const uint64_t l = holds == CacheHolds::Compressed ? cache.line_of(0, 0, x / info.block_w, y / info.block_h)
                                                               : cache.line_of(0, 0, x, y);
            const int sector = holds == CacheHolds::Compressed
                                   ? static_cast<int>(d[0].texel_address(0, x, y) % static_cast<uint64_t>(line) / 32)
                                   : ((y % side) * side + x % side) * 4 / 32;
            if (std::find(sectors.begin(), sectors.end(), std::pair{l, sector}) == sectors.end()) sectors.emplace_back(l, sector);
            if (std::find(lines.begin(), lines.end(), l) == lines.end()) lines.push_back(l);
          }
          int sector_hits = 0;
          for (const auto& [l, sector] : sectors) sector_hits += std::find(seen.begin(), seen.end(), l) != seen.end() ? 1 : 0;
          for (const uint64_t l : lines)
            if (std::find(seen.begin(), seen.end(), l) == seen.end()) seen.push_back(l);
          TapBlocks b;
          block_grid(block_format_info(f), g, b);
          const FootprintResult r = cache.access(0, 0, holds == CacheHolds::Compressed ? b.blocks : g);
          ASSERT_EQ(r.sector_lookups, static_cast<int>(sectors.size())) << block_format_name(f) << " " << line << " " << n;
          ASSERT_EQ(r.sector_hits, sector_hits) << block_format_name(f) << " " << line << " " << n;
        }
      }
}

// Random gradient requests over two textures (a compressed one and an uncompressed one,
// interleaved) and every sampler: the 12 filter modes with random wraps, and anisotropic samplers.
struct CompressedRun {
  Frame frame;
  Trace trace;
};
CompressedRun compressed_run(BlockFormat f, int line_bytes, std::mt19937& rng, int requests) {
  FrameBuilder b(line_bytes);
  BlockImage image = random_block_image(f, 36, 28, mip_level_count(36, 28), rng);
  image.srgb = (rng() & 1) != 0;
  const BlockDecodeRules rules{{static_cast<Bc1Interpolation>(rng() % 4), static_cast<Bc4Interpolation>(rng() % 2)},
                               image.srgb};
  b.add_texture(std::make_shared<const Texture>(texture_from_block_image(image, rules)), {block_format_name(f), {}});
  // The same blocks declared sRGB (texture 2, SRGBA8: decoded to linear before filtering).
  Texture srgb = texture_from_block_image(image, rules);
  srgb.format = TexelFormat::SRGBA8;
  Texture plain;  // RGBA8, tiled
  plain.levels.emplace_back(32, 32);
  for (Rgba8& t : plain.levels[0].texels)
    t = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), 255};
  generate_mipmaps(plain, MipMethod::Box);
  b.add_texture(std::make_shared<const Texture>(std::move(plain)), {"plain", {}});
  b.add_texture(std::make_shared<const Texture>(std::move(srgb)), {"srgb", {}});
  int samplers = 0;
  std::vector<uint8_t> srgb_samplers;  // those whose filter is defined on SRGBA8
  for (const FilterMode& m : all_filter_modes())
    for (const int aniso : {1, 8}) {
      if (aniso > 1 && m.mip == MipMode::None) continue;
      SamplerDescriptor s;
      s.mode = m;
      s.wrap_s = static_cast<WrapMode>(rng() % 4);
      s.wrap_t = static_cast<WrapMode>(rng() % 4);
      s.border = {static_cast<uint8_t>(rng()), 7, 200, 255};
      s.edge_shape = static_cast<EdgeShape>(rng() % 3);
      s.max_aniso = aniso;
      b.add_sampler(s, false);
      if (filters_format(m.base, TexelFormat::SRGBA8)) srgb_samplers.push_back(static_cast<uint8_t>(samplers));
      ++samplers;
    }
  Trace tr;
  tr.mode = TraceMode::Grad;
  std::uniform_real_distribution<float> pos(-0.2f, 1.2f), d(-0.12f, 0.12f);
  for (int n = 0; n < requests; ++n) {
    TraceRequest r;
    r.texture = static_cast<uint16_t>(rng() % 3 == 0 ? 1 : 0);
    r.sampler = static_cast<uint8_t>(rng() % static_cast<unsigned>(samplers));
    if (n % 4 == 3) {  // every fourth request to the sRGB texture
      r.texture = 2;
      r.sampler = srgb_samplers[rng() % srgb_samplers.size()];
    }
    r.s = pos(rng);
    r.t = pos(rng);
    r.dsdx = d(rng);
    r.dtdx = d(rng) / 4;
    r.dsdy = d(rng) / 4;
    r.dtdy = d(rng);
    tr.requests.push_back(r);
  }
  bind_requests(b, tr);
  return {b.finish(), std::move(tr)};
}

// Golden and cycle model on every request, both engines equal (pixels, cycles, statistics, every
// event), for every unsigned block format under both cache organizations and line sizes 64 and 256.
TEST(CompressedUnit, GoldenEqualsBothEnginesOnEveryFormatModeAndCacheOrganization) {
  std::mt19937 rng(11);
  const int requests = test::iterations(120);
  for (const BlockFormat f : unsigned_formats())
    for (const CacheHolds holds : {CacheHolds::Compressed, CacheHolds::Decoded}) {
      UnitConfig u;
      u.cache.line_bytes = rng() % 2 ? 64 : 256;
      u.cache.capacity_bytes = 4096;
      u.cache.ways = 2;
      u.cache.holds = holds;
      u.cache.bank_mapping = static_cast<BankMapping>(rng() % 2);
      u.memory.latency = 30;
      u.decoder.units = 1 + static_cast<int>(rng() % 2);
      u.decoder.latency = static_cast<int>(rng() % 4);
      const CompressedRun run = compressed_run(f, u.cache.line_bytes, rng, requests);
      const std::string what =
          fmt::format("{} holds {} line {}", block_format_name(f),
                      holds == CacheHolds::Compressed ? "compressed" : "decoded", u.cache.line_bytes);
      const UnitOutput clocked = run_unit(run.frame, run.trace, u, UnitEngine::Clocked, {});
      ASSERT_EQ(clocked.pixels.size(), run.trace.requests.size()) << what;
      const GoldenUnit golden(run.frame);
      EXPECT_EQ(first_mismatch(run.trace, golden_outputs(golden, run.trace, clocked), clocked), "") << what;
      const UnitOutput rec = run_unit(run.frame, run.trace, u, UnitEngine::Recurrence, {});
      EXPECT_EQ(rec.pixels, clocked.pixels) << what;
      EXPECT_EQ(rec.cycles, clocked.cycles) << what;
      EXPECT_EQ(rec.stats.json_text(), clocked.stats.json_text()) << what;
      EXPECT_EQ(compare_engines(run.frame, run.trace, u), "") << what;
      // The decoders worked, and the per-texture table holds the two compressed textures (linear
      // and sRGB), whose rows add up to the counters.
      EXPECT_GT(clocked.stats.counter("decoded_blocks"), 0u) << what;
      EXPECT_GT(clocked.stats.counter("decoder_busy_cycles"), 0u) << what;
      const sim::Stats::Table* t = clocked.stats.table("decoders");
      ASSERT_NE(t, nullptr) << what;
      ASSERT_EQ(t->rows.size(), 2u) << what;
      for (size_t col : {1u, 2u, 3u})
        EXPECT_EQ(t->rows[0].second[col] + t->rows[1].second[col],
                  clocked.stats.counter(col == 1   ? "decoded_blocks"
                                        : col == 2 ? "decoder_busy_cycles"
                                                   : "decoder_stall_cycles"))
            << what;
    }
}

// The decoder's timing: one decoder of 1 texel per clock is slower than 4 decoders of 4, the same
// pixels; with the decoders on fill, hits decode nothing (a second pass over a resident texture
// adds no decoded blocks).
TEST(CompressedUnit, DecoderThroughputAndOrganizationChangeTimingNotPixels) {
  std::mt19937 rng(5);
  const CompressedRun run = compressed_run(BlockFormat::BC1, 64, rng, 200);
  UnitConfig fast, slow;
  fast.decoder = {4, 4, 1};
  slow.decoder = {1, 1, 8};
  const UnitOutput a = run_unit(run.frame, run.trace, fast, UnitEngine::Recurrence, {});
  const UnitOutput b = run_unit(run.frame, run.trace, slow, UnitEngine::Recurrence, {});
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_LT(a.cycles, b.cycles);
  EXPECT_LT(a.stats.counter("decoder_busy_cycles"), b.stats.counter("decoder_busy_cycles"));
  // Decoded on fill with a cache holding the whole texture: a trace run twice decodes once.
  UnitConfig big;
  big.cache.holds = CacheHolds::Decoded;
  big.cache.capacity_bytes = 1 << 20;
  big.cache.ways = 16;
  Trace twice = run.trace;
  twice.requests.insert(twice.requests.end(), run.trace.requests.begin(), run.trace.requests.end());
  const UnitOutput once = run_unit(run.frame, run.trace, big, UnitEngine::Recurrence, {});
  const UnitOutput again = run_unit(run.frame, twice, big, UnitEngine::Recurrence, {});
  EXPECT_EQ(once.stats.counter("decoded_blocks"), again.stats.counter("decoded_blocks"));
  // A BC1 fill of a 4x4 tile is one 8-byte block; memory bytes are the blocks'.
  EXPECT_EQ(once.stats.table("decoders")->rows[0].second[1] * 8, once.stats.table("textures")->rows[0].second[4]);
}

// The address generator's block quotient (rtl/address_gen_blocks.hpp): floor(x / d) for
// every texel coordinate below 2^14 and every block side up to 16 (ASTC's go to 12).
TEST(CompressedUnit, BlockQuotientByMultiplicationIsExact) {
  for (int d = 1; d <= 16; ++d) {
    const uint32_t m = block_reciprocal(d);
    for (int x = 0; x < kMaxTextureSize; ++x) ASSERT_EQ(block_quotient(x, m), x / d) << x << " / " << d;
  }
  EXPECT_NE(block_quotient(1 << 18, block_reciprocal(12)), (1 << 18) / 12);  // the bound matters
  for (int d = 1; d <= 16; ++d) EXPECT_EQ(kBlockReciprocals[static_cast<size_t>(d)], block_reciprocal(d)) << d;
}

// The address generator's block coordinates (AddressGen::footprint: block_grid,
// rtl/address_gen_blocks.hpp), which the cache stage's tags, decoders and read-out take on a
// compressed texture, are the plain definition on every footprint: column i's block x[i] / block_w
// and texel x[i] mod block_w (floor division of a texel coordinate >= 0), row j's the same with
// block_h, -1 (clamp-to-border outside the level) kept, the grid's shape and used cells unchanged,
// and each used tap's block address (TextureDescriptor::block_address) the texel's
// (texel_address). Random pixels through the address generator's sequencer (begin / issue) on
// every unsigned block format (block sides 4x4 to 12x12), level 0 sizes that are not multiples of
// the block (partial edge blocks) up to 16384 wide, every filter mode (NEAREST 1 x 1, LINEAR 2 x 2,
// CUBIC 4 x 4, the edge cross, each plain, MIPMAP_NEAREST and MIPMAP_LINEAR), every wrap mode, and
// anisotropic probes; the loop counts the cases it must meet (wraps, partial blocks, border taps,
// each footprint shape, probes) and fails if one is missing.
TEST(CompressedUnit, AddressGenBlockCoordinatesAreTheTexelCoordinatesOverTheBlockSide) {
  std::mt19937 rng(404);
  Registers regs;
  for (const BlockFormat f : unsigned_formats()) {
    const BlockFormatInfo& info = block_format_info(f);
    TextureDescriptor d;
    d.compressed = true;
    d.block_format = f;
    const int n = static_cast<int>(regs.textures.size());
    d.width = n % 5 == 0 ? kMaxTextureSize : 1 + static_cast<int>(rng() % 300);
    d.height = n % 5 == 0 ? 1 + static_cast<int>(rng() % 40) : 1 + static_cast<int>(rng() % 300);
    if (d.width % info.block_w == 0) ++d.width;  // a partial block column at the right edge
    if (d.height % info.block_h == 0) ++d.height;
    d.levels = std::min(mip_level_count(d.width, d.height), kMaxLevels);
    uint64_t address = 0x10000;
    for (int l = 0; l < d.levels; ++l) {
      const auto pitch = static_cast<uint64_t>(blocks_across(f, d.level_width(l)) * info.block_bytes);
      d.level[static_cast<size_t>(l)] = {address, static_cast<uint32_t>(pitch)};
      address += (pitch * static_cast<uint64_t>(blocks_down(f, d.level_height(l))) + 255) / 256 * 256;
    }
    regs.textures.push_back(d);
  }
  for (const FilterMode& m : all_filter_modes())
    for (const int aniso : {1, 8}) {
      if (aniso > 1 && m.mip == MipMode::None) continue;
      SamplerDescriptor s;
      s.mode = m;
      s.max_aniso = aniso;
      for (int k = 0; k < 16; ++k) {  // every pair of wrap modes
        s.wrap_s = static_cast<WrapMode>(k / 4);
        s.wrap_t = static_cast<WrapMode>(k % 4);
        regs.samplers.push_back(s);
      }
    }
  const WeightRomBank roms(regs.samplers);
  sim::Simulator sim;
  sim::Channel<PixelReq> in("pixel", 2);
  sim::Channel<FootprintReq> out("footprint", 2);
  AddressGen gen(sim, in, out, regs, roms);
  std::uniform_real_distribution<float> coord(-1.5f, 2.5f);
  // Cases met: wrapped grid (a column or row below its predecessor), partial edge block, border
  // tap, 1 x 1, 2 x 2, 4 x 4, cross, anisotropic probe.
  std::array<int, 8> met{};
  int footprints = 0;
  for (int it = 0; it < test::iterations(20000); ++it) {
    PixelReq p;
    p.req.texture = static_cast<uint16_t>(rng() % regs.textures.size());
    p.req.sampler = static_cast<uint8_t>(rng() % regs.samplers.size());
    p.s = coord(rng);
    p.t = coord(rng);
    p.lambda_q8 = static_cast<int32_t>(rng() % (14 * 256)) - 256;
    if (regs.samplers[p.req.sampler].anisotropic()) {
      p.probes = 1 + static_cast<int>(rng() % 8);
      p.major_du_q16 = static_cast<int64_t>(rng() % (1u << 24)) - (1 << 23);
      p.major_dv_q16 = static_cast<int64_t>(rng() % (1u << 24)) - (1 << 23);
    }
    const TextureDescriptor& d = regs.textures[p.req.texture];
    const BlockFormatInfo& info = d.block();
    gen.begin(p);
    for (bool last = false; !last;) {
      FootprintReq f{};
      last = gen.issue(f);
      ++footprints;
      const TapGrid& g = f.grid;
      const TapBlocks& b = f.blocks;
      const int w = d.level_width(f.level), h = d.level_height(f.level);
      const auto where = [&] {
        return fmt::format("{} {}x{} level {}, {} wraps {} {}, s {} t {}", info.name, d.width, d.height, f.level,
                           filter_mode_name(regs.samplers[p.req.sampler].mode),
                           static_cast<int>(regs.samplers[p.req.sampler].wrap_s),
                           static_cast<int>(regs.samplers[p.req.sampler].wrap_t), p.s, p.t);
      };
      ASSERT_EQ(b.blocks.cols, g.cols) << where();
      ASSERT_EQ(b.blocks.rows, g.rows) << where();
      ASSERT_EQ(b.blocks.used, g.used) << where();
      const auto check = [&](int x, int16_t block, uint8_t texel, int side, int size) {
        if (x < 0) {
          ++met[2];
          return block == -1 && texel == 0;
        }
        if (size % side != 0 && x / side == size / side) ++met[1];
        return x < size && block == x / side && texel == x % side;
      };
      for (size_t i = 0; i < static_cast<size_t>(g.cols); ++i) {
        ASSERT_TRUE(check(g.x[i], b.blocks.x[i], b.u[i], info.block_w, w)) << where() << " column " << g.x[i];
        if (i > 0 && g.x[i] >= 0 && g.x[i] < g.x[i - 1]) ++met[0];
      }
      for (size_t j = 0; j < static_cast<size_t>(g.rows); ++j) {
        ASSERT_TRUE(check(g.y[j], b.blocks.y[j], b.v[j], info.block_h, h)) << where() << " row " << g.y[j];
        if (j > 0 && g.y[j] >= 0 && g.y[j] < g.y[j - 1]) ++met[0];
      }
      for (size_t cell = 0; cell < 16; ++cell) {
        if (((g.used >> cell) & 1u) == 0) continue;
        const int x = g.x[cell & 3u], y = g.y[cell >> 2];
        ASSERT_EQ(d.block_address(f.level, b.blocks.x[cell & 3u], b.blocks.y[cell >> 2]), d.texel_address(f.level, x, y))
            << where();
        ASSERT_EQ(texel_in_block(b, cell, info.block_w), static_cast<size_t>((y % info.block_h) * info.block_w + x % info.block_w))
            << where();
      }
      ++met[f.cross ? 6 : g.cols == 1 ? 3 : g.cols == 2 ? 4 : 5];
      met[7] += f.tag.probes > 1 ? 1 : 0;
    }
  }
  for (size_t k = 0; k < met.size(); ++k) EXPECT_GT(met[k], 0) << "case " << k << " of " << footprints << " footprints";
}

// The timing recurrences' LINEAR quad path on block-compressed textures (the blocks' 2 x 2
// footprints formed once per footprint, rtl/cache_stage_block_squares.cpp) gives the plain
// per-pixel path's and the clocked blocks' pixels, response cycles, cycles and every statistic
// (decoded blocks, decoder busy and stall cycles included), and the golden model's pixels: BC1,
// BC3, BC7, ETC2 RGBA and ASTC 4x4, 6x5 and 12x10 textures of 36 x 28 texels (partial edge blocks,
// a full MIP chain), interleaved quad by quad with an uncompressed texture and with quads the path
// does not take (clamp-to-border, anisotropic, NEAREST); LINEAR with every non-border wrap pair,
// LINEAR_MIPMAP_NEAREST and LINEAR_MIPMAP_LINEAR with LOD biases; both cache organizations; random
// unit configurations with small caches, one bank or four, both bank mappings, short FIFOs, slow
// memory and slow decoders (stalls of every kind).
TEST(CompressedUnit, LinearQuadPathEqualsThePlainBlocks) {
  std::mt19937 rng(2718);
  const int quads = test::iterations(400);
  for (const BlockFormat f : {BlockFormat::BC1, BlockFormat::BC3, BlockFormat::BC7, BlockFormat::ETC2A,
                              BlockFormat::ASTC_4x4, BlockFormat::ASTC_6x5, BlockFormat::ASTC_12x10}) {
    const int line_bytes = f == BlockFormat::BC3 || f == BlockFormat::ASTC_6x5 ? 256 : 64;
    FrameBuilder b(line_bytes);
    BlockImage image = random_block_image(f, 36, 28, mip_level_count(36, 28), rng);
    image.srgb = f == BlockFormat::ASTC_4x4;
    const BlockDecodeRules rules{{static_cast<Bc1Interpolation>(rng() % 4), static_cast<Bc4Interpolation>(rng() % 2)},
                                 image.srgb};
    Texture tex = texture_from_block_image(image, rules);
    // Declared sRGB (SRGBA8: decoded to linear before filtering) on two formats, the ASTC one among them.
    if (f == BlockFormat::ASTC_4x4 || f == BlockFormat::BC7) tex.format = TexelFormat::SRGBA8;
    b.add_texture(std::make_shared<const Texture>(std::move(tex)), {block_format_name(f), {}});
    Texture plain;  // RGBA8, tiled
    plain.levels.emplace_back(32, 32);
    for (Rgba8& t : plain.levels[0].texels)
      t = {static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), static_cast<uint8_t>(rng()), 255};
    generate_mipmaps(plain, MipMethod::Box);
    b.add_texture(std::make_shared<const Texture>(std::move(plain)), {"plain", {}});
    std::vector<SamplerDescriptor> samplers;
    for (int ws = 0; ws < 3; ++ws)
      for (int wt = 0; wt < 3; ++wt) {  // LINEAR with every non-border wrap pair
        SamplerDescriptor s;
        s.mode = filter_mode_from_name("LINEAR");
        s.wrap_s = static_cast<WrapMode>(ws);
        s.wrap_t = static_cast<WrapMode>(wt);
        samplers.push_back(s);
      }
    for (const char* mode : {"LINEAR_MIPMAP_NEAREST", "LINEAR_MIPMAP_LINEAR", "LINEAR_MIPMAP_LINEAR"}) {
      SamplerDescriptor s;
      s.mode = filter_mode_from_name(mode);
      s.wrap_s = static_cast<WrapMode>(rng() % 3);
      s.wrap_t = static_cast<WrapMode>(rng() % 3);
      s.lod.bias_q8 = static_cast<int32_t>(rng() % 768) - 256;
      samplers.push_back(s);
    }
    for (const char* mode : {"LINEAR_MIPMAP_LINEAR", "LINEAR", "NEAREST"}) {  // not taken
      SamplerDescriptor s;
      s.mode = filter_mode_from_name(mode);
      if (s.mode.mip == MipMode::Linear) s.max_aniso = 4;
      if (s.mode.base == BaseFilter::Linear && s.mode.mip == MipMode::None) s.wrap_t = WrapMode::ClampToBorder;
      s.border = {9, 200, 7, 255};
      samplers.push_back(s);
    }
    for (const SamplerDescriptor& s : samplers) b.add_sampler(s, false);
    Trace tr;
    tr.mode = TraceMode::Quad;
    std::uniform_real_distribution<float> uni(-1.5f, 2.5f), d(-0.06f, 0.06f);
    int taken = 0;
    for (int n = 0; n < quads; ++n) {
      TraceRequest r;
      r.texture = static_cast<uint16_t>(rng() % 4 == 0 ? 1 : 0);
      r.sampler = static_cast<uint8_t>(rng() % samplers.size());
      taken += r.texture == 0 && detail::LinearQuadPath::takes_sampler(samplers[r.sampler]) ? 1 : 0;
      const float s0 = uni(rng), t0 = uni(rng), step = std::abs(d(rng));
      for (size_t k = 0; k < 4; ++k) {
        r.s = s0 + static_cast<float>(k & 1) * step;
        r.t = t0 + static_cast<float>(k >> 1) * step * 0.5f;
        tr.requests.push_back(r);
      }
    }
    EXPECT_GT(taken, quads / 3) << block_format_name(f);  // 12/15 samplers x 3/4 of the quads: 0.6
    bind_requests(b, tr);
    const Frame frame = b.finish();
    ASSERT_TRUE(frame.regs.textures[0].compressed);
    EXPECT_TRUE(detail::LinearQuadPath::takes_texture(frame.regs.textures[0])) << block_format_name(f);
    const GoldenUnit golden(frame);
    for (int k = 0; k < 4; ++k) {
      const auto pick = [&rng](std::initializer_list<int> v) { return *(v.begin() + rng() % v.size()); };
      UnitConfig c;
      c.cache.line_bytes = line_bytes;
      c.cache.holds = k % 2 == 0 ? CacheHolds::Compressed : CacheHolds::Decoded;
      c.cache.ways = pick({1, 2, 4});
      c.cache.capacity_bytes = line_bytes * c.cache.ways * pick({1, 2, 8});
      c.cache.banks = pick({1, 4});
      c.cache.bank_mapping = static_cast<BankMapping>(rng() % 2);
      c.channel_depth = pick({1, 2, 4});
      c.miss_fifo_depth = pick({1, 2, 8});
      c.filter_lanes = pick({1, 4});
      c.memory.latency = pick({0, 7, 100});
      c.memory.bytes_per_cycle = pick({4, 16, 64});
      c.decoder = {pick({1, 4}), pick({1, 2}), pick({0, 2, 5})};
      const std::string what = fmt::format("{} config {}: {}", block_format_name(f), k, unit_config_to_json(c));
      const UnitOutput quad_path = run_unit_recurrence(frame, tr, c, true);
      const UnitOutput plain_path = run_unit_recurrence(frame, tr, c, false);
      const UnitOutput clocked = run_unit(frame, tr, c, UnitEngine::Clocked, {});
      EXPECT_EQ(first_mismatch(tr, golden_outputs(golden, tr, quad_path), quad_path), "") << what;
      EXPECT_GT(quad_path.stats.counter("decoded_blocks"), 0u) << what;
      for (const UnitOutput* other : {&plain_path, &clocked}) {
        EXPECT_EQ(quad_path.pixels, other->pixels) << what;
        EXPECT_EQ(quad_path.response_cycle, other->response_cycle) << what;
        EXPECT_EQ(quad_path.cycles, other->cycles) << what;
        EXPECT_EQ(quad_path.stats.json_text(), other->stats.json_text()) << what;
      }
    }
  }
}

}  // namespace
}  // namespace tfu::rtl
