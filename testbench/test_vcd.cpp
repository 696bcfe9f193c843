// Waveforms (docs/cycle-model.md, "Statistics"): the kernel's clock and cycle window written out
// exactly, and the unit's dump with its clock, request ids, texel cache lines, unique names, one
// file per unit and the window.
#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cmodel/error.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/scene.hpp"
#include "rtl/scene_sim.hpp"
#include "sim/kernel/kernel.hpp"

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

}  // namespace
}  // namespace tfu
