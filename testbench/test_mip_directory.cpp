// A MIP chain written by `tfu mipmap --out DIR` reads back as a texture (cmodel/texture.hpp): the
// edge-preserving levels (Lee & Jen Eq. 7) come back texel for texel, so a scene or trace can use them.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/procedural.hpp"
#include "cmodel/texture.hpp"

namespace tfu {
namespace {

namespace fs = std::filesystem;

TEST(MipDirectory, EdgePreservingLevelsReadBack) {
  Texture tex = make_procedural("text", 64).texture;
  generate_mipmaps(tex, MipMethod::Edge, 0.5);
  ASSERT_EQ(tex.levels.size(), 7u);
  const fs::path dir = fs::temp_directory_path() / fmt::format("tfu-test-mips-{}", ::getpid());
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (size_t l = 0; l < tex.levels.size(); ++l)
    save_image(tex.levels[l], (dir / fmt::format("level_{:02d}.png", l)).string(), false);
  const Texture back = load_texture(dir.string());
  ASSERT_EQ(back.levels.size(), tex.levels.size());
  for (size_t l = 0; l < tex.levels.size(); ++l) {
    EXPECT_EQ(back.levels[l].width, tex.levels[l].width);
    EXPECT_TRUE(back.levels[l].texels == tex.levels[l].texels) << "level " << l;
  }
  // A gap ends the chain; a wrong size is refused naming the directory.
  fs::remove(dir / "level_03.png");
  EXPECT_EQ(load_texture(dir.string()).levels.size(), 3u);
  fs::copy_file(dir / "level_01.png", dir / "level_03.png");  // 32x32 where 8x8 belongs
  fs::remove(dir / "level_02.png");
  fs::copy_file(dir / "level_01.png", dir / "level_02.png");
  EXPECT_THROW((void)load_texture(dir.string()), InputError);
  fs::remove_all(dir);
  fs::create_directories(dir);
  EXPECT_THROW((void)load_texture(dir.string()), InputError);  // no level_00.png
  fs::remove_all(dir);
}

}  // namespace
}  // namespace tfu
