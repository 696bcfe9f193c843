// The programming interface of the texture filter unit: texture and sampler descriptors, as a driver
// writes them and as both models read them (the golden sampler and every block of the cycle model).
// One definition: the C++ structs below are the decoded view; their register encoding (32-bit words,
// fields, bit widths, reset values) is the field tables of descriptors.cpp, which `tfu descriptors`
// prints and docs/descriptors.md reproduces.
//
//   TextureDescriptor  where a texture lives in the texel memory (per-level address and row pitch),
//                      its format, size, level count and memory layout (linear or tiled)
//   SamplerDescriptor  how it is filtered: filter mode, wraps, border, LOD bias and clamps, cubic
//                      kernel and weight-ROM parameters, edge-preserving kernel-shape policy, and the
//                      anisotropy limit
//   Registers          the unit's descriptor tables: a request names a texture and a sampler by index
//
// Level selection (GL 4.6 Sec. 8.14) is a pure function of lambda and the two descriptors,
// `select_levels`, shared by both models.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <memory>

#include "cmodel/aniso.hpp"
#include "cmodel/block_formats.hpp"
#include "cmodel/datapath.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/weight_rom.hpp"

namespace tfu {

// ---- Filter modes ----
enum class BaseFilter { Nearest, Linear, Cubic, EdgePreserving };
enum class MipMode { None, Nearest, Linear };

struct FilterMode {
  BaseFilter base = BaseFilter::Linear;
  MipMode mip = MipMode::None;
  friend constexpr bool operator==(const FilterMode&, const FilterMode&) = default;
};
// "linear_mipmap_linear", "LINEAR-MIPMAP-LINEAR", "cubic", "edge_preserving_mipmap_linear", and the
// aliases "bilinear" (LINEAR) and "trilinear" (LINEAR_MIPMAP_LINEAR).
FilterMode filter_mode_from_name(const std::string& name);
std::string filter_mode_name(FilterMode m);  // canonical upper-case name
const std::vector<FilterMode>& all_filter_modes();

// Kernel names accepted by CUBIC modes: the kernels of kernels.hpp plus "bspline-interp" (the cubic
// B-spline applied to prefiltered coefficients so that it interpolates; Hadwiger 2004 Sec. 3.2).
inline constexpr const char* kBsplineInterp = "bspline-interp";
const std::vector<std::string>& cubic_kernel_names();
int cubic_kernel_index(const std::string& name);  // throws InputError listing the valid names

// Which of Lee & Jen's kernel shapes the edge-preserving filter uses (Sec. 3):
//   Cross       always the 12-texel cross (reads whatever lines it needs)
//   Static      cross / T / L from the centre square's position in the texture's tiles (one cache
//               line each): the kernel uses only texels of the lines the bilinear footprint reads. A
//               linear-layout texture has no tiles: Static uses the cross there.
//   CacheAware  Static, plus every arm whose lines are resident in the cache when the footprint
//               reaches it (decided by the cycle model's tag probe; the golden model alone, which has
//               no cache, uses Static and takes the cycle model's shapes for a compare)
enum class EdgeShape { Cross, Static, CacheAware };
inline constexpr EnumNames<EdgeShape, 4> kEdgeShapeNames{"kernel-shape policy",
                                                          {{{EdgeShape::Static, "static"},
                                                            {EdgeShape::CacheAware, "cache-aware"},
                                                            {EdgeShape::Cross, "cross"},
                                                            {EdgeShape::Cross, "full-cross", false}}}};
EdgeShape edge_shape_from_name(const std::string& name);  // kEdgeShapeNames ("full-cross": an alias of "cross")
const char* edge_shape_name(EdgeShape s);

struct SamplerDescriptor {
  FilterMode mode{};
  WrapMode wrap_s = WrapMode::Repeat, wrap_t = WrapMode::Repeat;
  Rgba8 border{0, 0, 0, 0};  // texel word used outside the texture with ClampToBorder
  LodParams lod{};
  std::string kernel = "catmull-rom";  // CUBIC kernel (register: its index in cubic_kernel_names())
  TileRomSpec cubic_rom{64, 8, SamplePos::Centre, RomRounding::SumPreserving};
  RomRecon cubic_recon = RomRecon::Nearest;
  // Hadwiger 2004 Sec. 3.2: fit the kernel to each selected level (true), or keep the level-0
  // kernel footprint in every level (false, for the quality comparison: the 4-texel-wide kernel then
  // covers 4 / 2^L texels of level L and degenerates towards nearest).
  bool cubic_level_adapt = true;
  EdgeShape edge_shape = EdgeShape::Static;
  // Anisotropic filtering (docs/anisotropic.md): probes per pixel at most, 1..16 (1 = isotropic),
  // and the rounding of the probe count N (any integer, or up to a power of two), and the probe
  // threshold t (0..7; 0 = the spec's N; AnisoParams), and the axis lengths (the spec's screen
  // axes or the footprint ellipse's axes).
  int max_aniso = 1;
  AnisoRounding aniso_rounding = AnisoRounding::Integer;
  int aniso_threshold = 0;
  AnisoAxes aniso_axes = AnisoAxes::Screen;
  // Model option, not a register (no effect on results): evaluate the CUBIC tile-weight multipliers
  // once per ROM address pair instead of per sample (nearest reconstruction, R <= 128).
  bool memoize_cubic_weights = true;

