// Crop rectangles and integer zoom for looking at part of an image (tfu compare --crop, tfu montage
// --crop --zoom; docs/metrics.md).
//
//   crop   the rectangle's pixels (x .. x+w-1, y .. y+h-1; row 0 on top, as the image files are
//          stored), copied as they are (alpha included). The rectangle must lie wholly inside.
//   zoom   each pixel replicated into an n x n block (nearest neighbour, no filtering): output
//          (x, y) = input (x / n, y / n).
// Rectangles are written X,Y,W,H: four decimal integers, X, Y >= 0 and W, H >= 1 (no spaces, no
// sign), e.g. `--crop 120,40,64,48`.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "cmodel/texture.hpp"

namespace tfu {

struct CropRect {
  int64_t x = 0, y = 0, w = 0, h = 0;
};

inline constexpr int kMaxZoom = 16;  // --zoom 1..kMaxZoom

// Parses X,Y,W,H; InputError "OPTION 'TEXT': expected X,Y,W,H ..." otherwise. Each number is at most
// INT_MAX (an image side is an int), so X + W cannot overflow.
CropRect parse_crop(std::string_view text, std::string_view option);

// InputError "OPTION X,Y,W,H: ... outside IMAGE (WxH)" unless the rectangle lies inside a
// width x height image; `image` names the image in that message.
void check_crop(const CropRect& r, int width, int height, std::string_view option, std::string_view image);

// The rectangle's pixels (check_crop first; std::invalid_argument if it does not lie inside).
Image crop_image(const Image& img, const CropRect& r);

// Each pixel as an n x n block, n in 1..kMaxZoom (std::invalid_argument otherwise).
Image zoom_image(const Image& img, int n);

}  // namespace tfu
