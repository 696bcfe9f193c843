// The double-precision "ideal" reference of every filter mode (exact kernel weights, exact lerps,
// exact log2 fraction; the same texels as the datapath): the quality reference that isolates the
// datapath's own quantization. Floating point by design; never part of the bit-exact path.
#include <algorithm>
#include <cmath>

#include "cmodel/edge_filter.hpp"
#include "cmodel/sampler.hpp"
#include "cmodel/sampler_internal.hpp"

namespace tfu {

namespace {
// SRGBA8 in the ideal: R, G, B filtered as exact linear values (the EOTF of the stored code) and
// the result re-encoded with the exact OETF, as the datapath's decode and encode ROMs do in 12 and
// 8 bits; alpha untouched.
std::array<double, 4> srgb_encoded(std::array<double, 4> c) {
  for (size_t ch = 0; ch < 3; ++ch) c[ch] = srgb::detail::oetf(std::clamp(c[ch], 0.0, 1.0));
  return c;
}
std::array<double, 4> srgb_decoded(std::array<double, 4> c) {
  for (size_t ch = 0; ch < 3; ++ch) c[ch] = srgb::detail::eotf(c[ch]);
  return c;
}
}  // namespace

// ---------------------------------------------------------------- double-precision ideal
std::array<double, 4> Sampler::sample_ideal(double s, double t, double lambda) const {
  // Non-finite coordinates as the datapath treats them (docs/sampler.md): NaN -> 0, +-Inf
  // saturates (here at +-2^40, far outside any texture, so every index below stays finite).
  const auto saturate = [](double c) { return std::isnan(c) ? 0.0 : std::clamp(c, -0x1p40, 0x1p40); };
  s = saturate(s);
  t = saturate(t);
  // Same level selection as GL, in real arithmetic.
  lambda = std::clamp(lambda + cfg_.lod.bias_q8 / 256.0, cfg_.lod.min_lod_q8 / 256.0, cfg_.lod.max_lod_q8 / 256.0);
  const int q = tex_.max_level();
  int l0 = 0, l1 = 0;
  double blend = 0;
  if (lambda > 0) {
    if (cfg_.mode.mip == MipMode::Nearest) {
      l0 = l1 = std::min(lambda <= 0.5 ? 0 : static_cast<int>(std::ceil(lambda + 0.5)) - 1, q);
    } else if (cfg_.mode.mip == MipMode::Linear) {
      if (lambda >= q) {
        l0 = l1 = q;
      } else {
        l0 = static_cast<int>(std::floor(lambda));
        l1 = l0 + 1;
        blend = lambda - l0;
      }
    }
  }
  const double sc = impl_->scale;
  const bool srgb = tex_.format == TexelFormat::SRGBA8;
  const auto real_texel = [&](int level, int64_t x, int64_t y) {
    const int xi = static_cast<int>(std::clamp<int64_t>(x, INT32_MIN / 2, INT32_MAX / 2));
    const int yi = static_cast<int>(std::clamp<int64_t>(y, INT32_MIN / 2, INT32_MAX / 2));
    if (srgb) {  // the stored codes (the fetch's linear unorm12 is the datapath's rounding of these)
      const Rgba8 w = encode_texel(fetch(level, xi, yi), tex_.format);
      return srgb_decoded({w.r / 255.0, w.g / 255.0, w.b / 255.0, w.a / 255.0});
    }
    const Texel4 c = fetch(level, xi, yi);
    return std::array<double, 4>{c[0] / sc, c[1] / sc, c[2] / sc, c[3] / sc};
  };
  const auto level_sample = [&](int level) -> std::array<double, 4> {
    const Image& img = tex_.levels[static_cast<size_t>(level)];
    const double u = s * img.width - 0.5, v = t * img.height - 0.5;
    const double fi = std::floor(u), fj = std::floor(v);
    const double fu = u - fi, fv = v - fj;
    const auto i0 = static_cast<int64_t>(std::clamp(fi, -1e15, 1e15));
    const auto j0 = static_cast<int64_t>(std::clamp(fj, -1e15, 1e15));
    std::array<double, 4> out{};
    switch (cfg_.mode.base) {
      case BaseFilter::Nearest:
        return real_texel(level, static_cast<int64_t>(std::floor(s * img.width)),
                          static_cast<int64_t>(std::floor(t * img.height)));
      case BaseFilter::Linear: {
        const std::array<double, 4> w{(1 - fu) * (1 - fv), fu * (1 - fv), (1 - fu) * fv, fu * fv};
        const std::array<std::array<double, 4>, 4> c{real_texel(level, i0, j0), real_texel(level, i0 + 1, j0),
                                                     real_texel(level, i0, j0 + 1), real_texel(level, i0 + 1, j0 + 1)};
        for (size_t ch = 0; ch < 4; ++ch)
          for (size_t k = 0; k < 4; ++k) out[ch] += w[k] * c[k][ch];
        return out;
      }
      case BaseFilter::Cubic: {
        const FilterKernel& h = *impl_->kernel;
        const int taps = impl_->rom->taps(), m0 = impl_->rom->first_tap();
        // Without level adaptation the kernel keeps its level-0 footprint: distances in level-L
        // texels are scaled by 2^L before evaluating h (Hadwiger 2004 Sec. 3.2).
        const double k = cfg_.cubic_level_adapt ? 1.0 : std::ldexp(1.0, level);
        double wsum = 0;
        for (int j = 0; j < taps; ++j)
          for (int i = 0; i < taps; ++i) {
            const double w = h(k * (fu - (m0 + i))) * h(k * (fv - (m0 + j)));
            if (w == 0) continue;
            wsum += w;
            std::array<double, 4> c;
            if (impl_->prefiltered) {
              const auto& cl = impl_->coeffs.exact[static_cast<size_t>(level)];
              const int xi = wrap_index(cfg_.wrap_s, i0 + m0 + i, img.width);
              const int yj = wrap_index(cfg_.wrap_t, j0 + m0 + j, img.height);
              c = (xi < 0 || yj < 0) ? std::array<double, 4>{}
                                     : cl[static_cast<size_t>(yj) * static_cast<size_t>(img.width) +
                                          static_cast<size_t>(xi)];
            } else {
              c = real_texel(level, i0 + m0 + i, j0 + m0 + j);
            }
            for (size_t ch = 0; ch < 4; ++ch) out[ch] += w * c[ch];
          }
        if (!cfg_.cubic_level_adapt && wsum > 0)
          for (auto& x : out) x /= wsum;  // the unadapted kernel is renormalised (best case for it)
        const double lo = tex_.format == TexelFormat::VS16X2 ? -1.0 : 0.0;
        for (auto& x : out) x = std::clamp(x, lo, 1.0);
        return out;
      }
      case BaseFilter::EdgePreserving: {
        std::array<std::array<double, 4>, lee_jen::kTexels> c{};
        lee_jen::TexelMask mask = lee_jen::kAllTexels;
        if (const int block = static_shape_block(); block != 0)
          mask = lee_jen::cache_block_mask(wrap_index(cfg_.wrap_s, i0, img.width),
                                           wrap_index(cfg_.wrap_s, i0 + 1, img.width),
                                           wrap_index(cfg_.wrap_t, j0, img.height),
                                           wrap_index(cfg_.wrap_t, j0 + 1, img.height), block);
        for (int n = 1; n <= lee_jen::kTexels; ++n) {
          const lee_jen::TexelPos p = lee_jen::texel_pos(n);
          c[static_cast<size_t>(n - 1)] = real_texel(level, i0 + p.x, j0 + p.y);
        }
        return lee_jen::edge_preserving_ideal(c, mask, fu, fv, tex_.format);
      }
    }
    return out;
  };
  std::array<double, 4> a = level_sample(l0);
  if (blend > 0) {
    const std::array<double, 4> b = level_sample(l1);
    for (size_t ch = 0; ch < 4; ++ch) a[ch] = (1 - blend) * a[ch] + blend * b[ch];
  }
  return srgb ? srgb_encoded(a) : a;
}

// ---------------------------------------------------------------- anisotropic ideal
// EXT_texture_filter_anisotropic in real arithmetic: Px, Py exact lengths, N = min(ceil(Pmax /
// Pmin), maxAniso) (with aniso_threshold t: ceil(Pmax / ((1 + t/8) Pmin)); rounded up to a power
// of two with AnisoRounding::PowerOfTwo), lambda =
// log2(Pmax / N), probe i at the centre + (-1/2 + i / (N + 1)) times the major derivative vector,
// each probe the ideal sample of the mode, the plain mean. With AnisoAxes::Ellipse, Pmax and Pmin
// are the footprint ellipse's axes (the singular values of [a b]: Pmax^2 = (A + sqrt(E^2 + F^2)) /
// 2, Pmin = |D| / Pmax; aniso.hpp), and the probes stay on the longer derivative vector.
std::array<double, 4> Sampler::sample_ideal_aniso(double s, double t, const std::array<double, 4>& d) const {
  const double px = std::hypot(d[0], d[1]), py = std::hypot(d[2], d[3]);
  const bool major_x = px >= py;
  double pmax = std::max(px, py), pmin = std::min(px, py);
  const AnisoParams ap = cfg_.aniso();
  if (ap.aniso_axes == AnisoAxes::Ellipse && pmax > 0 && std::isfinite(pmax)) {
    const double a = px * px + py * py, e = px * px - py * py, f = 2 * (d[0] * d[2] + d[1] * d[3]);
    pmax = std::sqrt((a + std::hypot(e, f)) / 2);
    pmin = std::fabs(d[0] * d[3] - d[1] * d[2]) / pmax;
  }
  const int cap = std::clamp(ap.max_aniso, 1, kMaxAniso);
  int n = 1;
  const double widen = 1.0 + std::clamp(ap.aniso_threshold, 0, kAnisoThresholdMax) / 8.0;
  if (pmax > 0 && std::isfinite(pmax))
    n = pmin > 0 ? static_cast<int>(std::min<double>(cap, std::max(1.0, std::ceil(pmax / (widen * pmin))))) : cap;
  if (ap.aniso_rounding == AnisoRounding::PowerOfTwo)
    while ((n & (n - 1)) != 0) ++n;
  const double lambda = pmax > 0 ? std::log2(pmax / n) : kLodMinusInfinity / 256.0;
  // The major vector in (s, t) units.
  const double ds = (major_x ? d[0] : d[2]) / tex_.width(), dt = (major_x ? d[1] : d[3]) / tex_.height();
  std::array<double, 4> sum{};
  for (int i = 1; i <= n; ++i) {
    const double f = -0.5 + static_cast<double>(i) / (n + 1);
    std::array<double, 4> c = sample_ideal(s + f * ds, t + f * dt, lambda);
    if (tex_.format == TexelFormat::SRGBA8) c = srgb_decoded(c);  // probes average in linear
    for (size_t ch = 0; ch < 4; ++ch) sum[ch] += c[ch];
  }
  for (double& x : sum) x /= n;
  return tex_.format == TexelFormat::SRGBA8 ? srgb_encoded(sum) : sum;
}

}  // namespace tfu
