// ETC2 and EAC block decoders (ETC1 blocks are ETC2 RGB8 blocks in individual or differential mode):
// pure integer functions, one 4x4 block in, 16 texels out, as the Khronos Data Format Specification
// 1.3, chapter "ETC2 Compressed Texture Image Formats" (the OpenGL 4.5 / ES 3.0 text) defines them.
// docs/compressed-etc2.md has the bit layouts and the outside check against Mesa.
//
// Block word: the 8 bytes q0..q7 (q0 at the lowest address) form the big-endian 64-bit integer
// int64bit = q0 q1 ... q7. RGBA8 blocks are 16 bytes: bytes 0-7 the EAC alpha word, bytes 8-15 the
// ETC2 colour word. RG11 blocks: bytes 0-7 red, bytes 8-15 green, each decoded as R11.
//
// Texel order: every block decoder writes out[4 * y + x], x the column (u direction), y the row
// (v direction): row-major. The spec names the texels a..p down the columns (a = (0,0), b = (0,1),
// e = (1,0)); the pixel-index bits of texel (x, y) sit at spec position j = 4 x + y:
//   ETC2 colour (individual, differential, T, H): index MSB = bit 16 + j, LSB = bit j
//   EAC (R11, RG11, RGBA8's alpha):               3-bit index = bits 47 - 3j (MSB) .. 45 - 3j (LSB)
//
// ETC2 colour datapath (all channels unsigned 8-bit; "clamp" = clamp to [0, 255]):
//   mode         D = bit 33 (RGB8A1: the opaque bit, and no individual mode); R, G, B = bits 63-59,
//                55-51, 47-43 (5 bits), dR, dG, dB = bits 58-56, 50-48, 42-40 (3-bit two's
//                complement). D = 0: individual. Else R + dR outside [0, 31]: T; else G + dG
//                outside: H; else B + dB outside: planar; else differential.
//   individual   base_k = extend_4to8 (x * 17) of (R1, G1, B1) = bits 63-60, 55-52, 47-44 and
//                (R2, G2, B2) = bits 59-56, 51-48, 43-40
//   differential base_1 = extend_5to8 ((x << 3) | (x >> 2)) of (R, G, B); base_2 of (R + dR, ...)
//   subblocks    flip = bit 32: 0 -> subblock 2 is x >= 2; 1 -> subblock 2 is y >= 2; table
//                codeword 1 = bits 39-37, 2 = bits 36-34 -> modifiers (a, b) of kEtcModifiers
//   texel        index (MSB, LSB) 00 -> +a, 01 -> +b, 10 -> -a, 11 -> -b; colour = clamp(base + m)
//                per channel (9-bit sum + sign: -183..438)
//   T            base_1 = extend_4to8(R1a:R1b = bits 60-59:57-56, G1 55-52, B1 51-48), base_2 =
//                extend_4to8(47-44, 43-40, 39-36); d = kEtcDistances[da:db = bits 35-34:32];
//                paint 0 = base_1, 1 = clamp(base_2 + d), 2 = base_2, 3 = clamp(base_2 - d)
//   H            base_1 = extend_4to8(R1 62-59, G1a:G1b 58-56:52, B1a:B1b 51:49-47), base_2 =
//                extend_4to8(46-43, 42-39, 38-35); distance index = da (bit 34) : db (bit 32) :
//                (value(base_1) >= value(base_2)), value = R << 16 | G << 8 | B of the 8-bit
//                bases; paint 0/1 = clamp(base_1 +/- d), 2/3 = clamp(base_2 +/- d)
//   T, H texel   paint colour number = the 2-bit index (MSB, LSB)
//   planar       O, H, V in RGB 6:7:6 (RO 62-57, GO 56:54-49, BO 48:44-43:41-39, RH 38-34:32,
//                GH 31-25, BH 24-19, RV 18-13, GV 12-6, BV 5-0), widened by bit replication
//                ((x << 2) | (x >> 4), (x << 1) | (x >> 6)); texel (x, y) per channel =
//                clamp((x (H - O) + y (V - O) + 4 O + 2) >> 2): the spec's round-half-up of
//                O + x (H - O) / 4 + y (V - O) / 4 (sum -508..1532: 11 bits + sign; >> 2 is an
//                arithmetic shift, floor)
// Punch-through (RGB8A1), opaque bit = 0: in differential mode the modifiers of
//   indices 00 and 10 are 0; in differential, T and H mode index 10 decodes to (0, 0, 0, 0);
//   planar mode ignores the opaque bit. Every other texel has alpha 255.
//
// EAC datapath (base 8 bits, multiplier m = bits 55-52, table = bits 51-48, modifier from
// kEacModifiers[table][index], m = 0 allowed and special):
//   RGBA8 alpha  clamp(base + modifier * m) (m = 0 gives base), [0, 255]
//   R11 unsigned clamp(8 base + 4 + 8 modifier m) (m = 0: 8 base + 4 + modifier), [0, 2047];
//                11-bit result, 2047 = 1.0 (sum -1796..3724: 12 bits + sign)
//   R11 signed   base = two's complement bits 63-56, -128 read as -127; clamp(8 base + 8 modifier
//                m) (m = 0: 8 base + modifier), [-1023, 1023] (sum -2816..2696); 1023 = 1.0, -1023 = -1.0
// The 11-bit value is the exact result; its wider and narrower forms for the unit are below
// (eac11_to_unorm16 and the others).
//
// sRGB formats decode to the same UNORM8 bytes as their linear twins; the sRGB -> linear
// conversion belongs to the sampler (EtcFormatInfo::srgb says which formats need it).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "cmodel/texture.hpp"

