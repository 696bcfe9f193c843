#include "rtl/unit_watchdog.hpp"

namespace tfu::rtl {

uint64_t no_progress_limit(const UnitConfig& u) {
  constexpr uint64_t kLineSlots = 16, kBankCycles = 16, kPipelineSlack = 64;
  const auto line_bytes = static_cast<uint64_t>(u.cache.line_bytes);
  const auto bw = static_cast<uint64_t>(u.memory.bytes_per_cycle);
  const uint64_t head_wait = kLineSlots * ((line_bytes + bw - 1) / bw) + static_cast<uint64_t>(u.memory.latency);
  return 2 * (head_wait + kBankCycles + kPipelineSlack) + 10000;
}

}  // namespace tfu::rtl
