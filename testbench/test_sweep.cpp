// Design-space sweep (sim/sweep/, docs/design-space.md): the cost model's SRAM bits derived by hand,
// the gate table against docs/gates.md, provenance round trips (a stats file's recorded
// configuration reproduces its statistics), the spec's validation and expansion, and the local
// runner's results independent of the worker count, with resume.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <set>
#include <fstream>
#include <memory>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmodel/error.hpp"
#include "cmodel/temp_paths.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene_source.hpp"
#include "rtl/cost_model.hpp"
#include "rtl/scene_sim.hpp"
#include "sim/sweep/process.hpp"
#include "sim/sweep/provenance.hpp"
#include "sim/sweep/sweep_point.hpp"
#include "sim/sweep/sweep_report.hpp"
#include "sim/sweep/sweep_run.hpp"
#include "sim/sweep/sweep_spec.hpp"

namespace tfu {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// ---- cost model ----

TEST(CostModel, SramBitsOfTheDefaultCacheByHand) {
  // 16 KiB, 4 ways, 64-byte lines: 256 lines in 64 sets; a 40-bit byte address has 34 line-address
  // bits, 6 of which index the set: 28 tag bits per line; LRU: a 2-bit age per way.
  const rtl::CacheSramBits b = rtl::texel_cache_sram_bits(rtl::TexelCacheConfig{});
  EXPECT_EQ(b.tag_bits, 28);
  EXPECT_EQ(b.data, 16384u * 8);
  EXPECT_EQ(b.tag, 256u * 28);
  EXPECT_EQ(b.valid, 256u);
  EXPECT_EQ(b.lru, 64u * 4 * 2);
  EXPECT_EQ(b.total(), 131072u + 7168 + 256 + 512);
}

TEST(CostModel, SramBitsDirectMappedAndFullyAssociative) {
  rtl::TexelCacheConfig c;
  c.capacity_bytes = 4096;
  c.ways = 1;  // 64 sets of one line: no LRU; 34 - 6 = 28 tag bits
  rtl::CacheSramBits b = rtl::texel_cache_sram_bits(c);
  EXPECT_EQ(b.tag_bits, 28);
  EXPECT_EQ(b.lru, 0u);
  EXPECT_EQ(b.total(), 32768u + 64 * 28 + 64);
  c.ways = 64;  // one set: the whole 34-bit line address is the tag; 6-bit ages
  b = rtl::texel_cache_sram_bits(c);
  EXPECT_EQ(b.tag_bits, 34);
  EXPECT_EQ(b.lru, 64u * 6);
}

TEST(CostModel, GateTableMatchesDocsGates) {
  // The table compiled in from rtl/sv/filter_gates.json must carry the figures docs/gates.md reports.
  const std::string doc = read_text(fs::path(TFU_DOCS_DIR) / "gates.md");
  ASSERT_FALSE(rtl::filter_gate_table().empty());
  for (const rtl::GateBlock& b : rtl::filter_gate_table()) {
    // "14087.7" in the tables, or rounded with a thousands separator ("59,803") in the prose
    const auto whole = static_cast<long>(std::lround(b.ge));
    const std::string decimal = fmt::format("{:.1f}", b.ge), grouped = fmt::format("{},{:03d}", whole / 1000, whole % 1000);
    EXPECT_TRUE(doc.find(decimal) != std::string::npos || doc.find(grouped) != std::string::npos) << b.block << " " << decimal;
  }
}

TEST(SweepSpec, NodeKeyNamesAKnownNode) {
  const auto parse = [](const std::string& node) {
    return sweep::parse_spec(R"({"scenes": ["ground_plane"], "node": )" + node + R"(, "grid": {"cache.ways": [1]}})", "s.json");
  };
  EXPECT_EQ(parse("\"osu035\"").node, rtl::Node::Osu035);
  EXPECT_EQ(sweep::parse_spec(R"({"scenes": ["ground_plane"], "grid": {"cache.ways": [1]}})", "s.json").node, rtl::Node::Osu018);
  for (const char* bad : {"\"osu090\"", "35"}) {
    try {
      (void)parse(bad);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("s.json: node: "), std::string::npos) << e.what();
    }
  }
}

TEST(SweepReport, DocsListEveryResultColumn) {
  // docs/design-space.md ("What a sweep writes") names every column of results.csv the code writes.
  const std::string doc = read_text(fs::path(TFU_DOCS_DIR) / "design-space.md");
  const std::string section = doc.substr(doc.find("## What a sweep writes"), doc.find("## The local runner") - doc.find("## What a sweep writes"));
  for (const sweep::Column& c : sweep::result_columns()) EXPECT_NE(section.find("`" + c.name + "`"), std::string::npos) << c.name;
}

