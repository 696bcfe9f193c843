#include "cmodel/bspline_prefilter.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "cmodel/datapath.hpp"
#include "cmodel/error.hpp"

namespace tfu {

namespace {

// Cubic B-spline interpolation coefficients (Unser's recursive filter, pole z = sqrt(3) - 2) of a
// periodic sequence; mirror boundaries are handled by the caller as a periodic sequence of length 2N.
std::vector<double> bspline_coefficients_periodic(const std::vector<double>& x) {
  const size_t n = x.size();
  if (n == 1) return x;
  const double z = std::sqrt(3.0) - 2.0;
  constexpr int kTerms = 40;  // |z|^40 < 1e-22
  std::vector<double> cp(n), c(n);
  double acc = 0, zk = 1;
  for (int k = 0; k < kTerms; ++k, zk *= z) acc += zk * 6.0 * x[(n - static_cast<size_t>(k) % n) % n];
  cp[0] = acc;
  for (size_t i = 1; i < n; ++i) cp[i] = 6.0 * x[i] + z * cp[i - 1];
  acc = 0;
  zk = z;
  for (int k = 0; k < kTerms; ++k, zk *= z) acc -= zk * cp[(n - 1 + static_cast<size_t>(k)) % n];
  c[n - 1] = acc;
  for (size_t i = n - 1; i-- > 0;) c[i] = z * (c[i + 1] - cp[i]);
  return c;
}

std::vector<double> bspline_coefficients(const std::vector<double>& x, WrapMode wrap) {
  if (wrap == WrapMode::Repeat) return bspline_coefficients_periodic(x);
  // Mirror (half-sample symmetric) extension: x0..xN-1 xN-1..x0, exact for mirrored-repeat, the
  // documented approximation for the clamp modes.
  std::vector<double> ext(x);
  ext.insert(ext.end(), x.rbegin(), x.rend());
  std::vector<double> c = bspline_coefficients_periodic(ext);
  c.resize(x.size());
  return c;
}

}  // namespace

BsplineCoefficients prefilter_bspline(const Texture& tex, WrapMode wrap_s, WrapMode wrap_t) {
  if (!byte_channels(tex.format))
    throw InputError(fmt::format("kernel bspline-interp needs an 8-bit texel format (rgba8 or l8), not {}",
                                 texel_format_name(tex.format)));
  BsplineCoefficients out;
  // Offline prefilter per level (double precision), then quantize with a fitted scale and bias.
  double cmin = 0.0, cmax = 1.0;
  for (const Image& lvl : tex.levels) {
    const auto w = static_cast<size_t>(lvl.width), h = static_cast<size_t>(lvl.height);
    std::vector<std::array<double, 4>> c(w * h);
    for (size_t i = 0; i < c.size(); ++i)
      c[i] = {lvl.texels[i].r / 255.0, lvl.texels[i].g / 255.0, lvl.texels[i].b / 255.0, lvl.texels[i].a / 255.0};
    for (size_t ch = 0; ch < 4; ++ch) {
      std::vector<double> line;
      for (size_t y = 0; y < h; ++y) {
        line.resize(w);
        for (size_t x = 0; x < w; ++x) line[x] = c[y * w + x][ch];
        line = bspline_coefficients(line, wrap_s);
        for (size_t x = 0; x < w; ++x) c[y * w + x][ch] = line[x];
      }
      for (size_t x = 0; x < w; ++x) {
        line.resize(h);
        for (size_t y = 0; y < h; ++y) line[y] = c[y * w + x][ch];
        line = bspline_coefficients(line, wrap_t);
        for (size_t y = 0; y < h; ++y) c[y * w + x][ch] = line[y];
      }
    }
    for (const auto& px : c)
      for (double v : px) {
        cmin = std::min(cmin, v);
        cmax = std::max(cmax, v);
      }
    out.exact.push_back(std::move(c));
  }
  constexpr double one = 1 << dp::kBsplineScaleBits;
  out.scale_q = std::llround(std::ceil((cmax - cmin) * one));
  out.bias_q = std::llround(std::floor(255.0 * cmin * one));
  const double S = static_cast<double>(out.scale_q), B = static_cast<double>(out.bias_q);
  const auto code = [S, B](double v) {
    return static_cast<uint8_t>(std::clamp(std::floor((255.0 * v * one - B) / S + 0.5), 0.0, 255.0));
  };
  for (size_t l = 0; l < tex.levels.size(); ++l) {
    const auto& c = out.exact[l];
    Image q(tex.levels[l].width, tex.levels[l].height);
    for (size_t i = 0; i < c.size(); ++i) q.texels[i] = {code(c[i][0]), code(c[i][1]), code(c[i][2]), code(c[i][3])};
    out.codes.push_back(std::move(q));
  }
  return out;
}

Texture bspline_coefficient_texture(const Texture& source, const BsplineCoefficients& c) {
  Texture t;
  t.format = TexelFormat::RGBA8;
  t.layout = source.layout;
  t.tile_bytes = source.tile_bytes;
  t.levels = c.codes;
  return t;
}

}  // namespace tfu
