// Latency tolerance by Little's law (Igehy, Eldridge & Proudfoot 1998; docs/memory-system.md,
// "Latency tolerance"): the miss-FIFO and line-buffer depths (rtl/cache_stage.hpp) that keep, at
// the configuration's memory latency, the rate a zero-latency run reaches.
//
// A footprint stays in the miss FIFO, and a missed line in the line buffer, about
// W = latency + ceil(line_bytes / bytes_per_cycle) + 2 cycles when the memory keeps up (the
// request, the line's transfer on the interface, the cycle into the FIFO and the cycle out). The
// structures must hold what arrives in W cycles:
//   miss_fifo_depth   = ceil(F W), F = footprints / cycles of the zero-latency run (measured:
//                       `cache_footprints`; nearly uniform, at most 1 per cycle, the tag port's rate);
//   line_buffer_depth = ceil(W bytes_per_cycle / line_bytes) + kMaxFootprintLines: the lines the
//                       memory can deliver in W cycles (the bandwidth-delay product), not the
//                       average miss rate, because misses come in bursts (a new surface, a new MIP
//                       level) that run at the memory's rate; plus the slots the tag stage keeps
//                       free before a lookup.
// Integer arithmetic (ceil(F W) = ceil(footprints W / cycles)), clamped to the fields' ranges.
#pragma once

#include <cstdint>

#include "rtl/unit_config.hpp"

namespace tfu::rtl {

struct LatencyTolerantDepths {
  int miss_fifo_depth, line_buffer_depth;
};
// `footprints` and `cycles` of one unit's zero-latency run; InputError for cycles == 0.
LatencyTolerantDepths latency_tolerant_depths(const UnitConfig& c, uint64_t footprints, uint64_t cycles);

}  // namespace tfu::rtl
