// Image quality metrics between two images of the same size (see docs/metrics.md).
//
//   PSNR  over R, G, B (alpha ignored), 8-bit peak 255: 10 log10(255^2 / MSE); identical -> +inf.
//   SSIM  Wang, Bovik, Sheikh, Simoncelli 2004, on luma Y = 0.299 R + 0.587 G + 0.114 B in the
//         0..255 scale, Gaussian 11x11 window (sigma 1.5), K1 = 0.01, K2 = 0.03, L = 255; the mean
//         of the SSIM map over every window that lies fully inside the image ("valid" windows, as in
//         Wang's ssim_index.m). Along an axis shorter than 11 pixels every pixel is a window centre
//         and the window is cut at the image edge and renormalized.
//   max / mean absolute difference in 8-bit levels; `max_abs` and `mean_abs` over R, G, B, and
//         the per-channel maxima for R, G, B, A.
// The FloatImage overloads compare a model output with an ideal (double-precision, unquantized)
// image in [0, 1]; the ideal is scaled by 255 and not rounded.
// Every function throws InputError when the sizes differ (the message names both sizes).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "cmodel/texture.hpp"

namespace tfu {

// One byte per pixel, row-major: nonzero selects the pixel (RenderResult::interior).
using PixelMask = std::vector<uint8_t>;

// Double-precision RGBA image, values in [0, 1], row-major, row 0 on top.
struct FloatImage {
  int width = 0, height = 0;
  std::vector<std::array<double, 4>> px;
};

inline constexpr double kSsimK1 = 0.01;
inline constexpr double kSsimK2 = 0.03;
inline constexpr double kSsimSigma = 1.5;
inline constexpr int kSsimWindow = 11;  // Gaussian window side (radius 5)

// Absolute differences in 8-bit levels.
struct DiffStats {
  std::array<int, 4> max_abs_channel{};  // R, G, B, A
  int max_abs = 0;                       // max over R, G, B
  double mean_abs = 0;                   // mean over all pixels and R, G, B
};

// Everything `tfu compare` reports.
struct ImageMetrics {
  double mse = 0;      // over R, G, B, in squared 8-bit levels
  double psnr_db = 0;  // +inf when mse == 0
  double ssim = 1;
  DiffStats diff;
};

double mse_rgb(const Image& a, const Image& b);
double psnr_db(const Image& a, const Image& b);
double ssim_luma(const Image& a, const Image& b);
DiffStats diff_stats(const Image& a, const Image& b);
// Over the pixels a mask selects: their MSE (0 when none is selected), PSNR from it (+inf when they are equal or none is
// selected); SSIM as the mean of the SSIM map over the valid window centres the mask selects (the
// windows still read their unselected neighbours; 1 when none is selected). The mask must hold one
// entry per pixel (InputError otherwise).
double mse_rgb(const Image& a, const Image& b, const PixelMask& mask);
double psnr_db(const Image& a, const Image& b, const PixelMask& mask);
double ssim_luma(const Image& a, const Image& b, const PixelMask& mask);
ImageMetrics compare_images(const Image& a, const Image& b);

// Against an ideal image (values in [0, 1], compared as 255 * value).
double mse_rgb(const Image& a, const FloatImage& ideal);
double psnr_db(const Image& a, const FloatImage& ideal);
double ssim_luma(const Image& a, const FloatImage& ideal);

// PSNR from an MSE in squared 8-bit levels (+inf for 0).
double psnr_from_mse(double mse);
// "inf" for +infinity, otherwise fixed with `decimals` digits.
std::string format_metric(double v, int decimals = 4);

// Heat map of |a - b| (max over R, G, B per pixel) through black -> blue -> red -> yellow -> white;
// a difference of `scale` levels or more is white. Alpha 255. scale must be >= 1 (InputError).
Image diff_heatmap(const Image& a, const Image& b, int scale);
// The colour of a difference `d` (in levels) for a given scale; exposed for tests and docs.
Rgba8 heatmap_colour(int d, int scale);

}  // namespace tfu
