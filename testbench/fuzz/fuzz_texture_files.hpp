// The texture files the `bindings` and `scene` fuzz targets may name (docs/fuzzing.md): a private
// temporary directory (TempDir) holding `a.png` (8x8, opaque), `b b.png` (5x3, a space in its
// name) and `c.tga` (4x4 with alpha), written once per process. Any other file is skipped by the
// harnesses (the `texture` target fuzzes image files themselves).
#pragma once

#include <array>
#include <filesystem>
#include <string>

#include "cmodel/temp_paths.hpp"
#include "cmodel/texture.hpp"

namespace tfu::fuzz {

inline constexpr std::array<const char*, 3> kTextureFiles = {"a.png", "b b.png", "c.tga"};

inline bool is_texture_file(const std::string& name) {
  for (const char* f : kTextureFiles)
    if (name == f) return true;
  return false;
}

inline const std::filesystem::path& texture_file_dir() {
  static const TempDir d("tfu-fuzz-textures", std::filesystem::exists("/dev/shm") ? "/dev/shm" : "");
  static const bool written = [] {
    const auto pattern = [](int w, int h, int alpha_step) {
      Image img(w, h);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          img.texels[static_cast<size_t>(y * w + x)] = {static_cast<uint8_t>(37 * x), static_cast<uint8_t>(53 * y),
                                                        static_cast<uint8_t>(11 * (x + y)),
                                                        static_cast<uint8_t>(255 - alpha_step * (x + y))};
      return img;
    };
    write_image_file(pattern(8, 8, 0), "a.png", (d.path() / "a.png").string());
    write_image_file(pattern(5, 3, 0), "b b.png", (d.path() / "b b.png").string());
    write_image_file(pattern(4, 4, 20), "c.tga", (d.path() / "c.tga").string());
    return true;
  }();
  (void)written;
  return d.path();
}

}  // namespace tfu::fuzz
