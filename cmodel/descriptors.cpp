#include "cmodel/descriptors.hpp"

#include <algorithm>
#include <cctype>
#include <tuple>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/nearest_name.hpp"
#include "cmodel/kernels.hpp"
#include "cmodel/unorm.hpp"

namespace tfu {

// ---------------------------------------------------------------- names
namespace {
const char* base_name(BaseFilter b) {
  switch (b) {
    case BaseFilter::Nearest: return "NEAREST";
    case BaseFilter::Linear: return "LINEAR";
    case BaseFilter::Cubic: return "CUBIC";
    case BaseFilter::EdgePreserving: return "EDGE_PRESERVING";
  }
  return "?";
}
}  // namespace

FilterMode filter_mode_from_name(const std::string& name) {
  std::string n;
  for (char ch : name) n += ch == '-' ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  if (n == "BILINEAR") return {BaseFilter::Linear, MipMode::None};
  if (n == "TRILINEAR") return {BaseFilter::Linear, MipMode::Linear};
  for (const FilterMode& m : all_filter_modes())
    if (filter_mode_name(m) == n) return m;
  std::string list;
  std::vector<std::string> accepted{"bilinear", "trilinear"};
  for (const FilterMode& m : all_filter_modes()) {
    list += (list.empty() ? "" : ", ") + filter_mode_name(m);
    accepted.push_back(filter_mode_name(m));
  }
  throw InputError(fmt::format("unknown filter '{}' ({}expected one of {}, or bilinear, trilinear)", quote_input(name),
                               did_you_mean(name, accepted), list));
}

std::string filter_mode_name(FilterMode m) {
  std::string s = base_name(m.base);
  if (m.mip == MipMode::Nearest) s += "_MIPMAP_NEAREST";
  if (m.mip == MipMode::Linear) s += "_MIPMAP_LINEAR";
  return s;
}

const std::vector<FilterMode>& all_filter_modes() {
  static const std::vector<FilterMode> modes = [] {
    std::vector<FilterMode> v;
    for (BaseFilter b : {BaseFilter::Nearest, BaseFilter::Linear, BaseFilter::Cubic, BaseFilter::EdgePreserving})
      for (MipMode m : {MipMode::None, MipMode::Nearest, MipMode::Linear}) v.push_back({b, m});
    return v;
  }();
  return modes;
}

const std::vector<std::string>& cubic_kernel_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v = FilterKernel::names();
    v.emplace_back(kBsplineInterp);
    return v;
  }();
  return names;
}

int cubic_kernel_index(const std::string& name) {
  const auto& names = cubic_kernel_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it != names.end()) return static_cast<int>(it - names.begin());
  std::string list;
  for (const auto& k : names) list += (list.empty() ? "" : ", ") + k;
  throw InputError(fmt::format("unknown kernel '{}' ({}valid: {})", quote_input(name), did_you_mean(name, names), list));
}

EdgeShape edge_shape_from_name(const std::string& name) { return kEdgeShapeNames.from_name(name); }
const char* edge_shape_name(EdgeShape s) { return kEdgeShapeNames.name(s); }

// ---------------------------------------------------------------- validation
namespace {
constexpr int32_t kLodLimitQ8 = 1000 * 256;  // LOD registers are 20-bit signed Q.8: within +-1000 levels
}

void SamplerDescriptor::validate() const {
  cubic_kernel_index(kernel);
  cubic_rom.validate();
  for (const auto& [name, v] : {std::pair{"lod_bias", lod.bias_q8}, {"min_lod", lod.min_lod_q8}, {"max_lod", lod.max_lod_q8}})
    if (v < -kLodLimitQ8 || v > kLodLimitQ8)
      throw InputError(fmt::format("sampler {} {}/256 outside -1000..1000 levels", name, v));
  if (lod.min_lod_q8 > lod.max_lod_q8) throw InputError("sampler min_lod is above max_lod");
  if (max_aniso < 1 || max_aniso > 16) throw InputError(fmt::format("sampler max_aniso {} outside 1..16", max_aniso));
  if (aniso_threshold < 0 || aniso_threshold > kAnisoThresholdMax)
    throw InputError(fmt::format("sampler aniso_threshold {} outside 0..{}", aniso_threshold, kAnisoThresholdMax));
}

