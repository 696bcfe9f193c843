// Where the two engines first disagree (`tfu sim --compare-engines`, a debugging aid for a change
// to a block's timing: rtl/README.md). Both engines can record the cycle of every event of a run,
// item by item: each push of the request FIFO, and each item leaving each channel of the unit
// (rtl/unit_wiring.hpp) and the texel cache's miss FIFO, named by the block that moves it. The
// clocked engine reads them from the channels' committed counts before each evaluated cycle
// (rtl/unit_clocked.cpp); the recurrence engine records them as its ChannelTimes compute them
// (rtl/timing.hpp). The first difference is the one at the earliest cycle, so it names the block
// whose rule differs, not the blocks downstream that inherit the difference.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "cmodel/enum_names.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/trace.hpp"
#include "rtl/unit_config.hpp"
#include "rtl/unit_output.hpp"

namespace tfu::rtl {

// The events of a run, in data-flow order.
enum class UnitEvent {
  RequestFifoPushesQuad,        // request_fifo pushes a quad into channel quad
  LodUnitTakesQuad,             // lod_unit pops channel quad
  AddressGenTakesPixel,         // address_gen pops channel pixel
  KernelSelectTakesFootprint,   // kernel_select pops channel footprint
  CacheAcceptsFootprint,        // texel_cache's input side pops channel shaped_footprint
  CacheEmitsFootprint,          // texel_cache's output side: a footprint leaves the miss FIFO
  FilterFinishesFootprint,      // filter pops channel texels
  EdgeMedianTakesFootprint,     // edge_median pops channel edge_texels
  EdgeDirectionTakesFootprint,  // edge_direction pops channel edge_median_out
  EdgeMergeTakesFootprint,      // edge_merge pops channel edge_direction_out
  ResponseRetiresFilterPixel,   // response pops channel response (filter_pipe_N after N pipeline registers)
  ResponseRetiresEdgePixel,     // response pops channel edge_response (edge_pipe_N after N pipeline registers)
};
inline constexpr size_t kUnitEventCount = 12;
// What each event says in a report: the block, what it does, and the item it moves.
struct UnitEventText {
  UnitEvent event;
  const char* block;
  const char* action;
};
inline constexpr std::array<UnitEventText, kUnitEventCount> kUnitEventTexts{{
    {UnitEvent::RequestFifoPushesQuad, "request_fifo", "pushes quad"},
    {UnitEvent::LodUnitTakesQuad, "lod_unit", "takes quad"},
    {UnitEvent::AddressGenTakesPixel, "address_gen", "takes pixel"},
    {UnitEvent::KernelSelectTakesFootprint, "kernel_select", "takes footprint"},
    {UnitEvent::CacheAcceptsFootprint, "texel_cache", "accepts footprint"},
    {UnitEvent::CacheEmitsFootprint, "texel_cache", "emits footprint"},
    {UnitEvent::FilterFinishesFootprint, "filter", "finishes footprint"},
    {UnitEvent::EdgeMedianTakesFootprint, "edge_median", "takes edge footprint"},
    {UnitEvent::EdgeDirectionTakesFootprint, "edge_direction", "takes edge footprint"},
    {UnitEvent::EdgeMergeTakesFootprint, "edge_merge", "takes edge footprint"},
    {UnitEvent::ResponseRetiresFilterPixel, "response", "retires filter pixel"},
    {UnitEvent::ResponseRetiresEdgePixel, "response", "retires edge pixel"},
}};
static_assert(
    [] {
      for (size_t i = 0; i < kUnitEventCount; ++i)
        if (static_cast<size_t>(kUnitEventTexts[i].event) != i) return false;
      return true;
    }(),
    "kUnitEventTexts is in UnitEvent order");

// Per event, the cycle of each of its items in order (the items are numbered per event from 0).
using UnitEvents = std::array<std::vector<int64_t>, kUnitEventCount>;

enum class UnitEngine;
// The unit by `engine`, recording every event into `events` (emptied first). The same outputs as
// run_unit (software speed aside).
UnitOutput run_unit_recording(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, UnitEngine engine,
                              UnitEvents& events);

// "" when the two runs' events are equal; else one line naming the first difference: the event with
// the earliest cycle in either run at which they differ ("texel_cache accepts footprint #12 at cycle
// 40 clocked, 41 by the recurrences").
std::string first_event_difference(const UnitEvents& clocked, const UnitEvents& recurrences);

// Runs the frame through both engines with their events recorded: "" when they agree on every
// event, every pixel, the cycles and every statistic; else one line: the first event difference,
// or else the first pixel, response cycle or statistics line that differs.
std::string compare_engines(const Frame& frame, const Trace& trace, const UnitConfig& ucfg);

}  // namespace tfu::rtl