  void validate() const;  // throws InputError naming the field
  // Anisotropic: max_aniso > 1 on a MIP-mapped mode. A mode without MIP-mapping has no lambda to
  // lower (GL: level 0 whatever the footprint), so it ignores max_aniso and filters isotropically.
  bool anisotropic() const { return max_aniso > 1 && mode.mip != MipMode::None; }
  // What the LOD unit reads: max_aniso (1 unless anisotropic()), aniso_rounding, aniso_threshold
  // and aniso_axes.
  AnisoParams aniso() const { return {anisotropic() ? max_aniso : 1, aniso_rounding, aniso_threshold, aniso_axes}; }
  friend bool operator==(const SamplerDescriptor&, const SamplerDescriptor&) = default;
};

// Whether a filter is defined on a format: EDGE_PRESERVING's edge detector and luminance keys are
// Lee & Jen's, on 8-bit channels (edge_filter.hpp), not on SRGBA8's linear unorm12 channels.
constexpr bool filters_format(BaseFilter b, TexelFormat f) {
  return !(b == BaseFilter::EdgePreserving && f == TexelFormat::SRGBA8);
}

// What a texture's words hold: its texels, or (bspline-interp) the prefiltered B-spline coefficient
// codes, decoded by the cubic normalise stage with the scale S and bias B registers (Q.12).
enum class TextureContent { Texels, BsplineCoefficients };

inline constexpr int kMaxLevels = 15;          // 16384 x 16384 has 15 levels
inline constexpr uint64_t kLevelAlign = 256;   // every level (and every linear row) starts on 256 bytes
inline constexpr int kAddressBits = 40;        // texel memory byte addresses are below 2^40

struct LevelDescriptor {
  uint64_t address = 0;    // byte address of texel (0, 0), a multiple of kLevelAlign
  uint32_t row_pitch = 0;  // bytes from one texel row (linear), tile row (tiled) or block row (compressed) to the next
  friend constexpr bool operator==(const LevelDescriptor&, const LevelDescriptor&) = default;
};

struct TextureDescriptor {
  TexelFormat format = TexelFormat::RGBA8;
  int width = 1, height = 1;
  int levels = 1;  // stored levels, 1..kMaxLevels (a chain may stop before 1 x 1)
  MemoryLayout layout = MemoryLayout::Tiled;
  int tile_log2 = 2;  // tiled: tile side 2^tile_log2 texels (tile bytes = 4^tile_log2 bytes_per_texel)
  std::array<LevelDescriptor, kMaxLevels> level{};
  TextureContent content = TextureContent::Texels;
  int64_t coeff_scale_q = 0, coeff_bias_q = 0;  // S, B of bspline coefficients (Q.12), else 0
  // Block-compressed (cmodel/block_formats.hpp): the level holds blocks of `block_format`, row-major,
  // each block row starting row_pitch bytes after the previous (whatever `layout` says); the unit
  // decodes them with `decode` (BC1-BC5 interpolation rules, sRGB for ASTC) to RGBA8 words, so
  // `format` is RGBA8. Only unsigned formats (unit_filterable).
  bool compressed = false;
  BlockFormat block_format = BlockFormat::BC1;
  BlockDecodeRules decode{};

