// tfu_unit: the texture filter unit as a pipeline of clocked blocks, one C++ module per block
// (files named after the blocks), every block calling the golden model's arithmetic (cmodel/),
// never a copy of it. The unit is programmed as a GPU programs it: it reads the descriptor tables
// (cmodel/descriptors.hpp) and fetches texels by address from one texel memory holding every
// texture of the frame (cmodel/texture_memory.hpp); each request names its texture and sampler.
//
//   request_fifo --QuadReq--> lod_unit --PixelReq--> address_gen --FootprintReq--> kernel_select
//     --FootprintReq--> texel_cache (+ memory_model) --FilterReq--> filter ------------Response--+
//                                                   \--FilterReq--> edge_median --EdgeMedianOut-->  +--> response
//                                     edge_direction --EdgeDirectionOut--> edge_merge --Response--/
//
// Port payloads and widths: rtl/unit_ports.hpp and each block's header. Rates (cache hits):
// NEAREST, LINEAR and EDGE_PRESERVING 1 pixel/clock; a blending *_MIPMAP_LINEAR pixel 2 clocks (one
// level footprint per clock); CUBIC ceil(T*T / (4 lanes)) clocks per level footprint; an
// anisotropic pixel of N probes N times its mode's rate (one probe's footprints after the other). Latency per
// mode: docs/cycle-model.md (measured by the tests).
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "cmodel/enum_names.hpp"
#include "cmodel/frame.hpp"
#include "cmodel/trace.hpp"
#include "rtl/engine_compare.hpp"
#include "rtl/request_stream.hpp"
#include "rtl/unit_config.hpp"
#include "rtl/unit_output.hpp"

namespace tfu::rtl {

// Runs a trace through the unit (clocked by the simulation kernel) on the frame's registers and
// texel memory. `vcd`, if given, receives a value-change dump of every channel's valid/ready/
// occupancy and the stages' busy flags. Throws InputError for an invalid configuration or a trace
// that names an unbound descriptor, CheckFailed on deadlock (with every block's state).
UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, std::ostream* vcd = nullptr);

// The screen position of the pixel a request shades (scene runs; a trace file carries none).
struct ScreenPosition {
  uint16_t x = 0, y = 0;
};

// The waveform of a run (docs/cycle-model.md, "Waveforms"): where it goes, which cycles and which
// signals.
struct VcdOptions {
  std::ostream* out = nullptr;  // nullptr: no waveform
  uint64_t from = 0, to = UINT64_MAX;  // cycles dumped, inclusive
  // Signal patterns (sim::VcdWriter::select); empty: every signal. A pattern that selects no
  // signal is an InputError naming it, before the run.
  std::vector<std::string> signals{};
  // Per request id (its index in the trace): the pixel's screen position, for the x/y signals;
  // nullptr or empty: no x/y signals.
  const std::vector<ScreenPosition>* positions = nullptr;
};
// How the clocked engine simulates (options of the simulation, not of the hardware: not in UnitConfig
// nor in its JSON). Results and statistics are the same whatever they are.
struct ClockedOptions {
  bool idle_skip = true;  // jump over cycles in which no block can act (sim::Simulator::set_idle_skip)
};
UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, const VcdOptions& vcd,
                    const ClockedOptions& clocked = {});

// The same, as unit `shared.unit` of the memory system it shares with a scene's other units
// (rtl/shared_memory.hpp): its misses go there instead of to its own memory.
UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, const VcdOptions& vcd,
                    const ClockedOptions& clocked, MemoryBinding shared);

// run_unit through the simulation kernel's generic module list (a virtual evaluate() per block and
// cycle, forward or reverse) instead of the unit's static schedule: for the test that the schedule
// and the evaluation order change nothing.
UnitOutput run_unit_generic_schedule(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, bool reverse);

// How a unit is run: clocked (every block evaluated every cycle: the reference, and the only way
// that writes a waveform) or by timing recurrences (request by request through every block:
// the same outputs and statistics, several times faster). `tfu sim --engine`.
enum class UnitEngine { Recurrence, Clocked };
inline constexpr EnumNames<UnitEngine, 2> kUnitEngineNames{
    "engine", {{{UnitEngine::Recurrence, "recurrence"}, {UnitEngine::Clocked, "clocked"}}}};
const char* unit_engine_name(UnitEngine e);
UnitEngine unit_engine_from_name(const std::string& name);  // InputError naming the valid names
// The unit by `engine`; with a waveform (vcd.out) always clocked.
UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, UnitEngine engine, const VcdOptions& vcd);
// The same, bound to a shared memory system (`shared.port` nullptr: the unit's own memory). Both
// engines issue the same misses at the same cycles, so they give the same results here too.
UnitOutput run_unit(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, UnitEngine engine, const VcdOptions& vcd,
                    MemoryBinding shared);

// The same unit run by timing recurrences (rtl/unit_recurrence.cpp): request by request through
// every block instead of cycle by cycle; the same pixels, response cycles, cycles, edge shapes
// and statistics as the clocked run (tested). No waveform. `quad_paths` false runs every quad
// through the plain per-pixel path, without the LINEAR, probe and CUBIC quad paths (software speed
// only; rtl/unit_recurrence_linear_quads.hpp, rtl/unit_recurrence_probes.hpp,
// rtl/unit_recurrence_cubic_quads.hpp): for the tests that they are equal. `events`, if given,
// receives every event of the run (rtl/engine_compare.hpp).
UnitOutput run_unit_recurrence(const Frame& frame, const Trace& trace, const UnitConfig& ucfg, bool quad_paths = true,
                               UnitEvents* events = nullptr);

// A unit on a stream of requests (rtl/request_stream.hpp; a scene's render, band by band): the
// timing recurrences, as run_unit_recurrence, with the requests taken from `stream` as they come
// and the results handed to `sink` in request order, chunk by chunk (kStreamChunk requests, the
// last one shorter), so that the working set does not grow with the frame. The returned output
// has the cycles and statistics (the same as a run on the whole trace, tested) and no per-request
// vectors (they went to the sink). The stream's requests must have passed check_requests.
struct UnitChunk {
  size_t first = 0;  // the index of its first request in the unit's stream
  Trace trace;       // its requests (the stream's mode)
  UnitOutput out;    // their pixels, response cycles and edge shapes (no cycles, no statistics)
};
using UnitChunkSink = std::function<void(const UnitChunk&)>;
UnitOutput run_unit_stream(const Frame& frame, RequestStream& stream, const UnitConfig& ucfg, const UnitChunkSink& sink);

// What the unit refuses in requests (InputError naming request first + i): a descriptor index not
// bound, a sampler not defined on the texture's format, a B-spline sampler and a texture of texels
// (or the reverse). run_unit checks its trace; a stream's producer checks what it pushes.
void check_requests(const Frame& frame, const TraceRequest* r, size_t n, size_t first);

}  // namespace tfu::rtl