uint64_t TextureDescriptor::level_bytes(int l) const {
  const int h = level_height(l);
  if (compressed) return static_cast<uint64_t>(blocks_down(block_format, h)) * level[static_cast<size_t>(l)].row_pitch;
  const uint64_t rows = layout == MemoryLayout::Tiled ? static_cast<uint64_t>((h + tile_side() - 1) >> tile_log2)
                                                      : static_cast<uint64_t>(h);
  return rows * level[static_cast<size_t>(l)].row_pitch;
}

uint64_t TextureDescriptor::texel_address(int l, int x, int y) const {
  const LevelDescriptor& d = level[static_cast<size_t>(l)];
  const auto bpt = static_cast<uint64_t>(bytes_per_texel(format));
  if (compressed) return block_address(l, x / block().block_w, y / block().block_h);
  if (layout == MemoryLayout::Linear)
    return d.address + static_cast<uint64_t>(y) * d.row_pitch + static_cast<uint64_t>(x) * bpt;
  const int k = tile_log2, m = (1 << k) - 1;
  const uint64_t tile = d.address + static_cast<uint64_t>(y >> k) * d.row_pitch +
                        static_cast<uint64_t>(x >> k) * static_cast<uint64_t>(tile_bytes());
  return tile + (static_cast<uint64_t>(((y & m) << k) | (x & m)) * bpt);
}

void TextureDescriptor::validate(const std::string& what) const {
  const auto fail = [&what](const std::string& msg) { throw InputError(fmt::format("{}: {}", what, msg)); };
  if (width < 1 || height < 1 || width > kMaxTextureSize || height > kMaxTextureSize)
    fail(fmt::format("size {}x{} outside 1..{} per side", width, height, kMaxTextureSize));
  if (levels < 1 || levels > mip_level_count(width, height))
    fail(fmt::format("{} levels, a {}x{} chain has 1..{}", levels, width, height, mip_level_count(width, height)));
  if (layout == MemoryLayout::Tiled && !valid_tile_bytes(tile_bytes()))
    fail(fmt::format("tile side 2^{} of {} is {} bytes (expected 64, 256 or 1024)", tile_log2, texel_format_name(format),
                     tile_bytes()));
  if (content == TextureContent::BsplineCoefficients && (format != TexelFormat::RGBA8 || coeff_scale_q <= 0))
    fail("B-spline coefficients need rgba8 codes and a positive scale");
  if (compressed && ((format != TexelFormat::RGBA8 && format != TexelFormat::SRGBA8) ||
                     content != TextureContent::Texels || !unit_filterable(block_format)))
    fail(fmt::format("compressed {} needs rgba8 or srgba8 texels of an unsigned format",
                     block_format_name(block_format)));
  for (int l = 0; l < levels; ++l) {
    const LevelDescriptor& d = level[static_cast<size_t>(l)];
    const uint64_t min_pitch =
        compressed ? static_cast<uint64_t>(blocks_across(block_format, level_width(l))) *
                         static_cast<uint64_t>(block().block_bytes)
        : layout == MemoryLayout::Tiled
            ? static_cast<uint64_t>((level_width(l) + tile_side() - 1) >> tile_log2) *
                  static_cast<uint64_t>(tile_bytes())
            : static_cast<uint64_t>(level_width(l)) * static_cast<uint64_t>(bytes_per_texel(format));
    if (d.address % kLevelAlign != 0 || d.row_pitch % kLevelAlign != 0 || d.row_pitch < min_pitch ||
        d.address >= (uint64_t{1} << kAddressBits))
      fail(fmt::format("level {}: address {:#x} / row pitch {} (needs 256-byte alignment, below 2^40, pitch >= {})", l,
                       d.address, d.row_pitch, min_pitch));
  }
}

