// Fuzz target, bc (docs/fuzzing.md): BC1-BC5 (unsigned and signed) and BC7 images through the
// unit's decoder (decode_block_level, cmodel/block_formats.hpp) and two outside decoders:
//   * Mesa 22.3 (OSMesa softpipe, testbench/mesa_decoder.hpp) for every format, in the rules Mesa
//     follows (kBcRulesMesa: truncated BC1 thirds and BC4 interpolants; BC7 is exact everywhere);
//   * libsquish 1.15 for BC1 (RGB and RGBA), BC2, BC3 in its rules (kBcRulesLibsquish), and BC4 / BC5
//     UNORM as the alpha block of a DXT5 block (libsquish's kBc4 / kBc5 do not decode RGTC:
//     test_bc_decode.cpp, Bc4IsNotDecodedByLibsquish). BC1 RGB is compared in R, G, B only
//     (libsquish's DXT1 has alpha 0 on the 3-colour mode's black; BC1 RGB has none).
// And the model's own properties: the block decoder of the BC family (decode_bc_image) gives the
// same image as the unit's level decoder in every rule; in the unsigned formats the spec's rounded
// interpolants (EXACT) and the truncated ones differ by at most 1 per channel; the vendor rules
// (NVIDIA, AMD) decode without a fault.
// The first byte chooses the format (byte % 9, in BlockFormat order BC1 .. BC7); the next two the
// image width and height in blocks (1..4 each) and what the last block column and row keep (1..4
// texels: partial edge blocks); the rest is the blocks, zeros past the input's end. Any difference
// aborts with the format, the block and the texel.
#include <squish.h>
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

#include "cmodel/bc_decode.hpp"
#include "cmodel/block_formats.hpp"
#include "testbench/fuzz/fuzz_input.hpp"
#include "testbench/mesa_decoder.hpp"

namespace {

using tfu::BcFormat;
using tfu::BlockFormat;
using tfu::Rgba8;

struct BcCase {
  BlockFormat block_format;
  BcFormat bc_format;
  int squish_flags;  // 0: no libsquish comparison of the whole block (BC4 / BC5: alpha blocks below)
};
constexpr BcCase kCases[] = {
    {BlockFormat::BC1, BcFormat::BC1_RGB, squish::kDxt1},
    {BlockFormat::BC1A, BcFormat::BC1_RGBA, squish::kDxt1},
    {BlockFormat::BC2, BcFormat::BC2, squish::kDxt3},
    {BlockFormat::BC3, BcFormat::BC3, squish::kDxt5},
    {BlockFormat::BC4, BcFormat::BC4_UNORM, 0},
    {BlockFormat::BC4S, BcFormat::BC4_SNORM, 0},
    {BlockFormat::BC5, BcFormat::BC5_UNORM, 0},
    {BlockFormat::BC5S, BcFormat::BC5_SNORM, 0},
    {BlockFormat::BC7, BcFormat::BC7, 0},
};

constexpr uint32_t kGlRgba = 0x1908, kGlUnsignedByte = 0x1401, kGlByte = 0x1400;

[[noreturn]] void fail(const BcCase& c, std::span<const uint8_t> block, int x, int y, const char* what, Rgba8 ours,
                       Rgba8 ref) {
  std::fprintf(stderr, "bc: %s texel (%d, %d) block ", tfu::block_format_name(c.block_format), x, y);
  for (uint8_t b : block) std::fprintf(stderr, "%02x", b);
  std::fprintf(stderr, ": model %d,%d,%d,%d %s %d,%d,%d,%d\n", ours.r, ours.g, ours.b, ours.a, what, ref.r, ref.g,
               ref.b, ref.a);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tfu::fuzz::ByteReader in(data, size);
  const BcCase& c = kCases[in.byte() % std::size(kCases)];
  const tfu::BlockFormatInfo& info = tfu::block_format_info(c.block_format);
  const tfu::fuzz::FuzzBlockImage img = tfu::fuzz::read_block_image(in, static_cast<size_t>(info.block_bytes));
  const int width = img.width, height = img.height;
  const std::vector<uint8_t>& blocks = img.blocks;
  const auto block_of = [&img](int x, int y) { return img.block_at(x, y); };

  // The unit's level decoder against the family's image decoder, in every rule.
  for (const tfu::Bc1Interpolation colour : {tfu::Bc1Interpolation::EXACT, tfu::Bc1Interpolation::TRUNCATE,
                                             tfu::Bc1Interpolation::NVIDIA, tfu::Bc1Interpolation::AMD})
    for (const tfu::Bc4Interpolation alpha : {tfu::Bc4Interpolation::EXACT, tfu::Bc4Interpolation::TRUNCATE}) {
      const tfu::BcRules rules{colour, alpha};
      const tfu::Image level = tfu::decode_block_level(c.block_format, width, height, blocks, {rules, false});
      const std::vector<Rgba8> image = tfu::decode_bc_image(c.bc_format, width, height, blocks, rules);
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
          if (level.at(x, y) != image[static_cast<size_t>(y * width + x)])
            fail(c, block_of(x, y), x, y, "decode_bc_image", level.at(x, y), image[static_cast<size_t>(y * width + x)]);
    }

  const tfu::Image spec = tfu::decode_block_level(c.block_format, width, height, blocks, {tfu::kBcRulesSpec, false});
  const tfu::Image mesa_rules =
      tfu::decode_block_level(c.block_format, width, height, blocks, {tfu::kBcRulesMesa, false});
  if (!info.is_signed)
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const Rgba8 e = spec.at(x, y), t = mesa_rules.at(x, y);
        if (std::abs(e.r - t.r) > 1 || std::abs(e.g - t.g) > 1 || std::abs(e.b - t.b) > 1 || std::abs(e.a - t.a) > 1)
          fail(c, block_of(x, y), x, y, "more than 1 from the truncating rule's", e, t);
      }

