// Waveforms (docs/cycle-model.md, "Waveforms"): the kernel's clock and cycle window written out
// exactly, and the unit's dump with its clock, request ids, texel cache lines, unique names, one
// file per unit and the window; the texture, stage, MIP level and screen position of requests and
// footprints; the signal selection (--vcd-signals).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cmodel/datapath.hpp"
#include "cmodel/error.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/mipmap.hpp"
#include "cmodel/procedural.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/kernel/kernel.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/tfu_unit.hpp"

namespace tfu {
namespace {

std::string body(const std::string& vcd) { return vcd.substr(vcd.find("$enddefinitions $end\n") + 21); }

TEST(Vcd, ClockAndWindowWrittenExactly) {
  std::ostringstream os;
  sim::VcdWriter vcd(os);
  uint64_t value = 0;
  vcd.add("top.v", 2, [&value] { return value; });
  vcd.add_clock("top.clk");
  vcd.set_window(1, 2);
  for (uint64_t c = 0; c < 5; ++c) {
    value = c;
    vcd.sample(c);
  }
  // ids: v is '!', the clock the next one '"'; cycle c at time 2c (clock high), 2c + 1 (low); the
  // first cycle of the window dumps every signal.
  EXPECT_NE(os.str().find("$scope module top $end\n$var wire 1 \" clk $end\n$var wire 2 ! v $end\n$upscope $end\n"),
            std::string::npos)
      << os.str();
  EXPECT_EQ(body(os.str()), "#2\n1\"\nb01 !\n#3\n0\"\n#4\n1\"\nb10 !\n#5\n0\"\n");
  EXPECT_THROW(vcd.set_window(3, 2), InputError);
}

// Every full signal path of a dump (scopes joined with '.').
std::vector<std::string> signal_paths(const std::string& vcd) {
  std::vector<std::string> scopes, paths;
  std::istringstream in(vcd);
  for (std::string line; std::getline(in, line) && line != "$enddefinitions $end";) {
    std::istringstream w(line);
    std::string tok, a, b, c, name;
    w >> tok;
    if (tok == "$scope") {
      w >> a >> name;
      scopes.push_back(name);
    } else if (tok == "$upscope") {
      scopes.pop_back();
    } else if (tok == "$var") {
      w >> a >> b >> c >> name;
      std::string p;
      for (const std::string& s : scopes) p += s + ".";
      paths.push_back(p + name);
    }
  }
  return paths;
}

TEST(Vcd, EveryUnitWithClockIdsLinesAndWindow) {
  Scene scene = load_scene("magnified");
  scene.width = 64;
  scene.height = 64;  // four 32x32 tiles: both units get quads
  RenderOptions ro;
  ro.trace = true;
  ro.threads = 1;
  ro.line_bytes = 64;
  const RenderResult render = render_scene(scene, ro);
  std::ostringstream u0, u1;
  rtl::SceneSimOptions so;
  so.units = 2;
  so.unit_vcds = {&u0, &u1};
  so.vcd_from = 50;
  so.vcd_to = 59;
  const rtl::SceneSimResult r = rtl::simulate_scene(scene, render, rtl::UnitConfig{}, so);
  ASSERT_TRUE(r.mismatch.empty());
  for (const std::ostringstream* os : {&u0, &u1}) {
    const std::string v = os->str();
    const std::vector<std::string> paths = signal_paths(v);
    const std::set<std::string> unique(paths.begin(), paths.end());
    EXPECT_EQ(unique.size(), paths.size()) << "two signals share a name";
    for (const char* p : {"tfu.clk", "tfu.quad.id", "tfu.pixel.id", "tfu.response.id", "tfu.texel_cache.accepted_id",
                          "tfu.texel_cache.accepted_line", "tfu.texel_cache.miss_line", "tfu.texel_cache.misses"})
      EXPECT_EQ(unique.count(p), 1u) << p;
    // exactly the ten cycles of the window, each at 2c and 2c + 1
    std::set<uint64_t> times;
    std::istringstream in(body(v));
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && line[0] == '#') times.insert(std::stoull(line.substr(1)));
    std::set<uint64_t> want;
    for (uint64_t t = 100; t < 120; ++t) want.insert(t);
    EXPECT_EQ(times, want);
  }
}

// The per-tap texel addresses: a LINEAR (no MIP-map, repeat) run on a 16x16 texture; for every
// request, the four accepted_tap_addr values the waveform shows for its footprint are the
// descriptor's byte addresses of the taps (i0, j0), (i0 + 1, j0), (i0, j0 + 1), (i0 + 1, j0 + 1)
// that the golden address generator (dp::texel_coord) gives for its (s, t), and the rest are 0.
TEST(Vcd, TapAddressesAreTheFootprintsTexelAddresses) {
  const Scene scene = [] {
    Scene sc = load_scene("magnified");
    sc.width = 16;
    sc.height = 16;
    return sc;
  }();
  RenderOptions ro;
  ro.trace = true;
  ro.threads = 1;
  Trace tr = render_scene(scene, ro).trace;
  ASSERT_GT(tr.requests.size(), 100u);
  const rtl::UnitConfig u;
  FrameBuilder b(u.cache.line_bytes);
  b.add_texture(std::make_shared<const Texture>(make_checkerboard(16, 4).texture), {"test", {}});
  SamplerDescriptor smp;
  smp.mode = FilterMode{BaseFilter::Linear, MipMode::None};
  smp.wrap_s = smp.wrap_t = WrapMode::Repeat;
  b.add_sampler(smp);
  for (TraceRequest& r : tr.requests) r.texture = r.sampler = 0;
  bind_requests(b, tr);
  const Frame frame = b.finish();
  std::ostringstream os;
  const rtl::UnitOutput out = rtl::run_unit(frame, tr, u, rtl::VcdOptions{&os});
  ASSERT_EQ(out.pixels.size(), tr.requests.size());

  // Signal codes, then the values in effect at each cycle (time 2c); per accepted id, the taps.
  const std::string v = os.str();
  std::map<std::string, std::string> name_of;  // code -> name
  {
    std::istringstream in(v);
    for (std::string line; std::getline(in, line) && line != "$enddefinitions $end";) {
      std::istringstream w(line);
      std::string tok, type, width, code, name;
      if (w >> tok && tok == "$var" && w >> type >> width >> code >> name) name_of[code] = name;
    }
  }
  std::map<std::string, uint64_t> now;  // name -> value
  std::map<uint64_t, std::array<uint64_t, 17>> seen;  // accepted id -> taps, then 16 addresses
  const auto snapshot = [&] {
    if (!now.count("accepted_id")) return;
    std::array<uint64_t, 17>& a = seen[now["accepted_id"]];
    a[0] = now["accepted_taps"];
    for (int k = 0; k < 16; ++k) a[static_cast<size_t>(k + 1)] = now[fmt::format("accepted_tap_addr_{:02}", k)];
  };
  std::istringstream in(body(v));
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    if (line[0] == '#') {
      snapshot();  // the values of the cycle just ended
    } else if (line[0] == 'b') {
      const size_t sp = line.find(' ');
      now[name_of[line.substr(sp + 1)]] = std::stoull(line.substr(1, sp - 1), nullptr, 2);
    }
  }
  snapshot();
  const TextureDescriptor& d = frame.regs.textures[0];
  for (size_t id = 0; id < tr.requests.size(); ++id) {
    ASSERT_TRUE(seen.count(id)) << "request " << id << " never accepted";
    const std::array<uint64_t, 17>& a = seen[id];
    const dp::LevelCoord cu = dp::texel_coord(tr.requests[id].s, 16), cv = dp::texel_coord(tr.requests[id].t, 16);
    const auto wrap = [](int64_t i) { return static_cast<int>(i & 15); };
    const std::array<uint64_t, 4> want{d.texel_address(0, wrap(cu.i0), wrap(cv.i0)), d.texel_address(0, wrap(cu.i0 + 1), wrap(cv.i0)),
                                       d.texel_address(0, wrap(cu.i0), wrap(cv.i0 + 1)),
                                       d.texel_address(0, wrap(cu.i0 + 1), wrap(cv.i0 + 1))};
    ASSERT_EQ(a[0], 4u) << "request " << id;
    for (size_t k = 0; k < 4; ++k) ASSERT_EQ(a[k + 1], want[k]) << "request " << id << " tap " << k;
    for (size_t k = 4; k < 16; ++k) ASSERT_EQ(a[k + 1], 0u) << "request " << id << " tap " << k;
  }
}

