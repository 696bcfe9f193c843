// tfu render: draw a scene (built-in or JSON file) through the golden sampler; optionally write the
// quad request trace and the supersampled analytic ground truth (docs/renderer.md). Scenes named
// oa:MAP[:SPAWN] are single-stage previews of OpenArena levels (docs/real-frames.md).
#include <iostream>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include "cmodel/bindings.hpp"
#include "cmodel/error.hpp"
#include "cmodel/gl_replay.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/parallel.hpp"
#include "cmodel/q3_archives.hpp"
#include "cmodel/q3_scene.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/scene_frame.hpp"
#include "cmodel/scene_source.hpp"
#include "cmodel/trace.hpp"
#include "cmodel/upload_compression.hpp"
#include "sim/tfu/commands.hpp"
#include "sim/tfu/sampler_options.hpp"

namespace tfu::cli {
namespace {

struct RenderCliOptions {
  std::string scene = kDefaultScene;
  std::string filter;  // empty: each mesh keeps its own
  std::string max_aniso, aniso_rounding, aniso_threshold, aniso_axes;  // empty: each mesh keeps its own
  std::string out, trace_out, truth_out, surface_truth_out, interior_out;
  std::string game_dir;  // empty: $TFU_OPENARENA_DIR or the Debian default
  GlTraceOptions gl;  // --gl-trace, --frame, --alpha-bits
  std::string compress;  // oa: scenes: the base textures compressed at upload (none, s3tc, a block format)
  std::string raster = "scanline";  // the trace's quad order (cmodel/raster_order.hpp)
  std::string texture_layout;       // empty: each texture's own
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

// The levels of the game data, as oa:MAP scene names (or why there are none).
void list_levels(std::ostream& os, const std::string& game_dir) {
  const std::string dir = q3::openarena_dir(game_dir);
  try {
    const q3::GameArchives archives(dir);
    const auto names = archives.level_names();
    os << fmt::format(
        "\nOpenArena levels in {} ({}, as --scene oa:MAP[:SPAWN], each with the archive it is read from):\n", dir,
        names.size());
    for (const std::string& n : names)
      os << fmt::format("{}{}  {}\n", q3::kLevelScenePrefix, n, archives.describe(archives.locate_level(n)));
  } catch (const InputError& e) {
    os << fmt::format("\nNo OpenArena levels: {}\n", e.what());
  }
}

void check_size_override(const char* option, int v) {
  if (v < 0 || v > kMaxRenderSize) throw InputError(fmt::format("{} must be in 0..{} (0: the scene's), got {}", option, kMaxRenderSize, v));
}

// One frame of a GL command stream through the golden model (docs/gl-replay.md).
void run_gl_trace(const RenderCliOptions& o, const CLI::App& cmd) {
  for (const char* opt : {"--scene", "--compress", "--filter", "--max-aniso", "--aniso-rounding", "--aniso-threshold", "--trace-out",
                          "--truth-out", "--surface-truth-out", "--interior-out", "--ideal", "--width", "--height", "--game-dir", "--list"})
    if (const CLI::Option* opt_ = cmd.get_option_no_throw(opt); opt_ != nullptr && opt_->count() > 0)
      throw InputError(fmt::format("{} does not apply to --gl-trace (the trace carries the frame)", opt));
  const std::string out = o.out.empty() ? fmt::format("out/render/gl-frame{}.png", o.gl.frame) : o.out;
  OutputFiles outputs(o.force);
  OutputFile& image_file = outputs.add_image("--out", out);
  OutputFile* draws_file = o.gl.draws_out.empty() ? nullptr : &outputs.add("--draws-out", o.gl.draws_out);
  const gl::Replay r =
      gl::replay_frame(o.gl.trace, o.gl.frame, gl_replay_options(o.gl, gl::ReplayOptions{}.line_bytes));
  image_file.write_image(r.image);
  if (draws_file) gl::write_draw_table(r, draws_file->stream());
  outputs.commit();
  std::cout << out << '\n';
  print_summary_line(fmt::format("tfu render: GL trace {} frame {} (calls {}..{}) {}x{}: {} calls ({} in the frame), {} draws, {} triangles ({} culled, "
                                 "{} clipped away, {} degenerate), {} textures, {} quads, {} pixels, {} requests",
                                 o.gl.trace, o.gl.frame, r.first_call, r.last_call, r.width, r.height, r.stats.calls, r.stats.frame_calls, r.stats.draws,
                                 r.stats.triangles, r.stats.culled, r.stats.clipped_away, r.stats.degenerate, r.stats.textures,
                                 r.stats.quads, r.stats.pixels, r.requests.requests.size()));
}

void run(const RenderCliOptions& o) {
  if (o.list) {
    list_scenes(std::cout);
    list_levels(std::cout, o.game_dir);
    return;
  }
  checked_thread_count("--threads", o.threads, true);
  check_size_override("--width", o.width);
  check_size_override("--height", o.height);
  const bool level_scene = q3::is_level_scene(o.scene);
  UploadCompression compress;
  if (!o.compress.empty()) {
    try {
      compress = upload_compression_from_name(o.compress);
    } catch (const InputError& e) {
      throw InputError(fmt::format("--compress: {}", e.what()));
    }
  }
  const Scene scene = open_scene({o.scene, o.width, o.height, o.game_dir}, compress);

  RenderOptions ro;
  if (!o.filter.empty()) ro.filter = filter_mode_from_name(o.filter);
  // Anisotropy of every base stage: the sampler keys max_aniso, aniso_rounding, aniso_threshold and
  // aniso_axes (bindings.hpp).
  for (const auto& [flag, key, value] : {std::tuple{"--max-aniso", "max_aniso", &o.max_aniso},
                                         std::tuple{"--aniso-rounding", "aniso_rounding", &o.aniso_rounding},
                                         std::tuple{"--aniso-threshold", "aniso_threshold", &o.aniso_threshold},
                                         std::tuple{"--aniso-axes", "aniso_axes", &o.aniso_axes}}) {
    if (value->empty()) continue;
    SamplerDescriptor scratch;
    try {
      set_sampler_param(scratch, key, *value);
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", flag, e.what()));
    }
    ro.sampler_overrides[key] = *value;
  }
  ro.ideal = o.ideal;
  ro.threads = o.threads;
  ro.trace = !o.trace_out.empty();
  try {
    ro.raster = raster_order_from_name(o.raster);
  } catch (const InputError& e) {
    throw InputError(fmt::format("--raster: {}", e.what()));
  }
  if (!o.texture_layout.empty()) try {
      ro.texture_layout = memory_layout_from_name(o.texture_layout);
    } catch (const InputError& e) {
      throw InputError(fmt::format("--texture-layout: {}", e.what()));
    }
  ro.ground_truth = !o.truth_out.empty() || !o.surface_truth_out.empty() || !o.interior_out.empty();

  const std::string out = o.out.empty() ? fmt::format("out/render/{}.png", scene.name) : o.out;
  // Every output reserved (distinct files, none overwritten without --force) before the render.
  OutputFiles outputs(o.force);
  OutputFile& image_file = outputs.add_image("--out", out);
  OutputFile* trace_file = ro.trace ? &outputs.add("--trace-out", o.trace_out) : nullptr;
  OutputFile* truth_file = o.truth_out.empty() ? nullptr : &outputs.add_image("--truth-out", o.truth_out);
  OutputFile* surface_file =
      o.surface_truth_out.empty() ? nullptr : &outputs.add_image("--surface-truth-out", o.surface_truth_out);
  OutputFile* interior_file = o.interior_out.empty() ? nullptr : &outputs.add_image("--interior-out", o.interior_out);

  const RenderResult r = render_scene(scene, ro);
  image_file.write_image(r.image);
  if (trace_file) write_trace(trace_file->stream(), loadable_trace(r.frame->frame, r.trace));
  if (truth_file) truth_file->write_image(r.truth);
  if (surface_file) surface_file->write_image(r.surface_truth);
  if (interior_file) {
    Image mask(scene.width, scene.height);
    for (size_t i = 0; i < mask.texels.size(); ++i) {
      const uint8_t v = r.interior[i] ? 255 : 0;
      mask.texels[i] = {v, v, v, 255};
    }
    interior_file->write_image(mask);
  }
  outputs.commit();
  std::cout << out << '\n';
  if (trace_file) std::cout << o.trace_out << '\n';
  if (truth_file) std::cout << o.truth_out << '\n';
  if (surface_file) std::cout << o.surface_truth_out << '\n';
  if (interior_file) std::cout << o.interior_out << '\n';
  print_summary_line(
      fmt::format("tfu render: {} {}x{}, {} triangles ({} degenerate, {} clipped away), {} quads, {} pixels",
                  scene.name, scene.width, scene.height, r.stats.triangles, r.stats.degenerate, r.stats.clipped_away,
                  r.stats.quads, r.stats.pixels) +
      (r.stats.culled > 0 ? fmt::format(", {} culled", r.stats.culled) : std::string()));
  if (level_scene) print_summary_line("tfu render: " + scene.description);
}

}  // namespace

void register_render(CLI::App& app) {
  auto o = std::make_shared<RenderCliOptions>();
  auto* cmd = app.add_subcommand(
      "render", "Render a scene through the golden sampler (2x2 quads, quad-derivative LOD); optional trace and ground truth");
  cmd->add_option("--scene", o->scene, "Built-in scene name (see --list), a scene JSON file, or oa:MAP[:SPAWN] (an OpenArena level)")
      ->capture_default_str();
  add_gl_trace_options(*cmd, o->gl, "the golden model");
  cmd->add_option("--game-dir", o->game_dir,
                  fmt::format("OpenArena data directory for oa: scenes (default: ${} or {})", q3::kOpenArenaDirEnv,
                              q3::kDefaultOpenArenaDir));
  cmd->add_option("--compress", o->compress,
                  "oa: scenes: compress the base textures as the game uploads them: none (default), s3tc (ioquake3's rule: "
                  "DXT1 when opaque, else uncompressed) or a block format (bc1, bc7, astc4x4 ... astc12x12; docs/compressed.md)");
  cmd->add_option("--filter", o->filter,
                  "Override the filter of every mesh's base stage (e.g. trilinear, cubic, edge_preserving_mipmap_linear)");
  cmd->add_option("--max-aniso", o->max_aniso,
                  "Override the maximum anisotropy (probes per pixel, 1..16) of every mesh's base stage (MIP-mapped modes)");
  cmd->add_option("--aniso-rounding", o->aniso_rounding, "Override the probe-count rounding of every base stage: integer or pow2");
  cmd->add_option("--aniso-threshold", o->aniso_threshold,
                  "Override the probe threshold of every base stage: 0..7 eighths of Pmin (0: the spec's N; docs/anisotropic.md)");
  cmd->add_option("--aniso-axes", o->aniso_axes,
                  "Override the axis lengths of every base stage's LOD unit: screen (the spec's Px, Py) or ellipse (the footprint's axes)");
  cmd->add_option("--out", o->out, "Output image (default: out/render/SCENE.png)");
  cmd->add_option("--trace-out", o->trace_out, "Also write the quad request trace (docs/traces.md)");
  cmd->add_option("--raster", o->raster,
                  "The order of the trace's quads: scanline (16-row bands), tiled:N (NxN-pixel tiles in row order, "
                  "quads row by row) or morton:N (quads in Z order in each tile) (docs/renderer.md)")
      ->capture_default_str();
  cmd->add_option("--texture-layout", o->texture_layout,
                  "The memory layout of every texture, level textures included: linear or tiled (tiles of one cache line); "
                  "default: each texture's own");
  cmd->add_option("--truth-out", o->truth_out,
                  "Also write the 8x8-supersampled analytic ground truth image (antialiased polygon edges)");
  cmd->add_option("--surface-truth-out", o->surface_truth_out,
                  "Also write the surface truth: the render's coverage, each surface integrated over its pixels (docs/metrics.md)");
  cmd->add_option("--interior-out", o->interior_out,
                  "Also write the interior mask: white where the pixel's 2x2 quad lies inside one mesh (tfu compare --mask)");
  add_plain_option(*cmd);
  cmd->add_flag("--ideal", o->ideal, "Use the double-precision ideal sampler instead of the fixed-point datapath");
  cmd->add_option("--threads", o->threads, "Worker threads (0: all hardware threads)")->capture_default_str();
  cmd->add_option("--width", o->width, "Override the scene's output width (0: keep)");
  cmd->add_option("--height", o->height, "Override the scene's output height (0: keep)");
  cmd->add_flag("--force", o->force, "Overwrite existing output files");
  cmd->add_flag("--list", o->list, "List the built-in scenes and the OpenArena levels found, and exit");
  cmd->callback([o, cmd] {
    if (!o->gl.trace.empty()) return run_gl_trace(*o, *cmd);
    for (const char* opt : gl_trace_only_options())
      if (cmd->count(opt) > 0) throw InputError(fmt::format("{} needs --gl-trace", opt));
    run(*o);
  });
}

}  // namespace tfu::cli