TEST(CostModel, FilterGatesSumTheBlocksTheModesNeed) {
  const auto ge_of = [](const std::string& block) {
    for (const rtl::GateBlock& b : rtl::filter_gate_table())
      if (b.block == block) return b.ge;
    ADD_FAILURE() << block;
    return 0.0;
  };
  const auto mode = [](const char* n) { return filter_mode_from_name(n); };
  EXPECT_DOUBLE_EQ(rtl::filter_datapath_gates({mode("LINEAR")}).ge, ge_of("bilinear_top"));
  EXPECT_DOUBLE_EQ(rtl::filter_datapath_gates({mode("NEAREST"), mode("LINEAR")}).ge, ge_of("bilinear_top"));
  EXPECT_DOUBLE_EQ(rtl::filter_datapath_gates({mode("trilinear")}).ge, ge_of("bilinear_top") + ge_of("level_blend"));
  const rtl::FilterGates g = rtl::filter_datapath_gates({mode("CUBIC_MIPMAP_LINEAR"), mode("EDGE_PRESERVING")});
  EXPECT_DOUBLE_EQ(g.ge, ge_of("level_blend") + ge_of("cubic_filter") + ge_of("edge_interp_top"));
  EXPECT_EQ(g.blocks.size(), 3u);
}

TEST(CostModel, AnisotropicSamplersAddTheAnisoBlocks) {
  // docs/gates.md: major select 1053.3 + probe count 13749.4 + lambda 1073.9 + probe generator 9266.9.
  const double aniso = 1053.3 + 13749.4 + 1073.9 + 9266.9;
  const double trilinear = 14087.7 + 5284.3;  // bilinear_top + level_blend (Q.8 blend, docs/gates.md)
  const auto sampler = [](const char* mode, int max_aniso) {
    SamplerDescriptor d;
    d.mode = filter_mode_from_name(mode);
    d.max_aniso = max_aniso;
    return d;
  };
  EXPECT_NEAR(rtl::filter_datapath_gates({filter_mode_from_name("trilinear")}, true).ge, trilinear + aniso, 1e-6);
  EXPECT_NEAR(rtl::filter_datapath_gates({sampler("trilinear", 8)}).ge, trilinear + aniso, 1e-6);
  // max_aniso 1, or a mode without MIP-mapping (which ignores max_aniso): isotropic, no aniso blocks
  EXPECT_NEAR(rtl::filter_datapath_gates({sampler("trilinear", 1)}).ge, trilinear, 1e-6);
  EXPECT_NEAR(rtl::filter_datapath_gates({sampler("LINEAR", 16), sampler("trilinear", 1)}).ge, trilinear, 1e-6);
  // one figure for every maxAniso; blocks listed in table order
  const rtl::FilterGates g = rtl::filter_datapath_gates({sampler("LINEAR", 1), sampler("CUBIC_MIPMAP_NEAREST", 2)});
  EXPECT_NEAR(g.ge, 14087.7 + 46355.2 + aniso, 1e-6);
  EXPECT_EQ(g.blocks, (std::vector<std::string>{"bilinear_top", "cubic_filter", "aniso_major_select", "aniso_count",
                                                "aniso_lambda", "aniso_probe"}));
  // The footprint's true axes add tfu_aniso_lod's ellipse parts (docs/gates.md, "The ellipse axes"):
  // dot and cross 32672.5 + the hypot 11140.2 + the ellipse count 10195.0; only on an anisotropic
  // sampler (an isotropic one never reaches them).
  const double ellipse = 32672.5 + 11140.2 + 10195.0;
  SamplerDescriptor on_axes = sampler("trilinear", 8);
  on_axes.aniso_axes = AnisoAxes::Ellipse;
  const rtl::FilterGates e = rtl::filter_datapath_gates({on_axes, sampler("LINEAR", 1)});
  EXPECT_NEAR(e.ge, trilinear + aniso + ellipse, 1e-6);
  EXPECT_EQ(e.blocks, (std::vector<std::string>{"bilinear_top", "level_blend", "aniso_major_select", "aniso_count",
                                                "aniso_lambda", "aniso_probe", "aniso_dot_cross",
                                                "aniso_ellipse_major", "aniso_count_ellipse"}));
  on_axes.max_aniso = 1;
  EXPECT_NEAR(rtl::filter_datapath_gates({on_axes}).ge, trilinear, 1e-6);
  EXPECT_NEAR(rtl::filter_datapath_gates({filter_mode_from_name("trilinear")}, true, true).ge,
              trilinear + aniso + ellipse, 1e-6);
}