// The values of every signal at each dumped cycle (time 2c), by signal name (the full path).
std::vector<std::map<std::string, uint64_t>> cycle_values(const std::string& v) {
  std::map<std::string, std::string> path_of;  // code -> path
  {
    std::vector<std::string> scopes;
    std::istringstream in(v);
    for (std::string line; std::getline(in, line) && line != "$enddefinitions $end";) {
      std::istringstream w(line);
      std::string tok, type, width, code, name;
      w >> tok;
      if (tok == "$scope") {
        w >> type >> name;
        scopes.push_back(name);
      } else if (tok == "$upscope") {
        scopes.pop_back();
      } else if (tok == "$var" && w >> type >> width >> code >> name) {
        std::string p;
        for (const std::string& sc : scopes) p += sc + ".";
        path_of[code] = p + name;
      }
    }
  }
  std::vector<std::map<std::string, uint64_t>> cycles;
  std::map<std::string, uint64_t> now;
  std::istringstream in(body(v));
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    if (line[0] == '#') {
      if (std::stoull(line.substr(1)) % 2 == 1) cycles.push_back(now);  // the clock falls: cycle complete
    } else if (line[0] == 'b') {
      const size_t sp = line.find(' ');
      now[path_of.at(line.substr(sp + 1))] = std::stoull(line.substr(1, sp - 1), nullptr, 2);
    } else {
      now[path_of.at(line.substr(1))] = static_cast<uint64_t>(line[0] - '0');
    }
  }
  return cycles;
}

