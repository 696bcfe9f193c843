// Golden images: every built-in scene rendered small (64x48) in five modes must match the committed
// PNGs in testbench/golden/ pixel for pixel (and their FNV-1a checksums in checksums.txt).
// Regenerate deliberately with scripts/regen-golden (sets TFU_REGEN_GOLDEN=1), then review the
// images and commit them with the change that explains why they moved.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cmodel/metrics.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"

namespace tfu {
namespace {

namespace fs = std::filesystem;
const fs::path kGoldenDir = TFU_GOLDEN_DIR;
constexpr int kW = 64, kH = 48;
// "aniso16": LINEAR_MIPMAP_LINEAR with maxAniso 16 (docs/anisotropic.md).
const char* const kModes[] = {"default", "LINEAR_MIPMAP_LINEAR", "CUBIC_MIPMAP_LINEAR", "EDGE_PRESERVING_MIPMAP_LINEAR", "aniso16"};

uint64_t fnv1a(const Image& img) {
  uint64_t h = 1469598103934665603ull;
  for (const Rgba8& t : img.texels)
    for (uint8_t b : {t.r, t.g, t.b, t.a}) h = (h ^ b) * 1099511628211ull;
  return h;
}

Image render_small(const std::string& scene_name, const std::string& mode) {
  Scene s = load_scene(scene_name);
  s.width = kW;
  s.height = kH;
  RenderOptions o;
  if (mode == "aniso16") {
    o.filter = filter_mode_from_name("LINEAR_MIPMAP_LINEAR");
    o.sampler_overrides["max_aniso"] = "16";
  } else if (mode != "default") {
    o.filter = filter_mode_from_name(mode);
  }
  o.threads = 2;
  return render_scene(s, o).image;
}

TEST(Golden, SceneImagesMatchCommittedPngs) {
  const bool regen = std::getenv("TFU_REGEN_GOLDEN") != nullptr;
  std::map<std::string, std::string> sums;
  {
    std::ifstream f(kGoldenDir / "checksums.txt");
    std::string key, hash;
    while (f >> key >> hash) sums[key] = hash;
  }
  std::ostringstream out;
  out << "# scene/mode at 64x48 -> FNV-1a 64 of the RGBA bytes (testbench/test_golden.cpp)\n";
  int checked = 0;
  for (const std::string& scene : builtin_scene_names())
    for (const char* mode : kModes) {
      const std::string key = fmt::format("{}/{}", scene, mode);
      const Image img = render_small(scene, mode);
      const std::string hash = fmt::format("{:016x}", fnv1a(img));
      out << key << ' ' << hash << '\n';
      const fs::path png = kGoldenDir / fmt::format("{}_{}.png", scene, mode);
      if (regen) {
        save_image(img, png.string(), true);
        continue;
      }
      ASSERT_TRUE(fs::exists(png)) << png << " missing: run scripts/regen-golden";
      const Image ref = load_image(png.string());
      EXPECT_EQ(sums[key], hash) << key;
      if (ref.texels != img.texels) {
        const fs::path got = fs::temp_directory_path() / fmt::format("tfu_golden_{}_{}.png", scene, mode);
        save_image(img, got.string(), true);
        ADD_FAILURE() << key << " differs from " << png << " (max abs diff " << diff_stats(ref, img).max_abs
                      << "); this render: " << got;
      }
      ++checked;
    }
  if (regen) {
    std::ofstream(kGoldenDir / "checksums.txt") << out.str();
    GTEST_SKIP() << "golden images regenerated in " << kGoldenDir;
  }
  EXPECT_EQ(checked, static_cast<int>(builtin_scene_names().size() * std::size(kModes)));
}

}  // namespace
}  // namespace tfu