  // libsquish, block by block (its rules are Mesa's: kBcRulesLibsquish == kBcRulesMesa).
  static_assert(tfu::kBcRulesLibsquish == tfu::kBcRulesMesa);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::span<const uint8_t> block = block_of(x, y);
      const int t = 4 * (y % 4) + x % 4;
      const Rgba8 ours = mesa_rules.at(x, y);
      std::array<uint8_t, 64> ref{};
      if (c.squish_flags != 0) {
        squish::Decompress(ref.data(), block.data(), c.squish_flags);
        Rgba8 r{ref[4 * t], ref[4 * t + 1], ref[4 * t + 2], ref[4 * t + 3]};
        if (c.block_format == BlockFormat::BC1) r.a = ours.a;
        if (ours != r) fail(c, block, x, y, "libsquish", ours, r);
      } else if (c.block_format == BlockFormat::BC4 || c.block_format == BlockFormat::BC5) {
        for (size_t half = 0; half < img.block_bytes / 8; ++half) {  // red, then green: a DXT5 alpha block each
          std::array<uint8_t, 16> dxt5{};
          std::copy_n(block.begin() + static_cast<std::ptrdiff_t>(8 * half), 8, dxt5.begin());
          squish::Decompress(ref.data(), dxt5.data(), squish::kDxt5);
          const uint8_t v = half == 0 ? ours.r : ours.g;
          if (v != ref[4 * t + 3]) fail(c, block, x, y, "libsquish's DXT5 alpha", ours, Rgba8{ref[4 * t + 3], 0, 0, 0});
        }
      }
    }

  // Mesa, the whole image at once.
  if (!tfu::test::mesa_available()) return 0;
  const auto mesa = tfu::test::mesa_decode(info.gl_internal_format, width, height, blocks, kGlRgba,
                                           info.is_signed ? kGlByte : kGlUnsignedByte);
  if (!mesa) {
    std::fprintf(stderr, "bc: Mesa refused a %dx%d %s image\n", width, height, info.name);
    std::abort();
  }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t p = 4 * static_cast<size_t>(y * width + x);
      const Rgba8 m{(*mesa)[p], (*mesa)[p + 1], (*mesa)[p + 2], (*mesa)[p + 3]};
      if (mesa_rules.at(x, y) != m) fail(c, block_of(x, y), x, y, "Mesa", mesa_rules.at(x, y), m);
    }
  return 0;
}
