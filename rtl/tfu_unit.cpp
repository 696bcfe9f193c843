#include "rtl/tfu_unit.hpp"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "cmodel/datapath.hpp"
#include "cmodel/error.hpp"
#include "cmodel/lod.hpp"

namespace tfu::rtl {
namespace {

struct QuadReq {
  uint32_t id = 0;  // index of the quad's first pixel in the trace
  std::array<float, 4> s{}, t{};
};
struct PixelReq {
  uint32_t id = 0;
  float s = 0, t = 0;
  int32_t lambda = 0;
};
struct Tap {
  int x = 0, y = 0;
  bool border = false;  // outside the texture with clamp-to-border: the border word, no cache access
};
struct FootprintReq {
  uint32_t id = 0;
  int level = 0, ntaps = 0;
  std::array<Tap, 4> taps{};
  uint32_t fu = 0, fv = 0;
  int blend = 0;
  bool two = false, second = false;
};
struct FilterReq {
  uint32_t id = 0;
  int ntaps = 0;
  std::array<Rgba8, 4> texels{};
  uint32_t fu = 0, fv = 0;
  int blend = 0;
  bool two = false, second = false;
};
struct Response {
  uint32_t id = 0;
  Rgba8 rgba{};
};

using sim::Channel;
using sim::Module;
using sim::Simulator;

// request_fifo: feeds the trace's quads, one per cycle while the LOD unit accepts.
struct RequestSource : Module {
  const Trace& trace;
  Channel<QuadReq>& out;
  size_t next = 0;
  RequestSource(Simulator& s, const Trace& tr, Channel<QuadReq>& o) : Module(s, "request_fifo"), trace(tr), out(o) {}
  void evaluate() override {
    if (next >= trace.requests.size() || !out.can_push()) return;
    QuadReq q;
    q.id = static_cast<uint32_t>(next);
    for (size_t k = 0; k < 4; ++k) {
      q.s[k] = trace.requests[next + k].s;
      q.t[k] = trace.requests[next + k].t;
    }
    out.push(q);
    next += 4;
    sim_.progress();
  }
  std::string state() const override { return out.state(); }
};

// lod_unit: lambda from the quad's coarse derivatives (cmodel lambda_from_quad), then the quad's
// four pixels, one per cycle.
struct LodUnit : Module {
  Channel<QuadReq>& in;
  Channel<PixelReq>& out;
  int width, height;
  bool holding = false;
  QuadReq quad;
  int32_t lambda = 0;
  int k = 0;
  LodUnit(Simulator& s, Channel<QuadReq>& i, Channel<PixelReq>& o, int w, int h)
      : Module(s, "lod_unit"), in(i), out(o), width(w), height(h) {}
  void evaluate() override {
    if (!holding && in.can_pop()) {
      quad = in.front();
      in.pop();
      lambda = lambda_from_quad(quad.s.data(), quad.t.data(), width, height);
      holding = true;
      k = 0;
    }
    if (holding && out.can_push()) {
      out.push({quad.id + static_cast<uint32_t>(k), quad.s[static_cast<size_t>(k)], quad.t[static_cast<size_t>(k)], lambda});
      if (++k == 4) holding = false;
      sim_.progress();
    }
  }
  std::string state() const override { return fmt::format("{}, {}, holding {}", in.state(), out.state(), holding); }
};

// address_gen: level selection (Sampler::lod_info), integer texel coordinates and fractions per
// level (dp::texel_coord), wrap; one footprint per cycle (two for a MIPMAP_LINEAR pixel).
struct AddressGen : Module {
  Channel<PixelReq>& in;
  Channel<FootprintReq>& out;
  const Sampler& smp;
  bool holding = false;
  std::array<FootprintReq, 2> pending{};
  int count = 0, sent = 0;
  AddressGen(Simulator& s, Channel<PixelReq>& i, Channel<FootprintReq>& o, const Sampler& sm)
      : Module(s, "address_gen"), in(i), out(o), smp(sm) {}
  FootprintReq footprint(uint32_t id, int level, float s, float t) const {
    const Image& img = smp.texture().levels[static_cast<size_t>(level)];
    const SamplerConfig& c = smp.config();
    FootprintReq f;
    f.id = id;
    f.level = level;
    const auto tap = [&](int64_t x, int64_t y) {
      const int wx = wrap_index(c.wrap_s, x, img.width), wy = wrap_index(c.wrap_t, y, img.height);
      return Tap{wx, wy, wx < 0 || wy < 0};
    };
    if (c.mode.base == BaseFilter::Nearest) {  // GL: i = floor(s W)
      f.ntaps = 1;
      f.taps[0] = tap(float_to_fixed(s, static_cast<uint32_t>(img.width), 0),
                      float_to_fixed(t, static_cast<uint32_t>(img.height), 0));
      return f;
    }
    const dp::LevelCoord u = dp::texel_coord(s, img.width), v = dp::texel_coord(t, img.height);
    f.ntaps = 4;
    f.taps = {tap(u.i0, v.i0), tap(u.i0 + 1, v.i0), tap(u.i0, v.i0 + 1), tap(u.i0 + 1, v.i0 + 1)};
    f.fu = u.f;
    f.fv = v.f;
    return f;
  }
  void evaluate() override {
    if (!holding && in.can_pop()) {
      const PixelReq p = in.front();
      in.pop();
      const LodInfo li = smp.lod_info(p.lambda);
      pending[0] = footprint(p.id, li.level0, p.s, p.t);
      count = 1;
      if (li.blend != 0) {
        pending[1] = footprint(p.id, li.level1, p.s, p.t);
        pending[0].two = pending[1].two = true;
        pending[1].second = true;
        pending[0].blend = pending[1].blend = li.blend;
        count = 2;
      }
      holding = true;
      sent = 0;
    }
    if (holding && out.can_push()) {
      out.push(pending[static_cast<size_t>(sent)]);
      if (++sent == count) holding = false;
      sim_.progress();
    }
  }
  std::string state() const override { return fmt::format("{}, {}, holding {}", in.state(), out.state(), holding); }
};

// texel_cache stage: cache lookup of the footprint, stall until the memory model has delivered every
// missing line and the banks have served every texel, then the texel words go to the filter.
struct CacheStage : Module {
  Channel<FootprintReq>& in;
  Channel<FilterReq>& out;
  const Texture& tex;
  Rgba8 border;
  TexelCache& cache;
  MemoryModel& mem;
  bool busy = false;
  FootprintReq cur;
  uint64_t ready = 0, bank_ready = 0;
  // Counted in plain registers on the per-cycle path; published to the stats once, after the run.
  uint64_t line_hits = 0, line_misses = 0, stall_miss = 0, stall_bank = 0, stall_back = 0;
  std::vector<uint64_t> misses_per_level;
  CacheStage(Simulator& s, Channel<FootprintReq>& i, Channel<FilterReq>& o, const Texture& t, Rgba8 b, TexelCache& c,
             MemoryModel& m)
      : Module(s, "texel_cache"), in(i), out(o), tex(t), border(b), cache(c), mem(m) {}
  void evaluate() override {
    const uint64_t now = sim_.cycle();
    if (!busy && in.can_pop()) {
      cur = in.front();
      in.pop();
      std::array<TexelTap, 4> taps{};
      int n = 0;
      for (int k = 0; k < cur.ntaps; ++k)
        if (!cur.taps[static_cast<size_t>(k)].border) taps[static_cast<size_t>(n++)] = {cur.taps[static_cast<size_t>(k)].x, cur.taps[static_cast<size_t>(k)].y};
      const FootprintResult r = cache.access(cur.level, std::span<const TexelTap>(taps.data(), static_cast<size_t>(n)));
      bank_ready = now + static_cast<uint64_t>(std::max(r.cycles, 1) - 1);
      ready = bank_ready;
      for (size_t m = 0; m < r.missed_lines.size(); ++m) ready = std::max(ready, mem.read(now, cache.config().line_bytes()));
      line_hits += static_cast<uint64_t>(r.hits);
      line_misses += static_cast<uint64_t>(r.misses);
      if (misses_per_level.size() <= static_cast<size_t>(cur.level)) misses_per_level.resize(static_cast<size_t>(cur.level) + 1);
      misses_per_level[static_cast<size_t>(cur.level)] += static_cast<uint64_t>(r.misses);
      busy = true;
    }
    if (!busy) return;
    if (now < ready) {
      ++(now < bank_ready ? stall_bank : stall_miss);
      return;
    }
    if (!out.can_push()) {
      ++stall_back;
      return;
    }
    FilterReq f;
    f.id = cur.id;
    f.ntaps = cur.ntaps;
    for (int k = 0; k < cur.ntaps; ++k) {
      const Tap& tp = cur.taps[static_cast<size_t>(k)];
      f.texels[static_cast<size_t>(k)] = tp.border ? border : tex.levels[static_cast<size_t>(cur.level)].at(tp.x, tp.y);
    }
    f.fu = cur.fu;
    f.fv = cur.fv;
    f.blend = cur.blend;
    f.two = cur.two;
    f.second = cur.second;
    out.push(f);
    busy = false;
    sim_.progress();
  }
  std::string state() const override {
    return fmt::format("{}, {}, busy {} until {}", in.state(), out.state(), busy, ready);
  }
  void publish(sim::Stats& st) const {
    st.add("cache_line_hits", line_hits);
    st.add("cache_line_misses", line_misses);
    for (size_t l = 0; l < misses_per_level.size(); ++l) st.add(fmt::format("cache_line_misses_level{}", l), misses_per_level[l]);
    st.add("stall_cache_miss", stall_miss);
    st.add("stall_bank_conflict", stall_bank);
    st.add("stall_backpressure", stall_back);
  }
};

// filter: texel unpack, bilinear lerp unit (dp::bilinear_lerp) or nearest select, trilinear blend
// (dp::level_blend), encode.
struct FilterStage : Module {
  Channel<FilterReq>& in;
  Channel<Response>& out;
  TexelFormat fmt;
  bool nearest;
  Texel4 first{};
  FilterStage(Simulator& s, Channel<FilterReq>& i, Channel<Response>& o, TexelFormat f, bool n)
      : Module(s, "filter"), in(i), out(o), fmt(f), nearest(n) {}
  void evaluate() override {
    if (!in.can_pop()) return;
    const FilterReq& r = in.front();
    const bool emits = !r.two || r.second;
    if (emits && !out.can_push()) return;
    Texel4 c;
    if (nearest) {
      c = decode_texel(r.texels[0], fmt);
    } else {
      c = dp::bilinear_lerp({decode_texel(r.texels[0], fmt), decode_texel(r.texels[1], fmt), decode_texel(r.texels[2], fmt),
                             decode_texel(r.texels[3], fmt)},
                            r.fu, r.fv, fmt);
    }
    if (r.two && !r.second) {
      first = c;
    } else {
      if (r.two) c = dp::level_blend(first, c, r.blend);
      out.push({r.id, encode_texel(c, fmt)});
    }
    in.pop();
    sim_.progress();
  }
  std::string state() const override { return fmt::format("{}, {}", in.state(), out.state()); }
};

struct ResponseSink : Module {
  Channel<Response>& in;
  std::vector<Rgba8>& pixels;
  ResponseSink(Simulator& s, Channel<Response>& i, std::vector<Rgba8>& p) : Module(s, "response"), in(i), pixels(p) {}
  void evaluate() override {
    if (!in.can_pop()) return;
    if (in.front().id != pixels.size())
      throw CheckFailed(fmt::format("response {} out of order (expected {})", in.front().id, pixels.size()));
    pixels.push_back(in.front().rgba);
    in.pop();
    sim_.progress();
  }
};

}  // namespace

UnitOutput run_unit(const Texture& tex, const SamplerConfig& cfg, const Trace& trace, const UnitConfig& ucfg) {
  if (cfg.mode.base != BaseFilter::Nearest && cfg.mode.base != BaseFilter::Linear)
    throw InputError(fmt::format("the cycle model does not implement {} yet (NEAREST and LINEAR families only)",
                                 filter_mode_name(cfg.mode)));
  if (tex.format == TexelFormat::VS16X2) throw InputError("the cycle model does not implement vs16x2 textures yet");
  if (trace.mode != TraceMode::Quad) throw InputError("the cycle model takes quad traces");
  const Sampler smp(tex, cfg);
  TexelCacheConfig cc = ucfg.cache;
  cc.bytes_per_texel = bytes_per_texel(tex.format);
  std::vector<int> ws, hs;
  for (const Image& l : tex.levels) {
    ws.push_back(l.width);
    hs.push_back(l.height);
  }
  TexelCache cache(cc, ws, hs);
  MemoryModel mem(ucfg.memory);

  UnitOutput out;
  Simulator sim(static_cast<uint64_t>(ucfg.memory.latency) * 16 + 10000);
  const auto depth = static_cast<size_t>(ucfg.channel_depth);
  Channel<QuadReq> c_quad("quad", depth);
  Channel<PixelReq> c_pixel("pixel", depth);
  Channel<FootprintReq> c_fp("footprint", depth);
  Channel<FilterReq> c_filter("filter_in", depth);
  Channel<Response> c_resp("response", depth);
  for (sim::Clocked* c : std::initializer_list<sim::Clocked*>{&c_quad, &c_pixel, &c_fp, &c_filter, &c_resp}) sim.add_clocked(c);
  RequestSource src(sim, trace, c_quad);
  LodUnit lod(sim, c_quad, c_pixel, tex.width(), tex.height());
  AddressGen addr(sim, c_pixel, c_fp, smp);
  CacheStage cst(sim, c_fp, c_filter, tex, cfg.border, cache, mem);
  FilterStage flt(sim, c_filter, c_resp, tex.format, cfg.mode.base == BaseFilter::Nearest);
  ResponseSink sink(sim, c_resp, out.pixels);
  const size_t n = trace.requests.size();
  sim.run([&] { return out.pixels.size() == n; }, static_cast<uint64_t>(n) * 4096 + 1000000,
          [&] { return static_cast<uint64_t>(out.pixels.size()); }, n);
  out.cycles = sim.cycle();
  cst.publish(sim.stats());
  out.stats = sim.stats();
  out.stats.add("cycles", out.cycles);
  out.stats.add("pixels", n);
  out.stats.add("memory_bytes", mem.bytes_read());
  out.stats.set("pixels_per_clock", out.cycles ? static_cast<double>(n) / static_cast<double>(out.cycles) : 0.0);
  out.stats.set("memory_bytes_per_pixel", n ? static_cast<double>(mem.bytes_read()) / static_cast<double>(n) : 0.0);
  return out;
}

}  // namespace tfu::rtl
