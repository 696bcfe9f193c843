// tfu compare: image quality metrics (PSNR, SSIM, max/mean absolute difference) and a diff heat map.
// tfu montage: tile images side by side with labels, for looking at filter outputs together.
// Both take --crop X,Y,W,H (cmodel/image_crop.hpp): compare measures only the rectangle, montage
// shows only it (enlarged by --zoom N). Definitions in docs/metrics.md.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/image_crop.hpp"
#include "cmodel/json_output.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/metrics.hpp"
#include "cmodel/montage.hpp"
#include "cmodel/texture.hpp"
#include "sim/tfu/commands.hpp"

namespace tfu::cli {
namespace {

struct CompareOptions {
  std::string a, b;
  std::string diff;
  int scale = 16;
  std::string json;
  std::string mask;  // an image: the metrics over its non-black pixels
  std::string crop;  // X,Y,W,H; empty: the whole images
  bool force = false;
  std::optional<double> fail_below_psnr;  // exit 1 when PSNR (dB) is below it
};

struct MontageOptions {
  std::vector<std::string> inputs;
  std::string out;
  int columns = 4;
  std::string crop;  // X,Y,W,H; empty: the whole images
  int zoom = 1;
  bool force = false;
};

void print_metrics(const ImageMetrics& m) {
  fmt::print("psnr_db: {}\n", format_metric(m.psnr_db));
  fmt::print("ssim: {}\n", format_metric(m.ssim, 6));
  fmt::print("mse: {}\n", format_metric(m.mse, 6));
  fmt::print("max_abs_diff: {}\n", m.diff.max_abs);
  const auto& c = m.diff.max_abs_channel;
  fmt::print("max_abs_diff_rgba: {} {} {} {}\n", c[0], c[1], c[2], c[3]);
  fmt::print("mean_abs_diff: {}\n", format_metric(m.diff.mean_abs, 6));
}

// The rectangle of --crop, or nothing without one.
std::optional<CropRect> crop_of(const std::string& crop) {
  if (crop.empty()) return std::nullopt;
  return parse_crop(crop, "--crop");
}

// `img` (the file `name`) cut to the rectangle; the rectangle must lie inside it.
Image cropped(const Image& img, const std::optional<CropRect>& r, const std::string& name) {
  if (!r) return img;
  check_crop(*r, img.width, img.height, "--crop", name);
  return crop_image(img, *r);
}

// `a` is the compared image (the crop when --crop is given).
void write_json(const CompareOptions& o, const std::optional<CropRect>& crop, const Image& a, const ImageMetrics& m,
                std::ostream& out) {
  nlohmann::json j = {{"a", o.a},
                      {"b", o.b},
                      {"width", a.width},
                      {"height", a.height},
                      {"identical_rgb", m.mse == 0},
                      {"mse", m.mse},
                      {"ssim", m.ssim},
                      {"max_abs_diff", m.diff.max_abs},
                      {"max_abs_diff_rgba", m.diff.max_abs_channel},
                      {"mean_abs_diff", m.diff.mean_abs}};
  if (crop) j["crop"] = {{"x", crop->x}, {"y", crop->y}, {"width", crop->w}, {"height", crop->h}};
  // JSON has no infinity: identical images give the string "inf".
  if (std::isinf(m.psnr_db))
    j["psnr_db"] = "inf";
  else
    j["psnr_db"] = m.psnr_db;
  out << json_dump(j, 2) << '\n';
}

void run_compare(const CompareOptions& o) {
  if (o.scale < 1) throw InputError(fmt::format("--scale must be >= 1, got {}", o.scale));
  if (o.fail_below_psnr && !std::isfinite(*o.fail_below_psnr))
    throw InputError("--fail-below-psnr must be a finite number of dB");
  const std::optional<CropRect> crop = crop_of(o.crop);
  OutputFiles outputs(o.force);
  OutputFile* diff_file = o.diff.empty() ? nullptr : &outputs.add_image("--diff", o.diff);
  OutputFile* json_file = o.json.empty() ? nullptr : &outputs.add("--json", o.json);
  const Image full_a = load_image(o.a), full_b = load_image(o.b);  // InputError naming the file
  if (full_a.width != full_b.width || full_a.height != full_b.height)
    throw InputError(fmt::format("image sizes differ: {} is {}x{}, {} is {}x{}", o.a, full_a.width, full_a.height, o.b,
                                 full_b.width, full_b.height));
  // With --crop every figure (and the heat map) covers the rectangle only.
  const Image a = cropped(full_a, crop, o.a), b = cropped(full_b, crop, o.b);
  ImageMetrics m = compare_images(a, b);
  if (!o.mask.empty()) {  // MSE, PSNR and SSIM over the mask's pixels (docs/metrics.md); the differences stay whole
    const Image full_mask = load_image(o.mask);
    if (full_mask.width != full_a.width || full_mask.height != full_a.height)
      throw InputError(fmt::format("--mask '{}' is {}x{}, the images {}x{}", quote_path(o.mask), full_mask.width,
                                   full_mask.height, full_a.width, full_a.height));
    const Image mi = cropped(full_mask, crop, o.mask);
    PixelMask mask(mi.texels.size());
    size_t selected = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
      const Rgba8 t = mi.texels[i];
      mask[i] = (t.r | t.g | t.b) != 0;
      selected += mask[i];
    }
    if (selected == 0) throw InputError(fmt::format("--mask '{}' selects no pixel (it is black there)", quote_path(o.mask)));
    m.mse = mse_rgb(a, b, mask);
    m.psnr_db = psnr_from_mse(m.mse);
    m.ssim = ssim_luma(a, b, mask);
  }
  if (diff_file) diff_file->write_image(diff_heatmap(a, b, o.scale));
  if (json_file) write_json(o, crop, a, m, json_file->stream());
  outputs.commit();
  print_metrics(m);
  if (diff_file) print_summary_line(fmt::format("tfu compare: wrote {}", o.diff));
  if (json_file) print_summary_line(fmt::format("tfu compare: wrote {}", o.json));
  if (o.fail_below_psnr && m.psnr_db < *o.fail_below_psnr)
    throw CheckFailed(fmt::format("PSNR {:.4f} dB is below --fail-below-psnr {}", m.psnr_db, *o.fail_below_psnr));
}

// IMG[=LABEL]: an argument that names an existing file is taken whole; otherwise it splits at the
// first '='. Without a label the file name (no directory) is used. (The whole argument may be no
// valid path at all, e.g. a label longer than a file name may be: then it is not a file.)
std::pair<std::string, std::string> split_input(const std::string& arg) {
  const auto eq = arg.find('=');
  std::error_code ec;
  std::pair<std::string, std::string> r;
  if (std::filesystem::exists(arg, ec) || eq == std::string::npos)
    r = {arg, std::filesystem::path(arg).filename().string()};
  else
    r = {arg.substr(0, eq), arg.substr(eq + 1)};
  if (r.first.empty()) throw InputError(fmt::format("montage input '{}': no image file before '='", quote_input(arg)));
  return r;
}

void run_montage(const MontageOptions& o) {
  if (o.columns < 1) throw InputError(fmt::format("--columns must be >= 1, got {}", o.columns));
  if (o.zoom < 1 || o.zoom > kMaxZoom)
    throw InputError(fmt::format("--zoom must be in 1..{}, got {}", kMaxZoom, o.zoom));
  const std::optional<CropRect> crop = crop_of(o.crop);
  OutputFiles outputs(o.force);
  OutputFile& out = outputs.add_image("--out", o.out);
  std::vector<Image> images;
  std::vector<std::string> labels;
  for (const std::string& arg : o.inputs) {
    auto [path, label] = split_input(arg);
    Image img = cropped(load_image(path), crop, path);  // InputError naming the file
    // The zoomed tile must fit a montage side (before it is allocated).
    if (o.zoom > 1 && std::max(img.width, img.height) > kMaxMontageSize / o.zoom)
      throw InputError(fmt::format("--zoom {}: '{}' ({}x{}) would be wider or taller than {} pixels", o.zoom, quote_path(path),
                                   img.width, img.height, kMaxMontageSize));
    images.push_back(o.zoom > 1 ? zoom_image(img, o.zoom) : std::move(img));
    labels.push_back(std::move(label));
  }
  bool drawn = false;
  const Image m = montage(images, labels, o.columns, &drawn);
  out.write_image(m);
  outputs.commit();
  if (!drawn) fmt::print(stderr, "tfu montage: warning: font {} not available, labels omitted\n", kMontageFont);
  print_summary_line(fmt::format("tfu montage: wrote {} ({}x{})", o.out, m.width, m.height));
}

void register_montage(CLI::App& app) {
  auto o = std::make_shared<MontageOptions>();
  auto* cmd = app.add_subcommand("montage", "Tile images side by side with a label above each");
  cmd->add_option("images", o->inputs, "Input images as IMG or IMG=LABEL")->required();
  cmd->add_option("--out", o->out, "Output image (PNG, ...)")->required();
  cmd->add_option("--columns", o->columns, "Images per row")->capture_default_str();
  cmd->add_option("--crop", o->crop, "Show only this rectangle of each image: X,Y,W,H in pixels, 0,0 the top left corner");
  cmd->add_option("--zoom", o->zoom, "Enlarge each (cropped) image N times, each pixel an N x N block (1..16)")->capture_default_str();
  cmd->add_flag("--force", o->force, "Overwrite --out if it exists");
  cmd->callback([o] { run_montage(*o); });
}

}  // namespace

