// The raster order and the distribution of screen tiles over units (cmodel/raster_order.hpp,
// docs/renderer.md "Raster order"): hand-checked quad sequences on an 8x8 screen, the same pixels and
// the same request multiset in every order, screen positions in traces, and the cycle model equal
// to the golden model in every order and distribution.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <sstream>
#include <tuple>
#include <utility>
#include <vector>

#include "cmodel/error.hpp"
#include "cmodel/raster.hpp"
#include "cmodel/raster_order.hpp"
#include "cmodel/scene.hpp"
#include "cmodel/trace.hpp"
#include "rtl/scene_sim.hpp"
#include "rtl/unit_stats.hpp"

namespace tfu {
namespace {

using XY = std::pair<int, int>;

// The positions of `quads` in the sequence raster_sequence gives for `order`.
std::vector<XY> sequence(const char* order, const std::vector<QuadPlace>& quads) {
  std::vector<XY> out;
  for (size_t i : raster_sequence(raster_order_from_name(order), quads)) out.emplace_back(quads[i].x, quads[i].y);
  return out;
}

// Quads of one triangle in scanline order (row by row) covering a w x h screen.
std::vector<QuadPlace> full_screen(int w, int h) {
  std::vector<QuadPlace> q;
  for (int y = 0; y < h; y += 2)
    for (int x = 0; x < w; x += 2) q.push_back({0, x, y});
  return q;
}

TEST(RasterOrder, NamesReadAndPrint) {
  for (const char* n : {"scanline", "tiled:2", "tiled:6", "tiled:8", "tiled:256", "morton:4", "morton:16"})
    EXPECT_EQ(raster_order_name(raster_order_from_name(n)), n);
  EXPECT_EQ(raster_order_from_name("tiled:8"), (RasterOrder{RasterTraversal::Tiled, 8}));
  const auto error = [](const char* n) {
    try {
      raster_order_from_name(n);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(error("zigzag:8").find("unknown raster order 'zigzag' ("), std::string::npos);
  EXPECT_NE(error("zigzag:8").find("expected scanline, tiled or morton)"), std::string::npos);
  EXPECT_EQ(error("tiled"), "raster order 'tiled': tiled needs a tile size, e.g. tiled:8");
  EXPECT_EQ(error("tiled:7"), "raster order 'tiled:7': the tile size must be even (whole 2x2 quads)");
  EXPECT_EQ(error("morton:12"), "raster order 'morton:12': a Morton tile size must be a power of two");
  EXPECT_EQ(error("scanline:4"), "raster order 'scanline:4': scanline takes no tile size");
  EXPECT_EQ(error("tiled:512"), "raster order 'tiled:512': the tile size after ':' must be an integer 2..256");
  EXPECT_EQ(error("tiled:x"), "raster order 'tiled:x': the tile size after ':' must be an integer 2..256");
  EXPECT_EQ(unit_tiles_name(unit_tiles_from_name("bands")), "bands:32");
  EXPECT_EQ(unit_tiles_from_name("round-robin:16"), (UnitTiles{UnitDistribution::RoundRobin, 16}));
  EXPECT_THROW(unit_tiles_from_name("round-robin:5"), InputError);
  EXPECT_THROW(unit_tiles_from_name("stripes:8"), InputError);
}

TEST(RasterOrder, HandCheckedSequencesOnAnEightByEightScreen) {
  const std::vector<QuadPlace> one = full_screen(8, 8);
  // scanline and tiled:8 (one tile): row by row.
  const std::vector<XY> rows{{0, 0}, {2, 0}, {4, 0}, {6, 0}, {0, 2}, {2, 2}, {4, 2}, {6, 2},
                             {0, 4}, {2, 4}, {4, 4}, {6, 4}, {0, 6}, {2, 6}, {4, 6}, {6, 6}};
  EXPECT_EQ(sequence("scanline", one), rows);
  EXPECT_EQ(sequence("tiled:8", one), rows);
  // tiled:4: four tiles in row order, 2x2 quads each row by row.
  const std::vector<XY> tiles4{{0, 0}, {2, 0}, {0, 2}, {2, 2}, {4, 0}, {6, 0}, {4, 2}, {6, 2},
                               {0, 4}, {2, 4}, {0, 6}, {2, 6}, {4, 4}, {6, 4}, {4, 6}, {6, 6}};
  EXPECT_EQ(sequence("tiled:4", one), tiles4);
  // morton:8: Z order of the 4x4 quads, which visits the 2x2 blocks as tiled:4 does.
  EXPECT_EQ(sequence("morton:8", one), tiles4);
  EXPECT_EQ(sequence("morton:4", one), tiles4);
  // Morton ranks: x bit 0, y bit 0, x bit 1, ...: (3, 5) = x 011, y 101 -> 1 + 2 + 4 + 32.
  EXPECT_EQ(quad_rank_in_tile(raster_order_from_name("morton:16"), 3, 5), 39u);
  EXPECT_EQ(quad_rank_in_tile(raster_order_from_name("tiled:16"), 3, 5), 43u);  // 5 rows of 8 quads + 3
  // morton:16 on a 16x4 screen: the second 2x2 block of quads comes before the second quad row.
  // clang-format off
  EXPECT_EQ(sequence("morton:16", full_screen(16, 4)),
            (std::vector<XY>{{0, 0}, {2, 0}, {0, 2}, {2, 2}, {4, 0}, {6, 0}, {4, 2}, {6, 2},
                             {8, 0}, {10, 0}, {8, 2}, {10, 2}, {12, 0}, {14, 0}, {12, 2}, {14, 2}}));
  // clang-format on

  // Two triangles: 0 covers the quads with qx + qy <= 3, 1 those with qx + qy >= 3 (the anti-diagonal
  // quads are shaded by both), recorded in scanline order (one band: triangle 0, then 1).
  std::vector<QuadPlace> two;
  for (uint32_t tri : {0u, 1u})
    for (int qy = 0; qy < 4; ++qy)
      for (int qx = 0; qx < 4; ++qx)
        if (tri == 0 ? qx + qy <= 3 : qx + qy >= 3) two.push_back({tri, 2 * qx, 2 * qy});
  // tiled:4, by hand: in each tile triangle 0's quads, then triangle 1's, each row by row.
  const std::vector<XY> want{{0, 0}, {2, 0}, {0, 2}, {2, 2},                       // tile (0,0): 0 only
                             {4, 0}, {6, 0}, {4, 2}, /**/ {6, 0}, {4, 2}, {6, 2},  // tile (1,0): 0, then 1
                             {0, 4}, {2, 4}, {0, 6}, /**/ {2, 4}, {0, 6}, {2, 6},  // tile (0,1)
                             {4, 4}, {6, 4}, {4, 6}, {6, 6}};                      // tile (1,1): 1 only
  EXPECT_EQ(sequence("tiled:4", two), want);
  EXPECT_EQ(sequence("morton:4", two), want);
  // Records of one quad (its stages) keep their order: tiled:2 puts each triangle's quad together.
  std::vector<QuadPlace> stages{{0, 2, 0}, {0, 2, 0}, {0, 0, 0}};
  EXPECT_EQ(raster_sequence(raster_order_from_name("tiled:2"), stages), (std::vector<size_t>{2, 0, 1}));
}

TEST(RasterOrder, UnitsTakeTilesRoundRobinOrInBands) {
  const UnitTiles rr{UnitDistribution::RoundRobin, 32}, bands{UnitDistribution::Bands, 32};
  // 100x70: 4 tile columns, 3 tile rows.
  EXPECT_EQ(unit_of_quad(rr, 3, 100, 70, 0, 0), 0);
  EXPECT_EQ(unit_of_quad(rr, 3, 100, 70, 32, 0), 1);
  EXPECT_EQ(unit_of_quad(rr, 3, 100, 70, 98, 30), 0);  // tile 3
  EXPECT_EQ(unit_of_quad(rr, 3, 100, 70, 0, 32), 1);   // tile 4
  EXPECT_EQ(unit_of_quad(bands, 3, 100, 70, 98, 0), 0);
  EXPECT_EQ(unit_of_quad(bands, 3, 100, 70, 0, 40), 1);
  EXPECT_EQ(unit_of_quad(bands, 3, 100, 70, 50, 68), 2);
  // 2 units over 3 tile rows: rows 0, 1 -> unit 0, row 2 -> unit 1.
  EXPECT_EQ(unit_of_quad(bands, 2, 100, 70, 0, 40), 0);
  EXPECT_EQ(unit_of_quad(bands, 2, 100, 70, 0, 64), 1);
  // 4 units over 3 tile rows: unit 3 gets nothing.
  EXPECT_EQ(unit_of_quad(bands, 4, 100, 70, 0, 64), 2);
}

struct Quad {
  int x, y, mesh, mask, stage;
  auto operator<=>(const Quad&) const = default;
};
using Request = std::tuple<uint16_t, uint8_t, uint8_t, uint16_t, uint16_t, uint32_t, uint32_t>;

Request key(const TraceRequest& r) {
  uint32_t s = 0, t = 0;
  std::memcpy(&s, &r.s, 4);
  std::memcpy(&t, &r.t, 4);
  return {r.texture, r.sampler, r.stage, r.x, r.y, s, t};
}

Scene sized(const char* name, int w, int h) {
  Scene s = load_scene(name);
  s.width = w;
  s.height = h;
  return s;
}

TEST(RasterOrder, EveryOrderDrawsTheSamePixelsAndTheSameRequests) {
  for (const char* name : {"object", "lightmapped"}) {
    const Scene scene = sized(name, 96, 72);
    RenderOptions o;
    o.trace = true;
    o.threads = 2;
    const RenderResult base = render_scene(scene, o);
    ASSERT_TRUE(base.trace.positions);
    std::vector<Request> base_requests;
    for (const TraceRequest& r : base.trace.requests) base_requests.push_back(key(r));
    const std::vector<Request> base_sequence = base_requests;
    std::sort(base_requests.begin(), base_requests.end());
    std::vector<Quad> base_quads;
    for (const QuadTarget& t : base.quad_targets) base_quads.push_back({t.x, t.y, t.mesh, t.mask, t.stage});
    std::sort(base_quads.begin(), base_quads.end());
    for (const char* order : {"tiled:2", "tiled:8", "tiled:24", "tiled:32", "morton:8", "morton:64"}) {
      o.raster = raster_order_from_name(order);
      const RenderResult r = render_scene(scene, o);
      EXPECT_EQ(r.image.texels, base.image.texels) << name << " " << order;
      ASSERT_EQ(r.trace.requests.size(), base.trace.requests.size()) << name << " " << order;
      std::vector<Request> req;
      for (const TraceRequest& q : r.trace.requests) req.push_back(key(q));
      EXPECT_NE(req, base_sequence) << name << " " << order << ": the order changes";
      std::sort(req.begin(), req.end());
      EXPECT_EQ(req, base_requests) << name << " " << order;
      std::vector<Quad> quads;
      for (const QuadTarget& t : r.quad_targets) quads.push_back({t.x, t.y, t.mesh, t.mask, t.stage});
      // Tiles in row order; a quad's stages in order; each target at its requests' position.
      const RasterOrder ro = o.raster;
      const int tiles_x = (scene.width + ro.tile - 1) / ro.tile;
      for (size_t i = 0; i < quads.size(); ++i) {
        EXPECT_EQ(r.trace.requests[i * 4].x, quads[i].x);
        EXPECT_EQ(r.trace.requests[i * 4 + 3].y, quads[i].y);
        if (i == 0) continue;
        const auto tile = [&](const Quad& q) { return (q.y / ro.tile) * tiles_x + q.x / ro.tile; };
        EXPECT_LE(tile(quads[i - 1]), tile(quads[i])) << name << " " << order << " quad " << i;
        if (quads[i].stage > 0) {
          EXPECT_EQ(quads[i - 1].stage + 1, quads[i].stage);
          EXPECT_EQ(std::tie(quads[i - 1].x, quads[i - 1].y), std::tie(quads[i].x, quads[i].y));
        }
      }
      std::sort(quads.begin(), quads.end());
      EXPECT_EQ(quads, base_quads) << name << " " << order;
      // The order does not depend on the thread count.
      RenderOptions one = o;
      one.threads = 1;
      const RenderResult r1 = render_scene(scene, one);
      std::vector<Request> req1;
      for (const TraceRequest& q : r1.trace.requests) req1.push_back(key(q));
      std::vector<Request> req2;
      for (const TraceRequest& q : r.trace.requests) req2.push_back(key(q));
      EXPECT_EQ(req1, req2) << name << " " << order;
    }
  }
}

TEST(RasterOrder, CycleModelEqualsGoldenInEveryOrderAndDistribution) {
  const Scene scene = sized("lightmapped", 96, 64);
  RenderOptions o;
  o.trace = true;
  o.threads = 2;
  for (const char* order : {"scanline", "tiled:8", "morton:16"}) {
    o.raster = raster_order_from_name(order);
    const RenderResult render = render_scene(scene, o);
    for (const char* tiles : {"round-robin:32", "bands:16"})
      for (int units : {1, 3}) {
        rtl::SceneSimOptions so;
        so.units = units;
        so.tiles = unit_tiles_from_name(tiles);
        const rtl::SceneSimResult res = rtl::simulate_scene(scene, render, rtl::UnitConfig{}, so);
        EXPECT_EQ(res.mismatch, "") << order << " " << tiles << " units " << units;
        EXPECT_EQ(res.image.texels, render.image.texels) << order << " " << tiles << " units " << units;
        EXPECT_EQ(res.requests, render.trace.requests.size());
      }
  }
}

TEST(RasterOrder, TracesRecordScreenPositions) {
  const Scene scene = sized("object", 64, 48);
  RenderOptions o;
  o.trace = true;
  const RenderResult r = render_scene(scene, o);
  std::ostringstream out;
  write_trace(out, r.trace);
  EXPECT_EQ(out.str().rfind("# tfu-trace mode=quad fields=texture,sampler,stage,x,y,s,t\n", 0), 0u);
  std::istringstream in(out.str());
  const Trace back = parse_trace(in, "r.trace");
  ASSERT_TRUE(back.positions);
  ASSERT_EQ(back.requests.size(), r.trace.requests.size());
  for (size_t i = 0; i < back.requests.size(); ++i) EXPECT_EQ(key(back.requests[i]), key(r.trace.requests[i]));
  // Old traces read unchanged, without positions.
  std::istringstream old(
      "# tfu-trace mode=quad fields=texture,sampler,stage,s,t\n0,0,0,0.5,0.5\n0,0,0,0.5,0.5\n"
      "0,0,0,0.5,0.5\n0,0,0,0.5,0.5\n");
  EXPECT_FALSE(parse_trace(old, "old.trace").positions);
  const auto error = [](const std::string& text) {
    std::istringstream e(text);
    try {
      parse_trace(e, "e.txt");
    } catch (const InputError& err) {
      return std::string(err.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(error("# tfu-trace mode=quad fields=x,s,t\n"), "e.txt:1: a screen position needs both fields 'x' and 'y'");
  EXPECT_EQ(error("# tfu-trace mode=lod fields=x,y,s,t,lod\n"),
            "e.txt:1: screen positions 'x', 'y' belong to quad traces, not to a lod trace");
  EXPECT_EQ(error("# tfu-trace mode=quad fields=x,y,s,t\n0,0,0,0\n2,0,0,0\n"),
            "e.txt:3: the four pixels of a quad name one screen position x, y");
  EXPECT_EQ(error("# tfu-trace mode=quad fields=x,y,s,t\n8192,0,0,0\n"),
            "e.txt:2: field 1 '8192' is not an integer 0..8191");

  // A loaded trace re-ordered: tiles in the render's order, the same requests.
  RenderOptions tiled = o;
  tiled.raster = raster_order_from_name("tiled:16");
  const RenderResult rt = render_scene(scene, tiled);
  const Trace re = reorder_trace(back, tiled.raster);
  ASSERT_EQ(re.requests.size(), rt.trace.requests.size());
  std::vector<Request> a, b;
  for (size_t i = 0; i < re.requests.size(); ++i) {
    const auto tile = [](const TraceRequest& q) { return (q.y / 16) * 4 + q.x / 16; };
    EXPECT_EQ(tile(re.requests[i]), tile(rt.trace.requests[i])) << i;
    a.push_back(key(re.requests[i]));
    b.push_back(key(rt.trace.requests[i]));
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  std::istringstream no_positions("0.5,0.5\n0.5,0.5\n0.5,0.5\n0.5,0.5\n");
  EXPECT_THROW(reorder_trace(parse_trace(no_positions, "p.trace"), tiled.raster), InputError);
}

TEST(RasterOrder, EveryTextureTakesALayout) {
  const Scene scene = sized("lightmapped", 64, 48);
  RenderOptions o;
  o.trace = true;
  o.threads = 2;
  const RenderResult own = render_scene(scene, o);
  std::vector<uint64_t> bytes;
  for (MemoryLayout layout : {MemoryLayout::Linear, MemoryLayout::Tiled}) {
    o.texture_layout = layout;
    const RenderResult r = render_scene(scene, o);
    EXPECT_EQ(r.image.texels, own.image.texels);
    ASSERT_EQ(r.frame->frame.regs.textures.size(), own.frame->frame.regs.textures.size());
    for (const TextureDescriptor& d : r.frame->frame.regs.textures) EXPECT_EQ(d.layout, layout);
    for (const auto& t : r.frame->frame.textures) EXPECT_EQ(t.spec.params.at("layout"), memory_layout_name(layout));
    const rtl::SceneSimResult res = rtl::simulate_scene(scene, r, rtl::UnitConfig{}, {});
    EXPECT_EQ(res.mismatch, "") << memory_layout_name(layout);
    EXPECT_EQ(res.image.texels, own.image.texels);
    bytes.push_back(rtl::counter(res.stats, rtl::UnitStat::MemoryBytes));
  }
  EXPECT_NE(bytes[0], bytes[1]);  // linear rows and one-line tiles fetch different lines
}

}  // namespace
}  // namespace tfu
