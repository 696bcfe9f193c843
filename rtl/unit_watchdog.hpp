// unit_watchdog: how long a working texture filter unit can go without any block moving work
// forward, derived from its configuration. The simulation's no-progress watchdog uses it; there is
// no cap on the total number of cycles (a long trace or a slow memory is valid, however slow).
//
// Derivation (docs/cycle-model.md "Watchdog"): every block hands work on within a few cycles
// unless it waits for the texel cache, and the cache waits only for the miss-FIFO head's lines.
// Memory serves requests in order, and every line requested before the head's belongs to a
// footprint that has already left the FIFO (a transfer, i.e. progress), so from the last progress
// the head's data arrives within
//   lines x ceil(line_bytes / bytes_per_cycle) + latency
// cycles, lines <= 16 (the footprint's line slots), plus at most 16 bank cycles of the tag port and
// the pipeline's own few cycles. The watchdog allows twice that plus 10,000 cycles: it can only
// fire on a genuine deadlock (a bug; exit code 4). Units sharing one memory system (rtl/shared_memory.hpp)
// may find the other units' outstanding lines ahead of the head's: up to miss_fifo_depth x 16 each,
// each taking at most ceil(line_bytes / bytes_per_cycle) + 64 cycles (a DRAM row conflict) + the L2's
// hit latency; twice that is added per other unit.
#pragma once

#include <cstdint>

#include "rtl/unit_config.hpp"

namespace tfu::rtl {

uint64_t no_progress_limit(const UnitConfig& u, int sharing_units = 1);

}  // namespace tfu::rtl