void Registers::validate() const {
  if (textures.empty() || textures.size() > kMaxTextureDescriptors)
    throw InputError(fmt::format("{} texture descriptors (1..{})", textures.size(), kMaxTextureDescriptors));
  if (samplers.empty() || samplers.size() > kMaxSamplerDescriptors)
    throw InputError(fmt::format("{} sampler descriptors (1..{})", samplers.size(), kMaxSamplerDescriptors));
  for (size_t i = 0; i < textures.size(); ++i) textures[i].validate(fmt::format("texture descriptor {}", i));
  for (size_t i = 0; i < samplers.size(); ++i) {
    try {
      samplers[i].validate();
    } catch (const InputError& e) {
      throw InputError(fmt::format("sampler descriptor {}: {}", i, e.what()));
    }
  }
}

std::unique_ptr<TileWeightRom> make_cubic_rom(const SamplerDescriptor& s) {
  s.cubic_rom.validate();
  const FilterKernel kernel = s.kernel == kBsplineInterp ? FilterKernel::bspline() : FilterKernel::by_name(s.kernel);
  if (kernel.width() > 4) throw InputError(fmt::format("kernel '{}' is wider than the 4x4 CUBIC footprint", s.kernel));
  return std::make_unique<TileWeightRom>(kernel, s.cubic_rom);
}

dp::CubicNormalize cubic_normalize_registers(unsigned rom_bits, const TextureDescriptor& t) {
  dp::CubicNormalize n;
  n.M = static_cast<int64_t>(unorm::max_code(rom_bits));
  const TexelFormat f = t.content == TextureContent::BsplineCoefficients ? TexelFormat::RGBA8 : t.format;
  std::tie(n.lo, n.hi) = channel_range(f);
  n.prefiltered = t.content == TextureContent::BsplineCoefficients;
  n.scale_q = t.coeff_scale_q;
  n.bias_q = t.coeff_bias_q;
  return n;
}

