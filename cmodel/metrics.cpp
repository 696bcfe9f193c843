#include "cmodel/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {
namespace {

// R, G, B in the 0..255 scale as doubles: the common form of 8-bit and ideal images.
struct RgbPlane {
  int width = 0, height = 0;
  std::vector<std::array<double, 3>> px;
};

size_t pixel_count(int w, int h) { return static_cast<size_t>(w) * static_cast<size_t>(h); }

void check_same_size(int wa, int ha, int wb, int hb) {
  if (wa != wb || ha != hb) throw InputError(fmt::format("image sizes differ: {}x{} vs {}x{}", wa, ha, wb, hb));
  if (wa < 1 || ha < 1) throw InputError(fmt::format("cannot compare empty images ({}x{})", wa, ha));
}

RgbPlane to_plane(const Image& im) {
  if (im.texels.size() != pixel_count(im.width, im.height))
    throw InputError(fmt::format("{}x{} image holds {} texels", im.width, im.height, im.texels.size()));
  RgbPlane p{im.width, im.height, {}};
  p.px.reserve(im.texels.size());
  for (const Rgba8& t : im.texels)
    p.px.push_back({static_cast<double>(t.r), static_cast<double>(t.g), static_cast<double>(t.b)});
  return p;
}

RgbPlane to_plane(const FloatImage& im) {
  if (im.px.size() != pixel_count(im.width, im.height))
    throw InputError(fmt::format("{}x{} float image holds {} pixels", im.width, im.height, im.px.size()));
  RgbPlane p{im.width, im.height, {}};
  p.px.reserve(im.px.size());
  for (const auto& v : im.px) p.px.push_back({255.0 * v[0], 255.0 * v[1], 255.0 * v[2]});
  return p;
}

void check_mask(const RgbPlane& a, const PixelMask* mask) {
  if (mask && mask->size() != a.px.size())
    throw InputError(fmt::format("a pixel mask of {} entries for a {}x{} image", mask->size(), a.width, a.height));
}

// Over every pixel, or the pixels `mask` selects (0 when it selects none).
double mse(const RgbPlane& a, const RgbPlane& b, const PixelMask* mask = nullptr) {
  check_same_size(a.width, a.height, b.width, b.height);
  check_mask(a, mask);
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < a.px.size(); ++i) {
    if (mask && !(*mask)[i]) continue;
    ++n;
    for (size_t c = 0; c < 3; ++c) {
      const double d = a.px[i][c] - b.px[i][c];
      sum += d * d;
    }
  }
  return n ? sum / (3.0 * static_cast<double>(n)) : 0.0;
}

// ---- SSIM ----

std::vector<double> luma(const RgbPlane& p) {
  std::vector<double> y(p.px.size());
  for (size_t i = 0; i < y.size(); ++i) y[i] = 0.299 * p.px[i][0] + 0.587 * p.px[i][1] + 0.114 * p.px[i][2];
  return y;
}

// 1D Gaussian taps for offsets -r..r (not normalized: each output renormalizes over the taps it uses).
std::vector<double> gaussian_taps() {
  const int r = kSsimWindow / 2;
  std::vector<double> g(static_cast<size_t>(kSsimWindow));
  for (int k = -r; k <= r; ++k) g[static_cast<size_t>(k + r)] = std::exp(-(k * k) / (2.0 * kSsimSigma * kSsimSigma));
  return g;
}

// One separable pass along x (horizontal) or y; the window is cut at the edges and renormalized.
std::vector<double> blur_pass(const std::vector<double>& in, int w, int h, bool horizontal) {
  static const std::vector<double> g = gaussian_taps();
  const int r = kSsimWindow / 2;
  const int n = horizontal ? w : h;
  std::vector<double> out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int pos = horizontal ? x : y;
      double sum = 0, wsum = 0;
      for (int k = std::max(-r, -pos); k <= std::min(r, n - 1 - pos); ++k) {
        const int sx = horizontal ? x + k : x, sy = horizontal ? y : y + k;
        const double wk = g[static_cast<size_t>(k + r)];
        sum += wk * in[static_cast<size_t>(sy) * static_cast<size_t>(w) + static_cast<size_t>(sx)];
        wsum += wk;
      }
      out[static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)] = sum / wsum;
    }
  return out;
}

std::vector<double> blur(const std::vector<double>& in, int w, int h) {
  return blur_pass(blur_pass(in, w, h, true), w, h, false);
}

std::vector<double> product(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> p(a.size());
  for (size_t i = 0; i < a.size(); ++i) p[i] = a[i] * b[i];
  return p;
}

// Window centres along an axis of length n: fully inside ("valid") when n >= window, else all.
std::pair<int, int> centre_range(int n) {
  const int r = kSsimWindow / 2;
  return n >= kSsimWindow ? std::pair{r, n - 1 - r} : std::pair{0, n - 1};
}