// ---- provenance ----

TEST(Provenance, Fnv1a64KnownValues) {
  // FNV-1a 64 test vectors (Fowler/Noll/Vo reference): "" and "a".
  EXPECT_EQ(hex64(fnv1a64("")), "cbf29ce484222325");
  EXPECT_EQ(hex64(fnv1a64("a")), "af63dc4c8601ec8c");
}

TEST(Provenance, RecordedConfigurationReproducesTheStatistics) {
  rtl::UnitConfig u;
  u.cache.capacity_bytes = 4096;
  u.cache.ways = 2;
  u.memory.latency = 37;
  u.filter_lanes = 2;
  const Scene scene = open_scene({"ground_plane", 64, 48, ""});
  const auto run = [&](const rtl::UnitConfig& c) {
    RenderOptions ro;
    ro.trace = true;
    ro.threads = 1;
    ro.line_bytes = c.cache.line_bytes;
    ro.filter = filter_mode_from_name("LINEAR_MIPMAP_LINEAR");
    const RenderResult render = render_scene(scene, ro);
    rtl::SceneSimOptions so;
    so.engine = rtl::UnitEngine::Clocked;
    const rtl::SceneSimResult r = rtl::simulate_scene(scene, render, c, so);
    EXPECT_TRUE(r.mismatch.empty());
    RunRecord rec;
    rec.command = "sim";
    rec.scene = {"ground_plane", 64, 48, ""};
    rec.width = 64;
    rec.height = 48;
    rec.filter = "LINEAR_MIPMAP_LINEAR";
    rec.config = &c;
    rec.engine = so.engine;
    rec.textures = frame_texture_names(render.frame->frame);
    return stats_document(r.stats, provenance_json(rec));
  };
  const std::string first = run(u);
  const nlohmann::json doc = nlohmann::json::parse(first);
  const nlohmann::json& p = doc.at("provenance");
  EXPECT_EQ(p.at("scene").at("kind"), "builtin");
  EXPECT_EQ(p.at("scene").at("name"), "ground_plane");
  EXPECT_EQ(p.at("width"), 64);
  EXPECT_EQ(p.at("filter"), "LINEAR_MIPMAP_LINEAR");
  EXPECT_EQ(p.at("unit_config").at("memory").at("latency"), 37);
  EXPECT_EQ(p.at("unit_config").at("channel_depth"), u.channel_depth);  // defaults recorded too
  EXPECT_EQ(p.at("engine"), "clocked");
  RunRecord golden_only;  // no cycle model ran (tfu report): neither a configuration nor an engine
  golden_only.command = "report";
  golden_only.scene = {"ground_plane", 64, 48, ""};
  const nlohmann::json g = provenance_json(golden_only);
  EXPECT_FALSE(g.contains("unit_config"));
  EXPECT_FALSE(g.contains("engine"));
  EXPECT_FALSE(p.at("textures").empty());
  ASSERT_TRUE(doc.contains("definitions"));
  const rtl::UnitConfig back = rtl::unit_config_from_json(unit_config_text(first), "stats");
  EXPECT_EQ(back, u);
  const nlohmann::json again = nlohmann::json::parse(run(back));
  for (const char* k : {"counters", "values", "histograms", "tables"}) EXPECT_EQ(doc.at(k), again.at(k)) << k;
  EXPECT_NE(doc.at("counters").at("cycles"), nullptr);
}

TEST(Provenance, UnitConfigTextPassesAConfigurationThrough) {
  EXPECT_EQ(unit_config_text("{\"cache\": {\"ways\": 2}}"), "{\"cache\": {\"ways\": 2}}");
  EXPECT_EQ(unit_config_text("not json"), "not json");
}

TEST(Provenance, SceneLabels) {
  EXPECT_EQ(scene_label("ground_plane"), "ground_plane");
  EXPECT_EQ(scene_label("dir/my scene.json"), "my_scene");
  EXPECT_EQ(scene_label("oa:aggressor:2"), "oa_aggressor_2");
}

// ---- spec ----