// ---------------------------------------------------------------- register encoding
namespace {

// A field of descriptor D: its place in the words and how the struct holds it (raw field bits).
template <class D>
struct Codec {
  RegisterField field;
  uint32_t (*get)(const D&, int index);
  void (*set)(D&, int index, uint32_t bits);
};

constexpr uint32_t sext_mask(int32_t v, int width) { return static_cast<uint32_t>(v) & ((width == 32 ? 0 : (1u << width)) - 1u); }
constexpr int32_t sext(uint32_t bits, int width) {
  const uint32_t sign = 1u << (width - 1);
  return static_cast<int32_t>((bits ^ sign) - sign);
}
template <class E>
constexpr uint32_t u(E e) { return static_cast<uint32_t>(e); }

using TD = TextureDescriptor;
// The block_format codes, from the one table (cmodel/block_formats.hpp): 0 none, 1 + table index.
const char* block_format_meaning() {
  static const std::string m = [] {
    std::string s = "compressed levels: 0 none (the format's texels), else the block format";
    for (size_t i = 0; i < kBlockFormats.size(); ++i)
      if (unit_filterable(kBlockFormats[i].format))
        s += fmt::format("{} {} {}", i == 0 ? ":" : ",", i + 1, kBlockFormats[i].name);
    return s + " (signed formats are not filtered)";
  }();
  return m.c_str();
}
template <class E, size_t N>
const char* bc_rule_meaning(const EnumNames<E, N>& names, const char* what) {
  static const std::string m = [&] {
    std::string s = fmt::format("{}:", what);
    for (size_t i = 0; i < N; ++i)
      s += fmt::format("{} {} {}", i == 0 ? "" : ",", static_cast<int>(names.entries[i].value), names.entries[i].name);
    return s;
  }();
  return m.c_str();
}
const std::vector<Codec<TD>>& texture_codecs() {
  static const std::vector<Codec<TD>> c = {
      {{"format", 0, 0, 2, 1, 0,
        "texel format: 0 rgba8, 1 l8, 2 vs16x2, 3 srgba8 (R, G, B decoded to linear before filtering)"},
       [](const TD& d, int) { return u(d.format); },
       [](TD& d, int, uint32_t b) { d.format = static_cast<TexelFormat>(b); }},
      {{"layout", 0, 2, 1, 1, 0, "memory layout: 0 linear rows, 1 tiled (one tile = one cache line)"},
       [](const TD& d, int) { return u(d.layout); },
       [](TD& d, int, uint32_t b) { d.layout = static_cast<MemoryLayout>(b); }},
      {{"tile_log2", 0, 3, 4, 1, 0, "tiled: log2 of the tile side in texels"},
       [](const TD& d, int) { return static_cast<uint32_t>(d.tile_log2); },
       [](TD& d, int, uint32_t b) { d.tile_log2 = static_cast<int>(b); }},
      {{"levels_m1", 0, 7, 4, 1, 0, "stored levels minus 1"},
       [](const TD& d, int) { return static_cast<uint32_t>(d.levels - 1); },
       [](TD& d, int, uint32_t b) { d.levels = static_cast<int>(b) + 1; }},
      {{"content", 0, 11, 1, 1, 0, "0 texels, 1 B-spline coefficient codes (bspline-interp)"},
       [](const TD& d, int) { return u(d.content); },
       [](TD& d, int, uint32_t b) { d.content = static_cast<TextureContent>(b); }},
      {{"width_m1", 1, 0, 14, 1, 0, "level-0 width minus 1"},
       [](const TD& d, int) { return static_cast<uint32_t>(d.width - 1); },
       [](TD& d, int, uint32_t b) { d.width = static_cast<int>(b) + 1; }},
      {{"height_m1", 1, 14, 14, 1, 0, "level-0 height minus 1"},
       [](const TD& d, int) { return static_cast<uint32_t>(d.height - 1); },
       [](TD& d, int, uint32_t b) { d.height = static_cast<int>(b) + 1; }},
      {{"level_address", 2, 0, 32, kMaxLevels, 2, "level L: byte address / 256 (level 0: the base address)"},
       [](const TD& d, int i) { return static_cast<uint32_t>(d.level[static_cast<size_t>(i)].address >> 8); },
       [](TD& d, int i, uint32_t b) { d.level[static_cast<size_t>(i)].address = uint64_t{b} << 8; }},
      {{"level_row_pitch", 3, 0, 24, kMaxLevels, 2,
        "level L: bytes from one texel row (linear) or tile row (tiled) to the next"},
       [](const TD& d, int i) { return d.level[static_cast<size_t>(i)].row_pitch; },
       [](TD& d, int i, uint32_t b) { d.level[static_cast<size_t>(i)].row_pitch = b; }},
      {{"block_format", 0, 12, 5, 1, 0, block_format_meaning()},
       [](const TD& d, int) { return d.compressed ? 1u + u(d.block_format) : 0u; },
       [](TD& d, int, uint32_t b) {
         if (b > kBlockFormats.size()) throw InputError(fmt::format("block_format {} is not a block-format code", b));
         d.compressed = b != 0;
         d.block_format = b != 0 ? static_cast<BlockFormat>(b - 1) : BlockFormat::BC1;
       }},
      {{"srgb", 0, 17, 1, 1, 0,
        "compressed: sRGB-encoded texels (ASTC decodes them by the sRGB rule; the filter sees the stored bytes)"},
       [](const TD& d, int) { return uint32_t{d.decode.srgb}; },
       [](TD& d, int, uint32_t b) { d.decode.srgb = b != 0; }},
      {{"bc_colour_rule", 0, 18, 2, 1, 0, bc_rule_meaning(kBc1InterpolationNames, "BC1-BC3 colour interpolation")},
       [](const TD& d, int) { return u(d.decode.bc.colour); },
       [](TD& d, int, uint32_t b) { d.decode.bc.colour = static_cast<Bc1Interpolation>(b); }},
      {{"bc_alpha_rule", 0, 20, 1, 1, 0,
        bc_rule_meaning(kBc4InterpolationNames, "BC3-BC5 alpha / red / green interpolation")},
       [](const TD& d, int) { return u(d.decode.bc.alpha); },
       [](TD& d, int, uint32_t b) { d.decode.bc.alpha = static_cast<Bc4Interpolation>(b); }},
      {{"coeff_scale", 32, 0, 32, 1, 0, "B-spline coefficients: scale S (Q.12, two's complement)"},
       [](const TD& d, int) { return sext_mask(static_cast<int32_t>(d.coeff_scale_q), 32); },
       [](TD& d, int, uint32_t b) { d.coeff_scale_q = sext(b, 32); }},
      {{"coeff_bias", 33, 0, 32, 1, 0, "B-spline coefficients: bias B (Q.12, two's complement)"},
       [](const TD& d, int) { return sext_mask(static_cast<int32_t>(d.coeff_bias_q), 32); },
       [](TD& d, int, uint32_t b) { d.coeff_bias_q = sext(b, 32); }},
  };
  return c;
}

using SD = SamplerDescriptor;
const std::vector<Codec<SD>>& sampler_codecs() {
  static const std::vector<Codec<SD>> c = {
      {{"base_filter", 0, 0, 2, 1, 0, "0 NEAREST, 1 LINEAR, 2 CUBIC, 3 EDGE_PRESERVING"},
       [](const SD& d, int) { return u(d.mode.base); }, [](SD& d, int, uint32_t b) { d.mode.base = static_cast<BaseFilter>(b); }},
      {{"mip_mode", 0, 2, 2, 1, 0, "0 none, 1 MIPMAP_NEAREST, 2 MIPMAP_LINEAR"},
       [](const SD& d, int) { return u(d.mode.mip); }, [](SD& d, int, uint32_t b) { d.mode.mip = static_cast<MipMode>(b); }},
      {{"wrap_s", 0, 4, 2, 1, 0, "0 repeat, 1 mirrored-repeat, 2 clamp-to-edge, 3 clamp-to-border"},
       [](const SD& d, int) { return u(d.wrap_s); }, [](SD& d, int, uint32_t b) { d.wrap_s = static_cast<WrapMode>(b); }},
      {{"wrap_t", 0, 6, 2, 1, 0, "as wrap_s"},
       [](const SD& d, int) { return u(d.wrap_t); }, [](SD& d, int, uint32_t b) { d.wrap_t = static_cast<WrapMode>(b); }},
      {{"edge_shape", 0, 8, 2, 1, 0, "edge-preserving kernel shapes: 0 cross, 1 static T/L, 2 cache-aware"},
       [](const SD& d, int) { return u(d.edge_shape); }, [](SD& d, int, uint32_t b) { d.edge_shape = static_cast<EdgeShape>(b); }},
      {{"cubic_kernel", 0, 10, 4, 1, 0, "index into: box, tent, bspline, catmull-rom, mitchell, kaiser, blackman, bspline-interp"},
       [](const SD& d, int) { return static_cast<uint32_t>(cubic_kernel_index(d.kernel)); },
       [](SD& d, int, uint32_t b) {
         const auto& n = cubic_kernel_names();
         if (b >= n.size()) throw InputError(fmt::format("cubic_kernel {} is not a kernel index", b));
         d.kernel = n[b];
       }},
      {{"rom_samples_m1", 0, 14, 9, 1, 0, "weight ROM: samples per tile R minus 1 (R = 16..512)"},
       [](const SD& d, int) { return static_cast<uint32_t>(d.cubic_rom.samples - 1); },
       [](SD& d, int, uint32_t b) { d.cubic_rom.samples = static_cast<int>(b) + 1; }},
      {{"rom_bits", 0, 23, 5, 1, 0, "weight ROM: magnitude bits b (4..16)"},
       [](const SD& d, int) { return d.cubic_rom.bits; }, [](SD& d, int, uint32_t b) { d.cubic_rom.bits = b; }},
      {{"rom_corner", 0, 28, 1, 1, 0, "weight ROM sample positions: 0 tile centres, 1 corners"},
       [](const SD& d, int) { return u(d.cubic_rom.pos); }, [](SD& d, int, uint32_t b) { d.cubic_rom.pos = static_cast<SamplePos>(b); }},
      {{"rom_sum_preserving", 0, 29, 1, 1, 0, "weight ROM rounding: 0 nearest, 1 sum-preserving"},
       [](const SD& d, int) { return u(d.cubic_rom.rounding); },
       [](SD& d, int, uint32_t b) { d.cubic_rom.rounding = static_cast<RomRounding>(b); }},
      {{"rom_linear", 0, 30, 1, 1, 0, "weight reconstruction between ROM entries: 0 nearest, 1 linear"},
       [](const SD& d, int) { return u(d.cubic_recon); }, [](SD& d, int, uint32_t b) { d.cubic_recon = static_cast<RomRecon>(b); }},
      {{"cubic_level_adapt", 0, 31, 1, 1, 0, "cubic kernel fitted to each level (1) or kept at its level-0 footprint (0)"},
       [](const SD& d, int) { return uint32_t{d.cubic_level_adapt}; }, [](SD& d, int, uint32_t b) { d.cubic_level_adapt = b != 0; }},
      {{"border", 1, 0, 32, 1, 0, "border texel word: R [7:0], G [15:8], B [23:16], A [31:24]"},
       [](const SD& d, int) {
         return uint32_t{d.border.r} | uint32_t{d.border.g} << 8 | uint32_t{d.border.b} << 16 | uint32_t{d.border.a} << 24;
       },
       [](SD& d, int, uint32_t b) {
         d.border = {static_cast<uint8_t>(b), static_cast<uint8_t>(b >> 8), static_cast<uint8_t>(b >> 16),
                     static_cast<uint8_t>(b >> 24)};
       }},
      {{"lod_bias", 2, 0, 20, 1, 0, "LOD bias, signed Q.8 levels"},
       [](const SD& d, int) { return sext_mask(d.lod.bias_q8, 20); }, [](SD& d, int, uint32_t b) { d.lod.bias_q8 = sext(b, 20); }},
      {{"min_lod", 3, 0, 20, 1, 0, "lower clamp of lambda, signed Q.8"},
       [](const SD& d, int) { return sext_mask(d.lod.min_lod_q8, 20); }, [](SD& d, int, uint32_t b) { d.lod.min_lod_q8 = sext(b, 20); }},
      {{"max_lod", 4, 0, 20, 1, 0, "upper clamp of lambda, signed Q.8"},
       [](const SD& d, int) { return sext_mask(d.lod.max_lod_q8, 20); }, [](SD& d, int, uint32_t b) { d.lod.max_lod_q8 = sext(b, 20); }},
      {{"max_aniso_m1", 5, 0, 4, 1, 0, "maximum anisotropy minus 1 (probes per pixel, 1..16)"},
       [](const SD& d, int) { return static_cast<uint32_t>(d.max_aniso - 1); },
       [](SD& d, int, uint32_t b) { d.max_aniso = static_cast<int>(b) + 1; }},
      {{"aniso_rounding", 5, 4, 1, 1, 0, "probe count N: 0 any integer, 1 rounded up to a power of two"},
       [](const SD& d, int) { return u(d.aniso_rounding); },
       [](SD& d, int, uint32_t b) { d.aniso_rounding = static_cast<AnisoRounding>(b); }},
      {{"aniso_threshold", 5, 5, 3, 1, 0, "probe threshold t: N = ceil(Pmax / ((1 + t/8) Pmin)), 0 the spec's N"},
       [](const SD& d, int) { return static_cast<uint32_t>(d.aniso_threshold); },
       [](SD& d, int, uint32_t b) { d.aniso_threshold = static_cast<int>(b); }},
      {{"aniso_axes", 5, 8, 1, 1, 0, "axis lengths: 0 Px, Py along the screen axes (the EXT spec), 1 the footprint ellipse's axes"},
       [](const SD& d, int) { return u(d.aniso_axes); },
       [](SD& d, int, uint32_t b) { d.aniso_axes = static_cast<AnisoAxes>(b); }},
  };
  return c;
}

template <class D>
std::vector<RegisterField> fields_of(const std::vector<Codec<D>>& codecs) {
  std::vector<RegisterField> f;
  for (const auto& c : codecs) f.push_back(c.field);
  return f;
}

template <class D, size_t N>
std::array<uint32_t, N> encode_with(const std::vector<Codec<D>>& codecs, const D& d) {
  std::array<uint32_t, N> w{};
  for (const auto& c : codecs)
    for (int i = 0; i < c.field.count; ++i) {
      const uint32_t mask = c.field.width == 32 ? ~0u : (1u << c.field.width) - 1u;
      const uint32_t bits = c.get(d, i);
      if ((bits & ~mask) != 0)
        throw InputError(fmt::format("descriptor field {} value {:#x} does not fit {} bits", c.field.name, bits, c.field.width));
      w[static_cast<size_t>(c.field.word + i * c.field.stride)] |= bits << c.field.lsb;
    }
  return w;
}

template <class D, size_t N>
D decode_with(const std::vector<Codec<D>>& codecs, std::span<const uint32_t, N> w) {
  D d;
  for (const auto& c : codecs)
    for (int i = 0; i < c.field.count; ++i) {
      const uint32_t mask = c.field.width == 32 ? ~0u : (1u << c.field.width) - 1u;
      c.set(d, i, (w[static_cast<size_t>(c.field.word + i * c.field.stride)] >> c.field.lsb) & mask);
    }
  return d;
}

template <class D>
std::string table_markdown(const std::vector<Codec<D>>& codecs) {
  const D reset{};
  std::string md = "| field | word | bits | reset | meaning |\n|---|---:|---|---:|---|\n";
  for (const auto& c : codecs) {
    const auto& f = c.field;
    const std::string word = f.count > 1 ? fmt::format("{} + {} L", f.word, f.stride) : fmt::format("{}", f.word);
    const std::string bits = f.width == 1 ? fmt::format("[{}]", f.lsb) : fmt::format("[{}:{}]", f.lsb + f.width - 1, f.lsb);
    md += fmt::format("| `{}`{} | {} | {} | {:#x} | {} |\n", f.name, f.count > 1 ? fmt::format("[L], L < {}", f.count) : "",
                      word, bits, c.get(reset, 0), f.meaning);
  }
  return md;
}

}  // namespace

