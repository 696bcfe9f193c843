// The golden texture sampler: every filter mode, bit-accurate, untimed (no notion of cycles).
//
// Interface: sample(s, t, lambda) with s, t as FP32 and lambda from the LOD unit (lod.hpp, Q.8);
// sample_batch(requests) gives the same for a quad's (or any number of) requests at once.
// Anisotropic samplers (SamplerDescriptor::anisotropic()) take the LOD unit's whole result instead,
// sample(s, t, AnisoLod) (aniso.hpp: lambda, the probe count N and the major derivative vector):
// N probes of the mode along the major axis, averaged (docs/anisotropic.md).
// Datapath widths and rounding, per mode, are listed in docs/sampler.md, "Filter modes"; the short version:
//   texel coordinate  u = floor(s W_L 2^8) - 128 (Q.8, texel centres at integers): i0 = u >> 8, fu = u & 255
//   NEAREST           i = floor(s W_L) (GL)
//   LINEAR            w = (256 - fu | fu) x (256 - fv | fv) (Q.16); c = (sum c w + 2^15) >> 16
//   *_MIPMAP_LINEAR   c = (c0 (256 - f) + c1 f + 128) >> 8, f = lambda & 255
//   CUBIC             4x4 taps; 1D weights from TileWeightRom rows (sign + b-bit magnitude, scale
//                     M = 2^b - 1); w(x,y) = tile_weight_multiply(wx, wy) for 15 taps, the tap at
//                     offset (0,0) gets M - sum(others) (so a constant texture is exact);
//                     c = clamp(floor((2 sum c w + M) / (2 M)))
//   EDGE_PRESERVING   edge_filter.hpp (Lee & Jen 2003)
// Magnification vs minification (GL): lambda <= 0 -> magnification filter (the mode's first word).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cmodel/aniso.hpp"
#include "cmodel/datapath.hpp"
#include "cmodel/descriptors.hpp"
#include "cmodel/direction_rom.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/texture.hpp"
#include "cmodel/weight_rom.hpp"

namespace tfu {

// What the LOD unit / meta MIP-map supplies for one pixel (Hadwiger 2004 Sec. 3.2).
struct LodInfo {
  int32_t lambda_clamped_q8 = 0;  // lambda_q8 after bias and clamp (lambda_bias_clamp)
  bool magnify = false;
  int level0 = 0, level1 = 0;  // level1 == level0 unless blending
  int blend = 0;               // weight of level1, 0..255 (Q.8)
  int level0_width = 0, level0_height = 0;
  int kernel_scale = 1;  // level-0 texels per texel of level0 (2^level0): the kernel's scale
};

// What the edge-preserving datapath receives for one level (Lee & Jen Sec. 2-3): the 12 cross
// texels C1..C12 (zero where the shape has no texel), the shape mask (cross / T / L), the 8-bit
// fractions inside the centre square, and the wrapped columns/rows -1..2 around it.
struct EdgeFootprint {
  std::array<Texel4, lee_jen::kTexels> texels{};
  lee_jen::TexelMask mask = lee_jen::kAllTexels;
  uint32_t fu = 0, fv = 0;
  std::array<int, 4> col{}, row{};  // -1 = border (clamp-to-border outside the texture)
};

// One request of a batch: what sample() takes (lambda before bias and clamp, Q.8).
struct SampleRequest {
  float s, t;
  int32_t lambda_q8;
};

class Sampler {
 public:
  // Validates the configuration (throws InputError); precomputes ROMs and, for bspline-interp,
  // the prefiltered coefficient levels.
  // The sampler descriptor's registers over a texture's levels; the texture's layout and tile size
  // (its texture descriptor's) give the static edge-preserving shapes.
  Sampler(const Texture& tex, SamplerDescriptor cfg);
  ~Sampler();
  Sampler(const Sampler&) = delete;
  Sampler& operator=(const Sampler&) = delete;

  const SamplerDescriptor& descriptor() const { return cfg_; }
  const Texture& texture() const { return tex_; }

  LodInfo lod_info(int32_t lambda_q8) const;  // applies bias and clamp
  // One filtered colour, as the RGBA8 word of the texture's format.
  Rgba8 sample(float s, float t, int32_t lambda_q8) const { return sample_fn_(*this, s, t, lambda_q8); }
  // The unit's quad interface: out[i] = sample(req[i].s, req[i].t, req[i].lambda_q8) for i < n, bit
  // for bit (the renderer hands it the up to 4 covered pixels of a 2x2 quad). Software speed only:
  // the per-call dispatch is paid once per batch, the sampler's registers (level base, extent,
  // border) stay in machine registers, and LINEAR on 8-bit formats filters 4 requests at once in
  // the 4-lane lerp unit (dp::fast::bilinear_lerp8x4_lanes), a group of 1..3 with masked lanes, and
  // selects the levels once for a group that shares one lambda (Properties.BatchQuadsEqualPlainPath).
  // Array of structures, as the requests arrive.
  void sample_batch(const SampleRequest* req, size_t n, Rgba8* out) const { batch_fn_(*this, req, n, out); }
  // The same in datapath channels (before encoding).
  Texel4 sample_channels(float s, float t, int32_t lambda_q8) const;
  // Anisotropic filtering (docs/anisotropic.md): `lod` is the LOD unit's result for the pixel
  // (aniso_lod of its quad's or gradients' derivatives with descriptor().aniso(), or isotropic_lod).
  // N = lod.probes probes at lambda = lod.lambda_q8, probe i at the centre's Q.8 coordinate on each
  // level plus probe_offset(lod, i) (dp::probe_offset_on_level, dp::probe_texel_coord; NEAREST taps
  // by dp::probe_nearest_tap), each a full sample of the mode (both levels and their blend, static
  // edge shapes from the probe's own footprint), averaged by dp::aniso_average, encoded once.
  // N = 1 gives sample(s, t, lod.lambda_q8) bit for bit (the tests check the probe datapath against
  // the isotropic one over a derivative grid); N > 1 on a sampler without MIP-mapping is not
  // issued (its LOD unit gives N = 1: SamplerDescriptor::aniso()).
  Rgba8 sample(float s, float t, const AnisoLod& lod) const {
    return lod.probes == 1 ? sample_fn_(*this, s, t, lod.lambda_q8) : aniso_fn_(*this, s, t, lod);
  }
  // The plain probe datapath for any N, 1 included (what sample(s, t, lod) equals), in channels.
  Texel4 sample_channels(float s, float t, const AnisoLod& lod) const;
  // The double-precision ideal of anisotropic filtering: N, lambda and the probe positions from
  // real-valued level-0 texel derivatives (du/dx, dv/dx, du/dy, dv/dy) by the EXT spec's formulas
  // (exact square roots and ceil; N capped and rounded as descriptor().aniso()), each probe
  // sample_ideal, the plain mean.
  std::array<double, 4> sample_ideal_aniso(double s, double t, const std::array<double, 4>& texel_derivs) const;
  // Double-precision "ideal" reference of the same mode (exact kernel weights, exact lerps,
  // exact log2 fraction; same texels): channels in [0, 1] (or [-1, 1] for VS16X2).
  std::array<double, 4> sample_ideal(double s, double t, double lambda) const;

