#include "rtl/tfu_unit.hpp"

#include <algorithm>
#include <bit>
#include <memory>
#include <ostream>
#include <type_traits>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "rtl/unit_wiring.hpp"

namespace tfu::rtl {
namespace detail {

// check_inputs and derive_stats: rtl/unit_wiring.hpp.
void check_inputs(const Frame& frame, const Trace& trace, const UnitConfig& u) {
  u.validate();
  frame.regs.validate();
  if (frame.line_bytes != u.cache.line_bytes)
    throw InputError(fmt::format("the frame's textures are tiled for {}-byte lines, the cache has {}-byte lines",
                                 frame.line_bytes, u.cache.line_bytes));
  if (trace.mode == TraceMode::Quad && trace.requests.size() % 4 != 0)
    throw InputError("a quad trace needs a multiple of 4 requests");
  const size_t nt = frame.regs.textures.size(), ns = frame.regs.samplers.size();
  std::vector<uint8_t> seen(nt * ns, 0);
  for (size_t i = 0; i < trace.requests.size(); ++i) {
    const TraceRequest& r = trace.requests[i];
    if (r.texture >= nt || r.sampler >= ns)
      throw InputError(fmt::format("request {} names texture {} and sampler {}; {} and {} are bound", i, r.texture, r.sampler, nt, ns));
    uint8_t& s = seen[r.texture * ns + r.sampler];
    if (s) continue;
    s = 1;
    const SamplerDescriptor& smp = frame.regs.samplers[r.sampler];
    const bool wants = smp.mode.base == BaseFilter::Cubic && smp.kernel == kBsplineInterp;
    if (wants != (frame.regs.textures[r.texture].content == TextureContent::BsplineCoefficients))
      throw InputError(fmt::format("request {}: sampler {} ({} {}) and texture {} ({}) do not go together (bind_requests)", i,
                                   r.sampler, filter_mode_name(smp.mode), smp.kernel, r.texture,
                                   wants ? "texels" : "B-spline coefficients"));
  }
}

void derive_stats(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, Unit& u, UnitOutput& out) {
  sim::Stats& st = out.stats;
  const size_t n = trace.requests.size();
  u.cst.publish(st);
  u.addr.publish(st);
  st.add("cycles", out.cycles);
  st.add("pixels", n);
  st.add("memory_bytes", u.mem.bytes_read());
  st.add("memory_requests", u.mem.requests());
  if (u.filter) st.add("filter_lane_busy_cycles", u.filter->busy_cycles());
  if (u.e2) st.set_histogram("edge_direction", std::vector<uint64_t>(u.e2->chosen.begin(), u.e2->chosen.end()));
  st.set_histogram("latency", u.sink.latency);
  // Traffic per texture descriptor and per material stage.
  std::vector<uint64_t> tex_requests(frame.textures.size(), 0);
  std::array<uint64_t, 4> stage_requests{};
  for (const TraceRequest& r : trace.requests) {
    ++tex_requests[r.texture];
    ++stage_requests[r.stage];
  }
  sim::Stats::Table textures{{"index", "requests", "line_hits", "line_misses", "memory_bytes"}, {}};
  for (size_t t = 0; t < frame.textures.size(); ++t) {
    const int ti = static_cast<int>(t);
    if (tex_requests[t] == 0 && u.cache.texture_hits(ti) + u.cache.texture_misses(ti) == 0) continue;
    textures.rows.emplace_back(fmt::format("{} {}", t, frame.textures[t].name),
                               std::vector<uint64_t>{t, tex_requests[t], u.cache.texture_hits(ti), u.cache.texture_misses(ti),
                                                     u.mem.texture_bytes(ti)});
  }
  st.set_table("textures", std::move(textures));
  sim::Stats::Table stages{{"stage", "requests", "line_hits", "line_misses", "memory_bytes"}, {}};
  for (size_t k = 0; k < 4; ++k)
    if (stage_requests[k] > 0)
      stages.rows.emplace_back(fmt::format("stage {}", k),
                               std::vector<uint64_t>{k, stage_requests[k], u.cst.stage_hits[k], u.cst.stage_misses[k],
                                                     u.cst.stage_misses[k] * static_cast<uint64_t>(ucfg.cache.line_bytes)});
  st.set_table("stages", std::move(stages));
  derive_rates(st, n, out.cycles);
}

}  // namespace detail

using detail::Unit;

namespace {

// The request id a channel's head carries (its pixel's index in the trace), if its payload has one.
template <typename T>
constexpr bool kHasId = requires(const T& p) { p.id; } || requires(const T& p) { p.tag.id; };
template <typename T>
uint64_t payload_id(const T& p) {
  if constexpr (requires { p.id; }) {
    return p.id;
  } else {
    return p.tag.id;
  }
}

// The waveform probes: the clock, every channel's valid / ready / occupancy and head request id, the
// blocks' busy flags, the texel cache's request, line and per-tap texel addresses, and the pixels
// retired.
void add_probes(sim::VcdWriter& vcd, Unit& u) {
  vcd.add_clock("tfu.clk");
  const auto channel = [&vcd](const auto& ch) {
    vcd.add(fmt::format("tfu.{}.valid", ch.name()), 1, [&ch] { return uint64_t{ch.can_pop()}; });
    vcd.add(fmt::format("tfu.{}.ready", ch.name()), 1, [&ch] { return uint64_t{ch.can_push()}; });
    vcd.add(fmt::format("tfu.{}.count", ch.name()), 8, [&ch] { return uint64_t{ch.size()}; });
    using Payload = std::remove_cvref_t<decltype(ch.front())>;
    if constexpr (kHasId<Payload>)
      vcd.add(fmt::format("tfu.{}.id", ch.name()), 32, [&ch] { return ch.can_pop() ? payload_id(ch.front()) : uint64_t{0}; });
  };
  channel(u.c_quad);
  channel(u.c_pixel);
  channel(u.c_addr);
  channel(u.c_shape);
  channel(u.c_texels);
  channel(u.c_edge_texels);
  channel(u.c_s1);
  channel(u.c_s2);
  channel(u.c_resp);
  channel(u.c_edge_resp);
  vcd.add("tfu.lod_unit.busy", 1, [&u] { return uint64_t{u.lod.busy()}; });
  vcd.add("tfu.address_gen.busy", 1, [&u] { return uint64_t{u.addr.busy()}; });
  vcd.add("tfu.texel_cache.busy", 1, [&u] { return uint64_t{u.cst.busy()}; });
  vcd.add("tfu.texel_cache.id", 32, [&u] { return uint64_t{u.cst.current_id()}; });
  u.cst.probes(true);
  const int line_bits = kAddressBits - std::countr_zero(static_cast<unsigned>(u.cache.config().line_bytes));
  vcd.add("tfu.texel_cache.accepted_id", 32, [&u] { return uint64_t{u.cst.accepted_id()}; });
  vcd.add("tfu.texel_cache.accepted_line", line_bits, [&u] { return u.cst.accepted_line(); });
  vcd.add("tfu.texel_cache.miss_line", line_bits, [&u] { return u.cst.last_miss_line(); });
  vcd.add("tfu.texel_cache.misses", 5, [&u] { return static_cast<uint64_t>(u.cst.last_misses()); });
  vcd.add("tfu.texel_cache.accepted_taps", 5, [&u] { return static_cast<uint64_t>(u.cst.accepted_taps()); });
  for (int k = 0; k < static_cast<int>(std::tuple_size_v<decltype(FilterReq::texels)>); ++k)
    vcd.add(fmt::format("tfu.texel_cache.accepted_tap_addr_{:02}", k), kAddressBits,
            [&u, k] { return u.cst.accepted_tap_address(k); });
  vcd.add("tfu.response.retired", 32, [&u] { return uint64_t{u.sink.retired()}; });
}

}  // namespace

void derive_rates(sim::Stats& st, size_t requests, uint64_t cycles) {
  const auto n = static_cast<double>(requests);
  st.set("pixels_per_clock", cycles ? n / static_cast<double>(cycles) : 0.0);
  st.set("memory_bytes_per_pixel", requests ? static_cast<double>(st.counter("memory_bytes")) / n : 0.0);
  st.set("probes_per_pixel", requests ? static_cast<double>(st.counter("probes")) / n : 0.0);
  const uint64_t h = st.counter("cache_line_hits"), m = st.counter("cache_line_misses");
  st.set("cache_hit_rate", h + m ? static_cast<double>(h) / static_cast<double>(h + m) : 1.0);
  uint64_t lat_sum = 0, lat_min = UINT64_MAX, lat_max = 0;
  if (const std::vector<uint64_t>* lat = st.histogram("latency"))
    for (size_t c = 0; c < lat->size(); ++c)
      if ((*lat)[c]) {
        lat_sum += c * (*lat)[c];
        lat_min = std::min<uint64_t>(lat_min, c);
        lat_max = c;
      }
  st.set("latency_mean", requests ? static_cast<double>(lat_sum) / n : 0.0);
  st.set("latency_min", requests ? static_cast<double>(lat_min) : 0.0);
  st.set("latency_max", static_cast<double>(lat_max));
}

UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, std::ostream* vcd_stream) {
  return run_unit(frame, trace, ucfg, VcdOptions{vcd_stream});
}

