// The clocked engine (the reference): every block evaluated every cycle by the simulation kernel,
// with the waveform probes. The recurrence engine: rtl/unit_recurrence.cpp.
#include "rtl/tfu_unit.hpp"

#include <algorithm>
#include <bit>
#include <memory>
#include <ostream>
#include <type_traits>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/nearest_name.hpp"
#include "rtl/unit_wiring.hpp"

namespace tfu::rtl {

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

// What a request or footprint at a channel's head carries for the waveform: its descriptor
// indices and material stage, and its MIP level (footprints).
const RequestTag& request_tag(const PixelReq& p) { return p.req; }
const RequestTag& request_tag(const FootprintReq& p) { return p.tag.req; }

// The waveform probes: the clock, every channel's valid / ready / occupancy and head request id, the
// blocks' busy flags, the texel cache's request, line and per-tap texel addresses, and the pixels
// retired; the texture, material stage and screen position of the request at the pixel channel's
// head, and the same with the MIP level of the footprint at the footprint channel's head and of
// the footprint the texel cache accepted last (0 while none: `valid` says when).
void add_probes(sim::VcdWriter& vcd, Unit& u, const std::vector<ScreenPosition>* positions) {
  vcd.add_clock("tfu.clk");
  const auto channel = [&vcd](const auto& ch) {
    vcd.add(fmt::format("tfu.{}.valid", ch.name()), 1, [&ch] { return uint64_t{ch.can_pop()}; });
    vcd.add(fmt::format("tfu.{}.ready", ch.name()), 1, [&ch] { return uint64_t{ch.can_push()}; });
    vcd.add(fmt::format("tfu.{}.count", ch.name()), 8, [&ch] { return uint64_t{ch.size()}; });
    using Payload = std::remove_cvref_t<decltype(ch.front())>;
    if constexpr (kHasId<Payload>)
      vcd.add(fmt::format("tfu.{}.id", ch.name()), 32,
              [&ch] { return ch.can_pop() ? payload_id(ch.front()) : uint64_t{0}; });
  };
  // The request-tag signals of a channel whose head is a request (pixel) or a footprint: texture
  // [11:0], stage [1:0], MIP level [3:0] (footprints) and the pixel's screen position x, y [15:0]
  // (when given). The value functions read the head only while it is valid.
  const bool xy = positions != nullptr && !positions->empty();
  const auto position = [positions](uint64_t id, bool y) -> uint64_t {
    if (id >= positions->size()) return 0;
    const ScreenPosition& p = (*positions)[id];
    return y ? p.y : p.x;
  };
  const auto tag_signals = [&](const auto& ch) {
    using Payload = std::remove_cvref_t<decltype(ch.front())>;
    const std::string at = fmt::format("tfu.{}", ch.name());
    vcd.add(at + ".texture", 12, [&ch] { return ch.can_pop() ? uint64_t{request_tag(ch.front()).texture} : 0; });
    vcd.add(at + ".stage", 2, [&ch] { return ch.can_pop() ? uint64_t{request_tag(ch.front()).stage} : 0; });
    if constexpr (std::is_same_v<Payload, FootprintReq>)
      vcd.add(at + ".level", 4, [&ch] { return ch.can_pop() ? static_cast<uint64_t>(ch.front().level) : 0; });
    if (xy)
      for (const bool y : {false, true})
        vcd.add(at + (y ? ".y" : ".x"), 16,
                [&ch, position, y] { return ch.can_pop() ? position(payload_id(ch.front()), y) : 0; });
  };
  tag_signals(u.c_pixel);
  tag_signals(u.c_addr);
  channel(u.c_quad);
  channel(u.c_pixel);
  channel(u.c_addr);
  channel(u.c_shape);
  channel(u.c_texels);
  channel(u.c_edge_texels);
  channel(u.c_edge_median_out);
  channel(u.c_edge_direction_out);
  channel(u.c_resp);
  channel(u.c_edge_resp);
  for (const auto& c : u.filter_pipe.channels()) channel(*c);
  for (const auto& c : u.edge_pipe.channels()) channel(*c);
  vcd.add("tfu.lod_unit.busy", 1, [&u] { return uint64_t{u.lod_unit.busy()}; });
  vcd.add("tfu.address_gen.busy", 1, [&u] { return uint64_t{u.address_gen.busy()}; });
  vcd.add("tfu.texel_cache.busy", 1, [&u] { return uint64_t{u.cache_stage.busy()}; });
  vcd.add("tfu.texel_cache.id", 32, [&u] { return uint64_t{u.cache_stage.current_id()}; });
  u.cache_stage.probes(true);
  const int line_bits = kAddressBits - std::countr_zero(static_cast<unsigned>(u.cache.config().line_bytes));
  vcd.add("tfu.texel_cache.accepted_id", 32, [&u] { return uint64_t{u.cache_stage.accepted_id()}; });
  vcd.add("tfu.texel_cache.accepted_line", line_bits, [&u] { return u.cache_stage.accepted_line(); });
  vcd.add("tfu.texel_cache.miss_line", line_bits, [&u] { return u.cache_stage.last_miss_line(); });
  vcd.add("tfu.texel_cache.misses", 5, [&u] { return static_cast<uint64_t>(u.cache_stage.last_misses()); });
  vcd.add("tfu.texel_cache.accepted_taps", 5, [&u] { return static_cast<uint64_t>(u.cache_stage.accepted_taps()); });
  vcd.add("tfu.texel_cache.accepted_texture", 12, [&u] { return uint64_t{u.cache_stage.accepted().tag.req.texture}; });
  vcd.add("tfu.texel_cache.accepted_stage", 2, [&u] { return uint64_t{u.cache_stage.accepted().tag.req.stage}; });
  vcd.add("tfu.texel_cache.accepted_level", 4, [&u] { return static_cast<uint64_t>(u.cache_stage.accepted().level); });
  if (xy)
    for (const bool y : {false, true})
      vcd.add(y ? "tfu.texel_cache.accepted_y" : "tfu.texel_cache.accepted_x", 16, [&u, position, y] {
        return u.cache_stage.accepted_taps() > 0 ? position(u.cache_stage.accepted_id(), y) : 0;
      });
  for (int k = 0; k < static_cast<int>(std::tuple_size_v<decltype(FilterReq::texels)>); ++k)
    vcd.add(fmt::format("tfu.texel_cache.accepted_tap_addr_{:02}", k), kAddressBits,
            [&u, k] { return u.cache_stage.accepted_tap_address(k); });
  vcd.add("tfu.response.retired", 32, [&u] { return uint64_t{u.response.retired()}; });
}

// The names a waveform signal selection may use: every signal's path and every scope above one.
std::vector<std::string> signal_names_and_scopes(const std::vector<std::string>& paths) {
  std::vector<std::string> names;
  for (const std::string& p : paths)
    for (size_t dot = p.find('.'); dot != std::string::npos; dot = p.find('.', dot + 1))
      if (std::find(names.begin(), names.end(), p.substr(0, dot)) == names.end()) names.push_back(p.substr(0, dot));
  names.insert(names.end(), paths.begin(), paths.end());
  return names;
}

}  // namespace

UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, std::ostream* vcd_stream) {
  return run_unit(frame, trace, ucfg, VcdOptions{vcd_stream});
}

namespace {

enum class Schedule { Static, GenericForward, GenericReverse };

// The events of a clocked run (rtl/engine_compare.hpp), read from the channels' committed push and
// pop counts before each evaluated cycle: what moved since the previous evaluated cycle moved in
// it (no channel moves in a cycle the simulator skips as idle).
class EventRecorder {
 public:
  EventRecorder(const Unit& u, UnitEvents& events) : u_(u), events_(events) {
    for (std::vector<int64_t>& row : events_) row.clear();
  }
  // Before the cycle `now` is evaluated, and once after the run (`now`: the cycle the run ended).
  void sample(uint64_t now) {
    const std::array<uint32_t, kUnitEventCount> count = counts();
    for (size_t e = 0; e < kUnitEventCount; ++e)
      for (; seen_[e] != count[e]; ++seen_[e]) events_[e].push_back(last_evaluated_);
    last_evaluated_ = static_cast<int64_t>(now);
  }

 private:
  const Unit& u_;
  UnitEvents& events_;
  std::array<uint32_t, kUnitEventCount> seen_{};
  int64_t last_evaluated_ = -1;
  // The committed count of each event (in UnitEvent order): a footprint leaves the miss FIFO into
  // one of the cache's two output channels.
  std::array<uint32_t, kUnitEventCount> counts() const {
    return {u_.c_quad.pushes(),
            u_.c_quad.pops(),
            u_.c_pixel.pops(),
            u_.c_addr.pops(),
            u_.c_shape.pops(),
            u_.c_texels.pushes() + u_.c_edge_texels.pushes(),
            u_.c_texels.pops(),
            u_.c_edge_texels.pops(),
            u_.c_edge_median_out.pops(),
            u_.c_edge_direction_out.pops(),
            u_.filter_pipe.out().pops(),
            u_.edge_pipe.out().pops()};
  }
};

UnitOutput run(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, const VcdOptions& vcd_opt,
               const ClockedOptions& clocked, Schedule schedule, UnitEvents* events = nullptr, MemoryBinding shared = {}) {
  std::ostream* vcd_stream = vcd_opt.out;
  detail::check_inputs(frame, trace, ucfg);
  const size_t n = trace.requests.size();
  UnitOutput out;
  RequestStream whole(trace);
  auto unit = std::make_unique<Unit>(frame, whole, ucfg, shared);
  std::unique_ptr<sim::VcdWriter> vcd;
  if (vcd_stream) {
    vcd = std::make_unique<sim::VcdWriter>(*vcd_stream);
    vcd->set_window(vcd_opt.from, vcd_opt.to);
    vcd->select(vcd_opt.signals);
    add_probes(*vcd, *unit, vcd_opt.positions);
    if (const std::vector<std::string> bad = vcd->unmatched_patterns(); !bad.empty())
      throw InputError(
          fmt::format("--vcd-signals: '{}' selects no signal ({}signals are named tfu.<block or channel>.<signal>; "
                      "docs/cycle-model.md, \"Waveforms\")",
                      bad.front(), did_you_mean(bad.front(), signal_names_and_scopes(vcd->offered()))));
    unit->sim.set_vcd(vcd.get());
  }
  unit->sim.set_idle_skip(clocked.idle_skip);
  const ResponseSink& sink = unit->response;
  const auto done = [&sink, n] { return sink.retired() == n; };
  const std::function<uint64_t()> retired = [&sink] { return static_cast<uint64_t>(sink.retired()); };
  // No total-cycle cap: the watchdog only.
  if (events != nullptr) {
    Unit& u = *unit;
    EventRecorder recorder(u, *events);
    const auto evaluate = [&u, &recorder] {
      recorder.sample(u.sim.cycle());
      u.evaluate_all();
    };
    unit->sim.run_scheduled(evaluate, done, sim::Simulator::kNoCycleLimit, retired, n);
    recorder.sample(unit->sim.cycle());
  } else if (schedule == Schedule::Static) {
    Unit& u = *unit;
    unit->sim.run_scheduled([&u] { u.evaluate_all(); }, done, sim::Simulator::kNoCycleLimit, retired, n);
  } else {
    unit->sim.set_order(schedule == Schedule::GenericForward ? sim::Simulator::Order::Forward
                                                             : sim::Simulator::Order::Reverse);
    unit->sim.run(done, sim::Simulator::kNoCycleLimit, retired, n);
  }
  out.cycles = unit->sim.cycle();
  unit->drain_to(n, nullptr);
  unit->take_outputs(out);
  detail::derive_stats(frame, ucfg, *unit, out);
  return out;
}

}  // namespace

UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, const VcdOptions& vcd_opt,
                    const ClockedOptions& clocked) {
  return run(frame, trace, ucfg, vcd_opt, clocked, Schedule::Static);
}

UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, const VcdOptions& vcd_opt,
                    const ClockedOptions& clocked, MemoryBinding shared) {
  return run(frame, trace, ucfg, vcd_opt, clocked, Schedule::Static, nullptr, shared);
}

UnitOutput run_unit_recording(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, UnitEngine engine,
                              UnitEvents& events) {
  if (engine == UnitEngine::Recurrence) return run_unit_recurrence(frame, trace, ucfg, true, &events);
  return run(frame, trace, ucfg, VcdOptions{}, ClockedOptions{}, Schedule::Static, &events);
}

UnitOutput run_unit_generic_schedule(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, bool reverse) {
  return run(frame, trace, ucfg, VcdOptions{}, ClockedOptions{},
             reverse ? Schedule::GenericReverse : Schedule::GenericForward);
}

}  // namespace tfu::rtl
