// Where the two engines first disagree (rtl/engine_compare.hpp).
#include "rtl/engine_compare.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "rtl/tfu_unit.hpp"

namespace tfu::rtl {

namespace {

constexpr int64_t kNever = std::numeric_limits<int64_t>::max();

std::string cycle_text(int64_t c) { return c == kNever ? std::string("never") : fmt::format("at cycle {}", c); }

// The first line at which two texts differ (1-based), with both lines.
std::string first_line_difference(const std::string& a, const std::string& b) {
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  for (size_t line = 1;; ++line) {
    const bool ga = static_cast<bool>(std::getline(sa, la)), gb = static_cast<bool>(std::getline(sb, lb));
    if (!ga && !gb) return "";
    if (!ga) la = "(end)";
    if (!gb) lb = "(end)";
    if (la != lb) return fmt::format("statistics line {}: clocked '{}', recurrences '{}'", line, la, lb);
  }
}

}  // namespace

std::string first_event_difference(const UnitEvents& clocked, const UnitEvents& recurrences) {
  // Per event, its first differing item; of those, the one at the earliest cycle (in either run:
  // the run that moved it first shows where the rules part), ties to the event earlier in the
  // data flow.
  size_t best_event = kUnitEventCount, best_item = 0;
  int64_t best_cycle = kNever, best_a = 0, best_b = 0;
  for (size_t e = 0; e < kUnitEventCount; ++e) {
    const std::vector<int64_t>& a = clocked[e];
    const std::vector<int64_t>& b = recurrences[e];
    const size_t n = std::max(a.size(), b.size());
    for (size_t i = 0; i < n; ++i) {
      const int64_t ca = i < a.size() ? a[i] : kNever, cb = i < b.size() ? b[i] : kNever;
      if (ca == cb) continue;
      if (std::min(ca, cb) < best_cycle) {
        best_event = e;
        best_item = i;
        best_cycle = std::min(ca, cb);
        best_a = ca;
        best_b = cb;
      }
      break;
    }
  }
  if (best_event == kUnitEventCount) return "";
  const UnitEventText& t = kUnitEventTexts[best_event];
  return fmt::format("the engines first disagree where {} {} #{}: {} clocked, {} by the recurrences", t.block, t.action,
                     best_item, cycle_text(best_a), cycle_text(best_b));
}

std::string compare_engines(const Frame& frame, const Trace& trace, const UnitConfig& ucfg) {
  UnitEvents clocked_events, recurrence_events;
  const UnitOutput clocked = run_unit_recording(frame, trace, ucfg, UnitEngine::Clocked, clocked_events);
  const UnitOutput rec = run_unit_recording(frame, trace, ucfg, UnitEngine::Recurrence, recurrence_events);
  std::string d = first_event_difference(clocked_events, recurrence_events);
  if (!d.empty()) return d;
  for (size_t i = 0; i < clocked.pixels.size(); ++i)
    if (!(clocked.pixels[i] == rec.pixels[i]))
      return fmt::format("pixel {} differs: clocked {:08x}, recurrences {:08x}", i,
                         std::bit_cast<uint32_t>(clocked.pixels[i]), std::bit_cast<uint32_t>(rec.pixels[i]));
  if (clocked.response_cycle != rec.response_cycle) return "the response cycles differ";
  if (clocked.cycles != rec.cycles)
    return fmt::format("cycles differ: clocked {}, recurrences {}", clocked.cycles, rec.cycles);
  if (clocked.edge_shapes != rec.edge_shapes) return "the recorded edge shapes differ";
  return first_line_difference(clocked.stats.json_text(), rec.stats.json_text());
}

}  // namespace tfu::rtl