std::string spec_error(const std::string& text) {
  try {
    (void)sweep::expand(sweep::parse_spec(text, "s.json"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SweepSpec, BadSpecsNameTheKey) {
  EXPECT_EQ(spec_error(R"({"scenes": ["ground_plane"], "grid": {"cache.wayz": [1]}})").find("s.json: grid.cache.wayz: unknown key"), 0u);
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "grid": {"cache.ways": ["4"]}})").find("grid.cache.ways: values must be integers"),
            std::string::npos);
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "grid": {"cache.ways": []}})").find("grid.cache.ways: is an empty list"),
            std::string::npos);
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "grid": {}})").find("s.json: grid: empty"), std::string::npos);
  // ways 3 is in range but does not divide 16 KiB: the point is named with its keys
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "grid": {"cache.ways": [3]}})").find("grid: point 0 (ground_plane scene, cache.ways=3)"),
            std::string::npos);
  EXPECT_NE(spec_error(R"({"scenes": ["no_such_scene"], "grid": {"cache.ways": [1]}})").find("s.json: scenes:"), std::string::npos);
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "filters": ["BOXY"], "grid": {"cache.ways": [1]}})").find("s.json: filters:"),
            std::string::npos);
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "grid": {"cache.ways": [1]}, "extra": 1})").find("s.json: extra: unknown key"),
            std::string::npos);
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "base": {"memory": {"latency": -1}}, "grid": {"cache.ways": [1]}})")
                .find("memory.latency"),
            std::string::npos);
  // A relation between fields that only a point breaks: 64 KiB in 1 way of 64-byte lines is fine,
  // 128 bytes in 4 ways of 64-byte lines is not.
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "grid": {"cache.capacity_bytes": [128], "cache.ways": [4]}})").find("point 0"),
            std::string::npos);
}

TEST(SweepSpec, ExpansionOrderAndExplicitPoints) {
  const sweep::Spec s = sweep::parse_spec(
      R"({"scenes": ["ground_plane"], "filters": ["LINEAR", "trilinear"],
          "grid": {"cache.capacity_bytes": [4096, 16384], "cache.ways": [1, 4]},
          "points": [{"cache.ways": 16, "filter": "CUBIC"}]})",
      "s.json");
  const std::vector<sweep::Point> pts = sweep::expand(s);
  ASSERT_EQ(pts.size(), 2u * 2 * 2 + 1);
  EXPECT_EQ(s.filters[1], "LINEAR_MIPMAP_LINEAR");
  // scenes x filters x grid, last grid key fastest
  EXPECT_EQ(pts[0].values, (std::vector<std::string>{"4096", "1"}));
  EXPECT_EQ(pts[1].values, (std::vector<std::string>{"4096", "4"}));
  EXPECT_EQ(pts[2].values, (std::vector<std::string>{"16384", "1"}));
  EXPECT_EQ(pts[4].filter, "LINEAR_MIPMAP_LINEAR");
  EXPECT_EQ(pts[8].filter, "CUBIC");
  EXPECT_EQ(pts[8].config.cache.ways, 16);
  EXPECT_EQ(pts[8].values[0], "16384");  // unset keys: the base configuration's value
  EXPECT_EQ(pts[3].config.cache.capacity_bytes, 16384);
  // ids: distinct, and the same for the same spec
  std::set<std::string> ids;
  for (const auto& p : pts) ids.insert(p.id);
  EXPECT_EQ(ids.size(), pts.size());
  EXPECT_EQ(sweep::expand(s)[5].id, pts[5].id);
}

