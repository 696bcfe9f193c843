// A verifier written from the Vulkan specification's texel-filtering rules (chapter "Image
// Operations": "Scale Factor Operation", "LOD Operation", "Image Level(s) Selection", "(s,t,r,q,a)
// to (u,v,w,a) Transformation", "(u,v,w,a) to (i,j,k,l,n) Transformation", "Wrapping Operation",
// "Texel Filtering"; "Fixed-Point Data Conversions"; the limits subTexelPrecisionBits and
// mipmapPrecisionBits). For one request of a NEAREST or LINEAR filter, with or without
// MIP-mapping (mipmapMode NEAREST or LINEAR), it gives the interval of 8-bit codes each result
// channel may take in any implementation that follows those rules. Nothing here reads the golden
// model's datapath: only the texture's words (decode_texel: the format's definition), the
// sampler's registers and the request's floats.
//
// The freedoms the spec leaves, each taken in full (docs/sampler.md, "Within the spec's bounds"):
//   scale factor   rho_x may be any f_x with max(m_ux, m_vx) <= f_x <= sqrt(2) (m_ux + m_vx)
//                  (m_ux = |ds/dx| w_base, ...; likewise y); rho_max = max(rho_x, rho_y), eta = 1
//                  (isotropic). Quad derivatives are the coarse differences s(1,0) - s(0,0),
//                  s(0,1) - s(0,0), exact.
//   LOD            "computed with mipmapPrecisionBits of accuracy": lambda' = lambda_base + bias
//                  within +-2^-mipmapPrecisionBits of an admissible value, then clamped to
//                  [minLod, maxLod] (exact register values)
//   level          d' = clamp(lambda, 0, q); NEAREST: d = ceil(d' + 1/2) - 1 (preferred) or
//                  floor(d' + 1/2) (alternative); LINEAR: delta = frac(d') quantized to
//                  mipmapPrecisionBits (to either neighbour), d_hi = floor, d_lo = min(d_hi + 1, q)
//   sub-texel      u = s width_level exactly; u - 1/2 (LINEAR) or u (NEAREST) snapped to either
//                  neighbour on the 2^-subTexelPrecisionBits grid ("sub-texel values ... will snap
//                  to these locations"); i0 = floor, alpha = frac; each level on its own
//   wrap           the spec's formulas (repeat, mirrored repeat, clamp to edge, clamp to border:
//                  i in {-1, size} reads the border)
//   filter         the exact weighted average of the texels (codes / 255), the weights
//                  (1 - alpha) / alpha, (1 - beta) / beta, (1 - delta) / delta
//   conversion     the filtered value f to the 8-bit result: convertFloatToUint(255 f) is either of
//                  the two nearest codes, so floor(255 f_min) .. ceil(255 f_max)
// Without mipmapping (MipMode::None) the view has one level (q = 0). The spec's general floating-point
// allowance (about 1 part in 10^5 per operation, "Floating-Point Computation") is not taken.
//
// Domain: finite coordinates with |s width_0| and |t height_0| below 2^kCoordinateLog2, finite
// derivatives and explicit LODs; 8-bit formats (RGBA8, L8). The spec leaves NaN and infinite inputs
// undefined ("Floating-Point Computation"); in_domain() says whether a request is inside.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

#include <fmt/format.h>

#include "cmodel/descriptors.hpp"
#include "cmodel/texture.hpp"