// A hand-checked trace for the request and footprint signals: eight lod-mode requests alternating
// between a base stage (texture 0, 16x16 with its MIP levels, NEAREST_MIPMAP_NEAREST at lod 1 or 2:
// GL's nearest level, 1 or 2) and a light-map stage (texture 1, 4x4, LINEAR without MIP-map: level
// 0), request i at screen position (10 + i, 20 + 2i).
struct TaggedTrace {
  Frame frame;
  Trace trace;
  std::vector<rtl::ScreenPosition> positions;
  static int texture(size_t i) { return static_cast<int>(i % 2); }
  static int level(size_t i) { return i % 2 == 1 ? 0 : (i % 4 == 0 ? 1 : 2); }
};
TaggedTrace tagged_trace() {
  TaggedTrace t;
  FrameBuilder b(64);
  Texture base = make_checkerboard(16, 4).texture;
  generate_mipmaps(base, MipMethod::Box);
  b.add_texture(std::make_shared<const Texture>(std::move(base)), {"base", {}});
  b.add_texture(std::make_shared<const Texture>(make_checkerboard(4, 1).texture), {"lightmap", {}});
  SamplerDescriptor nearest, linear;
  nearest.mode = FilterMode{BaseFilter::Nearest, MipMode::Nearest};
  linear.mode = FilterMode{BaseFilter::Linear, MipMode::None};
  b.add_sampler(nearest);
  b.add_sampler(linear);
  t.trace.mode = TraceMode::Lod;
  for (size_t i = 0; i < 8; ++i) {
    TraceRequest r;
    r.texture = r.sampler = r.stage = static_cast<uint8_t>(TaggedTrace::texture(i));
    r.s = 0.1f + 0.1f * static_cast<float>(i);
    r.t = 0.3f;
    r.lod = static_cast<float>(TaggedTrace::level(i));
    t.trace.requests.push_back(r);
    t.positions.push_back({static_cast<uint16_t>(10 + i), static_cast<uint16_t>(20 + 2 * i)});
  }
  bind_requests(b, t.trace);
  t.frame = b.finish();
  return t;
}