namespace tfu {

inline constexpr int kEtcBlockDim = 4;  // texels per block side
inline constexpr int kEtcBlockTexels = 16;

// The ETC/EAC formats (kEtcFormats: names, GL names, block sizes).
enum class EtcFormat {
  Rgb8,
  Srgb8,
  Rgb8A1,
  Srgb8A1,
  Rgba8,
  Srgb8Alpha8,
  R11,
  R11Signed,
  Rg11,
  Rg11Signed,
};

struct EtcFormatInfo {
  EtcFormat format;
  const char* name;
  const char* gl_name;  // the GL internal format without its GL_ prefix
  int block_bytes;      // 8 or 16
  int channels;         // 3 (RGB), 4 (RGBA), 1 (R), 2 (RG)
  bool srgb;            // the RGB channels are sRGB-encoded (alpha never is)
  bool eac11;           // R11/RG11: 11-bit channels (decode_eac11_image)
  bool is_signed;       // signed R11/RG11
};
inline constexpr std::array<EtcFormatInfo, 10> kEtcFormats{{
    {EtcFormat::Rgb8, "etc2_rgb8", "COMPRESSED_RGB8_ETC2", 8, 3, false, false, false},
    {EtcFormat::Srgb8, "etc2_srgb8", "COMPRESSED_SRGB8_ETC2", 8, 3, true, false, false},
    {EtcFormat::Rgb8A1, "etc2_rgb8a1", "COMPRESSED_RGB8_PUNCHTHROUGH_ALPHA1_ETC2", 8, 4, false, false, false},
    {EtcFormat::Srgb8A1, "etc2_srgb8a1", "COMPRESSED_SRGB8_PUNCHTHROUGH_ALPHA1_ETC2", 8, 4, true, false, false},
    {EtcFormat::Rgba8, "etc2_rgba8", "COMPRESSED_RGBA8_ETC2_EAC", 16, 4, false, false, false},
    {EtcFormat::Srgb8Alpha8, "etc2_srgb8_alpha8", "COMPRESSED_SRGB8_ALPHA8_ETC2_EAC", 16, 4, true, false, false},
    {EtcFormat::R11, "eac_r11", "COMPRESSED_R11_EAC", 8, 1, false, true, false},
    {EtcFormat::R11Signed, "eac_r11_signed", "COMPRESSED_SIGNED_R11_EAC", 8, 1, false, true, true},
    {EtcFormat::Rg11, "eac_rg11", "COMPRESSED_RG11_EAC", 16, 2, false, true, false},
    {EtcFormat::Rg11Signed, "eac_rg11_signed", "COMPRESSED_SIGNED_RG11_EAC", 16, 2, false, true, true},
}};
constexpr bool etc_formats_in_enum_order() {
  for (size_t i = 0; i < kEtcFormats.size(); ++i)
    if (static_cast<size_t>(kEtcFormats[i].format) != i) return false;
  return true;
}
static_assert(etc_formats_in_enum_order(), "etc_format_info indexes kEtcFormats by the enum value");
constexpr const EtcFormatInfo& etc_format_info(EtcFormat f) { return kEtcFormats[static_cast<size_t>(f)]; }

// Spec tables (KDFS "Format RGB ETC2", "Format RGBA ETC2"): the one copy in the model.
// Individual/differential modifier pairs (a, b) by table codeword: +a, +b, -a, -b.
inline constexpr std::array<std::array<int, 2>, 8> kEtcModifiers{
    {{2, 8}, {5, 17}, {9, 29}, {13, 42}, {18, 60}, {24, 80}, {33, 106}, {47, 183}}};
// T and H mode distances by 3-bit index.
inline constexpr std::array<int, 8> kEtcDistances{3, 6, 11, 16, 23, 32, 41, 64};
// EAC modifier tables by 4-bit table index, indexed by the 3-bit pixel index.
inline constexpr std::array<std::array<int, 8>, 16> kEacModifiers{{
    {-3, -6, -9, -15, 2, 5, 8, 14},
    {-3, -7, -10, -13, 2, 6, 9, 12},
    {-2, -5, -8, -13, 1, 4, 7, 12},
    {-2, -4, -6, -13, 1, 3, 5, 12},
    {-3, -6, -8, -12, 2, 5, 7, 11},
    {-3, -7, -9, -11, 2, 6, 8, 10},
    {-4, -7, -8, -11, 3, 6, 7, 10},
    {-3, -5, -8, -11, 2, 4, 7, 10},
    {-2, -6, -8, -10, 1, 5, 7, 9},
    {-2, -5, -8, -10, 1, 4, 7, 9},
    {-2, -4, -8, -10, 1, 3, 7, 9},
    {-2, -5, -7, -10, 1, 4, 6, 9},
    {-3, -4, -7, -10, 2, 3, 6, 9},
    {-1, -2, -3, -10, 0, 1, 2, 9},
    {-4, -6, -8, -9, 3, 5, 7, 8},
    {-3, -5, -7, -9, 2, 4, 6, 8},
}};

// The colour block's mode (punchthrough: the RGB8A1 reading, where bit 33 is the opaque bit and
// there is no individual mode).
enum class Etc2Mode { Individual, Differential, T, H, Planar };
inline constexpr int kEtc2ModeCount = 5;
Etc2Mode etc2_block_mode(const uint8_t block[8], bool punchthrough);

// One block to 16 texels, out[4 * y + x].
void decode_etc2_rgb_block(const uint8_t block[8], Rgba8 out[16]);          // RGB8 (and ETC1), alpha 255
void decode_etc2_rgb8a1_block(const uint8_t block[8], Rgba8 out[16]);       // RGB8 punch-through alpha
void decode_etc2_rgba8_block(const uint8_t block[16], Rgba8 out[16]);       // EAC alpha + ETC2 colour
void decode_eac_alpha8_block(const uint8_t block[8], uint8_t out[16]);      // RGBA8's 8-bit EAC alpha
void decode_eac_r11_block(const uint8_t block[8], uint16_t out[16]);        // 0..2047
void decode_eac_r11_signed_block(const uint8_t block[8], int16_t out[16]);  // -1023..1023

// The 11-bit results in other widths (KDFS "Format Unsigned R11 EAC", "Format Signed R11 EAC"):
// 16 bits by the spec's bit replication; 8 bits (the unit's RGBA8 words) by rounding to nearest,
// exact in integers: 2047 and 1023 are odd, so v * 255 / 2047 and v * 127 / 1023 are never
// halfway. The spec forbids fewer than 11 bits for filtering; the 8-bit form is for the RGBA8
// texel word only, and docs/compressed-etc2.md records how Mesa's 8-bit read-back compares.
constexpr uint16_t eac11_to_unorm16(uint16_t v) { return static_cast<uint16_t>((v << 5) | (v >> 6)); }
constexpr int16_t eac11_signed_to_snorm16(int16_t v) {
  const int m = v < 0 ? -v : v;
  const int e = (m << 5) | (m >> 5);  // magnitude replicated without the sign bit, 0..32767
  return static_cast<int16_t>(v < 0 ? -e : e);
}
constexpr uint8_t eac11_to_unorm8(uint16_t v) { return static_cast<uint8_t>((v * 255 + 1023) / 2047); }
constexpr int8_t eac11_signed_to_snorm8(int16_t v) {
  const int m = v < 0 ? -v : v;
  const int e = (m * 127 + 511) / 1023;
  return static_cast<int8_t>(v < 0 ? -e : e);
}

// Whole images: width x height texels (1..kMaxTextureSize each) from ceil(width / 4) x
// ceil(height / 4) blocks, block rows top to bottom, blocks left to right in a row; partial edge
// blocks give only their texels inside the image. A block span of the wrong size, a size outside
// the range, or (decode_etc_image) a signed EAC format: InputError, one line.
// RGBA8 words, row-major from the top row. R11/RG11: (R, G or 0, 0, 255) with eac11_to_unorm8.
std::vector<Rgba8> decode_etc_image(EtcFormat f, int width, int height, std::span<const uint8_t> blocks);
// R11/RG11 only: the 11-bit values (0..2047 or -1023..1023), channels interleaved (R, G per texel
// for RG11), row-major.
std::vector<int16_t> decode_eac11_image(EtcFormat f, int width, int height, std::span<const uint8_t> blocks);
// Blocks in a width x height image of format f (the expected span size over block_bytes).
size_t etc_block_count(int width, int height);

// kEtcFormats as the Markdown table of docs/compressed-etc2.md, "Formats" (a test checks it is there).
std::string etc_formats_markdown();

}  // namespace tfu