std::span<const RegisterField> texture_descriptor_fields() {
  static const std::vector<RegisterField> f = fields_of(texture_codecs());
  return f;
}
std::span<const RegisterField> sampler_descriptor_fields() {
  static const std::vector<RegisterField> f = fields_of(sampler_codecs());
  return f;
}

std::array<uint32_t, kTextureDescriptorWords> encode(const TextureDescriptor& d) {
  return encode_with<TD, kTextureDescriptorWords>(texture_codecs(), d);
}
std::array<uint32_t, kSamplerDescriptorWords> encode(const SamplerDescriptor& d) {
  return encode_with<SD, kSamplerDescriptorWords>(sampler_codecs(), d);
}
TextureDescriptor decode_texture_descriptor(std::span<const uint32_t, kTextureDescriptorWords> w) {
  return decode_with<TD, kTextureDescriptorWords>(texture_codecs(), w);
}
SamplerDescriptor decode_sampler_descriptor(std::span<const uint32_t, kSamplerDescriptorWords> w) {
  return decode_with<SD, kSamplerDescriptorWords>(sampler_codecs(), w);
}

std::string descriptor_tables_markdown() {
  return fmt::format("### Texture descriptor ({} words of 32 bits)\n\n{}\n### Sampler descriptor ({} words of 32 bits)\n\n{}",
                     kTextureDescriptorWords, table_markdown(texture_codecs()), kSamplerDescriptorWords,
                     table_markdown(sampler_codecs()));
}

}  // namespace tfu