TEST(SweepSpec, RunKeysAreGridKeys) {
  const sweep::Spec s = sweep::parse_spec(
      R"({"scenes": ["ground_plane"], "width": 64, "height": 48,
          "grid": {"raster": ["scanline", "tiled:08", "morton:16"], "units": [1, 4], "unit_tiles": ["bands"]},
          "points": [{"width": 96, "height": 64}]})",
      "s.json");
  const std::vector<sweep::Point> pts = sweep::expand(s);
  ASSERT_EQ(pts.size(), 3u * 2 + 1);
  EXPECT_EQ(pts[2].values, (std::vector<std::string>{"tiled:8", "1", "bands:32", "64", "48"}));  // canonical names
  EXPECT_EQ(pts[2].raster, (RasterOrder{RasterTraversal::Tiled, 8}));
  EXPECT_EQ(pts[3].units, 4);
  EXPECT_EQ(pts[3].unit_tiles.distribution, UnitDistribution::Bands);
  EXPECT_EQ(pts[0].width, 64);
  EXPECT_EQ(pts[6].width, 96);  // the explicit point's size; the grid keys keep the spec's defaults
  EXPECT_EQ(pts[6].height, 64);
  EXPECT_EQ(pts[6].raster, RasterOrder{});
  std::set<std::string> ids;
  for (const auto& p : pts) ids.insert(p.id);
  EXPECT_EQ(ids.size(), pts.size());
  // Run keys at their defaults leave the point ids as a spec without them has them.
  const auto id0 = [](const std::string& grid) {
    return sweep::expand(sweep::parse_spec(R"({"scenes": ["ground_plane"], "width": 64, "height": 48, "grid": {)" + grid + "}}",
                                           "s.json"))[0].id;
  };
  EXPECT_EQ(id0(R"("cache.ways": [4])"), id0(R"("cache.ways": [4], "raster": ["scanline"], "unit_tiles": ["round-robin:32"], "units": [1])"));
  EXPECT_NE(id0(R"("cache.ways": [4])"), id0(R"("cache.ways": [4], "raster": ["tiled:8"])"));
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "grid": {"raster": ["tiled:8", "tiled:08"]}})").find("grid.raster: value tiled:8 is listed twice"),
            std::string::npos);
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "grid": {"raster": ["tiled:7"]}})").find("grid.raster: raster order 'tiled:7'"),
            std::string::npos);
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "grid": {"width": [1]}})").find("grid.width: must be 0"), std::string::npos);
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "grid": {"units": [0]}})").find("grid.units: 0 is outside 1..256"), std::string::npos);
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "raster": 8, "grid": {"units": [1]}})").find("s.json: raster: values must be strings"),
            std::string::npos);
  // The layout of every texture, and the spawn point of level scenes only.
  const std::vector<sweep::Point> lay = sweep::expand(sweep::parse_spec(
      R"({"scenes": ["ground_plane"], "width": 64, "height": 48, "grid": {"texture_layout": ["own", "linear", "tiled"]}})", "s.json"));
  ASSERT_EQ(lay.size(), 3u);
  EXPECT_EQ(lay[1].texture_layout, "linear");
  EXPECT_EQ(lay[0].id, id0(R"("units": [1])"));
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "grid": {"texture_layout": ["swizzled"]}})").find("grid.texture_layout: unknown memory layout"),
            std::string::npos);
  EXPECT_NE(spec_error(R"({"scenes": ["ground_plane"], "grid": {"spawn": [1]}})").find("point 0: spawn applies to oa: level scenes, not to 'ground_plane'"),
            std::string::npos);
}

// TFU-S E10: the duplicate checks are a hash set. A duplicate at the far end of a long list is still
// found (the speed is shown by build/bin/tfu_bench_sweep, not timed here).
TEST(SweepSpec, DuplicatesAreFoundAtTheFarEndOfLongLists) {
  std::string values, scenes;
  for (int i = 0; i < 100000; ++i) values += fmt::format("{},", i);
  EXPECT_NE(spec_error(fmt::format(R"({{"scenes": ["ground_plane"], "grid": {{"memory.latency": [{}7]}}}})", values))
                .find("s.json: grid.memory.latency: value 7 is listed twice"),
            std::string::npos);
  const sweep::Spec ok = sweep::parse_spec(
      fmt::format(R"({{"scenes": ["ground_plane"], "grid": {{"memory.latency": [{}100000]}}}})", values), "s.json");
  EXPECT_EQ(ok.grid_values.at(0).size(), 100001u);
  for (int i = 0; i < 30000; ++i) scenes += fmt::format("\"s{}.json\",", i);
  EXPECT_NE(spec_error(fmt::format(R"({{"scenes": [{}"s29999.json"], "grid": {{"cache.ways": [1]}}}})", scenes))
                .find("s.json: scenes: 's29999.json' is listed twice"),
            std::string::npos);
}

TEST(Provenance, Fnv1a64ContinuesOverBlocks) {
  EXPECT_EQ(fnv1a64_update(fnv1a64("ab"), "cde"), fnv1a64("abcde"));
  EXPECT_EQ(fnv1a64_update(fnv1a64("abcde"), ""), fnv1a64("abcde"));
}

