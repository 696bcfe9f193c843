// Fuzz target (a): a scene JSON through the parser and, when it parses, a 16x16 render with the
// request trace and the supersampled ground truth (docs/fuzzing.md). Bad input must end in an
// InputError; anything else (a crash, a sanitizer report, another exception) is a finding.
//
// Cost limits of the harness (not of the parser, whose own limits are larger): procedural textures
// of at most 64 texels, at most 8 meshes, tessellation and sphere segments of at most 32, and no
// texture files but the three of testbench/fuzz/fuzz_texture_files.hpp, relative to their
// directory (`"file": "b b.png"`; the texture target fuzzes image decoding).
#include <cstdlib>
#include <exception>

#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "testbench/fuzz/fuzz_input.hpp"
#include "testbench/fuzz/fuzz_texture_files.hpp"

namespace {

using nlohmann::json;

bool too_costly(const json& j) {
  if (j.is_array()) {
    for (const json& e : j)
      if (too_costly(e)) return true;
    return false;
  }
  if (!j.is_object()) return false;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    const json& v = it.value();
    if (key == "file" && !(v.is_string() && tfu::fuzz::is_texture_file(v.get<std::string>()))) return true;
    if (key == "meshes" && v.is_array() && v.size() > 8) return true;
    const auto over = [&](double limit) {
      if (v.is_number()) return !(v.get<double>() <= limit);
      if (v.is_array())
        for (const json& e : v)
          if (e.is_number() && !(e.get<double>() <= limit)) return true;
      return false;
    };
    if (key == "size" && over(64)) return true;
    if ((key == "segments" || key == "tessellation") && over(32)) return true;
    if (too_costly(v)) return true;
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 16384) return 0;
  const std::string text = tfu::fuzz::as_text(data, size);
  {
    const json pre = json::parse(text, nullptr, false);  // no exceptions: discarded on error
    if (!pre.is_discarded() && too_costly(pre)) return 0;
  }
  try {
    tfu::Scene scene = tfu::parse_scene(text, "fuzz.json", tfu::fuzz::texture_file_dir().string());
    scene.width = scene.height = 16;
    tfu::RenderOptions o;
    o.threads = 1;
    o.trace = true;
    o.ground_truth = true;
    const tfu::RenderResult r = tfu::render_scene(scene, o);
    // 4 requests per shaded quad and material stage (1..kMaxStages).
    const size_t n = r.trace.requests.size(), quads = static_cast<size_t>(r.stats.quads);
    if (n % 4 != 0 || n < 4 * quads || n > 4 * quads * tfu::kMaxStages) std::abort();
    o.ideal = true;
    o.ground_truth = false;
    tfu::render_scene(scene, o);
  } catch (const tfu::InputError&) {
  }
  return 0;
}
