// Fuzz target, etc2 (docs/fuzzing.md): ETC2 RGB8, RGB8 punch-through alpha, RGBA8 (ETC2 + EAC) and
// EAC R11 / RG11 (unsigned and signed) images, linear and sRGB, through the model's decoders and
// Mesa 22.3's (OSMesa softpipe, testbench/mesa_decoder.hpp), texel for texel: the colour formats
// read back as RGBA8 bytes, the 11-bit formats as 16-bit words (GL_UNSIGNED_SHORT / GL_SHORT,
// where Mesa keeps the spec's bit-replicated form: eac11_to_unorm16, eac11_signed_to_snorm16).
// And the model's own properties: the unit's level decoder (decode_block_level) gives the ETC image
// decoder's RGBA8 words (decode_etc_image) for the unsigned formats, and the 8-bit forms of the
// 11-bit values (eac11_to_unorm8, eac11_signed_to_snorm8) for all; the sRGB variants decode to the
// same bytes as their linear twins.
// The first byte chooses the format (byte % 10, in EtcFormat order: RGB8, SRGB8, RGB8A1, SRGB8A1,
// RGBA8, SRGB8_ALPHA8, R11, R11 signed, RG11, RG11 signed); the next two the image width and height
// in blocks (1..4 each) and what the last block column and row keep (1..4 texels: partial edge
// blocks); the rest is the blocks, zeros past the input's end. Any difference aborts with the
// format, the block and the texel.
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

#include "cmodel/block_formats.hpp"
#include "cmodel/etc2_decode.hpp"
#include "testbench/fuzz/fuzz_input.hpp"
#include "testbench/mesa_decoder.hpp"

