#include "rtl/unit_watchdog.hpp"

namespace tfu::rtl {

uint64_t no_progress_limit(const UnitConfig& u, int sharing_units) {
  constexpr uint64_t kLineSlots = 16, kBankCycles = 16, kPipelineSlack = 64;
  const auto line_bytes = static_cast<uint64_t>(u.cache.line_bytes);
  const auto bw = static_cast<uint64_t>(u.memory.bytes_per_cycle);
  const uint64_t head_wait = kLineSlots * ((line_bytes + bw - 1) / bw) + static_cast<uint64_t>(u.memory.latency);
  const uint64_t alone = 2 * (head_wait + kBankCycles + kPipelineSlack) + 10000;
  if (sharing_units <= 1) return alone;
  const uint64_t per_line = (line_bytes + bw - 1) / bw + 64 + static_cast<uint64_t>(u.l2.enabled() ? u.l2.hit_latency : 0);
  const uint64_t others = static_cast<uint64_t>(sharing_units - 1) * static_cast<uint64_t>(u.miss_fifo_depth) * kLineSlots;
  return alone + 2 * others * per_line;
}

}  // namespace tfu::rtl