// The request signals at the pixel channel's head, the footprint signals at the footprint
// channel's head and those of the texel cache's last accepted footprint carry the texture, stage,
// MIP level and screen position of their request id, for every request.
TEST(Vcd, RequestAndFootprintSignalsCarryTextureStageLevelAndPosition) {
  const TaggedTrace t = tagged_trace();
  std::ostringstream os;
  rtl::VcdOptions vo;
  vo.out = &os;
  vo.positions = &t.positions;
  const rtl::UnitOutput out = rtl::run_unit(t.frame, t.trace, rtl::UnitConfig{}, vo);
  ASSERT_EQ(out.pixels.size(), 8u);
  std::set<uint64_t> at_pixel, at_footprint, accepted;
  for (const std::map<std::string, uint64_t>& c : cycle_values(os.str())) {
    const auto expect_tag = [&c](const std::string& at, const std::string& id_name, bool has_level) {
      const uint64_t id = c.at(id_name);
      EXPECT_EQ(c.at(at + "texture"), static_cast<uint64_t>(TaggedTrace::texture(id))) << at << " id " << id;
      EXPECT_EQ(c.at(at + "stage"), static_cast<uint64_t>(TaggedTrace::texture(id))) << at << " id " << id;
      EXPECT_EQ(c.at(at + "x"), 10 + id) << at << " id " << id;
      EXPECT_EQ(c.at(at + "y"), 20 + 2 * id) << at << " id " << id;
      if (has_level) {
        EXPECT_EQ(c.at(at + "level"), static_cast<uint64_t>(TaggedTrace::level(id))) << at << " id " << id;
      }
      return id;
    };
    if (c.at("tfu.pixel.valid")) at_pixel.insert(expect_tag("tfu.pixel.", "tfu.pixel.id", false));
    if (c.at("tfu.footprint.valid")) at_footprint.insert(expect_tag("tfu.footprint.", "tfu.footprint.id", true));
    if (c.at("tfu.texel_cache.accepted_taps") > 0)
      accepted.insert(expect_tag("tfu.texel_cache.accepted_", "tfu.texel_cache.accepted_id", true));
  }
  const std::set<uint64_t> all{0, 1, 2, 3, 4, 5, 6, 7};
  EXPECT_EQ(at_pixel, all);
  EXPECT_EQ(at_footprint, all);
  EXPECT_EQ(accepted, all);
}

// --vcd-signals: a selection keeps exactly the signals it names (and the clock) with the same
// values, in a smaller file; a pattern that selects nothing is one line naming it, before the run.
TEST(Vcd, SignalSelectionKeepsExactlyTheSelectedSignals) {
  EXPECT_TRUE(sim::VcdWriter::selects("tfu.texel_cache", "tfu.texel_cache.id"));
  EXPECT_FALSE(sim::VcdWriter::selects("tfu.texel", "tfu.texel_cache.id"));
  EXPECT_TRUE(sim::VcdWriter::selects("tfu.*.valid", "tfu.quad.valid"));
  EXPECT_TRUE(sim::VcdWriter::selects("*_tap_addr_1?", "tfu.texel_cache.accepted_tap_addr_15"));
  EXPECT_FALSE(sim::VcdWriter::selects("tfu.pixel.x", "tfu.pixel.xy"));
  const TaggedTrace t = tagged_trace();
  std::ostringstream full, some;
  rtl::VcdOptions vo;
  vo.out = &full;
  vo.positions = &t.positions;
  rtl::run_unit(t.frame, t.trace, rtl::UnitConfig{}, vo);
  vo.out = &some;
  vo.signals = {"tfu.pixel", "tfu.texel_cache.accepted_l*"};
  rtl::run_unit(t.frame, t.trace, rtl::UnitConfig{}, vo);
  const std::vector<std::string> paths = signal_paths(some.str());
  EXPECT_EQ(std::set<std::string>(paths.begin(), paths.end()),
            (std::set<std::string>{"tfu.clk", "tfu.pixel.valid", "tfu.pixel.ready", "tfu.pixel.count", "tfu.pixel.id",
                                   "tfu.pixel.texture", "tfu.pixel.stage", "tfu.pixel.x", "tfu.pixel.y",
                                   "tfu.texel_cache.accepted_level", "tfu.texel_cache.accepted_line"}));
  EXPECT_LT(some.str().size() * 3, full.str().size());
  const std::vector<std::map<std::string, uint64_t>> a = cycle_values(full.str()), b = cycle_values(some.str());
  ASSERT_EQ(a.size(), b.size());
  for (size_t c = 0; c < a.size(); ++c)
    for (const auto& [name, v] : b[c]) EXPECT_EQ(v, a[c].at(name)) << name << " cycle " << c;
  std::ostringstream none;
  vo.out = &none;
  vo.signals = {"tfu.pixel", "tfu.pixl.texture"};
  try {
    rtl::run_unit(t.frame, t.trace, rtl::UnitConfig{}, vo);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    EXPECT_EQ(m.rfind("--vcd-signals: 'tfu.pixl.texture' selects no signal (did you mean 'tfu.pixel.texture'?", 0), 0u)
        << m;
  }
  EXPECT_EQ(none.str(), "");  // refused before the first cycle
}

}  // namespace
}  // namespace tfu
