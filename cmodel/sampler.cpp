// The golden texture sampler: the plain bit-accurate datapath of every filter mode (docs/sampler.md).
// Speed-only fast paths of the same arithmetic live in sampler_fast.cpp, the double-precision ideal
// path in sampler_ideal.cpp, the offline B-spline prefilter in bspline_prefilter.cpp.
#include "cmodel/sampler.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "cmodel/datapath.hpp"
#include "cmodel/edge_filter.hpp"
#include "cmodel/error.hpp"
#include "cmodel/fixed_coord.hpp"
#include "cmodel/sampler_internal.hpp"
#include "cmodel/unorm.hpp"

namespace tfu {

// ---------------------------------------------------------------- construction
Sampler::Sampler(const Texture& tex, SamplerDescriptor cfg) : tex_(tex), cfg_(std::move(cfg)), impl_(new Impl) {
  tex_.validate("texture");
  impl_->border = decode_texel(cfg_.border, tex_.format);
  impl_->scale = tex_.format == TexelFormat::VS16X2 ? 32640.0 : 255.0;
  cfg_.validate();
  if (!filters_format(cfg_.mode.base, tex_.format))
    throw InputError(
        fmt::format("{} is not defined on {} textures", filter_mode_name(cfg_.mode), texel_format_name(tex_.format)));
  if (cfg_.mode.base == BaseFilter::Cubic) build_cubic();
  FastPaths::setup(*this);
}

// CUBIC modes: kernel, tile-weight ROM, normalise registers, weight memo and, for bspline-interp,
// the prefiltered coefficient levels.
void Sampler::build_cubic() {
  impl_->prefiltered = cfg_.kernel == kBsplineInterp;
  impl_->kernel = std::make_unique<FilterKernel>(
      impl_->prefiltered ? FilterKernel::bspline() : FilterKernel::by_name(cfg_.kernel));  // the ideal path's h
  impl_->rom = make_cubic_rom(cfg_);
  impl_->norm.M = static_cast<int64_t>(unorm::max_code(impl_->rom->spec().bits));
  std::tie(impl_->norm.lo, impl_->norm.hi) = channel_range(tex_.format);
  if (cfg_.memoize_cubic_weights && cfg_.cubic_recon == RomRecon::Nearest && impl_->rom->entries() <= 129) {
    auto memo = std::make_unique<detail::WeightMemo>();
    memo->entries = impl_->rom->entries();
    const auto entries = static_cast<size_t>(memo->entries);
    memo->w.resize(entries * entries * detail::WeightMemo::kStride);
    // One representative fraction per address: the smallest 8-bit f that maps to it.
    std::vector<int> rep(entries, -1);
    for (uint32_t f = 0; f < 256; ++f) {
      const int a = impl_->rom->nearest_address(f, 8);
      if (rep[static_cast<size_t>(a)] < 0) rep[static_cast<size_t>(a)] = static_cast<int>(f);
      memo->col[f] = static_cast<uint32_t>(a);
      memo->row[f] = static_cast<uint32_t>(a) * static_cast<uint32_t>(entries);
    }
    for (size_t ay = 0; ay < entries; ++ay)
      for (size_t ax = 0; ax < entries; ++ax)
        if (rep[ax] >= 0 && rep[ay] >= 0) {
          std::array<int32_t, 16> w2{};
          dp::tile_weights_2d(*impl_->rom, RomRecon::Nearest, static_cast<uint32_t>(rep[ax]),
                              static_cast<uint32_t>(rep[ay]), w2);
          std::copy(w2.begin(), w2.end(),
                    memo->w.begin() + static_cast<ptrdiff_t>((ay * entries + ax) * detail::WeightMemo::kStride));
        }
    impl_->memo = std::move(memo);
  }
  if (!impl_->prefiltered) return;
  impl_->coeffs = prefilter_bspline(tex_, cfg_.wrap_s, cfg_.wrap_t);
  impl_->norm.prefiltered = true;
  impl_->norm.scale_q = impl_->coeffs.scale_q;
  impl_->norm.bias_q = impl_->coeffs.bias_q;
}

Sampler::~Sampler() = default;

// ---------------------------------------------------------------- LOD -> levels (GL 4.6 Sec. 8.14)
LodInfo Sampler::lod_info(int32_t lambda_q8) const {
  LodInfo li;
  li.lambda_clamped_q8 = lambda_bias_clamp(lambda_q8, cfg_.lod);
  li.magnify = li.lambda_clamped_q8 <= 0;
  const LevelPick p = select_levels(li.lambda_clamped_q8, cfg_.mode.mip, tex_.max_level());
  li.level0 = p.level0;
  li.level1 = p.level1;
  li.blend = p.blend;
  const Image& l0 = tex_.levels[static_cast<size_t>(li.level0)];
  li.level0_width = l0.width;
  li.level0_height = l0.height;
  li.kernel_scale = 1 << li.level0;
  return li;
}

int Sampler::static_shape_block() const {
  if (cfg_.edge_shape == EdgeShape::Cross || tex_.layout != MemoryLayout::Tiled) return 0;
  return tex_.tile_side();
}

// ---------------------------------------------------------------- texel fetch (wrap unit)
namespace {

using detail::WeightMemo;
using dp::LevelCoord;
using dp::texel_coord;

// Wrapped fetch that reads a given level image (the texture or the B-spline coefficients). The
// wrap unit maps each tap column and row once; a tap outside with clamp-to-border reads `border`.
struct LevelReader {
  const Image& img;
  WrapMode ws, wt;
  TexelFormat fmt;
  Texel4 border;
  int col(int64_t x) const { return wrap_index(ws, x, img.width); }
  int row(int64_t y) const { return wrap_index(wt, y, img.height); }
  Texel4 at(int wx, int wy) const {
    if ((wx | wy) < 0) return border;
    return decode_texel(img.texels[static_cast<size_t>(wy) * static_cast<size_t>(img.width) + static_cast<size_t>(wx)], fmt);
  }
  Texel4 operator()(int64_t x, int64_t y) const { return at(col(x), row(y)); }
};

}  // namespace

Texel4 Sampler::fetch(int level, int x, int y) const {
  const LevelReader rd{tex_.levels[static_cast<size_t>(level)], cfg_.wrap_s, cfg_.wrap_t, tex_.format, impl_->border};
  return rd(x, y);
}

namespace {

Texel4 filter_nearest(const LevelReader& rd, float s, float t) {
  // GL: i = floor(s W), j = floor(t H)
  return rd(float_to_fixed(s, static_cast<uint32_t>(rd.img.width), 0),
            float_to_fixed(t, static_cast<uint32_t>(rd.img.height), 0));
}

// The bilinear filter at a level coordinate (u, v): taps i0, i0 + 1 and j0, j0 + 1.
Texel4 filter_linear_at(const LevelReader& rd, LevelCoord u, LevelCoord v) {
  const int x0 = rd.col(u.i0), x1 = rd.col(u.i0 + 1), y0 = rd.row(v.i0), y1 = rd.row(v.i0 + 1);
  return dp::bilinear_lerp({rd.at(x0, y0), rd.at(x1, y0), rd.at(x0, y1), rd.at(x1, y1)}, u.f, v.f, rd.fmt);
}

Texel4 filter_linear(const LevelReader& rd, float s, float t) {
  return filter_linear_at(rd, texel_coord(s, rd.img.width), texel_coord(t, rd.img.height));
}

// The bilinear filter's Q.8 result for the blend unit (dp::bilinear_lerp_q8).
Texel4 filter_linear_q8_at(const LevelReader& rd, LevelCoord u, LevelCoord v) {
  const int x0 = rd.col(u.i0), x1 = rd.col(u.i0 + 1), y0 = rd.row(v.i0), y1 = rd.row(v.i0 + 1);
  return dp::bilinear_lerp_q8({rd.at(x0, y0), rd.at(x1, y0), rd.at(x0, y1), rd.at(x1, y1)}, u.f, v.f);
}

// Accumulated sum c w per channel at weight scale M, for a compile-time tap count (2 or 4).
template <int taps>
std::array<int64_t, 4> filter_tiled_acc_n(const LevelReader& rd, const TileWeightRom& rom, RomRecon recon,
                                          const detail::WeightMemo* memo, LevelCoord u, LevelCoord v) {
  const int m0 = rom.first_tap();
  std::array<int32_t, 16> w2_local;
  const int32_t* w2;
  if (memo) {
    w2 = memo->weights(u.f, v.f);
  } else {
    dp::tile_weights_2d(rom, recon, u.f, v.f, w2_local);
    w2 = w2_local.data();
  }
  std::array<int, 4> col, row;
  wrap_run(rd.ws, u.i0 + m0, taps, rd.img.width, col.data());
  wrap_run(rd.wt, v.i0 + m0, taps, rd.img.height, row.data());
  if (byte_channels(rd.fmt)) {
    // 8-bit channels: |sum c w| <= 255 M (sum |h|)^2 < 2^31 for b <= 16, so 32 bits suffice.
    const Rgba8 border = encode_texel(rd.border, rd.fmt);
    // Two channels per 64-bit word, (R, B) and (G, A), in signed 32-bit lanes: modular arithmetic
    // keeps x = low + high 2^32 exactly, and each lane's true sum is below 2^31 in magnitude, so
    // both lanes are recovered exactly afterwards.
    uint64_t arb = 0, aga = 0;
    for (int j = 0; j < taps; ++j) {
      const int y = row[static_cast<size_t>(j)];
      for (int i = 0; i < taps; ++i) {
        const auto w = static_cast<uint64_t>(static_cast<int64_t>(w2[j * taps + i]));
        const int x = col[static_cast<size_t>(i)];
        const Rgba8 c = (x | y) < 0 ? border
                                    : rd.img.texels[static_cast<size_t>(y) * static_cast<size_t>(rd.img.width) +
                                                    static_cast<size_t>(x)];
        arb += (uint64_t{c.r} | (uint64_t{c.b} << 32)) * w;
        aga += (uint64_t{c.g} | (uint64_t{c.a} << 32)) * w;
      }
    }
    const auto lanes = [](uint64_t x) {
      const auto lo = static_cast<int32_t>(static_cast<uint32_t>(x));
      const auto hi = static_cast<int32_t>(static_cast<uint32_t>((x - static_cast<uint64_t>(static_cast<int64_t>(lo))) >> 32));
      return std::pair<int64_t, int64_t>{lo, hi};
    };
    const auto [r, b] = lanes(arb);
    const auto [g, a] = lanes(aga);
    return {r, g, b, a};
  }
  std::array<int64_t, 4> acc{};
  for (int j = 0; j < taps; ++j)
    for (int i = 0; i < taps; ++i) {
      const int32_t w = w2[j * taps + i];
      if (w == 0) continue;
      const Texel4 c = rd.at(col[static_cast<size_t>(i)], row[static_cast<size_t>(j)]);
      for (size_t ch = 0; ch < 4; ++ch) acc[ch] += int64_t{c[ch]} * w;
    }
  return acc;
}

// The cubic datapath's sum at a level coordinate (u, v).
std::array<int64_t, 4> filter_tiled_acc(const LevelReader& rd, const TileWeightRom& rom, RomRecon recon,
                                        const detail::WeightMemo* memo, LevelCoord u, LevelCoord v) {
  return rom.taps() == 4 ? filter_tiled_acc_n<4>(rd, rom, recon, memo, u, v)
                         : filter_tiled_acc_n<2>(rd, rom, recon, memo, u, v);
}

// Probe i's coordinate on a level: the centre's texel_coord plus the probe offset on that level.
LevelCoord probe_coord(float s, int size, int64_t offset_q16, int level) {
  return dp::probe_texel_coord(texel_coord(s, size), dp::probe_offset_on_level(offset_q16, level));
}

}  // namespace

Texel4 Sampler::sample_level_filter(BaseFilter f, int level, float s, float t) const {
  const Image& img = tex_.levels[static_cast<size_t>(level)];
  const LevelReader rd{img, cfg_.wrap_s, cfg_.wrap_t, tex_.format, impl_->border};
  switch (f) {
    case BaseFilter::Nearest: return filter_nearest(rd, s, t);
    case BaseFilter::Linear: return filter_linear(rd, s, t);
    case BaseFilter::Cubic: return cubic_at(level, texel_coord(s, img.width), texel_coord(t, img.height));
    case BaseFilter::EdgePreserving: {
      const EdgeFootprint fp = edge_footprint(level, s, t);
      return lee_jen::edge_preserving_interpolate(fp.texels, fp.mask, fp.fu, fp.fv, tex_.format);
    }
  }
  return {};
}

// CUBIC on one level at (u, v): the tile-weight ROM over the texels, or over the B-spline
// coefficients when the sampler reads a prefiltered texture.
Texel4 Sampler::cubic_at(int level, LevelCoord u, LevelCoord v) const {
  if (impl_->prefiltered) {
    const LevelReader cr{impl_->coeffs.codes[static_cast<size_t>(level)], cfg_.wrap_s, cfg_.wrap_t, TexelFormat::RGBA8, {}};
    return dp::cubic_normalize(filter_tiled_acc(cr, *impl_->rom, cfg_.cubic_recon, impl_->memo.get(), u, v), impl_->norm);
  }
  const LevelReader rd{tex_.levels[static_cast<size_t>(level)], cfg_.wrap_s, cfg_.wrap_t, tex_.format, impl_->border};
  return dp::cubic_normalize(filter_tiled_acc(rd, *impl_->rom, cfg_.cubic_recon, impl_->memo.get(), u, v), impl_->norm);
}

Texel4 Sampler::probe_level_q8(BaseFilter f, int level, float s, float t, const ProbeOffset& o, int mask_override) const {
  if (f != BaseFilter::Linear) return dp::level_q8(probe_level_filter(f, level, s, t, o, mask_override));
  const Image& img = tex_.levels[static_cast<size_t>(level)];
  const LevelReader rd{img, cfg_.wrap_s, cfg_.wrap_t, tex_.format, impl_->border};
  return filter_linear_q8_at(rd, probe_coord(s, img.width, o.du_q16, level), probe_coord(t, img.height, o.dv_q16, level));
}

Texel4 Sampler::probe_level_filter(BaseFilter f, int level, float s, float t, const ProbeOffset& o, int mask_override) const {
  const Image& img = tex_.levels[static_cast<size_t>(level)];
  const LevelReader rd{img, cfg_.wrap_s, cfg_.wrap_t, tex_.format, impl_->border};
  const LevelCoord u = probe_coord(s, img.width, o.du_q16, level), v = probe_coord(t, img.height, o.dv_q16, level);
  switch (f) {
    case BaseFilter::Nearest: {
      const auto tap = [level](float x, int size, int64_t offset_q16) {
        return dp::probe_nearest_tap(float_to_fixed(x, static_cast<uint32_t>(size), 0), texel_coord(x, size),
                                     dp::probe_offset_on_level(offset_q16, level));
      };
      return rd(tap(s, img.width, o.du_q16), tap(t, img.height, o.dv_q16));
    }
    case BaseFilter::Linear: return filter_linear_at(rd, u, v);
    case BaseFilter::Cubic: return cubic_at(level, u, v);
    case BaseFilter::EdgePreserving: {
      const EdgeFootprint fp = edge_footprint_at(level, u, v, mask_override);
      return lee_jen::edge_preserving_interpolate(fp.texels, fp.mask, fp.fu, fp.fv, tex_.format);
    }
  }
  return {};
}

const TileWeightRom* Sampler::cubic_rom() const { return impl_->rom.get(); }
const dp::CubicNormalize& Sampler::cubic_normalize() const { return impl_->norm; }
const Image& Sampler::filtered_level(int level) const {
  return impl_->prefiltered ? impl_->coeffs.codes.at(static_cast<size_t>(level)) : tex_.levels.at(static_cast<size_t>(level));
}

EdgeFootprint Sampler::edge_footprint(int level, float s, float t, int mask_override) const {
  const Image& img = tex_.levels[static_cast<size_t>(level)];
  return edge_footprint_at(level, texel_coord(s, img.width), texel_coord(t, img.height), mask_override);
}

EdgeFootprint Sampler::edge_footprint_at(int level, LevelCoord u, LevelCoord v, int mask_override) const {
  const Image& img = tex_.levels[static_cast<size_t>(level)];
  const LevelReader rd{img, cfg_.wrap_s, cfg_.wrap_t, tex_.format, impl_->border};
  EdgeFootprint fp;
  fp.fu = u.f;
  fp.fv = v.f;
  // Columns and rows -1..2 around the centre square, wrapped once each.
  wrap_run(cfg_.wrap_s, u.i0 + lee_jen::kGridOrigin, lee_jen::kGridSide, img.width, fp.col.data());
  wrap_run(cfg_.wrap_t, v.i0 + lee_jen::kGridOrigin, lee_jen::kGridSide, img.height, fp.row.data());
  fp.mask = lee_jen::kAllTexels;
  if (mask_override >= 0)
    fp.mask = static_cast<lee_jen::TexelMask>(mask_override & lee_jen::kAllTexels);
  else if (const int b = static_shape_block(); b != 0)
    fp.mask = lee_jen::cache_block_mask_of_grid(fp.col, fp.row, b);
  for (int n = 1; n <= lee_jen::kTexels; ++n)
    fp.texels[static_cast<size_t>(n - 1)] =
        lee_jen::has_texel(fp.mask, n)
            ? rd.at(fp.col[static_cast<size_t>(lee_jen::grid_col(n))], fp.row[static_cast<size_t>(lee_jen::grid_row(n))])
            : Texel4{0, 0, 0, 0};
  return fp;
}

Rgba8 Sampler::sample_edge_masks(float s, float t, const AnisoLod& lod, const lee_jen::TexelMask* masks) const {
  if (cfg_.mode.base != BaseFilter::EdgePreserving) throw InputError("sample_edge_masks needs an EDGE_PRESERVING mode");
  return encode_texel(probes_channels(s, t, lod, masks), tex_.format);
}

Texel4 Sampler::sample_level(int level, float s, float t) const {
  return sample_level_filter(cfg_.mode.base, level, s, t);
}

Texel4 Sampler::sample_level_q8(int level, float s, float t) const {
  if (cfg_.mode.base != BaseFilter::Linear) return dp::level_q8(sample_level(level, s, t));
  const Image& img = tex_.levels[static_cast<size_t>(level)];
  const LevelReader rd{img, cfg_.wrap_s, cfg_.wrap_t, tex_.format, impl_->border};
  return filter_linear_q8_at(rd, texel_coord(s, img.width), texel_coord(t, img.height));
}

// Level select, the filter on one level (a code) or on two (Q.8 results), the blend unit.
Texel4 Sampler::sample_channels(float s, float t, int32_t lambda_q8) const {
  const LodInfo li = lod_info(lambda_q8);
  if (li.blend == 0) return sample_level(li.level0, s, t);
  return dp::level_blend(sample_level_q8(li.level0, s, t), sample_level_q8(li.level1, s, t), li.blend);
}

// The probe datapath: N probes (each its levels and their blend), the averaging unit.
Texel4 Sampler::probes_channels(float s, float t, const AnisoLod& lod, const lee_jen::TexelMask* masks) const {
  const LodInfo li = lod_info(lod.lambda_q8);
  const int n = lod.probes;
  dp::AnisoAccumulator acc;
  for (int i = 1; i <= n; ++i) {
    const ProbeOffset o = probe_offset(lod, i);
    const auto mask = [&](int k) { return masks ? int{masks[2 * (i - 1) + k]} : -1; };
    const Texel4 c = li.blend == 0 ? probe_level_filter(cfg_.mode.base, li.level0, s, t, o, mask(0))
                                   : dp::level_blend(probe_level_q8(cfg_.mode.base, li.level0, s, t, o, mask(0)),
                                                     probe_level_q8(cfg_.mode.base, li.level1, s, t, o, mask(1)), li.blend);
    acc.add(c, n, i);
  }
  return acc.result();
}

Texel4 Sampler::sample_channels(float s, float t, const AnisoLod& lod) const { return probes_channels(s, t, lod, nullptr); }

Rgba8 Sampler::sample_plain(const Sampler& sm, float s, float t, int32_t lambda_q8) {
  return encode_texel(sm.sample_channels(s, t, lambda_q8), sm.tex_.format);
}

Rgba8 Sampler::aniso_plain(const Sampler& sm, float s, float t, const AnisoLod& lod) {
  return encode_texel(sm.sample_channels(s, t, lod), sm.tex_.format);
}

void Sampler::batch_plain(const Sampler& sm, const SampleRequest* req, size_t n, Rgba8* out) {
  const SampleFn f = sm.sample_fn_;
  for (size_t i = 0; i < n; ++i) out[i] = f(sm, req[i].s, req[i].t, req[i].lambda_q8);
}

}  // namespace tfu
