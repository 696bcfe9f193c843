// The statistics field table (rtl/unit_stats.hpp) against what runs publish: every key a run of the
// unit writes (one unit and a scene's several, both engines, every datapath) is a row of the
// table with the same kind, and every row is published by one of these runs; and the docs show the
// table (docs/cycle-model.md "Statistics", `tfu sim --stats-fields`). A unit run of a compressed
// texture publishes the decoder rows.
#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cmodel/block_formats.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/procedural.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/unit_stats.hpp"
#include "testbench/docs_text.hpp"

namespace tfu::rtl {
namespace {

// The table row a published key belongs to: the exact key, or a per-level key followed by digits.
const UnitStatField* row_of(const std::string& key) {
  for (const UnitStatField& f : kUnitStatFields) {
    const std::string k = f.key;
    if (key == k) return f.per_level() ? nullptr : &f;
    if (f.per_level() && key.size() > k.size() && key.compare(0, k.size(), k) == 0 &&
        key.find_first_not_of("0123456789", k.size()) == std::string::npos)
      return &f;
  }
  return nullptr;
}

// Checks every key of `st` against the table (and of its groups, against the rows published in
// groups); returns the rows it published.
std::set<UnitStat> check_published(const sim::Stats& st, const std::string& what, bool in_group = false) {
  for (const sim::Stats::Group& g : st.groups()) {
    EXPECT_TRUE(g.breakdown == kStageGroups || g.breakdown == kTextureGroups) << what << ": group " << g.breakdown;
    const std::string in = fmt::format("{}: group {} '{}'", what, g.breakdown, g.label);
    EXPECT_TRUE(g.stats.groups().empty()) << in;
    for (const UnitStat f : check_published(g.stats, in, true))
      EXPECT_NE(kUnitStatFields[static_cast<size_t>(f)].in_group, nullptr)
          << in << ": '" << kUnitStatFields[static_cast<size_t>(f)].key
          << "' is published in a group; the table says not";
  }
  const nlohmann::json j = nlohmann::json::parse(st.json_text());
  const std::map<std::string, StatKind> sections{{"counters", StatKind::Counter},
                                                 {"values", StatKind::Value},
                                                 {"histograms", StatKind::Histogram},
                                                 {"tables", StatKind::Table}};
  std::set<UnitStat> seen;
  for (const auto& [section, kind] : sections) {
    if (!j.contains(section)) continue;
    for (const auto& [key, v] : j[section].items()) {
      if (in_group && section == "tables") ADD_FAILURE() << what << ": a table in a group";
      const UnitStatField* f = row_of(key);
      EXPECT_NE(f, nullptr) << what << ": published " << section << " '" << key << "' is not in kUnitStatFields";
      if (!f) continue;
      EXPECT_EQ(f->kind, kind) << what << ": '" << key << "' is published as " << section << ", the table says "
                               << kStatKindNames.name(f->kind);
      seen.insert(f->id);
    }
  }
  return seen;
}

SceneSimResult run_scene(const std::string& name, const std::string& mode, int max_aniso, int units, UnitEngine engine) {
  Scene scene = load_scene(name);
  scene.width = 48;
  scene.height = 32;
  RenderOptions o;
  o.trace = true;
  o.threads = 1;
  o.filter = filter_mode_from_name(mode);
  if (max_aniso > 1) o.sampler_overrides["max_aniso"] = std::to_string(max_aniso);
  const RenderResult render = render_scene(scene, o);
  SceneSimOptions so;
  so.units = units;
  so.engine = engine;
  const UnitConfig u;
  SceneSimResult r = simulate_scene(scene, render, u, so);
  EXPECT_TRUE(r.mismatch.empty()) << r.mismatch;
  return r;
}

TEST(UnitStats, EveryPublishedKeyIsInTheTable) {
  std::set<UnitStat> all;
  struct Case {
    const char* scene;
    const char* mode;
    int max_aniso, units;
    UnitEngine engine;
  };
  for (const Case& c : {Case{"ground_plane", "LINEAR_MIPMAP_LINEAR", 4, 2, UnitEngine::Recurrence},
                        Case{"ground_plane", "LINEAR_MIPMAP_LINEAR", 4, 1, UnitEngine::Clocked},
                        Case{"lightmapped", "EDGE_PRESERVING_MIPMAP_LINEAR", 1, 1, UnitEngine::Clocked},
                        Case{"magnified", "CUBIC", 1, 1, UnitEngine::Recurrence}}) {
    const std::string what = fmt::format("{} {} x{} units {} {}", c.scene, c.mode, c.max_aniso, c.units,
                                         unit_engine_name(c.engine));
    const SceneSimResult r = run_scene(c.scene, c.mode, c.max_aniso, c.units, c.engine);
    const std::set<UnitStat> seen = check_published(r.stats, what);
    all.insert(seen.begin(), seen.end());
    // The readers' names read the writers' values.
    EXPECT_EQ(counter(r.stats, UnitStat::Pixels), r.requests) << what;
    EXPECT_EQ(counter(r.stats, UnitStat::Cycles), r.cycles) << what;
    EXPECT_EQ(counter(r.stats, UnitStat::Units), static_cast<uint64_t>(c.units)) << what;
  }
  // A block-compressed texture beside an uncompressed one (the decoder statistics), both engines.
  {
    FrameBuilder b(64);
    BlockImage image;
    image.format = BlockFormat::BC3;
    image.levels.push_back({16, 16, std::vector<uint8_t>(block_level_bytes(BlockFormat::BC3, 16, 16))});
    for (size_t i = 0; i < image.levels[0].blocks.size(); ++i) image.levels[0].blocks[i] = static_cast<uint8_t>(i * 37);
    b.add_texture(std::make_shared<const Texture>(texture_from_block_image(image, {})), {"bc3", {}});
    b.add_sampler(SamplerDescriptor{});
    Trace tr;
    for (int k = 0; k < 16; ++k) {
      TraceRequest r;
      r.s = static_cast<float>(k) / 16.0f;
      r.t = 0.3f;
      tr.requests.push_back(r);
    }
    bind_requests(b, tr);
    const Frame frame = b.finish();
    for (const UnitEngine e : {UnitEngine::Clocked, UnitEngine::Recurrence}) {
      const std::set<UnitStat> seen = check_published(run_unit(frame, tr, UnitConfig{}, e, {}).stats, "bc3");
      all.insert(seen.begin(), seen.end());
    }
    // The misses served by a DRAM part (memory.dram): its statistics.
    UnitConfig with_dram;
    with_dram.memory.dram = 1;
    const std::set<UnitStat> seen = check_published(run_unit(frame, tr, with_dram, UnitEngine::Recurrence, {}).stats, "dram");
    all.insert(seen.begin(), seen.end());
  }
  for (const UnitStatField& f : kUnitStatFields)
    EXPECT_TRUE(all.contains(f.id)) << "kUnitStatFields row '" << f.key << "' is published by none of the runs";
}

// Every counter and histogram bucket of the groups of one breakdown, summed, against the total's;
// `cycles_add_up`: one unit (its groups' cycles add up to the run's).
void expect_groups_add_up(const sim::Stats& st, const char* breakdown, bool cycles_add_up, const std::string& what) {
  std::map<std::string, uint64_t> counters;
  std::map<std::string, std::vector<uint64_t>> histograms;
  size_t groups = 0;
  for (const sim::Stats::Group& g : st.groups()) {
    if (g.breakdown != breakdown) continue;
    ++groups;
    for (const auto& [k, v] : g.stats.counters()) counters[k] += v;
    const nlohmann::json j = nlohmann::json::parse(g.stats.json_text());
    if (j.contains("histograms"))
      for (const auto& [k, h] : j["histograms"].items()) {
        std::vector<uint64_t>& into = histograms[k];
        if (into.size() < h.size()) into.resize(h.size());
        for (size_t b = 0; b < h.size(); ++b) into[b] += h[b].get<uint64_t>();
      }
    // The rates are the group's own.
    const double px = static_cast<double>(counter(g.stats, UnitStat::Pixels));
    EXPECT_DOUBLE_EQ(value(g.stats, UnitStat::PixelsPerClock),
                     px / static_cast<double>(counter(g.stats, UnitStat::Cycles)))
        << what << " " << g.label;
    EXPECT_DOUBLE_EQ(value(g.stats, UnitStat::MemoryBytesPerPixel),
                     static_cast<double>(counter(g.stats, UnitStat::MemoryBytes)) / px)
        << what << " " << g.label;
    EXPECT_DOUBLE_EQ(value(g.stats, UnitStat::ProbesPerPixel),
                     static_cast<double>(counter(g.stats, UnitStat::Probes)) / px)
        << what << " " << g.label;
  }
  EXPECT_GT(groups, 0u) << what;
  for (const auto& [k, v] : st.counters()) {
    if (k == stat_key(UnitStat::Units) || (k == stat_key(UnitStat::Cycles) && !cycles_add_up)) continue;
    EXPECT_EQ(counters[k], v) << what << ": " << breakdown << " groups' '" << k << "'";
  }
  for (const auto& [k, v] : counters)
    EXPECT_TRUE(st.counters().contains(k)) << what << ": '" << k << "' only in groups";
  for (const char* h : {"latency", "aniso_probes", "edge_direction"}) {
    const std::vector<uint64_t>* total = st.histogram(h);
    if (!total) {
      EXPECT_FALSE(histograms.contains(h)) << what << ": '" << h << "' only in groups";
      continue;
    }
    std::vector<uint64_t> sum = histograms[h];
    sum.resize(std::max(sum.size(), total->size()));
    std::vector<uint64_t> want = *total;
    want.resize(sum.size());
    EXPECT_EQ(sum, want) << what << ": " << breakdown << " groups' histogram '" << h << "'";
  }
}

// The groups add up to the totals: every counter (the cycles of one unit too) and every histogram,
// per stage and per texture, on the two-stage lightmapped scene (both engines, one and two units,
// anisotropic and edge-preserving) and a compressed texture's decoder counters.
TEST(UnitStats, StageAndTextureGroupsAddUpToTheTotals) {
  struct Case {
    const char* scene;
    const char* mode;
    int max_aniso, units;
    UnitEngine engine;
  };
  for (const Case& c : {Case{"lightmapped", "LINEAR_MIPMAP_LINEAR", 4, 1, UnitEngine::Recurrence},
                        Case{"lightmapped", "LINEAR_MIPMAP_LINEAR", 4, 1, UnitEngine::Clocked},
                        Case{"lightmapped", "EDGE_PRESERVING_MIPMAP_LINEAR", 1, 2, UnitEngine::Recurrence},
                        Case{"lightmapped", "CUBIC", 1, 1, UnitEngine::Clocked}}) {
    const std::string what =
        fmt::format("{} {} x{} units {} {}", c.scene, c.mode, c.max_aniso, c.units, unit_engine_name(c.engine));
    const SceneSimResult r = run_scene(c.scene, c.mode, c.max_aniso, c.units, c.engine);
    ASSERT_NE(r.stats.find_group(kStageGroups, "stage 1"), nullptr) << what;  // the light maps
    expect_groups_add_up(r.stats, kStageGroups, c.units == 1, what);
    expect_groups_add_up(r.stats, kTextureGroups, c.units == 1, what);
  }
}

// A two-stage trace whose light-map stage is derived by hand. Stage 0 reads a 16x16 base texture
// NEAREST, stage 1 a 4x4 light map LINEAR (repeat, no MIP-map), interleaved quad by quad as the
// rasterizer issues a two-stage material: base quad A at texels (0..1, 0..1), its light-map quad,
// base quad C at (8..9, 8..9), its light-map quad. Textures tiled in 64-byte lines (4x4 RGBA8
// texels), so the light map is one line and every LINEAR footprint on it (columns i, i + 1 mod 4)
// reads that line: stage 1 has 8 pixels, 8 probes, 1 miss (its first footprint) and 7 hits, 64
// memory bytes in 1 request. Each base quad reads one tile (1 miss, 3 hits): stage 0 has 2 misses,
// 6 hits, 128 bytes. The 16 KiB cache evicts nothing.
TEST(UnitStats, LightMapStageCountsDerivedByHand) {
  const UnitConfig u;
  ASSERT_EQ(u.cache.line_bytes, 64);
  FrameBuilder b(u.cache.line_bytes);
  b.add_texture(std::make_shared<const Texture>(make_checkerboard(16, 4).texture), {"base", {}});
  b.add_texture(std::make_shared<const Texture>(make_checkerboard(4, 1).texture), {"lightmap", {}});
  SamplerDescriptor nearest, linear;
  nearest.mode = FilterMode{BaseFilter::Nearest, MipMode::None};
  linear.mode = FilterMode{BaseFilter::Linear, MipMode::None};
  linear.wrap_s = linear.wrap_t = WrapMode::Repeat;
  b.add_sampler(nearest);
  b.add_sampler(linear);
  Trace tr;
  const auto quad = [&tr](int stage, int size, int x, int y) {
    for (int k = 0; k < 4; ++k) {
      TraceRequest r;
      r.texture = r.sampler = static_cast<uint8_t>(stage);
      r.stage = static_cast<uint8_t>(stage);
      r.s = (static_cast<float>(x + (k & 1)) + 0.5f) / static_cast<float>(size);
      r.t = (static_cast<float>(y + (k >> 1)) + 0.5f) / static_cast<float>(size);
      tr.requests.push_back(r);
    }
  };
  quad(0, 16, 0, 0);
  quad(1, 4, 0, 0);
  quad(0, 16, 8, 8);
  quad(1, 4, 2, 2);
  bind_requests(b, tr);
  const Frame frame = b.finish();
  for (const UnitEngine e : {UnitEngine::Clocked, UnitEngine::Recurrence}) {
    const std::string what = unit_engine_name(e);
    const UnitOutput out = run_unit(frame, tr, u, e, {});
    const sim::Stats& st = out.stats;
    const sim::Stats* base = st.find_group(kStageGroups, "stage 0");
    const sim::Stats* light = st.find_group(kStageGroups, "stage 1");
    ASSERT_NE(base, nullptr) << what;
    ASSERT_NE(light, nullptr) << what;
    EXPECT_EQ(st.find_group(kStageGroups, "stage 2"), nullptr) << what;
    EXPECT_EQ(counter(*light, UnitStat::Pixels), 8u) << what;
    EXPECT_EQ(counter(*light, UnitStat::Probes), 8u) << what;
    EXPECT_EQ(counter(*light, UnitStat::CacheLineMisses), 1u) << what;
    EXPECT_EQ(counter(*light, UnitStat::CacheLineHits), 7u) << what;
    EXPECT_EQ(light->counter("cache_line_hits_level0"), 7u) << what;
    EXPECT_EQ(light->counter("cache_line_misses_level0"), 1u) << what;
    EXPECT_EQ(counter(*light, UnitStat::MemoryBytes), 64u) << what;
    EXPECT_EQ(counter(*light, UnitStat::MemoryRequests), 1u) << what;
    EXPECT_DOUBLE_EQ(value(*light, UnitStat::CacheHitRate), 7.0 / 8.0) << what;
    EXPECT_DOUBLE_EQ(value(*light, UnitStat::MemoryBytesPerPixel), 8.0) << what;
    EXPECT_DOUBLE_EQ(value(*light, UnitStat::ProbesPerPixel), 1.0) << what;
    EXPECT_EQ(counter(*base, UnitStat::Pixels), 8u) << what;
    EXPECT_EQ(counter(*base, UnitStat::CacheLineMisses), 2u) << what;
    EXPECT_EQ(counter(*base, UnitStat::CacheLineHits), 6u) << what;
    EXPECT_EQ(counter(*base, UnitStat::MemoryBytes), 128u) << what;
    // Each stage reads its own texture: the texture groups are the stage groups.
    const sim::Stats* lightmap = st.find_group(kTextureGroups, "1 lightmap");
    ASSERT_NE(lightmap, nullptr) << what;
    EXPECT_EQ(lightmap->json_text(), light->json_text()) << what;
    // The output cycles of both stages add up to the run's; each request's latency is counted
    // once in its stage.
    EXPECT_EQ(counter(*base, UnitStat::Cycles) + counter(*light, UnitStat::Cycles), out.cycles) << what;
    EXPECT_EQ(counter(st, UnitStat::MemoryBytes), 192u) << what;
    expect_groups_add_up(st, kStageGroups, true, what);
    expect_groups_add_up(st, kTextureGroups, true, what);
  }
}

TEST(UnitStats, KeysAndMarkdown) {
  EXPECT_STREQ(stat_key(UnitStat::CacheLineHits), "cache_line_hits");
  EXPECT_EQ(stat_key(UnitStat::CacheLineMissesLevel, 3), "cache_line_misses_level3");
  const std::string md = unit_stats_markdown();
  EXPECT_NE(md.find("| `cache_line_hits_levelN` | counter |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `latency` | histogram |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `pixels_per_clock` | value | pixels / cycles | yes: the group's pixels / its cycles |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| `units` | counter | units of a scene run (a scene run only) | no |"), std::string::npos) << md;
  EXPECT_EQ(static_cast<size_t>(std::count(md.begin(), md.end(), '\n')), kUnitStatFields.size() + 2);
}

TEST(Docs, CycleModelShowsTheStatFields) {
  EXPECT_NE(test::docs_text("cycle-model.md").find(unit_stats_markdown()), std::string::npos)
      << "docs/cycle-model.md is stale: paste `tfu sim --stats-fields` between the generated markers";
}

}  // namespace
}  // namespace tfu::rtl

