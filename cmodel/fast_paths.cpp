#include "cmodel/fast_paths.hpp"

#include <atomic>
#include <cstdlib>
#include <cstring>

namespace tfu {

namespace {

bool from_environment() {
  const char* v = std::getenv("TFU_PLAIN");
  return v == nullptr || *v == '\0' || std::strcmp(v, "0") == 0;
}

std::atomic<bool>& flag() {
  static std::atomic<bool> enabled{from_environment()};
  return enabled;
}

}  // namespace

bool fast_paths_enabled() { return flag().load(std::memory_order_relaxed); }

void set_fast_paths(bool enabled) { flag().store(enabled, std::memory_order_relaxed); }

}  // namespace tfu
