// Waveforms (docs/cycle-model.md, "Statistics"): the kernel's clock and cycle window written out
// exactly, and the unit's dump with its clock, request ids, texel cache lines, unique names, one
// file per unit and the window.
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
#include "cmodel/procedural.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/tfu_unit.hpp"
#include "rtl/kernel/kernel.hpp"

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

}  // namespace
}  // namespace tfu