// The mean of the SSIM map over the valid window centres, or over those `mask` selects (1 when it
// selects none).
double ssim(const RgbPlane& a, const RgbPlane& b, const PixelMask* mask = nullptr) {
  check_same_size(a.width, a.height, b.width, b.height);
  check_mask(a, mask);
  const int w = a.width, h = a.height;
  const std::vector<double> y1 = luma(a), y2 = luma(b);
  const std::vector<double> mu1 = blur(y1, w, h), mu2 = blur(y2, w, h);
  const std::vector<double> e11 = blur(product(y1, y1), w, h), e22 = blur(product(y2, y2), w, h),
                            e12 = blur(product(y1, y2), w, h);
  const double c1 = (kSsimK1 * 255.0) * (kSsimK1 * 255.0), c2 = (kSsimK2 * 255.0) * (kSsimK2 * 255.0);
  const auto [x0, x1] = centre_range(w);
  const auto [yb, ye] = centre_range(h);
  double sum = 0;
  size_t n = 0;
  for (int y = yb; y <= ye; ++y)
    for (int x = x0; x <= x1; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
      if (mask && !(*mask)[i]) continue;
      ++n;
      const double m1 = mu1[i], m2 = mu2[i];
      const double s11 = e11[i] - m1 * m1, s22 = e22[i] - m2 * m2, s12 = e12[i] - m1 * m2;
      sum += ((2 * m1 * m2 + c1) * (2 * s12 + c2)) / ((m1 * m1 + m2 * m2 + c1) * (s11 + s22 + c2));
    }
  return n ? sum / static_cast<double>(n) : 1.0;
}

// ---- heat map ----

int max_rgb_diff(const Rgba8& p, const Rgba8& q) {
  return std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
}

}  // namespace

double psnr_from_mse(double m) {
  if (m <= 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(255.0 * 255.0 / m);
}

std::string format_metric(double v, int decimals) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.{}f}", v, decimals);
}

double mse_rgb(const Image& a, const Image& b) { return mse(to_plane(a), to_plane(b)); }
double mse_rgb(const Image& a, const Image& b, const PixelMask& mask) { return mse(to_plane(a), to_plane(b), &mask); }
double psnr_db(const Image& a, const Image& b, const PixelMask& mask) { return psnr_from_mse(mse_rgb(a, b, mask)); }
double ssim_luma(const Image& a, const Image& b, const PixelMask& mask) { return ssim(to_plane(a), to_plane(b), &mask); }
double psnr_db(const Image& a, const Image& b) { return psnr_from_mse(mse_rgb(a, b)); }
double ssim_luma(const Image& a, const Image& b) { return ssim(to_plane(a), to_plane(b)); }

double mse_rgb(const Image& a, const FloatImage& ideal) { return mse(to_plane(a), to_plane(ideal)); }
double psnr_db(const Image& a, const FloatImage& ideal) { return psnr_from_mse(mse_rgb(a, ideal)); }
double ssim_luma(const Image& a, const FloatImage& ideal) { return ssim(to_plane(a), to_plane(ideal)); }

DiffStats diff_stats(const Image& a, const Image& b) {
  check_same_size(a.width, a.height, b.width, b.height);
  DiffStats s;
  long long sum = 0;
  for (size_t i = 0; i < a.texels.size(); ++i) {
    const Rgba8 &p = a.texels[i], &q = b.texels[i];
    const std::array<int, 4> d = {std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b),
                                  std::abs(p.a - q.a)};
    for (size_t c = 0; c < 4; ++c) s.max_abs_channel[c] = std::max(s.max_abs_channel[c], d[c]);
    sum += d[0] + d[1] + d[2];
  }
  s.max_abs = std::max({s.max_abs_channel[0], s.max_abs_channel[1], s.max_abs_channel[2]});
  s.mean_abs = static_cast<double>(sum) / (3.0 * static_cast<double>(a.texels.size()));
  return s;
}

ImageMetrics compare_images(const Image& a, const Image& b) {
  ImageMetrics m;
  m.diff = diff_stats(a, b);  // checks the sizes first
  m.mse = mse_rgb(a, b);
  m.psnr_db = psnr_from_mse(m.mse);
  m.ssim = ssim_luma(a, b);
  return m;
}

Rgba8 heatmap_colour(int d, int scale) {
  if (scale < 1) throw InputError(fmt::format("heat-map scale must be >= 1, got {}", scale));
  // Stops at t = 0, 1/4, 1/2, 3/4, 1: black, blue, red, yellow, white (luminance rises monotonically).
  static constexpr std::array<std::array<double, 3>, 5> kStops = {
      {{0, 0, 0}, {0, 0, 255}, {255, 0, 0}, {255, 255, 0}, {255, 255, 255}}};
  const double t = std::clamp(static_cast<double>(std::abs(d)) / scale, 0.0, 1.0);
  const double pos = t * 4.0;
  const int seg = std::min(3, static_cast<int>(pos));
  const double f = pos - seg;
  const auto& lo = kStops[static_cast<size_t>(seg)];
  const auto& hi = kStops[static_cast<size_t>(seg + 1)];
  auto mix = [&](size_t c) { return static_cast<uint8_t>(std::lround(lo[c] + f * (hi[c] - lo[c]))); };
  return {mix(0), mix(1), mix(2), 255};
}

Image diff_heatmap(const Image& a, const Image& b, int scale) {
  check_same_size(a.width, a.height, b.width, b.height);
  heatmap_colour(0, scale);  // validates scale
  Image out(a.width, a.height);
  for (size_t i = 0; i < a.texels.size(); ++i) out.texels[i] = heatmap_colour(max_rgb_diff(a.texels[i], b.texels[i]), scale);
  return out;
}

}  // namespace tfu
