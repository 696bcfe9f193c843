#include "cmodel/image_crop.hpp"

#include <charconv>
#include <limits>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {

namespace {

// Image sides are ints: a larger number cannot lie inside any image, and sums of two stay in int64.
inline constexpr int64_t kMaxCropNumber = std::numeric_limits<int>::max();

std::string text_of(const CropRect& r) { return fmt::format("{},{},{},{}", r.x, r.y, r.w, r.h); }

}  // namespace

CropRect parse_crop(std::string_view text, std::string_view option) {
  const auto bad = [&](std::string_view why) {
    return InputError(fmt::format("{} '{}': expected X,Y,W,H, four integers with X, Y >= 0 and W, H >= 1 ({})", option,
                                  quote_input(text, 40), why));
  };
  int64_t v[4] = {};
  const char* p = text.data();
  const char* const end = text.data() + text.size();
  for (int i = 0; i < 4; ++i) {
    if (i > 0) {
      if (p == end || *p != ',') throw bad(p == end ? "fewer than four numbers" : "numbers are separated by commas");
      ++p;
    }
    if (p == end || *p < '0' || *p > '9') throw bad("a number is missing or signed");
    const auto [next, ec] = std::from_chars(p, end, v[i]);
    if (ec != std::errc{} || v[i] > kMaxCropNumber) throw bad(fmt::format("numbers are at most {}", kMaxCropNumber));
    p = next;
  }
  if (p != end) throw bad("more than four numbers, or text after them");
  if (v[2] < 1 || v[3] < 1) throw bad("W and H must be >= 1");
  return {v[0], v[1], v[2], v[3]};
}

void check_crop(const CropRect& r, int width, int height, std::string_view option, std::string_view image) {
  if (r.x < 0 || r.y < 0 || r.w < 1 || r.h < 1 || r.x + r.w > width || r.y + r.h > height)
    throw InputError(fmt::format("{} {}: the rectangle (x {}..{}, y {}..{}) is not inside '{}' ({}x{})", option,
                                 text_of(r), r.x, r.x + r.w - 1, r.y, r.y + r.h - 1, quote_path(image), width, height));
}

Image crop_image(const Image& img, const CropRect& r) {
  if (r.x < 0 || r.y < 0 || r.w < 1 || r.h < 1 || r.x + r.w > img.width || r.y + r.h > img.height)
    throw std::invalid_argument("crop_image: rectangle " + text_of(r) + " outside the image");
  Image out(static_cast<int>(r.w), static_cast<int>(r.h));
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) out.at(x, y) = img.at(static_cast<int>(r.x) + x, static_cast<int>(r.y) + y);
  return out;
}

Image zoom_image(const Image& img, int n) {
  if (n < 1 || n > kMaxZoom)
    throw std::invalid_argument(fmt::format("zoom_image: factor {} outside 1..{}", n, kMaxZoom));
  Image out(img.width * n, img.height * n);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) out.at(x, y) = img.at(x / n, y / n);
  return out;
}

}  // namespace tfu
