// tfu sim: run requests through the cycle model (rtl/) and the golden model, compare every output
// bit for bit (exit 1 on the first mismatch, naming the request, both values and the cycle), and
// report cycles, cache, memory, shape and latency statistics, per texture and per stage
// (docs/cycle-model.md).
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iterator>
#include <iostream>
#include <memory>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/gl_replay.hpp"
#include "cmodel/golden_unit.hpp"
#include "cmodel/input_file.hpp"
#include "cmodel/json_input.hpp"
#include "cmodel/json_output.hpp"
#include "cmodel/output_files.hpp"
#include "cmodel/q3_scene.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/scene_source.hpp"
#include "cmodel/upload_compression.hpp"
#include "rtl/golden_compare.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/latency_tolerance.hpp"
#include "rtl/unit_config.hpp"
#include "rtl/unit_stats.hpp"
#include "sim/sweep/provenance.hpp"
#include "sim/tfu/choices.hpp"
#include "sim/tfu/commands.hpp"
#include "sim/tfu/sampler_options.hpp"
#include "sim/tfu/sim_bench.hpp"

namespace tfu::cli {
namespace {

// Sampler keys a scene run takes from the command line for every base stage (besides --filter).
constexpr const char* kSceneSamplerOverrides[] = {"max_aniso", "aniso_rounding", "aniso_threshold", "aniso_axes"};

struct SimOptions {
  std::string scene;  // default: the default scene when no --requests
  std::string requests;
  GlTraceOptions gl;  // --gl-trace, --frame, --alpha-bits
  TextureOptions tex;
  SamplerOptions smp;
  int width = 0, height = 0;  // 0: the scene's own size
  std::string game_dir;       // OpenArena data for oa: scenes
  std::string config;
  std::map<std::string, std::string> unit_flags;  // one per unit config field (the flags' storage)
  std::string shape_policy;
  int units = 1;
  std::string raster = "scanline", unit_tiles = "round-robin:32";  // cmodel/raster_order.hpp
  std::string texture_layout;  // scene runs: every texture's layout (empty: each texture's own)
  std::string stats, out, vcd, config_out;
  std::string depths_for_latency;  // a zero-latency run's statistics: the Little's-law depths
  uint64_t vcd_from = 0, vcd_to = UINT64_MAX;  // cycles the waveform covers
  std::string vcd_signals;                     // comma-separated patterns (empty: every signal)
  std::vector<std::string> vcd_patterns;       // from vcd_signals
  bool force = false, bench = false, config_fields = false, stats_fields = false, compare_engines = false;
  std::string engine;  // empty: recurrence, or clocked when a waveform is asked for
  rtl::UnitEngine unit_engine = rtl::UnitEngine::Recurrence;  // from engine
};

// The unit configuration: the defaults, then --config (a unit configuration, or a statistics file
// whose provenance records one), then the field flags given.
rtl::UnitConfig unit_config(const SimOptions& o, const CLI::App& cmd) {
  rtl::UnitConfig u;
  if (!o.config.empty())
    u = rtl::unit_config_from_json(
        unit_config_text(read_input_file(o.config, "--config " + quoted_path(o.config), kMaxTextInputBytes)),
        quote_path(o.config));
  for (const rtl::UnitField& f : rtl::unit_config_fields()) {
    if (cmd.count(f.flag) == 0) continue;
    try {
      f.set_text(u, o.unit_flags.at(f.key));
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", f.flag, e.what()));
    }
  }
  if (!o.depths_for_latency.empty()) {
    // The miss FIFO and line buffer the configuration's latency needs (rtl::latency_tolerant_depths)
    // at the footprint rate of a zero-latency run: its footprints and cycles per unit.
    const std::string name = "--depths-for-latency " + quoted_path(o.depths_for_latency);
    const nlohmann::json j =
        parse_json_input(read_input_file(o.depths_for_latency, name, kMaxTextInputBytes), quote_path(o.depths_for_latency));
    const auto counter = [&](const char* key, bool required) -> uint64_t {
      const nlohmann::json* c = j.is_object() && j.contains("counters") ? &j.at("counters") : nullptr;
      if (c == nullptr || !c->is_object() || !c->contains(key) || !c->at(key).is_number_unsigned()) {
        if (!required) return 1;
        throw InputError(fmt::format("{}: no counter '{}' (a statistics file of tfu sim --stats)", name, key));
      }
      return c->at(key).get<uint64_t>();
    };
    const uint64_t units = std::max<uint64_t>(counter("units", false), 1);
    const uint64_t cycles = counter("cycles", true);
    if (cycles == 0) throw InputError(fmt::format("{}: 0 cycles", name));
    const rtl::LatencyTolerantDepths d = rtl::latency_tolerant_depths(u, counter("cache_footprints", true) / units, cycles);
    u.miss_fifo_depth = d.miss_fifo_depth;
    u.line_buffer_depth = d.line_buffer_depth;
  }
  try {
    u.validate();
  } catch (const InputError& e) {
    throw InputError(fmt::format("unit configuration: {}", e.what()));
  }
  return u;
}

// A table row's name in lines of at most `width` characters: whole, wrapped (after a '/', ':' or
// ' ' where one falls in the line's second half), never cut.
std::vector<std::string> wrap_name(const std::string& name, size_t width) {
  std::vector<std::string> lines;
  size_t p = 0;
  while (name.size() - p > width) {
    size_t cut = width;
    for (size_t k = width; k > width / 2; --k)
      if (const char c = name[p + k - 1]; c == '/' || c == ':' || c == ' ') {
        cut = k;
        break;
      }
    lines.push_back(name.substr(p, cut));
    p += cut;
  }
  lines.push_back(name.substr(p));
  return lines;
}

// One table row: the name's first line with the figures, its further lines below, indented.
void print_row(const std::string& name, const std::string& figures) {
  constexpr size_t kNameWidth = 40;
  const std::vector<std::string> lines = wrap_name(name, kNameWidth);
  std::cout << fmt::format("    {:<{}} {}\n", lines[0], kNameWidth, figures);
  for (size_t k = 1; k < lines.size(); ++k) std::cout << fmt::format("      {}\n", lines[k]);
}

// The memory system a scene's units share (memory.shared or an L2): its L2 in total and per unit,
// and its DRAM.
void print_shared_memory(const sim::Stats& st) {
  const uint64_t sharers = rtl::counter(st, rtl::UnitStat::MemorySharedBy);
  if (sharers == 0) return;
  std::cout << fmt::format("  memory system shared by {} unit{}\n", sharers, sharers == 1 ? "" : "s");
  if (const sim::Stats::Table* t = st.table(rtl::stat_key(rtl::UnitStat::L2Units))) {
    std::cout << fmt::format(
        "  L2: {} requests, {} hits (hit rate {:.4f}), {} misses, {} bank conflicts, {} queueing cycles; {} bytes read "
        "from memory\n",
        rtl::counter(st, rtl::UnitStat::L2Requests), rtl::counter(st, rtl::UnitStat::L2Hits),
        rtl::value(st, rtl::UnitStat::L2HitRate), rtl::counter(st, rtl::UnitStat::L2Misses),
        rtl::counter(st, rtl::UnitStat::L2BankConflicts), rtl::counter(st, rtl::UnitStat::L2QueueCycles),
        rtl::counter(st, rtl::UnitStat::L2MemoryBytes));
    std::cout << "  L2 per unit: requests, hits, misses, bank conflicts, queueing cycles\n";
    for (const auto& [label, v] : t->rows)
      print_row(label, fmt::format("{:>10} {:>10} {:>10} {:>10} {:>12}", v[1], v[2], v[3], v[4], v[5]));
  }
  if (const uint64_t bursts = rtl::counter(st, rtl::UnitStat::DramBursts))
    std::cout << fmt::format(
        "  DRAM: {} bursts, {} row hits (row hit rate {:.4f}), {} row empty, {} row conflicts, {} activates, {} refreshes, "
        "mean latency {:.1f} DRAM clocks\n",
        bursts, rtl::counter(st, rtl::UnitStat::DramRowHits), rtl::value(st, rtl::UnitStat::DramRowHitRate),
        rtl::counter(st, rtl::UnitStat::DramRowEmpty), rtl::counter(st, rtl::UnitStat::DramRowConflicts),
        rtl::counter(st, rtl::UnitStat::DramActivates), rtl::counter(st, rtl::UnitStat::DramRefreshes),
        rtl::value(st, rtl::UnitStat::DramLatencyMean));
}

void print_summary(const std::string& head, size_t n, uint64_t cycles, const sim::Stats& st) {
  const uint64_t hits = rtl::counter(st, rtl::UnitStat::CacheLineHits), misses = rtl::counter(st, rtl::UnitStat::CacheLineMisses);
  const auto dn = static_cast<double>(n);
  std::cout << head;
  std::cout << fmt::format("  cycles {}  pixels/clock {:.3f}  cache line hit rate {:.4f}  memory bytes/pixel {:.3f}\n",
                           cycles, cycles ? dn / static_cast<double>(cycles) : 0.0,
                           hits + misses ? static_cast<double>(hits) / static_cast<double>(hits + misses) : 1.0,
                           n ? static_cast<double>(rtl::counter(st, rtl::UnitStat::MemoryBytes)) / dn : 0.0);
  const uint64_t sector_hits = rtl::counter(st, rtl::UnitStat::CacheSectorHits),
                 sector_lookups = rtl::counter(st, rtl::UnitStat::CacheSectorLookups);
  std::cout << fmt::format("  cache 32-byte sector hit rate {:.4f} ({} of {} sector lookups)\n",
                           sector_lookups ? static_cast<double>(sector_hits) / static_cast<double>(sector_lookups) : 1.0,
                           sector_hits, sector_lookups);
  std::cout << fmt::format("  stalls: cache miss {}  bank conflict {}  back-pressure {}\n", rtl::counter(st, rtl::UnitStat::StallCacheMiss),
                           rtl::counter(st, rtl::UnitStat::StallBankConflict), rtl::counter(st, rtl::UnitStat::StallBackpressure));
  print_shared_memory(st);
  if (const std::vector<uint64_t>* h = st.histogram(rtl::stat_key(rtl::UnitStat::AnisoProbes))) {
    std::string hist;
    for (size_t k = 1; k < h->size(); ++k)
      if ((*h)[k]) hist += fmt::format("  N={} {}", k, (*h)[k]);
    std::cout << fmt::format("  anisotropic probes: {} ({:.3f} per pixel); pixels per N:{}\n", rtl::counter(st, rtl::UnitStat::Probes),
                             n ? static_cast<double>(rtl::counter(st, rtl::UnitStat::Probes)) / dn : 0.0, hist);
  }
  if (rtl::counter(st, rtl::UnitStat::ShapeCross) + rtl::counter(st, rtl::UnitStat::ShapeT) + rtl::counter(st, rtl::UnitStat::ShapeL) > 0)
    std::cout << fmt::format("  kernel shapes: cross {}  T {}  L {}\n", rtl::counter(st, rtl::UnitStat::ShapeCross), rtl::counter(st, rtl::UnitStat::ShapeT),
                             rtl::counter(st, rtl::UnitStat::ShapeL));
  if (const sim::Stats::Table* t = st.table(rtl::stat_key(rtl::UnitStat::Decoders)); t && !t->rows.empty()) {
    std::cout << fmt::format(
        "  block decoders: {} blocks decoded, {} busy and {} stall cycles; per compressed texture:\n",
        rtl::counter(st, rtl::UnitStat::DecodedBlocks), rtl::counter(st, rtl::UnitStat::DecoderBusyCycles),
        rtl::counter(st, rtl::UnitStat::DecoderStallCycles));
    for (const auto& [label, v] : t->rows) print_row(label, fmt::format("{:>10} {:>10} {:>10}", v[1], v[2], v[3]));
  }
  // The groups (every statistic per stage and per texture: --stats), their main figures; stages in
  // order, textures by descriptor index (the label's leading number).
  for (const char* breakdown : {rtl::kStageGroups, rtl::kTextureGroups}) {
    std::vector<const sim::Stats::Group*> rows;
    for (const sim::Stats::Group& g : st.groups())
      if (g.breakdown == breakdown) rows.push_back(&g);
    if (rows.empty()) continue;
    std::sort(rows.begin(), rows.end(), [](const sim::Stats::Group* a, const sim::Stats::Group* b) {
      const auto index = [](const std::string& l) { return std::stoull(l.substr(l.find_first_of("0123456789"))); };
      return index(a->label) < index(b->label);
    });
    std::cout << fmt::format(
        "  per {}: requests, pixels/clock (of the cycles given to them), probes/pixel, line hit rate, "
        "sector hit rate, memory bytes/pixel, memory bytes, mean latency\n",
        breakdown);
    for (const sim::Stats::Group* g : rows) {
      const sim::Stats& s = g->stats;
      print_row(g->label,
                fmt::format("{:>10} {:>7.3f} {:>7.3f} {:>8.4f} {:>8.4f} {:>8.3f} {:>12} {:>8.1f}",
                            rtl::counter(s, rtl::UnitStat::Pixels), rtl::value(s, rtl::UnitStat::PixelsPerClock),
                            rtl::value(s, rtl::UnitStat::ProbesPerPixel), rtl::value(s, rtl::UnitStat::CacheHitRate),
                            rtl::value(s, rtl::UnitStat::CacheSectorHitRate),
                            rtl::value(s, rtl::UnitStat::MemoryBytesPerPixel),
                            rtl::counter(s, rtl::UnitStat::MemoryBytes), rtl::value(s, rtl::UnitStat::LatencyMean)));
    }
  }
}

RasterOrder raster_option(const SimOptions& o) {
  try {
    return raster_order_from_name(o.raster);
  } catch (const InputError& e) {
    throw InputError(fmt::format("--raster: {}", e.what()));
  }
}

// A request trace through the unit and the golden model.
// A golden-compare failure is returned in `mismatch` (the outputs are still written: they show it).
sim::Stats run_requests(SimOptions& o, const CLI::App& cmd, const rtl::UnitConfig& unit, std::vector<std::ostream*> vcds,
                        RunRecord& rec, std::string& mismatch) {
  if (!o.out.empty()) throw InputError("--out needs a scene (a request trace has no image)");
  Trace trace = load_trace(o.requests);
  if (const RasterOrder order = raster_option(o); !(order == RasterOrder{})) trace = reorder_trace(trace, order);
  if (!o.shape_policy.empty()) o.smp.values["edge_shape"] = o.shape_policy;
  const Frame frame = frame_for_trace(cmd, o.tex, o.smp, trace, unit.cache.line_bytes, o.game_dir);
  rec.has_scene = false;
  rec.trace = o.requests;
  rec.raster = raster_order_name(raster_option(o));
  rec.textures = frame_texture_names(frame);
  const rtl::UnitOutput got =
      rtl::run_unit(frame, trace, unit, o.unit_engine,
                    rtl::VcdOptions{vcds.empty() ? nullptr : vcds[0], o.vcd_from, o.vcd_to, o.vcd_patterns});
  const GoldenUnit golden(frame);
  mismatch = rtl::first_mismatch(trace, rtl::golden_outputs(golden, trace, got), got);
  if (mismatch.empty() && o.compare_engines) mismatch = rtl::compare_engines(frame, trace, unit);
  std::string modes;
  for (const SamplerDescriptor& s : frame.regs.samplers) modes += (modes.empty() ? "" : ", ") + filter_mode_name(s.mode);
  rec.filter = modes;
  rec.sampler_overrides = sampler_params_given(cmd, o.smp);
  if (!mismatch.empty()) return got.stats;
  print_summary(fmt::format("tfu sim: {} {} requests ({}), golden compare: all {} equal\n", modes, trace.requests.size(),
                            o.requests, trace.requests.size()),
                trace.requests.size(), got.cycles, got.stats);
  if (o.compare_engines) std::cout << "  engine compare: both engines agree on every event, pixel and statistic\n";
  return got.stats;
}

// A scene rendered by the golden model, its trace through the units.
sim::Stats run_scene(SimOptions& o, const CLI::App& cmd, const rtl::UnitConfig& unit, std::vector<std::ostream*> vcds,
                     RunRecord& rec, OutputFile* out_file, std::string& mismatch) {
  const std::string name = o.scene.empty() ? kDefaultScene : o.scene;
  if (o.width < 0 || o.height < 0 || o.width == 1 || o.height == 1 || o.width > kMaxRenderSize || o.height > kMaxRenderSize)
    throw InputError(fmt::format("--width/--height must be in 2..{} (0: the scene's own size)", kMaxRenderSize));
  UploadCompression compress;  // --compress with an oa: scene: the level's textures as the game uploads them
  if (cmd.count("--compress") > 0) {
    try {
      compress = upload_compression_from_name(o.tex.values.at("compress"));
    } catch (const InputError& e) {
      throw InputError(fmt::format("--compress: {}", e.what()));
    }
  }
  const auto load_start = std::chrono::steady_clock::now();
  const Scene scene = open_scene({name, o.width, o.height, o.game_dir}, compress);
  const double load_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
  RenderOptions ro;
  ro.trace = true;
  ro.line_bytes = unit.cache.line_bytes;
  const Params given = sampler_params_given(cmd, o.smp);
  if (given.contains("filter")) ro.filter = filter_mode_from_name(given.at("filter"));
  for (const char* key : kSceneSamplerOverrides)
    if (given.contains(key)) ro.sampler_overrides[key] = given.at(key);
  if (!o.shape_policy.empty()) ro.sampler_overrides["edge_shape"] = o.shape_policy;
  ro.raster = raster_option(o);
  if (!o.texture_layout.empty()) try {
      ro.texture_layout = memory_layout_from_name(o.texture_layout);
    } catch (const InputError& e) {
      throw InputError(fmt::format("--texture-layout: {}", e.what()));
    }
  rtl::SceneSimOptions so;
  so.units = o.units;
  try {
    so.tiles = unit_tiles_from_name(o.unit_tiles);
  } catch (const InputError& e) {
    throw InputError(fmt::format("--unit-tiles: {}", e.what()));
  }
  so.unit_vcds = std::move(vcds);
  so.vcd_from = o.vcd_from;
  so.vcd_to = o.vcd_to;
  so.vcd_signals = o.vcd_patterns;
  so.engine = o.unit_engine;
  so.compare_engines = o.compare_engines;
  SceneRun run = render_and_simulate(scene, ro, unit, so, o.bench);
  run.load_wall = load_wall;
  const RenderResult& render = run.render;
  rtl::SceneSimResult& res = run.res;
  rec.scene = {name, o.width, o.height, o.game_dir};
  rec.width = scene.width;
  rec.height = scene.height;
  rec.filter = ro.filter ? filter_mode_name(*ro.filter) : std::string("scene");
  rec.sampler_overrides = ro.sampler_overrides;
  rec.units = o.units;
  rec.raster = raster_order_name(ro.raster);
  rec.unit_tiles = unit_tiles_name(so.tiles);
  if (ro.texture_layout) rec.texture_layout = memory_layout_name(*ro.texture_layout);
  rec.textures = frame_texture_names(render.frame->frame);
  if (const auto level = requested_level({name, o.width, o.height, o.game_dir})) {
    std::cout << "tfu sim: " << scene.description << '\n';
    for (const auto& [field, n] : q3::level_count_fields(*level)) res.stats.add("level_" + field, static_cast<uint64_t>(n));
  }
  if (out_file) out_file->write_image(res.image);
  mismatch = res.mismatch;
  if (!mismatch.empty()) return res.stats;
  const std::string mode = ro.filter ? filter_mode_name(*ro.filter) : std::string("scene filters");
  print_summary(fmt::format("tfu sim: {} {} requests (scene {} at {}x{}, {} unit{}), golden compare: all {} equal\n", mode,
                            res.requests, name, scene.width, scene.height, o.units, o.units == 1 ? "" : "s", res.requests),
                res.requests, res.cycles, res.stats);
  if (o.compare_engines) std::cout << "  engine compare: both engines agree on every event, pixel and statistic\n";
  if (o.bench) print_bench(run, o.unit_engine, o.units);
  return res.stats;
}

// One frame of a GL command stream (docs/gl-replay.md): its requests through the unit and the golden
// model, the frame composed from the unit's outputs.
sim::Stats run_gl_trace(SimOptions& o, const rtl::UnitConfig& unit, std::vector<std::ostream*> vcds, RunRecord& rec,
                        OutputFile* out_file, OutputFile* draws_file, std::string& mismatch) {
  const auto start = std::chrono::steady_clock::now();
  const gl::Replay r = gl::replay_frame(o.gl.trace, o.gl.frame, gl_replay_options(o.gl, unit.cache.line_bytes));
  const double replay_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (draws_file) gl::write_draw_table(r, draws_file->stream());
  const Frame& frame = *r.unit_frame;
  rec.has_scene = false;
  rec.trace = o.gl.trace;
  rec.width = r.width;
  rec.height = r.height;
  rec.textures = frame_texture_names(frame);
  std::vector<rtl::ScreenPosition> positions;
  if (!vcds.empty()) {
    positions.resize(r.requests.requests.size());
    for (const gl::FragmentQuad& q : r.quads)
      for (size_t i = q.first_request; i < (&q == &r.quads.back() ? r.requests.requests.size() : (&q + 1)->first_request); ++i)
        positions[i] = {static_cast<uint16_t>(q.x + ((i - q.first_request) & 1)), static_cast<uint16_t>(q.y + (((i - q.first_request) >> 1) & 1))};
  }
  const double t0 = rtl::thread_cpu_seconds();
  const rtl::UnitOutput got = rtl::run_unit(
      frame, r.requests, unit, o.unit_engine,
      rtl::VcdOptions{vcds.empty() ? nullptr : vcds[0], o.vcd_from, o.vcd_to, o.vcd_patterns, vcds.empty() ? nullptr : &positions});
  const double t1 = rtl::thread_cpu_seconds();
  const GoldenUnit golden(frame);
  const std::vector<Rgba8> want = rtl::golden_outputs(golden, r.requests, got);
  const double t2 = rtl::thread_cpu_seconds();
  mismatch = rtl::first_mismatch(r.requests, want, got);
  const Image image = gl::compose_frame(r, got.pixels);
  if (out_file) out_file->write_image(image);
  if (!mismatch.empty()) return got.stats;
  if (image.texels != r.image.texels) {
    mismatch = "the frame composed from the unit's outputs differs from the golden replay's";
    return got.stats;
  }
  const size_t n = r.requests.requests.size();
  std::cout << fmt::format("tfu sim: GL trace {} frame {} (calls {}..{}, {}x{}): {} draws, {} triangles ({} culled, {} clipped away), {} textures, "
                           "{} samplers\n",
                           o.gl.trace, o.gl.frame, r.first_call, r.last_call, r.width, r.height, r.stats.draws, r.stats.triangles, r.stats.culled,
                           r.stats.clipped_away, r.stats.textures, r.stats.samplers);
  print_summary(fmt::format("tfu sim: {} requests (GL trace {} frame {}), golden compare: all {} equal\n", n, o.gl.trace, o.gl.frame, n),
                n, got.cycles, got.stats);
  const auto rate = [n](double s) { return s > 0 ? static_cast<double>(n) / s : 0.0; };
  std::cout << fmt::format(
      "  speed (thread CPU time): cycle model {:.0f} requests/s ({:.3f} s), golden model {:.0f} requests/s ({:.3f} s), "
      "both {:.0f} requests/s; the replay (apitrace dump, GL state, rasterizer and golden model) took {:.2f} s wall\n",
      rate(t1 - t0), t1 - t0, rate(t2 - t1), t2 - t1, rate(t2 - t0), replay_seconds);
  if (o.bench)
    bench_gl_trace(o.gl.trace, o.gl.frame, gl_replay_options(o.gl, unit.cache.line_bytes), r, unit, o.unit_engine,
                   got.pixels);
  return got.stats;
}

void run(SimOptions& o, CLI::App& cmd) {
  if (o.config_fields) {
    std::cout << rtl::unit_config_markdown();
    return;
  }
  if (o.stats_fields) {
    std::cout << rtl::unit_stats_markdown();
    return;
  }
  // Every output reserved before any work (cmodel/output_files.hpp); written at the end, or not at all.
  OutputFiles outputs(o.force);
  OutputFile* stats_file = o.stats.empty() ? nullptr : &outputs.add("--stats", o.stats);
  OutputFile* out_file = o.out.empty() ? nullptr : &outputs.add_image("--out", o.out);
  OutputFile* draws_file = o.gl.draws_out.empty() ? nullptr : &outputs.add("--draws-out", o.gl.draws_out);
  OutputFile* config_out_file = o.config_out.empty() ? nullptr : &outputs.add("--config-out", o.config_out);
  // One waveform per unit: --vcd FILE for unit 0, FILE's name with .unitK before the extension for unit K.
  std::vector<std::string> vcd_paths;
  std::vector<OutputFile*> vcd_files;
  if (!o.vcd.empty()) {
    vcd_paths.push_back(o.vcd);
    const std::filesystem::path p(o.vcd);
    for (int k = 1; k < (o.requests.empty() ? o.units : 1); ++k) {
      std::filesystem::path q = p;
      q.replace_filename(fmt::format("{}.unit{}{}", p.stem().string(), k, p.extension().string()));
      vcd_paths.push_back(q.string());
    }
    for (const std::string& path : vcd_paths) vcd_files.push_back(&outputs.add("--vcd", path));
  }
  const rtl::UnitConfig unit = unit_config(o, cmd);
  if (cmd.count("--engine") == 0) {  // the default: the recurrences, unless a waveform is asked for
    o.unit_engine = o.vcd.empty() ? rtl::UnitEngine::Recurrence : rtl::UnitEngine::Clocked;
  } else {
    try {
      o.unit_engine = rtl::unit_engine_from_name(o.engine);
    } catch (const InputError& e) {
      throw InputError(fmt::format("--engine: {}", e.what()));
    }
    if (o.unit_engine == rtl::UnitEngine::Recurrence && !o.vcd.empty())
      throw InputError("--vcd needs --engine clocked: the timing recurrences write no waveform");
  }
  if (cmd.count("--shape-policy") > 0) {  // given, even empty, it must name a policy
    try {
      edge_shape_from_name(o.shape_policy);
    } catch (const InputError& e) {
      throw InputError(fmt::format("--shape-policy: {}", e.what()));
    }
  }
  // Options that do not apply to this kind of run are errors, not silently ignored.
  const auto given = [&cmd](const std::string& name) {
    const CLI::Option* opt = cmd.get_option_no_throw(name);
    return opt != nullptr && opt->count() > 0;
  };
  if (!o.gl.trace.empty()) {
    for (const char* opt : {"--scene", "--requests", "--width", "--height", "--units", "--texture", "--shape-policy", "--wrap", "--game-dir"})
      if (given(opt)) throw InputError(fmt::format("{} does not apply to --gl-trace runs (the trace carries the frame)", opt));
    for (const SamplerParam& p : sampler_params())
      if (given(flag_of(p.key))) throw InputError(fmt::format("{} does not apply to --gl-trace runs (the trace's texture parameters are the samplers)", flag_of(p.key)));
    for (const char* key : texture_param_keys())
      if (given(flag_of(key))) throw InputError(fmt::format("{} does not apply to --gl-trace runs", flag_of(key)));
  } else if (const auto gl_only = std::find_if(gl_trace_only_options().begin(), gl_trace_only_options().end(), given);
             gl_only != gl_trace_only_options().end()) {
    throw InputError(fmt::format("{} needs --gl-trace", *gl_only));
  } else if (!o.requests.empty()) {
    // --game-dir applies to both: a level's trace binds oa:MAP:... textures (TFU-S E16)
    for (const char* opt : {"--scene", "--width", "--height", "--units", "--unit-tiles", "--texture-layout"})
      if (given(opt)) throw InputError(fmt::format("{} applies to scene runs, not to --requests", opt));
  } else {
    if (given("--texture")) throw InputError("--texture applies to --requests runs; a scene's stages carry their own textures");
    for (const char* key : texture_param_keys()) {
      const bool compress = std::string(key) == "compress";
      if (given(flag_of(key)) && !(compress && q3::is_level_scene(o.scene)))
        throw InputError(fmt::format("{} applies to --requests runs{}", flag_of(key), compress ? " and oa: level scenes" : ""));
    }
    for (const SamplerParam& p : sampler_params())
      if (given(flag_of(p.key)) && std::string(p.key) != "filter" &&
          std::find(std::begin(kSceneSamplerOverrides), std::end(kSceneSamplerOverrides), std::string(p.key)) ==
              std::end(kSceneSamplerOverrides))
        throw InputError(fmt::format("{} applies to --requests runs; a scene's stages carry their own samplers "
                                     "(--filter, --max-aniso, --aniso-rounding, --aniso-threshold, --aniso-axes and --shape-policy override the base stage's)",
                                     flag_of(p.key)));
    if (given("--wrap")) throw InputError("--wrap applies to --requests runs");
  }
  if (o.vcd_from > o.vcd_to) throw InputError(fmt::format("--vcd-from {} is after --vcd-to {}", o.vcd_from, o.vcd_to));
  if (given("--vcd-signals")) {
    if (o.vcd.empty()) throw InputError("--vcd-signals needs --vcd (it selects the waveform's signals)");
    for (size_t p = 0; p <= o.vcd_signals.size();) {
      const size_t comma = std::min(o.vcd_signals.find(',', p), o.vcd_signals.size());
      const std::string pattern = o.vcd_signals.substr(p, comma - p);
      if (pattern.empty() || pattern.find_first_of(" \t") != std::string::npos)
        throw InputError(
            fmt::format("--vcd-signals '{}': expected comma-separated signal names or globs without spaces, "
                        "e.g. 'tfu.pixel.*,tfu.texel_cache.accepted_*'",
                        o.vcd_signals));
      o.vcd_patterns.push_back(pattern);
      p = comma + 1;
    }
  }
  if (config_out_file) config_out_file->stream() << rtl::unit_config_to_json(unit) << '\n';
  std::vector<std::ostream*> vcds;
  for (OutputFile* f : vcd_files) vcds.push_back(&f->stream());
  RunRecord rec;
  rec.command = "sim";
  rec.config = &unit;
  rec.engine = o.unit_engine;
  std::string mismatch;
  const sim::Stats stats = !o.gl.trace.empty()  ? run_gl_trace(o, unit, vcds, rec, out_file, draws_file, mismatch)
                           : o.requests.empty() ? run_scene(o, cmd, unit, vcds, rec, out_file, mismatch)
                                                : run_requests(o, cmd, unit, vcds, rec, mismatch);
  if (stats_file) stats_file->stream() << stats_document(stats, provenance_json(rec));
  outputs.commit();
  if (config_out_file) std::cout << "  unit configuration -> " << o.config_out << '\n';
  if (out_file) std::cout << "  image -> " << o.out << '\n';
  if (stats_file) std::cout << "  stats -> " << o.stats << '\n';
  for (const std::string& path : vcd_paths) std::cout << "  vcd -> " << path << '\n';
  if (!mismatch.empty()) throw CheckFailed(mismatch);
}

// ---- tfu sim-results: the cycle model's measured results (the cycle model section of docs/results.md) ----
struct ResultsOptions {
  int width = 256, height = 192;      // 0: each scene's own size
  std::vector<std::string> scenes;    // empty: every built-in scene
  std::string config, game_dir;       // unit configuration (default: the defaults); OpenArena data
  std::string markdown = "-", json;
  bool force = false;
};

struct ResultRow {
  std::string scene, mode, policy;
  int line_bytes = 64;
  int max_aniso = 1;
  double cycles_per_pixel = 0, hit_rate = 0, sector_hit_rate = 0, bytes_per_pixel = 0;
  uint64_t requests = 0, cycles = 0, probes = 0, bytes = 0, stall_miss = 0, cross = 0, t = 0, l = 0;
};

// One scene in one mode (the base stages' filter) with one edge-shape policy, line size and maxAniso.
ResultRow measure(const Scene& scene, const std::string& scene_name, const rtl::UnitConfig& base, FilterMode mode, EdgeShape policy,
                  int line_bytes, int max_aniso = 1) {
  RenderOptions ro;
  ro.trace = true;
  ro.filter = mode;
  ro.line_bytes = line_bytes;
  ro.sampler_overrides["edge_shape"] = edge_shape_name(policy);
  ro.sampler_overrides["max_aniso"] = std::to_string(max_aniso);
  const RenderResult render = render_scene(scene, ro);
  rtl::UnitConfig u = base;
  u.cache.line_bytes = line_bytes;
  u.validate();  // InputError if the base configuration does not take this line size
  const rtl::SceneSimResult r = rtl::simulate_scene(scene, render, u, {});
  if (!r.mismatch.empty()) throw CheckFailed(r.mismatch);
  ResultRow row{scene_name, filter_mode_name(mode), mode.base == BaseFilter::EdgePreserving ? edge_shape_name(policy) : "",
                line_bytes, max_aniso};
  row.requests = r.requests;
  row.cycles = r.cycles;
  row.probes = rtl::counter(r.stats, rtl::UnitStat::Probes);
  const auto n = static_cast<double>(r.requests);
  row.cycles_per_pixel = static_cast<double>(r.cycles) / n;
  const uint64_t h = rtl::counter(r.stats, rtl::UnitStat::CacheLineHits), m = rtl::counter(r.stats, rtl::UnitStat::CacheLineMisses);
  row.hit_rate = h + m ? static_cast<double>(h) / static_cast<double>(h + m) : 1.0;
  const uint64_t sh = rtl::counter(r.stats, rtl::UnitStat::CacheSectorHits),
                 sl = rtl::counter(r.stats, rtl::UnitStat::CacheSectorLookups);
  row.sector_hit_rate = sl ? static_cast<double>(sh) / static_cast<double>(sl) : 1.0;
  row.bytes = rtl::counter(r.stats, rtl::UnitStat::MemoryBytes);
  row.bytes_per_pixel = static_cast<double>(row.bytes) / n;
  row.stall_miss = rtl::counter(r.stats, rtl::UnitStat::StallCacheMiss);
  row.cross = rtl::counter(r.stats, rtl::UnitStat::ShapeCross);
  row.t = rtl::counter(r.stats, rtl::UnitStat::ShapeT);
  row.l = rtl::counter(r.stats, rtl::UnitStat::ShapeL);
  return row;
}

void run_results(const ResultsOptions& o) {
  // Checked (and a temporary created) before the long run, so that an unwritable output fails first.
  OutputFiles outputs(o.force);
  OutputFile* md_file = o.markdown == "-" ? nullptr : &outputs.add("--markdown", o.markdown);
  OutputFile* json_file = o.json.empty() ? nullptr : &outputs.add("--json", o.json);
  std::vector<ResultRow> rows;
  std::string ratio_table, aniso_table;
  const std::vector<std::string> scenes = o.scenes.empty() ? builtin_scene_names() : o.scenes;
  const rtl::UnitConfig base =
      o.config.empty() ? rtl::UnitConfig{} : rtl::unit_config_from_json(
                             unit_config_text(read_input_file(o.config, "--config " + quoted_path(o.config), kMaxTextInputBytes)),
                             quote_path(o.config));
  for (const std::string& name : scenes) (void)open_scene({name, o.width, o.height, o.game_dir});  // bad names fail before any work
  for (size_t si = 0; si < scenes.size(); ++si) {
    const std::string& name = scenes[si];
    std::cerr << fmt::format("sim-results: scene {}/{} {}\n", si + 1, scenes.size(), name);
    const Scene scene = open_scene({name, o.width, o.height, o.game_dir});
    const int line0 = base.cache.line_bytes;
    for (const FilterMode& m : all_filter_modes()) {
      if (m.base == BaseFilter::EdgePreserving) {
        for (EdgeShape p : {EdgeShape::Static, EdgeShape::CacheAware, EdgeShape::Cross}) rows.push_back(measure(scene, name, base, m, p, line0));
      } else {
        rows.push_back(measure(scene, name, base, m, EdgeShape::Static, line0));
      }
    }
    // Lee & Jen Sec. 3: memory bytes of EDGE_PRESERVING per policy over LINEAR's, 64- and 256-byte lines.
    for (int line : {64, 256}) {
      const ResultRow lin = measure(scene, name, base, filter_mode_from_name("LINEAR"), EdgeShape::Static, line);
      const FilterMode edge = filter_mode_from_name("EDGE_PRESERVING");
      const ResultRow st = measure(scene, name, base, edge, EdgeShape::Static, line);
      const ResultRow ca = measure(scene, name, base, edge, EdgeShape::CacheAware, line);
      const ResultRow fc = measure(scene, name, base, edge, EdgeShape::Cross, line);
      const auto ratio = [&](const ResultRow& r) { return static_cast<double>(r.bytes) / static_cast<double>(lin.bytes); };
      ratio_table += fmt::format("| {} | {} | {} | {:.4f} | {:.4f} | {:.4f} |\n", name, line, lin.bytes, ratio(st), ratio(ca),
                                 ratio(fc));
    }
    // Anisotropic filtering: LINEAR_MIPMAP_LINEAR (and EDGE_PRESERVING_MIPMAP_LINEAR, static shapes) probes per maxAniso.
    for (int n : {1, 2, 4, 8, 16}) {
      const ResultRow tri = measure(scene, name, base, filter_mode_from_name("LINEAR_MIPMAP_LINEAR"), EdgeShape::Static, line0, n);
      const ResultRow ep = measure(scene, name, base, filter_mode_from_name("EDGE_PRESERVING_MIPMAP_LINEAR"), EdgeShape::Static, line0, n);
      const auto per_pixel = [](uint64_t x, uint64_t d) { return d ? static_cast<double>(x) / static_cast<double>(d) : 0.0; };
      aniso_table += fmt::format("| {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.4f} |\n", name, n, per_pixel(tri.probes, tri.requests),
                                 per_pixel(tri.requests, tri.cycles), tri.bytes_per_pixel, per_pixel(tri.requests, ep.cycles),
                                 tri.bytes ? static_cast<double>(ep.bytes) / static_cast<double>(tri.bytes) : 1.0);
    }
  }
  std::ostringstream md;
  const std::string size = o.width ? fmt::format("{}x{} per scene", o.width, o.height) : std::string("each scene's own size");
  const std::string unit_text =
      o.config.empty()
          ? std::string("default unit configuration of docs/cycle-model.md: 16 KiB 4-way cache of 64-byte lines, textures tiled "
                        "4x4 (RGBA8), block-parity banks, memory latency 100 cycles and 16 bytes/cycle, one filter lane")
          : fmt::format("unit configuration of {}: `{}`", o.config, json_dump(nlohmann::json::parse(rtl::unit_config_to_json(base))));
  md << fmt::format("\n## Cycle model\n\nGenerated by `scripts/results` (`tfu sim-results`, {}, {}; every texture of a "
                    "scene resident in one texel memory, no flush between meshes). Every output of every run below was compared "
                    "with the golden model bit for bit (all equal). Cycles per pixel include the memory stalls.\n\n",
                    size, unit_text);
  md << "### Lee & Jen's bandwidth claim: memory bytes of EDGE_PRESERVING / LINEAR, same scene and cache\n\n"
        "| scene | line bytes | LINEAR bytes | static | cache-aware | cross |\n|---|---:|---:|---:|---:|---:|\n"
     << ratio_table
     << "\nWith the `static` policy the edge-preserving filter reads exactly the bytes of bilinear (ratio 1.0000), as Lee & "
        "Jen Sec. 3 designs it; `cross` pays for the neighbouring tiles' lines.\n\n";
  md << "### Anisotropic filtering: pixels per clock and bytes per pixel per maxAniso\n\n"
        "Base stages LINEAR_MIPMAP_LINEAR with maxAniso N (the probe count of a pixel is at most N, any integer, docs/anisotropic.md); "
        "the last two columns run the same footprints as EDGE_PRESERVING_MIPMAP_LINEAR probes with static T/L shapes "
        "(Lee & Jen Sec. 3): its pixels per clock, and its memory bytes over LINEAR_MIPMAP_LINEAR's. As in the tables below a pixel is one request: "
        "a lightmapped pixel makes two, and its light-map request stays isotropic (one probe).\n\n"
        "| scene | maxAniso | probes/pixel | pixels/clock | memory bytes/pixel | EDGE_PRESERVING pixels/clock | EDGE_PRESERVING / LINEAR bytes |\n"
        "|---|---:|---:|---:|---:|---:|---:|\n"
     << aniso_table << "\n";
  md << "### Every scene x mode (x kernel-shape policy)\n\n"
        "| scene | mode | policy | cycles/pixel | line hit rate | sector hit rate | memory bytes/pixel | miss stall "
        "cycles | shapes cross/T/L |\n"
        "|---|---|---|---:|---:|---:|---:|---:|---|\n";
  nlohmann::json js = nlohmann::json::array();
  for (const ResultRow& r : rows) {
    md << fmt::format("| {} | {} | {} | {:.3f} | {:.4f} | {:.4f} | {:.3f} | {} | {} |\n", r.scene, r.mode, r.policy,
                      r.cycles_per_pixel, r.hit_rate, r.sector_hit_rate, r.bytes_per_pixel, r.stall_miss,
                      r.cross + r.t + r.l ? fmt::format("{}/{}/{}", r.cross, r.t, r.l) : std::string());
    js.push_back({{"scene", r.scene},
                  {"mode", r.mode},
                  {"policy", r.policy},
                  {"line_bytes", r.line_bytes},
                  {"max_aniso", r.max_aniso},
                  {"cycles_per_pixel", r.cycles_per_pixel},
                  {"hit_rate", r.hit_rate},
                  {"sector_hit_rate", r.sector_hit_rate},
                  {"bytes_per_pixel", r.bytes_per_pixel},
                  {"memory_bytes", r.bytes},
                  {"stall_cache_miss", r.stall_miss},
                  {"shape_cross", r.cross},
                  {"shape_T", r.t},
                  {"shape_L", r.l}});
  }
  if (md_file) md_file->stream() << md.str();
  if (json_file) json_file->stream() << json_dump(js, 2) << '\n';
  outputs.commit();
  if (!md_file) std::cout << md.str();
}

}  // namespace

void register_sim(CLI::App& app) {
  auto ro = std::make_shared<ResultsOptions>();
  CLI::App* res = app.add_subcommand("sim-results", "Cycle model results for every scene x mode x policy (Markdown, JSON)");
  res->add_option("--scene", ro->scenes, "Built-in scene, scene JSON or oa:MAP[:SPAWN] (repeatable; default: every built-in scene)");
  res->add_option("--game-dir", ro->game_dir, "OpenArena data directory for oa: scenes");
  res->add_option("--config", ro->config, "Unit configuration JSON or statistics file (its recorded configuration; the line "
                                          "size experiment sets cache.line_bytes to 64 and 256)");
  res->add_option("--width", ro->width, "Render width per scene (0 with --height 0: each scene's own size)")->capture_default_str();
  res->add_option("--height", ro->height, "Render height per scene")->capture_default_str();
  res->add_option("--markdown", ro->markdown, "Markdown output file, - for stdout (default)");
  res->add_option("--json", ro->json, "JSON output file");
  res->add_flag("--force", ro->force, "Overwrite output files that exist");
  res->callback([ro] {
    const auto bad = [](int v) { return v < 0 || v == 1 || v > kMaxRenderSize; };
    if (bad(ro->width) || bad(ro->height))
      throw InputError(fmt::format("--width/--height must be in 2..{} (0: the scene's own size)", kMaxRenderSize));
    run_results(*ro);
  });

  auto o = std::make_shared<SimOptions>();
  CLI::App* cmd = app.add_subcommand("sim", "Cycle model vs golden reference: bit-exact compare, cycles, cache and memory statistics");
  cmd->add_option("--scene", o->scene,
                  "Built-in scene, scene JSON or oa:MAP[:SPAWN] (an OpenArena level; default: the default scene) whose trace is simulated");
  cmd->add_option("--game-dir", o->game_dir,
                  "OpenArena data directory for oa: scenes and a level trace's oa: textures (default: $TFU_OPENARENA_DIR or Debian's)");
  cmd->add_option("--width", o->width, "Scene render width (default: the scene's own)");
  cmd->add_option("--height", o->height, "Scene render height (default: the scene's own)");
  cmd->add_option("--requests", o->requests, "A request trace (quad, lod or grad mode) instead of a scene (docs/traces.md)");
  add_gl_trace_options(*cmd, o->gl, "both models");
  add_texture_options(*cmd, o->tex, false);
  add_sampler_options(*cmd, o->smp);
  cmd->add_option("--config", o->config,
                  "Unit configuration JSON (docs/cycle-model.md), or a statistics file (--stats) whose recorded "
                  "configuration to use; the flags below override it");
  cmd->add_option("--config-out", o->config_out, "Write the effective unit configuration (every field) as JSON");
  for (const rtl::UnitField& f : rtl::unit_config_fields()) cmd->add_option(f.flag, o->unit_flags[f.key], fmt::format("{}: {}", f.key, f.meaning));
  cmd->add_option("--depths-for-latency", o->depths_for_latency,
                  "Set miss_fifo_depth and line_buffer_depth by the Little's-law rule for this configuration's "
                  "memory.latency, from a zero-latency run's statistics file (docs/memory-system.md, \"Latency tolerance\")");
  cmd->add_flag("--config-fields", o->config_fields, "Print the unit configuration's fields (Markdown) and exit");
  cmd->add_flag("--stats-fields", o->stats_fields, "Print the statistics' fields (Markdown) and exit");
  cmd->add_option("--shape-policy", o->shape_policy,
                  "Edge kernel shapes of every edge-preserving sampler (a scene: its base stages): static, cache-aware or cross");
  cmd->add_option("--units", o->units, "Texture filter units, each taking its screen tiles (--unit-tiles; threads)");
  cmd->add_option("--unit-tiles", o->unit_tiles,
                  "Which unit draws which screen tile: round-robin:T (TxT-pixel tiles dealt in turn) or bands:T "
                  "(contiguous rows of tiles per unit) (docs/cycle-model.md)")
      ->capture_default_str();
  cmd->add_option("--raster", o->raster,
                  "The rasterizer's quad order: scanline, tiled:N or morton:N (docs/renderer.md); with --requests, "
                  "re-orders a trace that records screen positions")
      ->capture_default_str();
  cmd->add_option("--texture-layout", o->texture_layout,
                  "Scene runs: the memory layout of every texture, level textures included: linear or tiled (tiles of one "
                  "cache line); default: each texture's own (--requests runs: --layout)");
  cmd->add_option("--out", o->out, "Write the cycle model's image (scenes) as PNG");
  cmd->add_option("--stats", o->stats, "Write the statistics as JSON");
  cmd->add_option("--vcd", o->vcd,
                  "Write a value-change dump (GTKWave): clock, channels with their request ids, stages, texel cache "
                  "lines, the texture, stage, MIP level and screen position of requests and footprints; with --units N "
                  "also FILE.unitK.vcd per further unit");
  cmd->add_option("--vcd-from", o->vcd_from, "First cycle the waveform covers")->capture_default_str()->check(unsigned_integer());
  cmd->add_option("--vcd-to", o->vcd_to, "Last cycle the waveform covers (default: the end)")->check(unsigned_integer());
  cmd->add_option(
      "--vcd-signals", o->vcd_signals,
      "Only these waveform signals (and the clock): comma-separated names or globs, a scope selecting "
      "everything under it, e.g. 'tfu.pixel,tfu.texel_cache.accepted_*' (docs/cycle-model.md, \"Waveforms\")");
  cmd->add_option("--engine", o->engine,
                  "How the cycle model runs: recurrence (request by request through every block, by the timing "
                  "recurrences of rtl/unit_recurrence.cpp; the default) or clocked (every block every cycle: the "
                  "reference, and the one that writes --vcd; the default with --vcd); the same outputs, cycles and "
                  "statistics (tested)");
  add_plain_option(*cmd);
  cmd->add_flag("--compare-engines", o->compare_engines,
                "Also run both engines with every event recorded; name the first block and item where they disagree");
  cmd->add_flag("--bench", o->bench, "Print the simulation speed (with the recurrences, of the clocked blocks too)");
  cmd->add_flag("--force", o->force, "Overwrite output files that exist");
  cmd->callback([o, cmd] { run(*o, *cmd); });
}

}  // namespace tfu::cli
