// tfu sim: run requests through the cycle model (rtl/tfu_unit) and the golden sampler, compare
// every output bit for bit, and report cycles, cache and memory statistics.
// First slice: NEAREST and LINEAR families (docs/cycle-model.md).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/tfu_unit.hpp"
#include "sim/tfu/commands.hpp"
#include "sim/tfu/sampler_options.hpp"

namespace tfu::cli {
namespace {

struct SimOptions {
  std::string scene;  // default: the default scene when no --requests
  std::string requests;
  TextureOptions tex;
  SamplerOptions smp;
  bool filter_given = false;
  int width = 128, height = 96;  // scene render size for the trace
  rtl::UnitConfig unit;
  std::string stats;
  bool force = false;
};

void run(SimOptions& o, CLI::App& cmd) {
  if (!o.stats.empty() && std::filesystem::exists(o.stats) && !o.force)
    throw InputError(fmt::format("--stats '{}' already exists (use --force to overwrite)", o.stats));
  o.unit.cache.validate();
  o.unit.memory.validate();
  Texture texture;
  SamplerConfig cfg;
  Trace trace;
  std::string what;
  if (!o.requests.empty()) {
    if (o.tex.texture.empty()) throw InputError("--requests needs --texture");
    texture = load_texture_from_options(o.tex);
    cfg = sampler_config_from_options(o.smp);
    trace = load_trace(o.requests);
    what = o.requests;
  } else {
    const std::string name = o.scene.empty() ? kDefaultScene : o.scene;
    Scene scene = load_scene(name);
    if (o.width < 2 || o.height < 2 || o.width > kMaxRenderSize || o.height > kMaxRenderSize)
      throw InputError(fmt::format("--width/--height must be in 2..{}", kMaxRenderSize));
    scene.width = o.width;
    scene.height = o.height;
    RenderOptions ro;
    ro.trace = true;
    trace = render_scene(scene, ro).trace;
    const Mesh& mesh = scene.meshes.front();
    texture = *mesh.texture;
    cfg = mesh.sampler;
    if (cmd.count("--filter")) cfg.mode = filter_mode_from_name(o.smp.filter);
    what = fmt::format("scene {} at {}x{}", name, o.width, o.height);
  }
  const rtl::UnitOutput got = rtl::run_unit(texture, cfg, trace, o.unit);
  // Golden reference on the same requests.
  const Sampler smp(texture, cfg);
  const std::vector<int32_t> lam = trace_lambdas(trace, texture.width(), texture.height());
  for (size_t i = 0; i < trace.requests.size(); ++i) {
    const TraceRequest& r = trace.requests[i];
    const Rgba8 want = smp.sample(r.s, r.t, lam[i]), have = got.pixels[i];
    if (want != have)
      throw CheckFailed(fmt::format("request {} (s={:.9g}, t={:.9g}): cycle model {},{},{},{} vs golden {},{},{},{}", i, r.s,
                                    r.t, have.r, have.g, have.b, have.a, want.r, want.g, want.b, want.a));
  }
  const auto n = static_cast<double>(trace.requests.size());
  const uint64_t hits = got.stats.counter("cache_line_hits"), misses = got.stats.counter("cache_line_misses");
  std::cout << fmt::format("tfu sim: {} {} requests ({}), golden compare: all {} equal\n", filter_mode_name(cfg.mode),
                           trace.requests.size(), what, trace.requests.size());
  std::cout << fmt::format("  cycles {}  pixels/clock {:.3f}  cache line hit rate {:.4f}  memory bytes/pixel {:.3f}\n",
                           got.cycles, n / static_cast<double>(got.cycles),
                           hits + misses ? static_cast<double>(hits) / static_cast<double>(hits + misses) : 1.0,
                           static_cast<double>(got.stats.counter("memory_bytes")) / n);
  std::cout << fmt::format("  stalls: cache miss {}  bank conflict {}  back-pressure {}\n",
                           got.stats.counter("stall_cache_miss"), got.stats.counter("stall_bank_conflict"),
                           got.stats.counter("stall_backpressure"));
  if (!o.stats.empty()) {
    std::ofstream f(o.stats);
    got.stats.write_json(f);
    if (!f) throw InputError(fmt::format("--stats '{}' cannot be written", o.stats));
    std::cout << "  stats -> " << o.stats << '\n';
  }
}

}  // namespace

void register_sim(CLI::App& app) {
  auto o = std::make_shared<SimOptions>();
  CLI::App* cmd = app.add_subcommand("sim", "Cycle model vs golden reference: bit-exact compare, cycles, cache and memory statistics");
  cmd->add_option("--scene", o->scene, "Built-in scene or scene JSON (default: the default scene) whose trace is simulated");
  cmd->add_option("--width", o->width, "Scene render width for the trace");
  cmd->add_option("--height", o->height, "Scene render height for the trace");
  cmd->add_option("--requests", o->requests, "A quad-mode request trace instead of a scene (needs --texture)");
  cmd->add_option("--texture", o->tex.texture, "Texture file or proc:NAME[:SIZE] (with --requests)");
  cmd->add_option("--mipmaps", o->tex.mipmaps, "MIP levels (with --requests): auto, stored, none, box, gaussian, edge");
  add_sampler_options(*cmd, o->smp);
  cmd->add_option("--block", o->unit.cache.block, "Cache block side B in texels (4 or 8)");
  cmd->add_option("--cache-bytes", o->unit.cache.capacity_bytes, "Cache capacity in bytes");
  cmd->add_option("--ways", o->unit.cache.ways, "Cache associativity");
  cmd->add_option("--banks", o->unit.cache.banks, "Cache banks (1 or 4)");
  cmd->add_option("--latency", o->unit.memory.latency, "Memory latency in cycles");
  cmd->add_option("--bandwidth", o->unit.memory.bytes_per_cycle, "Memory bandwidth in bytes per cycle");
  cmd->add_option("--stats", o->stats, "Write the statistics as JSON");
  cmd->add_flag("--force", o->force, "Overwrite --stats if it exists");
  cmd->callback([o, cmd] { run(*o, *cmd); });
}

}  // namespace tfu::cli