  // CUBIC modes: the tile-weight ROM (nullptr otherwise), the normalise stage's registers, and the
  // image the cubic datapath reads for a level (the stored B-spline coefficients for
  // bspline-interp, the texture level otherwise).
  const TileWeightRom* cubic_rom() const;
  const dp::CubicNormalize& cubic_normalize() const;
  const Image& filtered_level(int level) const;

  // Static edge shapes: the texture's tile side (0: the cross, for EdgeShape::Cross or a linear layout).
  int static_shape_block() const;
  // The edge-preserving footprint of (s, t) on `level` under this sampler's wrap modes and static
  // shape, or with the shape `mask_override` (0..0xFFF) when it is >= 0.
  EdgeFootprint edge_footprint(int level, float s, float t, int mask_override = -1) const;
  // EDGE_PRESERVING modes with the kernel shape of each probe and level given (the cycle model's
  // cache-aware shapes depend on the cache contents, which the untimed model cannot know):
  // masks[2 (i - 1) + k] is probe i's shape on level0 (k = 0) and level1 (k = 1).
  Rgba8 sample_edge_masks(float s, float t, const AnisoLod& lod, const lee_jen::TexelMask* masks) const;

  // Texel fetch through the wrap unit (level, integer texel coordinates): what the datapath sees.
  Texel4 fetch(int level, int x, int y) const;

 private:
  struct Impl;
  const Texture& tex_;
  SamplerDescriptor cfg_;
  std::unique_ptr<Impl> impl_;
  void build_cubic();
  Texel4 sample_level(int level, float s, float t) const;
  // The level's result for the blend unit, Q.8 (dp::bilinear_lerp_q8 for LINEAR, else dp::level_q8).
  Texel4 sample_level_q8(int level, float s, float t) const;
  Texel4 sample_level_filter(BaseFilter f, int level, float s, float t) const;
  // One probe on one level: the mode's filter at the centre's coordinate plus the probe's offset
  // (`offset`: probe_offset, Q.16 level-0 texels); mask_override as edge_footprint.
  Texel4 probe_level_filter(BaseFilter f, int level, float s, float t, const ProbeOffset& offset, int mask_override = -1) const;
  Texel4 probe_level_q8(BaseFilter f, int level, float s, float t, const ProbeOffset& offset, int mask_override = -1) const;
  Texel4 probes_channels(float s, float t, const AnisoLod& lod, const lee_jen::TexelMask* masks) const;
  EdgeFootprint edge_footprint_at(int level, dp::LevelCoord u, dp::LevelCoord v, int mask_override) const;
  Texel4 cubic_at(int level, dp::LevelCoord u, dp::LevelCoord v) const;
  // sample() dispatches once, at construction, to the plain datapath or to a fast path of the
  // mode (LINEAR, CUBIC, EDGE_PRESERVING) specialized for the wrap modes (bit-identical to the
  // plain datapath, which sample_channels() keeps; software speed only). FastPaths is defined in
  // sampler.cpp.
  // sample_batch() dispatches the same way: LINEAR's fast paths have a batch variant, every other
  // configuration loops over sample_fn_.
  // aniso_fn_ (N > 1) likewise: a fast path of LINEAR, CUBIC and EDGE_PRESERVING MIP-mapped modes
  // on 8-bit formats, else the plain probe datapath.
  using SampleFn = Rgba8 (*)(const Sampler&, float, float, int32_t);
  using BatchFn = void (*)(const Sampler&, const SampleRequest*, size_t, Rgba8*);
  using AnisoFn = Rgba8 (*)(const Sampler&, float, float, const AnisoLod&);
  SampleFn sample_fn_ = nullptr;
  BatchFn batch_fn_ = nullptr;
  AnisoFn aniso_fn_ = nullptr;
  static Rgba8 sample_plain(const Sampler& sm, float s, float t, int32_t lambda_q8);
  static Rgba8 aniso_plain(const Sampler& sm, float s, float t, const AnisoLod& lod);
  static void batch_plain(const Sampler& sm, const SampleRequest* req, size_t n, Rgba8* out);
  struct FastPaths;
};

}  // namespace tfu