namespace tfu {
namespace {

// The run's probe histogram is the units' histograms added: it must count every pixel of every unit,
// those of a unit that met only one-probe pixels included (each unit publishes it when a bound
// sampler is anisotropic, not when its own pixels happen to need more than one probe).
TEST(UnitStats, ProbeHistogramOfSeveralUnitsCountsEveryPixel) {
  Scene s = load_scene("ground_plane");
  s.width = 128;
  s.height = 96;
  RenderOptions ro;
  ro.trace = true;
  ro.sampler_overrides["max_aniso"] = "16";
  const RenderResult render = render_scene(s, ro);
  for (int units : {1, 3, 12}) {
    rtl::SceneSimOptions so;
    so.units = units;
    so.tiles.tile = 16;
    const rtl::SceneSimResult r = rtl::simulate_scene(s, render, rtl::UnitConfig{}, so);
    ASSERT_TRUE(r.mismatch.empty()) << r.mismatch;
    const std::vector<uint64_t>* h = r.stats.histogram("aniso_probes");
    ASSERT_NE(h, nullptr) << units;
    uint64_t pixels = 0, probes = 0;
    for (size_t n = 0; n < h->size(); ++n) {
      pixels += (*h)[n];
      probes += n * (*h)[n];
    }
    EXPECT_EQ(pixels, r.requests) << units << " units";
    EXPECT_EQ(probes, r.stats.counter("probes")) << units << " units";
  }
}

}  // namespace
}  // namespace tfu