// Registers both `compare` and `montage` (they share the image-comparison tooling).
void register_compare(CLI::App& app) {
  auto o = std::make_shared<CompareOptions>();
  auto* cmd = app.add_subcommand("compare", "Image quality metrics of B against A: PSNR, SSIM, max/mean abs difference");
  cmd->add_option("a", o->a, "Reference image")->required();
  cmd->add_option("b", o->b, "Image to compare")->required();
  cmd->add_option("--diff", o->diff, "Write a heat map of |A - B| (max over RGB) to this image");
  cmd->add_option("--scale", o->scale, "Heat map: difference in levels that saturates to white")->capture_default_str();
  cmd->add_option("--json", o->json, "Also write the metrics as JSON");
  cmd->add_option("--mask", o->mask,
                  "PSNR, SSIM and MSE over the non-black pixels of this image only (e.g. tfu render --interior-out)");
  cmd->add_option("--crop", o->crop, "Measure only this rectangle: X,Y,W,H in pixels, 0,0 the top left corner (e.g. 120,40,64,48)");
  cmd->add_option("--fail-below-psnr", o->fail_below_psnr, "Exit with status 1 when the PSNR (dB) is below this (as idiff's thresholds)");
  cmd->add_flag("--force", o->force, "Overwrite --diff / --json if they exist");
  cmd->callback([o] { run_compare(*o); });
  register_montage(app);
}

}  // namespace tfu::cli