// TFU-S E5: every file a sweep reads goes through the input checks: a FIFO is refused without
// waiting for a writer, /dev/zero behind a link is refused without reading it.
TEST(SweepInputs, EveryFileTheSweepReadsIsCheckedFirst) {
  const TempDir tmp("tfu-test-sweep-inputs");
  const fs::path fifo = tmp.path() / "fifo.json", zero = tmp.path() / "zero.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", zero);
  const auto error = [](auto&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error([&] { (void)sweep::load_spec(fifo.string()); }).find("sweep spec '" + fifo.string() + "': is a named pipe"),
            std::string::npos);
  EXPECT_NE(error([&] { (void)sweep::load_spec(zero.string()); }).find("is a character device, not a regular file"),
            std::string::npos);
  // the sweep directory's record
  const fs::path dir = tmp.path() / "sw";
  fs::create_directories(dir / "points");
  ASSERT_EQ(::mkfifo((dir / "sweep.json").c_str(), 0600), 0);
  EXPECT_NE(error([&] { (void)sweep::load_sweep_dir(dir.string()); }).find("sweep record '"), std::string::npos);
  // a point's file, on resume and --collect
  const sweep::Spec spec = sweep::parse_spec(R"({"scenes": ["ground_plane"], "grid": {"cache.ways": [1]}})", "s.json");
  const std::vector<sweep::Point> pts = sweep::expand(spec);
  fs::create_symlink("/dev/zero", sweep::point_path(dir.string(), pts[0]));
  const std::string e = error([&] { (void)sweep::read_point_files(dir.string(), pts); });
  EXPECT_EQ(e.find("point file '" + sweep::point_path(dir.string(), pts[0]) + "': is a character device"), 0u) << e;
}

// TFU-S E6: a point file marked complete is checked before it is read: one line naming the file and the
// key (it was nlohmann's out_of_range or type_error, exit 3). A file not marked complete runs again.
TEST(SweepInputs, APointFileMarkedCompleteIsCheckedLikeASpec) {
  const TempDir tmp("tfu-test-sweep-points");
  const std::string dir = tmp.path().string();
  fs::create_directories(tmp.path() / "points");
  const sweep::Spec spec = sweep::parse_spec(R"({"scenes": ["ground_plane"], "grid": {"cache.ways": [1]}})", "s.json");
  const std::vector<sweep::Point> pts = sweep::expand(spec);
  const sweep::Point& p = pts.at(0);
  const std::string path = sweep::point_path(dir, p);
  nlohmann::json result;
  for (const sweep::Column& c : sweep::result_columns()) {
    if (c.type == sweep::ResultType::Number) result[c.name] = 1.5;
    if (c.type == sweep::ResultType::NumberOrInf) result[c.name] = "inf";
    if (c.type == sweep::ResultType::Bool) result[c.name] = true;
    if (c.type == sweep::ResultType::NumberOrNull) result[c.name] = nullptr;
  }
  const nlohmann::json good = {{"complete", true}, {"point", {{"id", p.id}}}, {"result", result}};
  const auto read_with = [&](const nlohmann::json& doc) -> std::string {
    std::ofstream(path, std::ios::trunc) << (doc.is_string() ? doc.get<std::string>() : doc.dump());
    try {
      return sweep::read_point_file(dir, p) ? "done" : "not done";
    } catch (const InputError& e) {
      return e.what();
    }
  };
  EXPECT_EQ(read_with(good), "done");
  EXPECT_EQ(read_with(std::string("{\"complete\": tr")), "not done");  // a write cut short
  nlohmann::json doc = good;
  doc["complete"] = false;
  EXPECT_EQ(read_with(doc), "not done");
  const std::string label = "point file '" + path + "': ";
  const auto refused = [&](nlohmann::json d, const std::string& key_and_why) {
    const std::string e = read_with(d);
    EXPECT_EQ(e.find(label + key_and_why), 0u) << e;
  };
  doc = good;
  doc["complete"] = "yes";
  refused(doc, "complete: must be true or false");
  doc = good;
  doc.erase("result");
  refused(doc, "result: missing or not an object");
  doc = good;
  doc["result"]["golden_equal"] = "yes";
  refused(doc, "result.golden_equal: must be true or false");
  doc = good;
  doc["result"]["psnr"] = "high";
  refused(doc, "result.psnr: must be a number or \"inf\"");
  doc = good;
  doc["result"].erase("cycles");
  refused(doc, "result.cycles: missing");
  doc = good;
  doc["result"]["hit_rate"] = true;
  refused(doc, "result.hit_rate: must be a number");
  doc = good;
  doc.erase("result");
  doc["error"] = 5;
  refused(doc, "error: must be a one-line string");
  doc["error"] = "two\nlines";
  refused(doc, "error: must be a one-line string");
  doc["error"] = "the point's configuration is refused";
  EXPECT_EQ(read_with(doc), "done");
  doc = good;
  doc["point"]["id"] = "0123";
  refused(doc, "point.id: '0123' is not this point's id");
  doc = good;
  doc.erase("point");
  refused(doc, "point: missing or not an object");
  // and the reports read what was checked
  std::ofstream(path, std::ios::trunc) << good.dump();
  const std::vector<nlohmann::json> files = sweep::read_point_files(dir, {p});
  // psnr, ssim, psnr_surface, psnr_interior, golden_equal
  EXPECT_NE(sweep::results_csv(spec, {p}, files).find(",inf,1.500000,inf,inf,true,"), std::string::npos);
}

