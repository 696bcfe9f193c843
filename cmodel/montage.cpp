#include "cmodel/montage.hpp"

#include <algorithm>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {
namespace {

bool any_label(const std::vector<std::string>& labels) {
  return std::any_of(labels.begin(), labels.end(), [](const std::string& s) { return !s.empty(); });
}

// Top-left corner of cell i (the label band starts there; the image starts label_h lower).
std::pair<int, int> cell_origin(const MontageLayout& l, int i) {
  const int col = i % l.columns, row = i / l.columns;
  return {kMontagePad + col * (l.cell_w + kMontagePad), kMontagePad + row * (l.label_h + l.cell_h + kMontagePad)};
}

void blit(Image& dst, const Image& src, int x0, int y0) {
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < src.width; ++x) dst.at(x0 + x, y0 + y) = src.at(x, y);
}

// Draws the labels into `out` (wrapped as an OpenImageIO buffer); false if any rendering failed.
bool draw_labels(Image& out, const MontageLayout& l, const std::vector<std::string>& labels) {
  OIIO::ImageSpec spec(out.width, out.height, 4, OIIO::TypeDesc::UINT8);
  OIIO::ImageBuf buf(spec, out.texels.data());
  const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  bool ok = true;
  for (size_t i = 0; i < labels.size(); ++i) {
    if (labels[i].empty()) continue;
    const auto [x0, y0] = cell_origin(l, static_cast<int>(i));
    const OIIO::ROI band(x0, x0 + l.cell_w, y0, y0 + l.label_h, 0, 1, 0, 4);  // clip long labels to the cell
    const int baseline = y0 + l.label_h - 5;
    ok = OIIO::ImageBufAlgo::render_text(buf, x0 + 2, baseline, labels[i], kMontageFontSize, kMontageFont, white,
                                         OIIO::ImageBufAlgo::TextAlignX::Left,
                                         OIIO::ImageBufAlgo::TextAlignY::Baseline, 0, band) &&
         ok;
  }
  if (!ok) (void)buf.geterror();  // drop the message; the caller only needs to know
  return ok;
}

}  // namespace

MontageLayout montage_layout(const std::vector<Image>& images, int columns, int label_h) {
  if (images.empty()) throw InputError("montage needs at least one image");
  if (columns < 1) throw InputError(fmt::format("montage columns must be >= 1, got {}", columns));
  MontageLayout l;
  for (const Image& im : images) {
    if (im.width < 1 || im.height < 1) throw InputError(fmt::format("montage: empty image ({}x{})", im.width, im.height));
    l.cell_w = std::max(l.cell_w, im.width);
    l.cell_h = std::max(l.cell_h, im.height);
  }
  const int n = static_cast<int>(images.size());
  l.columns = std::min(columns, n);
  l.rows = (n + l.columns - 1) / l.columns;
  l.label_h = label_h;
  // 64-bit sizes, checked: many large images must not wrap an int.
  const int64_t w = kMontagePad + int64_t{l.columns} * (l.cell_w + kMontagePad);
  const int64_t h = kMontagePad + int64_t{l.rows} * (l.label_h + l.cell_h + kMontagePad);
  if (w > kMaxMontageSize || h > kMaxMontageSize)
    throw InputError(fmt::format("montage would be {}x{} pixels, more than {} per side (use fewer or smaller images, or --columns)",
                                 w, h, kMaxMontageSize));
  l.width = static_cast<int>(w);
  l.height = static_cast<int>(h);
  return l;
}

bool montage_font_available() {
  static const bool available = [] {
    const OIIO::ROI r = OIIO::ImageBufAlgo::text_size("Ag", kMontageFontSize, kMontageFont);
    if (!r.defined()) (void)OIIO::geterror();  // clear the global error so later messages stay clean
    return r.defined();
  }();
  return available;
}

Image montage(const std::vector<Image>& images, const std::vector<std::string>& labels, int columns,
              bool* labels_drawn) {
  if (labels.size() > images.size())
    throw InputError(fmt::format("montage: {} labels for {} images", labels.size(), images.size()));
  const bool want_labels = any_label(labels) && montage_font_available();
  const MontageLayout l = montage_layout(images, columns, want_labels ? kMontageLabelHeight : 0);
  Image out(l.width, l.height, kMontageBackground);
  for (size_t i = 0; i < images.size(); ++i) {
    const auto [x0, y0] = cell_origin(l, static_cast<int>(i));
    blit(out, images[i], x0 + (l.cell_w - images[i].width) / 2, y0 + l.label_h);
  }
  bool drawn = false;
  if (want_labels) {
    try {
      drawn = draw_labels(out, l, labels);
    } catch (const std::exception&) {
      drawn = false;  // never let text rendering break the montage
    }
  }
  if (labels_drawn) *labels_drawn = drawn;
  return out;
}

}  // namespace tfu