namespace {

enum class Schedule { Static, GenericForward, GenericReverse };

UnitOutput run(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, const VcdOptions& vcd_opt, Schedule schedule) {
  std::ostream* vcd_stream = vcd_opt.out;
  detail::check_inputs(frame, trace, ucfg);
  const size_t n = trace.requests.size();
  UnitOutput out;
  out.pixels.resize(n);
  out.response_cycle.resize(n);
  auto unit = std::make_unique<Unit>(frame, trace, ucfg, out);
  std::unique_ptr<sim::VcdWriter> vcd;
  if (vcd_stream) {
    vcd = std::make_unique<sim::VcdWriter>(*vcd_stream);
    vcd->set_window(vcd_opt.from, vcd_opt.to);
    add_probes(*vcd, *unit);
    unit->sim.set_vcd(vcd.get());
  }
  unit->sim.set_idle_skip(ucfg.idle_skip);
  const ResponseSink& sink = unit->sink;
  const auto done = [&sink, n] { return sink.retired() == n; };
  const std::function<uint64_t()> retired = [&sink] { return static_cast<uint64_t>(sink.retired()); };
  // No total-cycle cap: the watchdog only.
  if (schedule == Schedule::Static) {
    Unit& u = *unit;
    unit->sim.run_scheduled([&u] { u.evaluate_all(); }, done, sim::Simulator::kNoCycleLimit, retired, n);
  } else {
    unit->sim.set_order(schedule == Schedule::GenericForward ? sim::Simulator::Order::Forward : sim::Simulator::Order::Reverse);
    unit->sim.run(done, sim::Simulator::kNoCycleLimit, retired, n);
  }
  out.cycles = unit->sim.cycle();
  out.edge_shapes = std::move(unit->cst.shapes);
  detail::derive_stats(frame, trace, ucfg, *unit, out);
  return out;
}

}  // namespace

UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, const VcdOptions& vcd_opt) {
  return run(frame, trace, ucfg, vcd_opt, Schedule::Static);
}

UnitOutput run_unit_generic_schedule(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, bool reverse) {
  return run(frame, trace, ucfg, VcdOptions{}, reverse ? Schedule::GenericReverse : Schedule::GenericForward);
}

}  // namespace tfu::rtl
