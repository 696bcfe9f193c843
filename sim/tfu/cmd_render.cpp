// tfu render: draw a scene (built-in or JSON file) through the golden sampler; optionally write the
// quad request trace and the supersampled analytic ground truth (docs/renderer.md).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/parallel.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/trace.hpp"
#include "sim/tfu/commands.hpp"

namespace tfu::cli {
namespace {

struct RenderCliOptions {
  std::string scene = kDefaultScene;
  std::string filter;  // empty: each mesh keeps its own
  std::string out, trace_out, truth_out;
  bool ideal = false, force = false, list = false;
  int threads = 0;
  int width = 0, height = 0;  // 0: the scene's size
};

void list_scenes(std::ostream& os) {
  os << "| scene | size | meshes | description |\n|---|---|---:|---|\n";
  for (const std::string& name : builtin_scene_names()) {
    const Scene s = parse_scene(builtin_scene_json(name), name + ".json");
    os << fmt::format("| {} | {}x{} | {} | {} |\n", name, s.width, s.height, s.meshes.size(), s.description);
  }
}

void check_size_override(const char* option, int v) {
  if (v < 0 || v > kMaxRenderSize) throw InputError(fmt::format("{} must be in 0..{} (0: the scene's), got {}", option, kMaxRenderSize, v));
}

void run(const RenderCliOptions& o) {
  if (o.list) {
    list_scenes(std::cout);
    return;
  }
  checked_thread_count("--threads", o.threads, true);
  check_size_override("--width", o.width);
  check_size_override("--height", o.height);
  Scene scene = load_scene(o.scene);
  if (o.width > 0) scene.width = o.width;
  if (o.height > 0) scene.height = o.height;

  RenderOptions ro;
  if (!o.filter.empty()) ro.filter = filter_mode_from_name(o.filter);
  ro.ideal = o.ideal;
  ro.threads = o.threads;
  ro.trace = !o.trace_out.empty();
  ro.ground_truth = !o.truth_out.empty();

  const std::string out = o.out.empty() ? fmt::format("out/render/{}.png", scene.name) : o.out;
  // Every output reserved (distinct files, none overwritten without --force) before the render.
  OutputFiles outputs(o.force);
  OutputFile& image_file = outputs.add_image("--out", out);
  OutputFile* trace_file = ro.trace ? &outputs.add("--trace-out", o.trace_out) : nullptr;
  OutputFile* truth_file = ro.ground_truth ? &outputs.add_image("--truth-out", o.truth_out) : nullptr;

  const RenderResult r = render_scene(scene, ro);
  image_file.write_image(r.image);
  if (trace_file) write_trace(trace_file->stream(), r.trace);
  if (truth_file) truth_file->write_image(r.truth);
  outputs.commit();
  std::cout << out << '\n';
  if (trace_file) std::cout << o.trace_out << '\n';
  if (truth_file) std::cout << o.truth_out << '\n';
  std::cerr << fmt::format("tfu render: {} {}x{}, {} triangles ({} degenerate, {} clipped away), {} quads, {} pixels\n",
                           scene.name, scene.width, scene.height, r.stats.triangles, r.stats.degenerate,
                           r.stats.clipped_away, r.stats.quads, r.stats.pixels);
}

}  // namespace

void register_render(CLI::App& app) {
  auto o = std::make_shared<RenderCliOptions>();
  auto* cmd = app.add_subcommand(
      "render", "Render a scene through the golden sampler (2x2 quads, quad-derivative LOD); optional trace and ground truth");
  cmd->add_option("--scene", o->scene, "Built-in scene name (see --list) or a scene JSON file")->capture_default_str();
  cmd->add_option("--filter", o->filter, "Override every mesh's filter (e.g. linear_mipmap_linear, cubic, edge_preserving)");
  cmd->add_option("--out", o->out, "Output image (default: out/render/SCENE.png)");
  cmd->add_option("--trace-out", o->trace_out, "Also write the quad request trace (docs/traces.md)");
  cmd->add_option("--truth-out", o->truth_out, "Also write the 8x8-supersampled analytic ground truth image");
  cmd->add_flag("--ideal", o->ideal, "Use the double-precision ideal sampler instead of the fixed-point datapath");
  cmd->add_option("--threads", o->threads, "Worker threads (0: all hardware threads)")->capture_default_str();
  cmd->add_option("--width", o->width, "Override the scene's output width (0: keep)");
  cmd->add_option("--height", o->height, "Override the scene's output height (0: keep)");
  cmd->add_flag("--force", o->force, "Overwrite existing output files");
  cmd->add_flag("--list", o->list, "List the built-in scenes and exit");
  cmd->callback([o] { run(*o); });
}

}  // namespace tfu::cli