// tfu ignores SIGPIPE (sim/tfu/main.cpp, TFU-S E15); a child it runs (the plot script, sbatch) starts
// with the default disposition, as from a shell: its SigIgn mask has no bit 13 (0x1000).
TEST(Process, AChildStartsWithSigpipeAtItsDefault) {
  const auto old = std::signal(SIGPIPE, SIG_IGN);
  const sweep::ProcessResult r = sweep::run_process({"/bin/sh", "-c", "grep '^SigIgn' /proc/self/status"});
  std::signal(SIGPIPE, old);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string mask = r.out.substr(r.out.find_first_of("0123456789abcdef", 7));
  EXPECT_EQ(std::stoull(mask, nullptr, 16) & 0x1000u, 0u) << r.out;
  // failure_line: a traceback is named by its exception
  EXPECT_EQ(sweep::failure_line("Traceback (most recent call last):\n  File \"x\", line 1\nValueError: bad\n\n"), "ValueError: bad");
  EXPECT_EQ(sweep::failure_line("\nplot: error: --csv 'a': no rows\nmore\n"), "plot: error: --csv 'a': no rows");
}

// ---- the local runner ----

TEST(SweepRun, ResultsIndependentOfWorkersAndResumable) {
  const std::string text = R"({"scenes": ["ground_plane"], "filters": ["LINEAR", "EDGE_PRESERVING"], "width": 32, "height": 24,
                               "grid": {"cache.capacity_bytes": [2048, 8192]}})";
  const fs::path root = fs::temp_directory_path() / fmt::format("tfu-test-sweep-{}", ::getpid());
  fs::remove_all(root);
  fs::create_directories(root);
  {
    std::ofstream(root / "spec.json") << text;
  }
  const sweep::Spec spec = sweep::load_spec((root / "spec.json").string());
  const std::vector<sweep::Point> pts = sweep::expand(spec);
  ASSERT_EQ(pts.size(), 4u);
  std::vector<std::string> csv;
  for (int workers : {1, 3}) {
    const std::string dir = (root / fmt::format("w{}", workers)).string();
    sweep::prepare_sweep_dir(dir, spec, false);
    const sweep::RunSummary s = sweep::run_points(spec, pts, dir, {workers, 0, 1, false});
    EXPECT_EQ(s.ran, 4u);
    const auto files = sweep::read_point_files(dir, pts);
    EXPECT_EQ(sweep::failed_points(files), 0u);
    csv.push_back(sweep::results_csv(spec, pts, files));
    // resume: nothing left to run
    const sweep::RunSummary again = sweep::run_points(spec, pts, dir, {workers, 0, 1, false});
    EXPECT_EQ(again.ran, 0u);
    EXPECT_EQ(again.skipped, 4u);
  }
  EXPECT_EQ(csv[0], csv[1]);
  // array tasks: two shares make the whole
  const std::string dir = (root / "tasks").string();
  sweep::prepare_sweep_dir(dir, spec, false);
  EXPECT_EQ(sweep::run_points(spec, pts, dir, {1, 0, 2, false}).ran, 2u);
  EXPECT_THROW((void)sweep::read_point_files(dir, pts), CheckFailed);
  EXPECT_EQ(sweep::run_points(spec, pts, dir, {1, 1, 2, false}).ran, 2u);
  EXPECT_EQ(sweep::results_csv(spec, pts, sweep::read_point_files(dir, pts)), csv[0]);
  // the header and a row, as the issue lists the columns
  const std::string header = csv[0].substr(0, csv[0].find('\n'));
  for (const char* c : {"cache.capacity_bytes", "scene", "filter", "cycles", "pixels_per_clock", "hit_rate", "bytes_per_pixel",
                        "stall_cache_miss", "stall_bank_conflict", "stall_backpressure", "psnr", "ssim", "golden_equal", "sram_bits",
                        "filter_gates", "logic_um2", "sram_um2", "area_mm2", "fmax_mhz", "energy_pj_per_pixel"})
    EXPECT_NE(header.find(c), std::string::npos) << c;
  EXPECT_NE(csv[0].find(",ground_plane,EDGE_PRESERVING,"), std::string::npos);
  // a bigger cache never reads more memory bytes here (same requests, LRU)
  const nlohmann::json small = nlohmann::json::parse(read_text(sweep::point_path((root / "w1").string(), pts[0])));
  const nlohmann::json big = nlohmann::json::parse(read_text(sweep::point_path((root / "w1").string(), pts[1])));
  EXPECT_LE(big.at("result").at("memory_bytes").get<uint64_t>(), small.at("result").at("memory_bytes").get<uint64_t>());
  EXPECT_EQ(small.at("result").at("sram_bits").get<uint64_t>(),
            rtl::texel_cache_sram_bits(pts[0].config.cache).total());
  // the whole unit at the default node (osu018): numbers, the area the sum of its parts, the clock a table block's
  const nlohmann::json& sr = small.at("result");
  EXPECT_EQ(sr.at("node"), "osu018");
  for (const char* c : {"logic_um2", "sram_um2", "area_mm2", "fmax_mhz", "energy_pj_per_pixel"}) EXPECT_TRUE(sr.at(c).is_number()) << c;
  EXPECT_NEAR(sr.at("area_mm2").get<double>(), (sr.at("logic_um2").get<double>() + sr.at("sram_um2").get<double>()) * 1e-6, 1e-9);
  EXPECT_GT(sr.at("energy_pj_per_pixel").get<double>(), 0.0);
  const double ssim = small.at("result").at("ssim").get<double>();  // of the same image as psnr: below 1 when psnr is finite
  EXPECT_GT(ssim, 0.0);
  EXPECT_LT(ssim, 1.0);
  EXPECT_EQ(small.at("provenance").at("command"), "sweep");
  EXPECT_EQ(small.at("provenance").at("engine"), "recurrence");  // a sweep runs the recurrences
  fs::remove_all(root);
}

