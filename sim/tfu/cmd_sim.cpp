// tfu sim: run requests through the cycle model (rtl/) and the golden sampler, compare every output
// bit for bit (exit 1 on the first mismatch, naming the request, both values and the cycle), and
// report cycles, cache, memory, shape and latency statistics (docs/cycle-model.md).
#include <chrono>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/lod.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/tfu_unit.hpp"
#include "sim/tfu/commands.hpp"
#include "sim/tfu/sampler_options.hpp"

namespace tfu::cli {
namespace {

constexpr int kBenchRuns = 7;  // --bench: best of this many runs

struct SimOptions {
  std::string scene;  // default: the default scene when no --requests
  std::string requests;
  TextureOptions tex;
  SamplerOptions smp;
  int width = 128, height = 96;  // scene render size for the trace
  std::string config;
  rtl::UnitConfig unit;
  std::string shape_policy;
  int units = 1;
  std::string stats, out, vcd;
  bool force = false, bench = false;
};

void print_summary(const std::string& head, size_t n, uint64_t cycles, const sim::Stats& st) {
  const uint64_t hits = st.counter("cache_line_hits"), misses = st.counter("cache_line_misses");
  const auto dn = static_cast<double>(n);
  std::cout << head;
  std::cout << fmt::format("  cycles {}  pixels/clock {:.3f}  cache line hit rate {:.4f}  memory bytes/pixel {:.3f}\n",
                           cycles, cycles ? dn / static_cast<double>(cycles) : 0.0,
                           hits + misses ? static_cast<double>(hits) / static_cast<double>(hits + misses) : 1.0,
                           n ? static_cast<double>(st.counter("memory_bytes")) / dn : 0.0);
  std::cout << fmt::format("  stalls: cache miss {}  bank conflict {}  back-pressure {}\n", st.counter("stall_cache_miss"),
                           st.counter("stall_bank_conflict"), st.counter("stall_backpressure"));
  if (st.counter("shape_cross") + st.counter("shape_T") + st.counter("shape_L") > 0)
    std::cout << fmt::format("  kernel shapes: cross {}  T {}  L {}\n", st.counter("shape_cross"), st.counter("shape_T"),
                             st.counter("shape_L"));
}

void run(SimOptions& o, CLI::App& cmd) {
  // Every output reserved before any work (cmodel/output_files.hpp); written at the end, or not at all.
  OutputFiles outputs(o.force);
  OutputFile* stats_file = o.stats.empty() ? nullptr : &outputs.add("--stats", o.stats);
  OutputFile* out_file = o.out.empty() ? nullptr : &outputs.add_image("--out", o.out);
  OutputFile* vcd_file = o.vcd.empty() ? nullptr : &outputs.add("--vcd", o.vcd);
  if (!o.config.empty())
    o.unit = rtl::unit_config_from_json(read_input_file(o.config, "--config " + quoted_path(o.config), kMaxTextInputBytes),
                                        o.config);
  // Command-line flags override the config file.
  if (cmd.count("--block")) o.unit.cache.block = static_cast<int>(cmd.get_option("--block")->as<int>());
  if (cmd.count("--cache-bytes")) o.unit.cache.capacity_bytes = cmd.get_option("--cache-bytes")->as<int>();
  if (cmd.count("--ways")) o.unit.cache.ways = cmd.get_option("--ways")->as<int>();
  if (cmd.count("--banks")) o.unit.cache.banks = cmd.get_option("--banks")->as<int>();
  if (cmd.count("--latency")) o.unit.memory.latency = cmd.get_option("--latency")->as<int>();
  if (cmd.count("--bandwidth")) o.unit.memory.bytes_per_cycle = cmd.get_option("--bandwidth")->as<int>();
  if (cmd.count("--lanes")) o.unit.filter_lanes = cmd.get_option("--lanes")->as<int>();
  if (cmd.count("--shape-policy")) o.unit.shape_policy = rtl::shape_policy_from_name(o.shape_policy);
  o.unit.validate();
  // Options that do not apply to this kind of run are errors, not silently ignored.
  const auto given = [&cmd](const char* name) {
    const CLI::Option* opt = cmd.get_option_no_throw(name);
    return opt != nullptr && opt->count() > 0;
  };
  for (const char* opt : {"--edge-shape", "--cache-block"})
    if (given(opt))
      throw InputError(fmt::format("{} does not apply to tfu sim: the unit's kernel-shape selector decides (--shape-policy, --block)", opt));
  if (!o.requests.empty()) {
    for (const char* opt : {"--scene", "--width", "--height", "--units"})
      if (given(opt)) throw InputError(fmt::format("{} applies to scene runs, not to --requests", opt));
  } else {
    for (const char* opt : {"--texture", "--format", "--mipmaps", "--alpha", "--kernel", "--wrap", "--wrap-s", "--wrap-t",
                            "--border", "--lod-bias", "--min-lod", "--max-lod", "--rom-samples", "--rom-bits", "--rom-recon"})
      if (given(opt))
        throw InputError(fmt::format("{} applies to --requests runs; a scene's meshes carry their own textures and samplers "
                                     "(only --filter overrides them)", opt));
  }
  std::ostream* vcd = vcd_file ? &vcd_file->stream() : nullptr;
  sim::Stats stats;
  std::string mismatch;  // a golden-compare failure: the outputs are still written (they show it)
  if (!o.requests.empty()) {
    if (o.tex.texture.empty()) throw InputError("--requests needs --texture");
    if (!o.out.empty()) throw InputError("--out needs a scene (a request trace has no image)");
    const Texture texture = load_texture_from_options(o.tex);
    const SamplerConfig cfg = sampler_config_from_options(o.smp);
    const Trace trace = load_trace(o.requests);
    const rtl::UnitOutput got = rtl::run_unit(texture, cfg, trace, o.unit, vcd);
    const Sampler golden(texture, rtl::golden_sampler_config(cfg, o.unit));
    const std::vector<int32_t> lam = trace_lambdas(trace, texture.width(), texture.height());
    for (size_t i = 0; i < trace.requests.size(); ++i) {
      const TraceRequest& r = trace.requests[i];
      const Rgba8 want = rtl::golden_pixel(golden, o.unit, got, r, lam[i], i), have = got.pixels[i];
      if (want != have && mismatch.empty())
        mismatch = fmt::format("request {} (s={:.9g}, t={:.9g}) at cycle {}: cycle model {},{},{},{} vs golden {},{},{},{}",
                               i, r.s, r.t, got.response_cycle[i], have.r, have.g, have.b, have.a, want.r, want.g,
                               want.b, want.a);
    }
    if (mismatch.empty())
      print_summary(fmt::format("tfu sim: {} {} requests ({}), golden compare: all {} equal\n", filter_mode_name(cfg.mode),
                              trace.requests.size(), o.requests, trace.requests.size()),
                  trace.requests.size(), got.cycles, got.stats);
    stats = got.stats;
  } else {
    const std::string name = o.scene.empty() ? kDefaultScene : o.scene;
    Scene scene = load_scene(name);
    if (o.width < 2 || o.height < 2 || o.width > kMaxRenderSize || o.height > kMaxRenderSize)
      throw InputError(fmt::format("--width/--height must be in 2..{}", kMaxRenderSize));
    scene.width = o.width;
    scene.height = o.height;
    RenderOptions ro;
    ro.trace = true;
    rtl::SceneSimOptions so;
    if (cmd.count("--filter")) ro.filter = so.filter = filter_mode_from_name(o.smp.filter);
    so.units = o.units;
    so.vcd = vcd;
    if (o.bench) ro.threads = 1;  // the golden render's time, one thread, for the cost-of-cycle-accuracy ratio
    // --bench: best of kBenchRuns runs of the golden render and of the simulation, in thread CPU
    // seconds, so that the figures do not depend on other work on the machine; the two alternate
    // run by run, so that a slow spell of the (virtual) machine falls on both sides of the ratio.
    // Each render is assigned over the previous result, which keeps the allocator's memory mapped
    // as in consecutive renders (the simulation allocates in its own threads).
    const int runs = o.bench ? kBenchRuns : 1;
    double render_secs = 1e300, secs = 0;
    RenderResult render;
    rtl::SceneSimResult res;
    std::vector<double> pair_ratio;  // cycle model / golden render of each run (adjacent in time)
    for (int run = 0; run < runs; ++run) {
      const double tr = rtl::thread_cpu_seconds();
      render = render_scene(scene, ro);
      const double this_render = rtl::thread_cpu_seconds() - tr;
      render_secs = std::min(render_secs, this_render);
      if (run == 0) {
        const auto t0 = std::chrono::steady_clock::now();
        res = rtl::simulate_scene(scene, render, o.unit, so);
        secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        pair_ratio.push_back(res.cycle_seconds / this_render);
      } else {
        const rtl::SceneSimResult again = rtl::simulate_scene(scene, render, o.unit, so);
        res.cycle_seconds = std::min(res.cycle_seconds, again.cycle_seconds);
        res.golden_seconds = std::min(res.golden_seconds, again.golden_seconds);
        pair_ratio.push_back(again.cycle_seconds / this_render);
      }
    }
    std::sort(pair_ratio.begin(), pair_ratio.end());
    mismatch = res.mismatch;
    const std::string mode = so.filter ? filter_mode_name(*so.filter) : std::string("scene filters");
    if (mismatch.empty())
      print_summary(fmt::format("tfu sim: {} {} requests (scene {} at {}x{}, {} unit{}), golden compare: all {} equal\n", mode,
                              res.requests, name, o.width, o.height, o.units, o.units == 1 ? "" : "s", res.requests),
                  res.requests, res.cycles, res.stats);
    if (o.bench && mismatch.empty()) {
      const auto n = static_cast<double>(res.requests);
      // The scene end to end: the rasterizer's share of the golden render (its time less the LOD +
      // sampler time) is common to both paths; the cycle model replaces the LOD + sampler.
      const double raster_secs = std::max(0.0, render_secs - res.golden_seconds);
      const double scene_cycle_secs = raster_secs + res.cycle_seconds;
      std::cout << fmt::format(
          "  speed, one thread each, CPU seconds, best of {} runs: cycle model {:.3f} s = {:.2f} M simulated pixels/s\n"
          "    golden LOD + sampler on the same requests {:.3f} s = {:.2f} M pixels/s: cycle model / golden sampling = {:.2f}x\n"
          "    golden render of the scene (raster + LOD + sampler) {:.3f} s: cycle model / golden render = {:.2f}x\n"
          "      (per run, render and simulation adjacent in time: median {:.2f}x, range {:.2f}-{:.2f}x)\n"
          "    the scene end to end through the cycle model (raster + cycle model) {:.3f} s: / golden render = {:.2f}x\n"
          "    wall {:.3f} s for {} unit(s) (first run: cycle model + golden compare)\n",
          runs, res.cycle_seconds, n / res.cycle_seconds / 1e6, res.golden_seconds, n / res.golden_seconds / 1e6,
          res.cycle_seconds / res.golden_seconds, render_secs, res.cycle_seconds / render_secs, pair_ratio[pair_ratio.size() / 2], pair_ratio.front(),
          pair_ratio.back(), scene_cycle_secs,
          scene_cycle_secs / render_secs, secs,
          o.units);
    }
    if (out_file) out_file->write_image(res.image);
    stats = res.stats;
  }
  if (stats_file) stats.write_json(stats_file->stream());
  outputs.commit();
  if (out_file) std::cout << "  image -> " << o.out << '\n';
  if (stats_file) std::cout << "  stats -> " << o.stats << '\n';
  if (vcd_file) std::cout << "  vcd -> " << o.vcd << '\n';
  if (!mismatch.empty()) throw CheckFailed(mismatch);
}

// ---- tfu sim-results: the cycle model's measured results (TFU-C item 5) ----
struct ResultsOptions {
  int width = 256, height = 192;
  std::string markdown = "-", json;
  bool force = false;
};

struct ResultRow {
  std::string scene, mode, policy;
  int block = 4;
  double cycles_per_pixel = 0, hit_rate = 0, bytes_per_pixel = 0;
  uint64_t bytes = 0, stall_miss = 0, cross = 0, t = 0, l = 0;
};

ResultRow measure(const Scene& scene, const RenderResult& render, const std::string& scene_name, FilterMode mode,
                  rtl::ShapePolicy policy, int block) {
  rtl::UnitConfig u;
  u.cache.block = block;
  u.shape_policy = policy;
  rtl::SceneSimOptions so;
  so.filter = mode;
  const rtl::SceneSimResult r = rtl::simulate_scene(scene, render, u, so);
  if (!r.mismatch.empty()) throw CheckFailed(r.mismatch);
  ResultRow row{scene_name, filter_mode_name(mode), mode.base == BaseFilter::EdgePreserving ? rtl::shape_policy_name(policy) : "",
                block};
  const auto n = static_cast<double>(r.requests);
  row.cycles_per_pixel = static_cast<double>(r.cycles) / n;
  const uint64_t h = r.stats.counter("cache_line_hits"), m = r.stats.counter("cache_line_misses");
  row.hit_rate = h + m ? static_cast<double>(h) / static_cast<double>(h + m) : 1.0;
  row.bytes = r.stats.counter("memory_bytes");
  row.bytes_per_pixel = static_cast<double>(row.bytes) / n;
  row.stall_miss = r.stats.counter("stall_cache_miss");
  row.cross = r.stats.counter("shape_cross");
  row.t = r.stats.counter("shape_T");
  row.l = r.stats.counter("shape_L");
  return row;
}

void run_results(const ResultsOptions& o) {
  // Checked (and a temporary created) before the long run, so that an unwritable output fails first.
  OutputFiles outputs(o.force);
  OutputFile* md_file = o.markdown == "-" ? nullptr : &outputs.add("--markdown", o.markdown);
  OutputFile* json_file = o.json.empty() ? nullptr : &outputs.add("--json", o.json);
  std::vector<ResultRow> rows;
  std::string ratio_table;
  const std::vector<std::string> scenes = builtin_scene_names();
  for (size_t si = 0; si < scenes.size(); ++si) {
    const std::string& name = scenes[si];
    std::cerr << fmt::format("sim-results: scene {}/{} {}\n", si + 1, scenes.size(), name);
    Scene scene = load_scene(name);
    scene.width = o.width;
    scene.height = o.height;
    RenderOptions ro;
    ro.trace = true;
    for (const FilterMode& m : all_filter_modes()) {
      ro.filter = m;
      const RenderResult render = render_scene(scene, ro);
      if (m.base == BaseFilter::EdgePreserving) {
        for (rtl::ShapePolicy p : {rtl::ShapePolicy::Static, rtl::ShapePolicy::CacheAware, rtl::ShapePolicy::FullCross})
          rows.push_back(measure(scene, render, name, m, p, 4));
      } else {
        rows.push_back(measure(scene, render, name, m, rtl::ShapePolicy::Static, 4));
      }
    }
    // Lee & Jen Sec. 3: memory bytes of EDGE_PRESERVING per policy over LINEAR's, B = 4 and 8.
    for (int block : {4, 8}) {
      ro.filter = filter_mode_from_name("LINEAR");
      const RenderResult render = render_scene(scene, ro);
      const ResultRow lin = measure(scene, render, name, *ro.filter, rtl::ShapePolicy::Static, block);
      const FilterMode edge = filter_mode_from_name("EDGE_PRESERVING");
      const ResultRow st = measure(scene, render, name, edge, rtl::ShapePolicy::Static, block);
      const ResultRow ca = measure(scene, render, name, edge, rtl::ShapePolicy::CacheAware, block);
      const ResultRow fc = measure(scene, render, name, edge, rtl::ShapePolicy::FullCross, block);
      const auto ratio = [&](const ResultRow& r) { return static_cast<double>(r.bytes) / static_cast<double>(lin.bytes); };
      ratio_table += fmt::format("| {} | {} | {} | {:.4f} | {:.4f} | {:.4f} |\n", name, block, lin.bytes, ratio(st), ratio(ca),
                                 ratio(fc));
    }
  }
  std::ostringstream md;
  md << fmt::format("\n## Cycle model (TFU-C)\n\nGenerated by `scripts/results` (`tfu sim-results`, {}x{} per scene, default unit "
                    "configuration of docs/cycle-model.md: 16 KiB 4-way cache, B = 4, block-parity banks, memory latency 100 "
                    "cycles and 16 bytes/cycle, one filter lane). Every output of every run below was compared with the golden "
                    "model bit for bit (all equal). Cycles per pixel include the memory stalls.\n\n",
                    o.width, o.height);
  md << "### Lee & Jen's bandwidth claim: memory bytes of EDGE_PRESERVING / LINEAR, same scene and cache\n\n"
        "| scene | B | LINEAR bytes | static | cache-aware | full-cross |\n|---|---:|---:|---:|---:|---:|\n"
     << ratio_table
     << "\nWith the `static` policy the edge-preserving filter reads exactly the bytes of bilinear (ratio 1.0000), as Lee & "
        "Jen Sec. 3 designs it; `full-cross` pays for the neighbouring blocks' lines.\n\n";
  md << "### Every scene x mode (x kernel-shape policy)\n\n"
        "| scene | mode | policy | cycles/pixel | line hit rate | memory bytes/pixel | miss stall cycles | shapes cross/T/L |\n"
        "|---|---|---|---:|---:|---:|---:|---|\n";
  nlohmann::json js = nlohmann::json::array();
  for (const ResultRow& r : rows) {
    md << fmt::format("| {} | {} | {} | {:.3f} | {:.4f} | {:.3f} | {} | {} |\n", r.scene, r.mode, r.policy, r.cycles_per_pixel,
                      r.hit_rate, r.bytes_per_pixel, r.stall_miss,
                      r.cross + r.t + r.l ? fmt::format("{}/{}/{}", r.cross, r.t, r.l) : std::string());
    js.push_back({{"scene", r.scene}, {"mode", r.mode}, {"policy", r.policy}, {"block", r.block},
                  {"cycles_per_pixel", r.cycles_per_pixel}, {"hit_rate", r.hit_rate}, {"bytes_per_pixel", r.bytes_per_pixel},
                  {"memory_bytes", r.bytes}, {"stall_cache_miss", r.stall_miss}, {"shape_cross", r.cross}, {"shape_T", r.t},
                  {"shape_L", r.l}});
  }
  if (md_file) md_file->stream() << md.str();
  if (json_file) json_file->stream() << js.dump(2) << '\n';
  outputs.commit();
  if (!md_file) std::cout << md.str();
}

}  // namespace

void register_sim(CLI::App& app) {
  auto ro = std::make_shared<ResultsOptions>();
  CLI::App* res = app.add_subcommand("sim-results", "Cycle model results for every scene x mode x policy (Markdown, JSON)");
  res->add_option("--width", ro->width, "Render width per scene");
  res->add_option("--height", ro->height, "Render height per scene");
  res->add_option("--markdown", ro->markdown, "Markdown output file, - for stdout (default)");
  res->add_option("--json", ro->json, "JSON output file");
  res->add_flag("--force", ro->force, "Overwrite output files that exist");
  res->callback([ro] {
    if (ro->width < 2 || ro->height < 2 || ro->width > kMaxRenderSize || ro->height > kMaxRenderSize)
      throw InputError(fmt::format("--width/--height must be in 2..{}", kMaxRenderSize));
    run_results(*ro);
  });

  auto o = std::make_shared<SimOptions>();
  CLI::App* cmd = app.add_subcommand("sim", "Cycle model vs golden reference: bit-exact compare, cycles, cache and memory statistics");
  cmd->add_option("--scene", o->scene, "Built-in scene or scene JSON (default: the default scene) whose trace is simulated");
  cmd->add_option("--width", o->width, "Scene render width for the trace");
  cmd->add_option("--height", o->height, "Scene render height for the trace");
  cmd->add_option("--requests", o->requests, "A request trace (quad, lod or grad mode) instead of a scene (needs --texture)");
  cmd->add_option("--texture", o->tex.texture, "Texture file or proc:NAME[:SIZE] (with --requests)");
  cmd->add_option("--mipmaps", o->tex.mipmaps, "MIP levels (with --requests): auto, stored, none, box, gaussian, edge");
  add_sampler_options(*cmd, o->smp);
  cmd->add_option("--config", o->config, "Unit configuration JSON (docs/cycle-model.md); flags below override it");
  int dummy = 0;
  cmd->add_option("--block", dummy, "Cache block side B in texels (4 or 8)");
  cmd->add_option("--cache-bytes", dummy, "Cache capacity in bytes");
  cmd->add_option("--ways", dummy, "Cache associativity");
  cmd->add_option("--banks", dummy, "Cache banks (1 or 4)");
  cmd->add_option("--latency", dummy, "Memory latency in cycles");
  cmd->add_option("--bandwidth", dummy, "Memory bandwidth in bytes per cycle");
  cmd->add_option("--lanes", dummy, "Filter lanes (1, 2 or 4)");
  cmd->add_option("--shape-policy", o->shape_policy, "Edge kernel shapes: static, cache-aware or full-cross");
  cmd->add_option("--units", o->units, "Texture filter units, each taking 32x32 screen tiles round-robin (threads)");
  cmd->add_option("--out", o->out, "Write the cycle model's image (scenes) as PNG");
  cmd->add_option("--stats", o->stats, "Write the statistics as JSON");
  cmd->add_option("--vcd", o->vcd, "Write a value-change dump (GTKWave) of the first unit's channels and stages");
  cmd->add_flag("--bench", o->bench, "Print the simulation speed");
  cmd->add_flag("--force", o->force, "Overwrite output files that exist");
  cmd->callback([o, cmd] { run(*o, *cmd); });
}

}  // namespace tfu::cli