namespace tfu::spec {

inline constexpr int kCoordinateLog2 = 30;  // |s W|, |t H| below 2^30 texels

struct Precision {
  int sub_texel_bits = 8;  // subTexelPrecisionBits (at most 8)
  int mipmap_bits = 8;     // mipmapPrecisionBits
};

// How the request gives its LOD (the three request kinds of the unit's traces).
enum class LodKind { Explicit, Gradients, Quad };
struct LodInput {
  LodKind kind = LodKind::Explicit;
  float lod = 0;                                 // Explicit
  float dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0;  // Gradients
  std::array<float, 4> qs{}, qt{};               // Quad: pixels (0,0), (1,0), (0,1), (1,1)
};

// Per channel, the codes a result may take: lo[c] <= result[c] <= hi[c].
struct Bounds {
  Texel4 lo{}, hi{};
  bool contains(const Texel4& c) const {
    for (size_t k = 0; k < 4; ++k)
      if (c[k] < lo[k] || c[k] > hi[k]) return false;
    return true;
  }
};

namespace detail {

// floor and ceil of x size 2^bits - offset, exactly, for finite x with |x size| < 2^kCoordinateLog2.
struct Snap {
  int64_t lo, hi;
};
inline Snap snap(float x, int size, int bits, int64_t offset) {
  const auto b = std::bit_cast<uint32_t>(x);
  const int exp = static_cast<int>((b >> 23) & 0xFF);
  const uint64_t sig = exp == 0 ? (b & 0x7FFFFF) : ((b & 0x7FFFFF) | 0x800000);
  const int e = (exp == 0 ? -149 : exp - 150) + bits;    // x size 2^bits = sig size 2^e
  const uint64_t n = sig * static_cast<uint64_t>(size);  // < 2^38
  int64_t q;
  bool frac;
  if (e >= 0) {
    q = static_cast<int64_t>(n << e);  // < 2^48 in the domain
    frac = false;
  } else if (e <= -64) {
    q = 0;
    frac = n != 0;
  } else {
    q = static_cast<int64_t>(n >> -e);
    frac = (n & ((uint64_t{1} << -e) - 1)) != 0;
  }
  if (b >> 31) return {-q - (frac ? 1 : 0) - offset, -q - offset};
  return {q - offset, q + (frac ? 1 : 0) - offset};
}

// The spec's wrapping of an integer texel coordinate; -1 for a border texel.
inline int wrap(WrapMode m, int64_t i, int size) {
  const auto mod = [](int64_t a, int64_t n) { return ((a % n) + n) % n; };
  const auto mirror = [](int64_t n) { return n >= 0 ? n : -(1 + n); };
  switch (m) {
    case WrapMode::Repeat: return static_cast<int>(mod(i, size));
    case WrapMode::MirroredRepeat: return static_cast<int>((size - 1) - mirror(mod(i, 2 * int64_t{size}) - size));
    case WrapMode::ClampToEdge: return static_cast<int>(std::clamp<int64_t>(i, 0, size - 1));
    case WrapMode::ClampToBorder: {
      const int64_t c = std::clamp<int64_t>(i, -1, size);
      return c == -1 || c == size ? -1 : static_cast<int>(c);
    }
  }
  return 0;
}

struct Range {  // per channel, in codes x 2^16
  std::array<int64_t, 4> lo, hi;
};

struct LevelView {
  const Image& img;
  TexelFormat fmt;
  Texel4 border;
  WrapMode ws, wt;
  Texel4 at(int64_t i, int64_t j) const {
    const int x = wrap(ws, i, img.width), y = wrap(wt, j, img.height);
    if (x < 0 || y < 0) return border;
    return decode_texel(img.at(x, y), fmt);
  }
};

// The values one level's filter may give: every admissible snapped position.
inline Range level_range(const LevelView& v, BaseFilter f, float s, float t, const Precision& p) {
  Range r;
  r.lo.fill(INT64_MAX);
  r.hi.fill(INT64_MIN);
  const int b = p.sub_texel_bits;
  const auto add = [&r](const std::array<int64_t, 4>& c) {
    for (size_t k = 0; k < 4; ++k) {
      r.lo[k] = std::min(r.lo[k], c[k]);
      r.hi[k] = std::max(r.hi[k], c[k]);
    }
  };
  if (f == BaseFilter::Nearest) {
    // i = floor(u), u snapped to the sub-texel grid
    const Snap us = snap(s, v.img.width, b, 0), vs = snap(t, v.img.height, b, 0);
    for (const int64_t uu : {us.lo, us.hi})
      for (const int64_t vv : {vs.lo, vs.hi}) {
        const Texel4 c = v.at(uu >> b, vv >> b);
        add({int64_t{c[0]} << 16, int64_t{c[1]} << 16, int64_t{c[2]} << 16, int64_t{c[3]} << 16});
      }
    return r;
  }
  // LINEAR: i0 = floor(u - 1/2), alpha = frac(u - 1/2), u - 1/2 snapped to the sub-texel grid
  const int64_t one = int64_t{1} << b, half = one >> 1;
  const Snap us = snap(s, v.img.width, b, half), vs = snap(t, v.img.height, b, half);
  for (const int64_t uu : {us.lo, us.hi})
    for (const int64_t vv : {vs.lo, vs.hi}) {
      const int64_t i0 = uu >> b, j0 = vv >> b, a = uu & (one - 1), be = vv & (one - 1);
      const Texel4 c00 = v.at(i0, j0), c10 = v.at(i0 + 1, j0), c01 = v.at(i0, j0 + 1), c11 = v.at(i0 + 1, j0 + 1);
      std::array<int64_t, 4> acc{};
      for (size_t k = 0; k < 4; ++k) {
        const int64_t sum =
            (one - a) * (one - be) * c00[k] + a * (one - be) * c10[k] + (one - a) * be * c01[k] + a * be * c11[k];
        acc[k] = (sum << 16) >> (2 * b);  // exact: 2 b <= 16
      }
      add(acc);
    }
  return r;
}

}  // namespace detail

// Whether the spec defines the request's result and the verifier covers it (see the header).
inline bool in_domain(const Texture& tex, float s, float t, const LodInput& lod) {
  if (tex.format == TexelFormat::VS16X2) return false;
  const double lim = std::ldexp(1.0, kCoordinateLog2);
  const auto ok = [lim](float x, int size) { return std::isfinite(x) && std::fabs(double{x} * size) < lim; };
  if (!ok(s, tex.width()) || !ok(t, tex.height())) return false;
  switch (lod.kind) {
    case LodKind::Explicit: return std::isfinite(lod.lod);
    case LodKind::Gradients:
      return ok(lod.dsdx, tex.width()) && ok(lod.dsdy, tex.width()) && ok(lod.dtdx, tex.height()) &&
             ok(lod.dtdy, tex.height());
    case LodKind::Quad:
      for (size_t k = 0; k < 4; ++k)
        if (!ok(lod.qs[k], tex.width()) || !ok(lod.qt[k], tex.height())) return false;
      return true;
  }
  return false;
}

// lambda_base's admissible range [lo, hi] in levels (-inf for a zero footprint).
inline std::array<long double, 2> lambda_base_range(const Texture& tex, const LodInput& lod) {
  if (lod.kind == LodKind::Explicit) return {lod.lod, lod.lod};
  long double dsdx, dtdx, dsdy, dtdy;
  if (lod.kind == LodKind::Gradients) {
    dsdx = lod.dsdx, dtdx = lod.dtdx, dsdy = lod.dsdy, dtdy = lod.dtdy;
  } else {
    dsdx = static_cast<long double>(lod.qs[1]) - lod.qs[0];
    dtdx = static_cast<long double>(lod.qt[1]) - lod.qt[0];
    dsdy = static_cast<long double>(lod.qs[2]) - lod.qs[0];
    dtdy = static_cast<long double>(lod.qt[2]) - lod.qt[0];
  }
  const long double w = tex.width(), h = tex.height();
  const long double mux = std::fabs(dsdx) * w, mvx = std::fabs(dtdx) * h, muy = std::fabs(dsdy) * w,
                    mvy = std::fabs(dtdy) * h;
  const long double rho_lo = std::max(std::max(mux, mvx), std::max(muy, mvy));
  const long double rho_hi = std::sqrt(2.0L) * std::max(mux + mvx, muy + mvy);
  // log2 in long double: widened by 2^-40 of a level, far below the 2^-8 tolerance it feeds
  const long double eps = std::ldexp(1.0L, -40);
  return {rho_lo == 0 ? -INFINITY : std::log2(rho_lo) - eps, rho_hi == 0 ? -INFINITY : std::log2(rho_hi) + eps};
}

// The interval of each result channel (codes) for sample(s, t) of `tex` under `sd`'s filter
// mode, wraps, border, bias and LOD clamps. Requires in_domain(); NEAREST or LINEAR base filter.
inline Bounds filter_bounds(const Texture& tex, const SamplerDescriptor& sd, float s, float t, const LodInput& lod,
                            const Precision& p = {}) {
  const int q = sd.mode.mip == MipMode::None ? 0 : tex.max_level();
  const long double tol = std::ldexp(1.0L, -p.mipmap_bits);
  const std::array<long double, 2> base = lambda_base_range(tex, lod);
  const long double bias = std::ldexp(static_cast<long double>(sd.lod.bias_q8), -kLodFracBits);
  const long double min_lod = std::ldexp(static_cast<long double>(sd.lod.min_lod_q8), -kLodFracBits);
  const long double max_lod = std::ldexp(static_cast<long double>(sd.lod.max_lod_q8), -kLodFracBits);
  // lambda within the LOD accuracy, clamped; d' = clamp(lambda, 0, q)
  const auto d_prime = [&](long double l) {
    return std::clamp(std::clamp(l, min_lod, max_lod), 0.0L, static_cast<long double>(q));
  };
  const long double d0 = d_prime(base[0] + bias - tol), d1 = d_prime(base[1] + bias + tol);

  const Texel4 border = decode_texel(sd.border, tex.format);
  const auto range_of = [&](int level) {
    const detail::LevelView v{tex.levels[static_cast<size_t>(level)], tex.format, border, sd.wrap_s, sd.wrap_t};
    return detail::level_range(v, sd.mode.base, s, t, p);
  };
  // Accumulated extremes, in codes x 2^16 x 2^mipmap_bits.
  std::array<int64_t, 4> lo, hi;
  lo.fill(INT64_MAX);
  hi.fill(INT64_MIN);
  const int mb = p.mipmap_bits;
  const int64_t one = int64_t{1} << mb;
  const auto add_blend = [&](const detail::Range& rh, const detail::Range& rl, int64_t delta) {
    for (size_t k = 0; k < 4; ++k) {
      lo[k] = std::min(lo[k], (one - delta) * rh.lo[k] + delta * rl.lo[k]);
      hi[k] = std::max(hi[k], (one - delta) * rh.hi[k] + delta * rl.hi[k]);
    }
  };
  if (sd.mode.mip != MipMode::Linear) {
    // one level: NEAREST's either rounding of d' (q = 0 without mipmapping)
    const int first = static_cast<int>(std::ceil(d0 + 0.5L)) - 1, last = static_cast<int>(std::floor(d1 + 0.5L));
    for (int d = std::max(first, 0); d <= std::min(last, q); ++d) {
      const detail::Range r = range_of(d);
      add_blend(r, r, 0);
    }
  } else {
    // delta = frac(d') quantized to mipmap_bits (either neighbour): k = d' 2^mb in [floor, ceil]
    const auto k0 = static_cast<int64_t>(std::floor(std::ldexp(d0, mb)));
    const auto k1 = static_cast<int64_t>(std::ceil(std::ldexp(d1, mb)));
    for (int64_t dh = k0 >> mb; dh <= (k1 >> mb); ++dh) {
      const int hi_level = static_cast<int>(dh), lo_level = std::min(hi_level + 1, q);
      const detail::Range rh = range_of(hi_level);
      const detail::Range rl = lo_level == hi_level ? rh : range_of(lo_level);
      // the blend is linear in delta: its extremes are at the ends of the run of k on this level
      const int64_t ka = std::max(k0, dh << mb) - (dh << mb), kb = std::min(k1, (dh << mb) + one - 1) - (dh << mb);
      add_blend(rh, rl, ka);
      add_blend(rh, rl, kb);
    }
  }
  Bounds out;
  const int shift = 16 + mb;
  for (size_t k = 0; k < 4; ++k) {
    out.lo[k] = static_cast<int32_t>(lo[k] >> shift);                                // floor
    out.hi[k] = static_cast<int32_t>((hi[k] + (int64_t{1} << shift) - 1) >> shift);  // ceil
  }
  return out;
}

// One line naming a request for a finding.
inline std::string describe(const Texture& tex, const SamplerDescriptor& sd, float s, float t, const LodInput& lod) {
  std::string l;
  switch (lod.kind) {
    case LodKind::Explicit: l = fmt::format("lod {}", lod.lod); break;
    case LodKind::Gradients: l = fmt::format("grad ({}, {}, {}, {})", lod.dsdx, lod.dtdx, lod.dsdy, lod.dtdy); break;
    case LodKind::Quad:
      l = fmt::format("quad s ({}, {}, {}) t ({}, {}, {})", lod.qs[0], lod.qs[1], lod.qs[2], lod.qt[0], lod.qt[1],
                      lod.qt[2]);
      break;
  }
  return fmt::format("{} {}x{} {} levels, {} wraps {}/{}, bias {} lod [{}, {}] (Q.8); s {} t {}; {}",
                     texel_format_name(tex.format), tex.width(), tex.height(), tex.levels.size(),
                     filter_mode_name(sd.mode), wrap_mode_name(sd.wrap_s), wrap_mode_name(sd.wrap_t), sd.lod.bias_q8,
                     sd.lod.min_lod_q8, sd.lod.max_lod_q8, s, t, l);
}

}  // namespace tfu::spec