namespace {

using tfu::BlockFormat;
using tfu::EtcFormat;

// The unit's format of each ETC format (the sRGB variants are the linear format with the flag).
struct EtcCase {
  EtcFormat etc_format;
  BlockFormat block_format;
  bool srgb;
};
constexpr EtcCase kCases[] = {
    {EtcFormat::Rgb8, BlockFormat::ETC2, false},     {EtcFormat::Srgb8, BlockFormat::ETC2, true},
    {EtcFormat::Rgb8A1, BlockFormat::ETC2A1, false}, {EtcFormat::Srgb8A1, BlockFormat::ETC2A1, true},
    {EtcFormat::Rgba8, BlockFormat::ETC2A, false},   {EtcFormat::Srgb8Alpha8, BlockFormat::ETC2A, true},
    {EtcFormat::R11, BlockFormat::EAC_R11, false},   {EtcFormat::R11Signed, BlockFormat::EAC_R11S, false},
    {EtcFormat::Rg11, BlockFormat::EAC_RG11, false}, {EtcFormat::Rg11Signed, BlockFormat::EAC_RG11S, false},
};

constexpr uint32_t kGlRed = 0x1903, kGlRg = 0x8227, kGlRgba = 0x1908;
constexpr uint32_t kGlUnsignedByte = 0x1401, kGlShort = 0x1402, kGlUnsignedShort = 0x1403;

[[noreturn]] void fail(const EtcCase& c, std::span<const uint8_t> block, int x, int y, const char* what, int ours,
                       int ref) {
  std::fprintf(stderr, "etc2: %s texel (%d, %d) block ", tfu::etc_format_info(c.etc_format).name, x, y);
  for (uint8_t b : block) std::fprintf(stderr, "%02x", b);
  std::fprintf(stderr, ": model %08x %s %08x\n", static_cast<unsigned>(ours), what, static_cast<unsigned>(ref));
  std::abort();
}

uint32_t word(tfu::Rgba8 t) {
  return static_cast<uint32_t>(t.r) << 24 | static_cast<uint32_t>(t.g) << 16 | static_cast<uint32_t>(t.b) << 8 | t.a;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tfu::fuzz::ByteReader in(data, size);
  const EtcCase& c = kCases[in.byte() % std::size(kCases)];
  const tfu::EtcFormatInfo& info = tfu::etc_format_info(c.etc_format);
  const tfu::BlockFormatInfo& unit = tfu::block_format_info(c.block_format);
  const tfu::fuzz::FuzzBlockImage img = tfu::fuzz::read_block_image(in, static_cast<size_t>(info.block_bytes));
  const int width = img.width, height = img.height;
  const std::vector<uint8_t>& blocks = img.blocks;
  const auto block_of = [&img](int x, int y) { return img.block_at(x, y); };
  const auto at = [&](int x, int y) { return static_cast<size_t>(y * width + x); };

  // The unit's view (RGBA8 words; signed: SNORM8 bytes) against the image decoders.
  const tfu::Image level = tfu::decode_block_level(c.block_format, width, height, blocks, {tfu::kBcRulesSpec, c.srgb});
  std::vector<int16_t> eac;
  if (info.eac11) {
    eac = tfu::decode_eac11_image(c.etc_format, width, height, blocks);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        for (int ch = 0; ch < info.channels; ++ch) {
          const int16_t v = eac[at(x, y) * static_cast<size_t>(info.channels) + static_cast<size_t>(ch)];
          const int want = info.is_signed ? static_cast<uint8_t>(tfu::eac11_signed_to_snorm8(v))
                                          : tfu::eac11_to_unorm8(static_cast<uint16_t>(v));
          const int got = ch == 0 ? level.at(x, y).r : level.at(x, y).g;
          if (got != want) fail(c, block_of(x, y), x, y, "8-bit form of the 11-bit value", got, want);
        }
  }
  if (!info.is_signed) {
    const std::vector<tfu::Rgba8> image = tfu::decode_etc_image(c.etc_format, width, height, blocks);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        if (level.at(x, y) != image[at(x, y)])
          fail(c, block_of(x, y), x, y, "decode_etc_image", static_cast<int>(word(level.at(x, y))),
               static_cast<int>(word(image[at(x, y)])));
  }
  if (c.srgb) {
    const tfu::Image linear =
        tfu::decode_block_level(c.block_format, width, height, blocks, {tfu::kBcRulesSpec, false});
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        if (level.at(x, y) != linear.at(x, y))
          fail(c, block_of(x, y), x, y, "linear twin", static_cast<int>(word(level.at(x, y))),
               static_cast<int>(word(linear.at(x, y))));
  }

  // Mesa, the whole image at once.
  if (!tfu::test::mesa_available()) return 0;
  const uint32_t gl_format = c.srgb ? unit.gl_srgb_internal_format : unit.gl_internal_format;
  const uint32_t read_format = !info.eac11 ? kGlRgba : info.channels == 1 ? kGlRed : kGlRg;
  const uint32_t read_type = !info.eac11 ? kGlUnsignedByte : info.is_signed ? kGlShort : kGlUnsignedShort;
  const auto mesa = tfu::test::mesa_decode(gl_format, width, height, blocks, read_format, read_type);
  if (!mesa) {
    std::fprintf(stderr, "etc2: Mesa refused a %dx%d %s image\n", width, height, info.name);
    std::abort();
  }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (!info.eac11) {
        const size_t p = 4 * at(x, y);
        const tfu::Rgba8 m{(*mesa)[p], (*mesa)[p + 1], (*mesa)[p + 2], (*mesa)[p + 3]};
        if (level.at(x, y) != m)
          fail(c, block_of(x, y), x, y, "Mesa", static_cast<int>(word(level.at(x, y))), static_cast<int>(word(m)));
        continue;
      }
      for (int ch = 0; ch < info.channels; ++ch) {
        const size_t i = at(x, y) * static_cast<size_t>(info.channels) + static_cast<size_t>(ch);
        const int16_t v = eac[i];
        const uint16_t ours = info.is_signed ? static_cast<uint16_t>(tfu::eac11_signed_to_snorm16(v))
                                             : tfu::eac11_to_unorm16(static_cast<uint16_t>(v));
        const auto m = static_cast<uint16_t>((*mesa)[2 * i] | (*mesa)[2 * i + 1] << 8);  // host order, little-endian
        if (ours != m) fail(c, block_of(x, y), x, y, "Mesa (16-bit)", ours, m);
      }
    }
  return 0;
}
