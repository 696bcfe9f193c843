// Fuzz target (f): Quake III game data through the level loader (docs/fuzzing.md). The first byte
// chooses the container: even, the rest is a BSP file (parse_bsp, build_level); odd, the rest is a
// .pk3 (zip) archive, written to a private temporary directory and opened as a game directory
// (Pk3Archive, GameArchives, its levels in turn, textures from the archive). A level that loads
// becomes the level scene from each of up to two spawn points at 16x12, rendered with the request
// trace and the supersampled ground truth, as `tfu render --scene oa:MAP --trace-out --truth-out`
// does. Bad input must end in an InputError; anything else is a finding.
//
// Cost limits of the harness (the loader's own are larger): at most 2 levels of an archive, and a
// level above 20,000 triangles is loaded but not rendered.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "cmodel/bsp.hpp"
#include "cmodel/error.hpp"
#include "cmodel/q3_archives.hpp"
#include "cmodel/q3_level.hpp"
#include "cmodel/q3_scene.hpp"
#include "cmodel/q3_textures.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/temp_paths.hpp"
#include "testbench/fuzz/fuzz_input.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path& work_dir() {
  static const tfu::TempDir d("tfu-fuzz-level", fs::exists("/dev/shm") ? "/dev/shm" : "");
  return d.path();
}

void render_level(const tfu::q3::Level& level) {
  if (level.counts.triangles > 20000) return;
  const int spawns = static_cast<int>(level.spawns.size());
  for (int spawn = 0; spawn < std::max(1, std::min(spawns, 2)); ++spawn) {
    const tfu::Scene scene = tfu::q3::level_scene(level, spawn, 16, 12);
    tfu::RenderOptions o;
    o.threads = 1;
    o.trace = true;
    o.ground_truth = true;
    const tfu::RenderResult r = tfu::render_scene(scene, o);
    // 4 requests per shaded quad and material stage (base texture and light map).
    const size_t n = r.trace.requests.size(), quads = static_cast<size_t>(r.stats.quads);
    if (n % 4 != 0 || n > 4 * quads * tfu::kMaxStages) std::abort();
    if (r.truth.width != 16 || r.truth.height != 12) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1 || size > 262144) return 0;
  const std::span<const uint8_t> body(data + 1, size - 1);
  try {
    if (data[0] % 2 == 0) {
      const tfu::q3::Bsp bsp = tfu::q3::parse_bsp(body, "fuzz.bsp");
      const tfu::q3::GameArchives none(std::vector<std::string>{});
      tfu::q3::TextureCache cache(none);
      render_level(tfu::q3::build_level(bsp, "fuzz", "fuzz.bsp", cache));
    } else {
      const fs::path pk3 = work_dir() / "pak0.pk3";
      {
        std::ofstream f(pk3, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char*>(body.data()), static_cast<std::streamsize>(body.size()));
      }
      const tfu::q3::GameArchives archives(work_dir().string());
      tfu::q3::TextureCache cache(archives);
      const std::vector<std::string> levels = archives.level_names();
      for (size_t k = 0; k < levels.size() && k < 2; ++k) {
        try {
          render_level(tfu::q3::load_level(archives, levels[k], cache));
        } catch (const tfu::InputError&) {
        }
      }
    }
  } catch (const tfu::InputError&) {
  }
  return 0;
}