// The points of a cache grid share one golden render (same scene, size, sampler keys, filter and
// line), equal to the render tfu sim makes; it is dropped after the last planned point.
TEST(SweepRun, PointsOfACacheGridShareOneRenderDroppedAfterTheLast) {
  const fs::path root = fs::temp_directory_path() / fmt::format("tfu-test-sweep-share-{}", ::getpid());
  fs::create_directories(root);
  {
    std::ofstream(root / "spec.json")
        << R"({"scenes": ["ground_plane"], "filters": ["LINEAR"], "width": 32, "height": 24,
               "grid": {"cache.capacity_bytes": [2048, 8192], "cache.line_bytes": [64, 256]}})";
  }
  const sweep::Spec spec = sweep::load_spec((root / "spec.json").string());
  fs::remove_all(root);
  const std::vector<sweep::Point> pts = sweep::expand(spec);
  ASSERT_EQ(pts.size(), 4u);
  std::vector<const sweep::Point*> todo;
  for (const sweep::Point& p : pts) todo.push_back(&p);
  sweep::SceneCache cache;
  cache.plan(spec, todo);
  std::vector<std::shared_ptr<const RenderResult>> r;
  for (const sweep::Point& p : pts) r.push_back(cache.render(spec, p));
  std::set<const RenderResult*> distinct;
  for (const auto& x : r) distinct.insert(x.get());
  EXPECT_EQ(distinct.size(), 2u);  // one per line size
  for (size_t i = 0; i < pts.size(); ++i)
    for (size_t j = 0; j < pts.size(); ++j)
      EXPECT_EQ(r[i] == r[j], pts[i].config.cache.line_bytes == pts[j].config.cache.line_bytes) << i << " " << j;
  // the same trace and image as a render of its own
  Scene scene = load_scene("ground_plane");
  scene.width = 32;
  scene.height = 24;
  RenderOptions ro;
  ro.trace = true;
  ro.threads = 1;
  ro.line_bytes = pts[0].config.cache.line_bytes;
  ro.filter = filter_mode_from_name("LINEAR");
  const RenderResult own = render_scene(scene, ro);
  EXPECT_EQ(own.image.texels, r[0]->image.texels);
  ASSERT_EQ(own.trace.requests.size(), r[0]->trace.requests.size());
  // dropped when the last point that planned it is done
  const std::weak_ptr<const RenderResult> first = r[0];
  r.clear();
  size_t sharing = 0;
  for (const sweep::Point& p : pts) sharing += p.config.cache.line_bytes == pts[0].config.cache.line_bytes;
  ASSERT_EQ(sharing, 2u);
  bool released_one = false;
  for (const sweep::Point& p : pts) {
    if (p.config.cache.line_bytes != pts[0].config.cache.line_bytes) continue;
    EXPECT_FALSE(first.expired());
    cache.done_with_render(spec, p);
    released_one = true;
  }
  EXPECT_TRUE(released_one);
  EXPECT_TRUE(first.expired());
}

}  // namespace
}  // namespace tfu
