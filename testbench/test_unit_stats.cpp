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

// Checks every key of `st` against the table; returns the rows it published.
std::set<UnitStat> check_published(const sim::Stats& st, const std::string& what) {
  const nlohmann::json j = nlohmann::json::parse(st.json_text());
  const std::map<std::string, StatKind> sections{{"counters", StatKind::Counter},
                                                 {"values", StatKind::Value},
                                                 {"histograms", StatKind::Histogram},
                                                 {"tables", StatKind::Table}};
  std::set<UnitStat> seen;
  for (const auto& [section, kind] : sections) {
    if (!j.contains(section)) continue;
    for (const auto& [key, v] : j[section].items()) {
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
  }
  for (const UnitStatField& f : kUnitStatFields)
    EXPECT_TRUE(all.contains(f.id)) << "kUnitStatFields row '" << f.key << "' is published by none of the runs";
}

TEST(UnitStats, KeysAndMarkdown) {
  EXPECT_STREQ(stat_key(UnitStat::CacheLineHits), "cache_line_hits");
  EXPECT_EQ(stat_key(UnitStat::CacheLineMissesLevel, 3), "cache_line_misses_level3");
  const std::string md = unit_stats_markdown();
  EXPECT_NE(md.find("| `cache_line_hits_levelN` | counter |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `latency` | histogram |"), std::string::npos) << md;
  EXPECT_EQ(static_cast<size_t>(std::count(md.begin(), md.end(), '\n')), kUnitStatFields.size() + 2);
}

TEST(Docs, CycleModelShowsTheStatFields) {
  EXPECT_NE(test::docs_text("cycle-model.md").find(unit_stats_markdown()), std::string::npos)
      << "docs/cycle-model.md is stale: paste `tfu sim --stats-fields` between the generated markers";
}

}  // namespace
}  // namespace tfu::rtl
