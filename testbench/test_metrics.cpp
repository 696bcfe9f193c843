// Image metrics (cmodel/metrics.hpp), montage layout (cmodel/montage.hpp) and crops
// (cmodel/image_crop.hpp): hand-derived values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include "cmodel/error.hpp"
#include "cmodel/image_crop.hpp"
#include "cmodel/metrics.hpp"
#include "cmodel/montage.hpp"
#include "cmodel/texture.hpp"
#include "testbench/input_error.hpp"

namespace tfu {
namespace {

// A deterministic textured test image (gradients plus a checker), so SSIM has structure to lose.
Image pattern(int w, int h) {
  Image im(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int c = ((x / 4 + y / 4) % 2) * 60;
      im.at(x, y) = {static_cast<uint8_t>(40 + 4 * x % 120 + c), static_cast<uint8_t>(30 + 3 * y % 150 + c),
                     static_cast<uint8_t>(100 + c), 255};
    }
  return im;
}

// `im` plus uniform integer noise in [-amp, amp] on R, G, B (clamped), fixed seed.
Image noisy(const Image& im, int amp, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> d(-amp, amp);
  Image out = im;
  auto add = [&](uint8_t v) { return static_cast<uint8_t>(std::clamp(v + d(rng), 0, 255)); };
  for (Rgba8& t : out.texels) t = {add(t.r), add(t.g), add(t.b), t.a};
  return out;
}

FloatImage to_float(const Image& im) {
  FloatImage f{im.width, im.height, {}};
  for (const Rgba8& t : im.texels) f.px.push_back({t.r / 255.0, t.g / 255.0, t.b / 255.0, t.a / 255.0});
  return f;
}

TEST(Metrics, IdenticalImages) {
  const Image a = pattern(32, 24);
  EXPECT_EQ(mse_rgb(a, a), 0.0);
  EXPECT_TRUE(std::isinf(psnr_db(a, a)));
  EXPECT_GT(psnr_db(a, a), 0);
  EXPECT_EQ(format_metric(psnr_db(a, a)), "inf");
  EXPECT_DOUBLE_EQ(ssim_luma(a, a), 1.0);
  const DiffStats d = diff_stats(a, a);
  EXPECT_EQ(d.max_abs, 0);
  EXPECT_EQ(d.mean_abs, 0.0);
}

TEST(Metrics, UniformOffsetOfOne) {
  // Every R, G, B one level up: MSE = 1, PSNR = 20 log10(255) = 48.1308 dB.
  const Image a(16, 16, {10, 20, 30, 255});
  const Image b(16, 16, {11, 21, 31, 255});
  EXPECT_DOUBLE_EQ(mse_rgb(a, b), 1.0);
  EXPECT_NEAR(psnr_db(a, b), 48.1308, 5e-5);
  EXPECT_DOUBLE_EQ(psnr_db(a, b), 20.0 * std::log10(255.0));
  EXPECT_EQ(format_metric(psnr_db(a, b)), "48.1308");
  const DiffStats d = diff_stats(a, b);
  EXPECT_EQ(d.max_abs, 1);
  EXPECT_EQ(d.max_abs_channel, (std::array<int, 4>{1, 1, 1, 0}));
  EXPECT_DOUBLE_EQ(d.mean_abs, 1.0);
}

TEST(Metrics, OnePixelOff) {
  // N = 10 x 10 pixels, one pixel's red off by d = 30: MSE = d^2 / (3 N) = 900 / 300 = 3.
  const Image a(10, 10, {100, 100, 100, 255});
  Image b = a;
  b.at(3, 7).r = 130;
  b.at(3, 7).a = 0;  // alpha counts only in the per-channel maximum
  EXPECT_DOUBLE_EQ(mse_rgb(a, b), 3.0);
  EXPECT_DOUBLE_EQ(psnr_db(a, b), 10.0 * std::log10(255.0 * 255.0 / 3.0));
  const DiffStats d = diff_stats(a, b);
  EXPECT_EQ(d.max_abs, 30);
  EXPECT_EQ(d.max_abs_channel, (std::array<int, 4>{30, 0, 0, 255}));
  EXPECT_DOUBLE_EQ(d.mean_abs, 30.0 / 300.0);
}

TEST(Metrics, SsimDecreasesWithNoiseAndIsSymmetric) {
  const Image a = pattern(48, 40);
  double prev = ssim_luma(a, a);
  for (int amp : {2, 8, 24, 64}) {
    const Image b = noisy(a, amp, 7u);
    const double s = ssim_luma(a, b);
    EXPECT_LT(s, prev) << "amp " << amp;
    EXPECT_GT(s, -1.0);
    EXPECT_EQ(s, ssim_luma(b, a)) << "amp " << amp;  // the formula is symmetric term by term
    EXPECT_EQ(psnr_db(a, b), psnr_db(b, a));
    prev = s;
  }
}

TEST(Metrics, OverAMask) {
  // One pixel's red off by 30 in a 10 x 10 image; a mask of 20 pixels that holds it: MSE over the
  // mask = 900 / (3 x 20) = 15; a mask without it: identical, +inf; a full mask: the whole-image figures.
  const Image a(10, 10, {100, 100, 100, 255});
  Image b = a;
  b.at(3, 7).r = 130;
  PixelMask with(100, 0), without(100, 0), all(100, 1);
  for (int i = 0; i < 20; ++i) with[static_cast<size_t>(70 + i)] = 1;  // rows 7 and 8
  for (int i = 0; i < 20; ++i) without[static_cast<size_t>(i)] = 1;    // rows 0 and 1
  EXPECT_DOUBLE_EQ(mse_rgb(a, b, with), 15.0);
  EXPECT_DOUBLE_EQ(psnr_db(a, b, with), 10.0 * std::log10(255.0 * 255.0 / 15.0));
  EXPECT_TRUE(std::isinf(psnr_db(a, b, without)));
  EXPECT_DOUBLE_EQ(psnr_db(a, b, all), psnr_db(a, b));
  const Image p = pattern(40, 32), q = noisy(p, 20, 3u);
  EXPECT_DOUBLE_EQ(ssim_luma(p, q, PixelMask(p.texels.size(), 1)), ssim_luma(p, q));
  // Only the noisy half is selected: SSIM lower than over the whole image, where the other half is clean.
  Image half = p;
  PixelMask left(p.texels.size(), 0);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 20; ++x) {
      half.at(x, y) = q.at(x, y);
      left[static_cast<size_t>(y * 40 + x)] = 1;
    }
  EXPECT_LT(ssim_luma(p, half, left), ssim_luma(p, half));
  EXPECT_DOUBLE_EQ(ssim_luma(p, half, PixelMask(p.texels.size(), 0)), 1.0);
  EXPECT_THROW(psnr_db(a, b, PixelMask(99, 1)), InputError);
}

TEST(Metrics, SsimSmallImagesAndUniformOffset) {
  // Smaller than the 11x11 window: every pixel is a centre, window cut at the edges.
  const Image a = pattern(5, 3);
  EXPECT_DOUBLE_EQ(ssim_luma(a, a), 1.0);
  EXPECT_LT(ssim_luma(a, noisy(a, 30, 1u)), 1.0);
  // Flat images with a luma offset: variances are 0, so SSIM = (2 m1 m2 + C1) / (m1^2 + m2^2 + C1).
  const Image f1(12, 12, {100, 100, 100, 255}), f2(12, 12, {110, 110, 110, 255});
  const double c1 = (0.01 * 255) * (0.01 * 255);
  EXPECT_NEAR(ssim_luma(f1, f2), (2 * 100.0 * 110.0 + c1) / (100.0 * 100.0 + 110.0 * 110.0 + c1), 1e-9);
}

TEST(Metrics, AgainstFloatImage) {
  const Image a = pattern(20, 20);
  const FloatImage fa = to_float(a);
  EXPECT_NEAR(mse_rgb(a, fa), 0.0, 1e-20);
  EXPECT_NEAR(ssim_luma(a, fa), 1.0, 1e-12);
  // Ideal value half a level above every 8-bit value: MSE = 0.25, PSNR = 20 log10(255) + 6.0206 dB.
  FloatImage half = fa;
  for (auto& p : half.px)
    for (int c = 0; c < 3; ++c) p[static_cast<size_t>(c)] += 0.5 / 255.0;
  EXPECT_NEAR(mse_rgb(a, half), 0.25, 1e-9);
  EXPECT_NEAR(psnr_db(a, half), 20.0 * std::log10(255.0) + 20.0 * std::log10(2.0), 1e-6);
}

TEST(Metrics, SizeMismatchNamesBothSizes) {
  const Image a(4, 4), b(8, 2);
  try {
    (void)psnr_db(a, b);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("4x4"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("8x2"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)ssim_luma(a, b), InputError);
  EXPECT_THROW((void)diff_stats(a, b), InputError);
  EXPECT_THROW((void)diff_heatmap(a, b, 16), InputError);
  EXPECT_THROW((void)psnr_db(a, FloatImage{8, 2, std::vector<std::array<double, 4>>(16)}), InputError);
  EXPECT_THROW((void)diff_heatmap(a, a, 0), InputError);
}

TEST(Heatmap, IdenticalIsBlackAndScaleSaturates) {
  const Image a = pattern(9, 7);
  const Image h = diff_heatmap(a, a, 16);
  ASSERT_EQ(h.width, 9);
  ASSERT_EQ(h.height, 7);
  for (const Rgba8& t : h.texels) EXPECT_EQ(t, (Rgba8{0, 0, 0, 255}));
  // Stops: black, blue, red, yellow, white at 0, 1/4, 1/2, 3/4, 1 of the scale.
  EXPECT_EQ(heatmap_colour(0, 16), (Rgba8{0, 0, 0, 255}));
  EXPECT_EQ(heatmap_colour(4, 16), (Rgba8{0, 0, 255, 255}));
  EXPECT_EQ(heatmap_colour(8, 16), (Rgba8{255, 0, 0, 255}));
  EXPECT_EQ(heatmap_colour(12, 16), (Rgba8{255, 255, 0, 255}));
  EXPECT_EQ(heatmap_colour(16, 16), (Rgba8{255, 255, 255, 255}));
  EXPECT_EQ(heatmap_colour(200, 16), (Rgba8{255, 255, 255, 255}));
  EXPECT_EQ(heatmap_colour(2, 16), (Rgba8{0, 0, 128, 255}));  // halfway to blue: 127.5 rounds up
  // The per-pixel difference is the maximum over R, G, B.
  Image b = a;
  b.at(2, 3).g = static_cast<uint8_t>(a.at(2, 3).g + 8);
  EXPECT_EQ(diff_heatmap(a, b, 16).at(2, 3), (Rgba8{255, 0, 0, 255}));
}

TEST(Metrics, PngRoundTrip) {
  // What `tfu compare` does: save both images as PNG, load them back, measure.
  const auto dir = std::filesystem::temp_directory_path() / "tfu_test_metrics";
  std::filesystem::create_directories(dir);
  const Image a = pattern(16, 16);
  const Image b(16, 16, {200, 0, 0, 255});
  save_image(a, (dir / "a.png").string(), true);
  save_image(b, (dir / "b.png").string(), true);
  const Image la = load_image((dir / "a.png").string()), lb = load_image((dir / "b.png").string());
  EXPECT_EQ(la.texels, a.texels);
  EXPECT_EQ(compare_images(la, lb).mse, mse_rgb(a, b));
  std::filesystem::remove_all(dir);
}

TEST(Montage, LayoutArithmetic) {
  const std::vector<Image> ims = {Image(10, 6), Image(8, 12), Image(10, 10)};
  // 2 columns: cells 10 x 12, 2 rows; width = 4 + 2 (10 + 4) = 32, height = 4 + 2 (20 + 12 + 4) = 76.
  MontageLayout l = montage_layout(ims, 2, 20);
  EXPECT_EQ(l.columns, 2);
  EXPECT_EQ(l.rows, 2);
  EXPECT_EQ(l.cell_w, 10);
  EXPECT_EQ(l.cell_h, 12);
  EXPECT_EQ(l.width, 32);
  EXPECT_EQ(l.height, 76);
  // More columns than images: one row of 3; no labels: height = 4 + 12 + 4 = 20, width = 4 + 3 * 14 = 46.
  l = montage_layout(ims, 8, 0);
  EXPECT_EQ(l.columns, 3);
  EXPECT_EQ(l.rows, 1);
  EXPECT_EQ(l.width, 46);
  EXPECT_EQ(l.height, 20);
  EXPECT_THROW(montage_layout({}, 2, 0), InputError);
  EXPECT_THROW(montage_layout(ims, 0, 0), InputError);
}

TEST(Montage, PlacesImagesAndNeverFailsOnLabels) {
  const Image red(6, 4, {255, 0, 0, 255}), blue(4, 4, {0, 0, 255, 255});
  bool drawn = true;
  // No labels: the layout is exact and the pixels are where the layout says.
  Image m = montage({red, blue}, {}, 2, &drawn);
  EXPECT_FALSE(drawn);
  EXPECT_EQ(m.width, 4 + 2 * (6 + 4));
  EXPECT_EQ(m.height, 4 + 4 + 4);
  EXPECT_EQ(m.at(0, 0), kMontageBackground);
  EXPECT_EQ(m.at(4, 4), red.at(0, 0));
  EXPECT_EQ(m.at(4 + 10 + 1, 4), blue.at(0, 0));  // 4-wide image centred in a 6-wide cell
  EXPECT_EQ(m.at(4 + 10, 4), kMontageBackground);
  // With labels: the band exists only if the font was found; either way a montage comes back.
  m = montage({red, blue}, {"red", "a very long label that does not fit in the cell"}, 1, &drawn);
  const int band = montage_font_available() ? kMontageLabelHeight : 0;
  EXPECT_EQ(drawn, montage_font_available());
  EXPECT_EQ(m.width, 4 + 6 + 4);
  EXPECT_EQ(m.height, 4 + 2 * (band + 4 + 4));
  EXPECT_EQ(m.at(4, 4 + band), red.at(0, 0));
  EXPECT_THROW(montage({red}, {"a", "b"}, 1), InputError);
}

// ---- crop rectangles (cmodel/image_crop.hpp) ----

TEST(ImageCrop, ParsesXYWHAndRefusesEverythingElse) {
  const CropRect r = parse_crop("120,40,64,48", "--crop");
  EXPECT_EQ(r.x, 120);
  EXPECT_EQ(r.y, 40);
  EXPECT_EQ(r.w, 64);
  EXPECT_EQ(r.h, 48);
  const auto why = [](const char* text) { return input_error([&] { (void)parse_crop(text, "--crop"); }); };
  EXPECT_EQ(why("1,2,3"), "--crop '1,2,3': expected X,Y,W,H, four integers with X, Y >= 0 and W, H >= 1 (fewer than four numbers)");
  for (const char* bad : {"", "a", "1,2,3,4,5", "-1,2,3,4", "1,-2,3,4", "1, 2,3,4", "1,2,3,4x", "1;2;3;4", "+1,2,3,4", "0x1,2,3,4"})
    EXPECT_EQ(why(bad).find("--crop '"), 0u) << bad;
  EXPECT_NE(why("1,2,0,4").find("(W and H must be >= 1)"), std::string::npos);
  EXPECT_NE(why("1,2,3,0").find("(W and H must be >= 1)"), std::string::npos);
  EXPECT_NE(why("2147483648,0,1,1").find("at most 2147483647"), std::string::npos);  // no int overflow later
  EXPECT_EQ(parse_crop("2147483647,0,2147483647,1", "--crop").w, 2147483647);
}

TEST(ImageCrop, RectangleMustLieInside) {
  const auto why = [](const char* text, int w, int h) {
    return input_error([&] { check_crop(parse_crop(text, "--crop"), w, h, "--crop", "a.png"); });
  };
  EXPECT_EQ(why("0,0,8,6", 8, 6), "(no InputError)");  // the whole image
  EXPECT_EQ(why("7,5,1,1", 8, 6), "(no InputError)");  // the last pixel
  EXPECT_EQ(why("7,5,2,1", 8, 6), "--crop 7,5,2,1: the rectangle (x 7..8, y 5..5) is not inside 'a.png' (8x6)");
  EXPECT_NE(why("0,6,1,1", 8, 6).find("is not inside"), std::string::npos);
  EXPECT_NE(why("2147483647,0,2147483647,1", 8, 6).find("is not inside"), std::string::npos);
}

// The hand-made PNGs of testbench/data: crop_a.png and crop_b.png (12x9; B differs from A by at most
// 2 levels inside the rectangle 3,2,6,5 and by 40-46 outside it) and the same rectangle cut out by
// PIL (Image.crop((3, 2, 9, 7))): the crop is PIL's, pixel for pixel, and the metrics on the crop
// are those of the cut-out files.
TEST(ImageCrop, MetricsOnACropEqualThoseOfTheCutOutImages) {
  const std::filesystem::path data = std::filesystem::path(TFU_GOLDEN_DIR).parent_path() / "data";
  const Image a = load_image((data / "crop_a.png").string()), b = load_image((data / "crop_b.png").string());
  const Image a_cut = load_image((data / "crop_a_3_2_6_5.png").string());
  const Image b_cut = load_image((data / "crop_b_3_2_6_5.png").string());
  const CropRect r = parse_crop("3,2,6,5", "--crop");
  const Image a_crop = crop_image(a, r), b_crop = crop_image(b, r);
  ASSERT_EQ(a_crop.width, 6);
  ASSERT_EQ(a_crop.height, 5);
  EXPECT_EQ(a_crop.texels, a_cut.texels);
  EXPECT_EQ(b_crop.texels, b_cut.texels);
  const ImageMetrics m = compare_images(a_crop, b_crop), cut = compare_images(a_cut, b_cut);
  EXPECT_EQ(m.mse, cut.mse);
  EXPECT_EQ(m.psnr_db, cut.psnr_db);
  EXPECT_EQ(m.ssim, cut.ssim);
  EXPECT_EQ(m.diff.max_abs, cut.diff.max_abs);
  EXPECT_EQ(m.diff.max_abs_channel, cut.diff.max_abs_channel);
  EXPECT_EQ(m.diff.mean_abs, cut.diff.mean_abs);
  EXPECT_EQ(m.diff.max_abs, 2);  // inside the rectangle: at most 2 levels (R up, B down)
  EXPECT_GE(compare_images(a, b).diff.max_abs, 40);  // the whole images differ by more
  EXPECT_THROW((void)crop_image(a, parse_crop("3,2,10,5", "--crop")), std::invalid_argument);
}

TEST(ImageCrop, ZoomReplicatesEachPixelIntoABlock) {
  Image im(2, 2);
  im.at(0, 0) = {1, 0, 0, 255};
  im.at(1, 0) = {2, 0, 0, 255};
  im.at(0, 1) = {3, 0, 0, 255};
  im.at(1, 1) = {4, 0, 0, 128};
  const Image z = zoom_image(im, 3);
  ASSERT_EQ(z.width, 6);
  ASSERT_EQ(z.height, 6);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) EXPECT_EQ(z.at(x, y), im.at(x / 3, y / 3)) << x << "," << y;
  EXPECT_EQ(zoom_image(im, 1).texels, im.texels);
  EXPECT_THROW((void)zoom_image(im, 0), std::invalid_argument);
  EXPECT_THROW((void)zoom_image(im, kMaxZoom + 1), std::invalid_argument);
}

}  // namespace
}  // namespace tfu
