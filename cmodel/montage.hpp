// Side-by-side montage of images with a text label above each (for comparing filter outputs).
//
// Layout (all in pixels; P = kMontagePad, L = label band height, 0 when no label is drawn):
//   cell_w = max image width, cell_h = max image height, columns = min(columns, n),
//   rows = ceil(n / columns)
//   width  = P + columns * (cell_w + P)
//   height = P + rows * (L + cell_h + P)
// Image i sits in column i % columns, row i / columns, horizontally centred in its cell, below its
// label band. The background is opaque dark grey; images are copied as they are (alpha included).
// Labels are rendered with OpenImageIO's render_text in the font "DejaVuSans" (Debian package
// fonts-dejavu-core). When that font cannot be found, the montage is produced without labels
// (L = 0) rather than failing.
#pragma once

#include <string>
#include <vector>

#include "cmodel/texture.hpp"

namespace tfu {

inline constexpr int kMontagePad = 4;
inline constexpr int64_t kMaxMontageSize = 32768;  // pixels per side of a montage
inline constexpr int kMontageLabelHeight = 20;
inline constexpr int kMontageFontSize = 14;
inline constexpr Rgba8 kMontageBackground{48, 48, 48, 255};
inline constexpr const char* kMontageFont = "DejaVuSans";

struct MontageLayout {
  int columns = 0, rows = 0;
  int cell_w = 0, cell_h = 0, label_h = 0;
  int width = 0, height = 0;
};

// Pure size arithmetic (see above). Throws InputError for no images, an empty image or columns < 1.
MontageLayout montage_layout(const std::vector<Image>& images, int columns, int label_h);

// True if OpenImageIO can render text in kMontageFont on this machine.
bool montage_font_available();

// Tiles `images` into `columns` columns with labels[i] above image i (labels may be shorter than
// images; missing labels are blank; more labels than images is an InputError). If `labels_drawn`
// is given it says whether labels were rendered (false when none were asked for or the font is
// missing).
Image montage(const std::vector<Image>& images, const std::vector<std::string>& labels, int columns,
              bool* labels_drawn = nullptr);

}  // namespace tfu