  uint64_t base() const { return level[0].address; }  // the base address: level 0
  int level_width(int l) const { return mip_extent(width, l); }
  int level_height(int l) const { return mip_extent(height, l); }
  int tile_side() const { return 1 << tile_log2; }
  int tile_bytes() const { return bytes_per_texel(format) << (2 * tile_log2); }
  const BlockFormatInfo& block() const { return block_format_info(block_format); }
  // Bytes a level occupies (rows or tile rows times the pitch).
  uint64_t level_bytes(int l) const;
  // Byte address of texel (x, y) of level l (inside the level); of its block when compressed:
  // block_address(l, x / block_w, y / block_h).
  uint64_t texel_address(int l, int x, int y) const;
  // Compressed: byte address of block (bx, by) of level l (block column, block row inside the
  // level): the level's address + by row_pitch + bx block_bytes.
  uint64_t block_address(int l, int bx, int by) const {
    const LevelDescriptor& d = level[static_cast<size_t>(l)];
    return d.address + static_cast<uint64_t>(by) * d.row_pitch +
           static_cast<uint64_t>(bx) * static_cast<uint64_t>(block().block_bytes);
  }
  void validate(const std::string& what) const;  // throws InputError naming `what` and the field
  friend bool operator==(const TextureDescriptor&, const TextureDescriptor&) = default;
};

// The descriptor tables of a unit: a request's texture index selects textures[i], its sampler
// index samplers[j]. Index fields are 12 bits (texture) and 8 bits (sampler) wide.
inline constexpr size_t kMaxTextureDescriptors = 4096, kMaxSamplerDescriptors = 256;
struct Registers {
  std::vector<TextureDescriptor> textures;
  std::vector<SamplerDescriptor> samplers;
  void validate() const;  // sizes, every descriptor
};

// ---- Level selection (GL 4.6 Sec. 8.14), shared by the golden sampler and the address generator ----
// lambda_clamped_q8 (lambda after bias and clamp, Q.8) -> the level(s) and the blend weight; `last` is the last level.
struct LevelPick {
  int level0 = 0, level1 = 0;  // level1 == level0 unless blending
  int blend = 0;               // weight of level1 (Q.8), 0 unless MipMode::Linear between two levels
};
constexpr LevelPick select_levels(int32_t lambda_clamped_q8, MipMode mip, int last) {
  LevelPick p;
  if (lambda_clamped_q8 <= 0) return p;  // c = 0: the magnification filter is the mode's first word
  switch (mip) {
    case MipMode::None: break;
    case MipMode::Nearest: {
      // d = lambda <= 1/2 ? 0 : ceil(lambda + 1/2) - 1
      const int d = lambda_clamped_q8 <= 128 ? 0 : (lambda_clamped_q8 + 127) >> kLodFracBits;
      p.level0 = p.level1 = d < last ? d : last;
      break;
    }
    case MipMode::Linear:
      if (lambda_clamped_q8 >= (last << kLodFracBits)) {
        p.level0 = p.level1 = last;
      } else {
        p.level0 = lambda_clamped_q8 >> kLodFracBits;
        p.level1 = p.level0 + 1;
        p.blend = lambda_clamped_q8 & 255;
      }
      break;
  }
  return p;
}
// The same from lambda before bias and clamp, with the sampler's LOD registers.
constexpr LevelPick select_levels(int32_t lambda_q8, const SamplerDescriptor& s, int last) {
  return select_levels(lambda_bias_clamp(lambda_q8, s.lod), s.mode.mip, last);
}

// ---- What the descriptors configure in the cubic datapath (both models build it with these) ----
// The tile-weight ROM of a CUBIC sampler: its kernel (the cubic B-spline for bspline-interp) sampled
// by its ROM fields (weight_rom.hpp); InputError for a kernel wider than the 4 x 4 footprint.
std::unique_ptr<TileWeightRom> make_cubic_rom(const SamplerDescriptor& s);
// The normalise stage's registers for a ROM of `rom_bits` and a texture: M = 2^b - 1, the format's
// channel range, and for B-spline coefficient textures the decode with S and B (dp::cubic_normalize).
dp::CubicNormalize cubic_normalize_registers(unsigned rom_bits, const TextureDescriptor& t);

// ---- Register encoding ----
// One field of a descriptor's register words: bits [lsb, lsb + width) of word `word` (+ `stride`
// per element for array fields of `count` elements).
struct RegisterField {
  const char* name;
  int word, lsb, width;
  int count, stride;  // array fields (per level); 1, 0 otherwise
  const char* meaning;
};
std::span<const RegisterField> texture_descriptor_fields();
std::span<const RegisterField> sampler_descriptor_fields();
inline constexpr int kTextureDescriptorWords = 34, kSamplerDescriptorWords = 6;

std::array<uint32_t, kTextureDescriptorWords> encode(const TextureDescriptor& d);
std::array<uint32_t, kSamplerDescriptorWords> encode(const SamplerDescriptor& d);
TextureDescriptor decode_texture_descriptor(std::span<const uint32_t, kTextureDescriptorWords> w);
SamplerDescriptor decode_sampler_descriptor(std::span<const uint32_t, kSamplerDescriptorWords> w);
// The field tables as Markdown (field, word, bits, reset value, meaning): docs/descriptors.md.
std::string descriptor_tables_markdown();

}  // namespace tfu
