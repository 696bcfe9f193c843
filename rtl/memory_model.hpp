// memory_model: texture memory behind the texel cache.
//
// Ports:
//   in  req_valid, req_line[63:0], req_bytes[15:0], req_texture[11:0]   one line request per call
//   out done_cycle[63:0]                              cycle at which the line is in the cache
// Model: requests are served in order; each occupies the memory interface for
// ceil(bytes / bytes_per_cycle) cycles (bandwidth), then arrives `latency` cycles later. Several
// misses can be outstanding: a request does not wait for the previous one's latency, only for the
// interface. Every byte read is counted, in total and per texture (the texture whose footprint
// missed the line).
#pragma once

#include <cstdint>
#include <vector>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu::rtl {

struct MemoryConfig {
  int latency = 100;         // cycles from issue to data
  int bytes_per_cycle = 16;  // interface bandwidth
  friend bool operator==(const MemoryConfig&, const MemoryConfig&) = default;
  void validate() const {
    if (latency < 0 || latency > 1000000)
      throw InputError(fmt::format("memory latency {} must be in 0..1000000 cycles", latency));
    if (bytes_per_cycle < 1 || bytes_per_cycle > 65536)
      throw InputError(fmt::format("memory bytes_per_cycle {} must be in 1..65536", bytes_per_cycle));
  }
};

class MemoryModel {
 public:
  MemoryModel(MemoryConfig cfg, size_t textures) : cfg_(cfg), texture_bytes_(textures, 0) { cfg_.validate(); }
  // Issues a read of `bytes` for `texture` at cycle `now`; returns the cycle at which the data has arrived.
  uint64_t read(uint64_t now, int bytes, int texture) {
    const uint64_t start = now > busy_until_ ? now : busy_until_;
    busy_until_ = start + static_cast<uint64_t>((bytes + cfg_.bytes_per_cycle - 1) / cfg_.bytes_per_cycle);
    bytes_read_ += static_cast<uint64_t>(bytes);
    texture_bytes_[static_cast<size_t>(texture)] += static_cast<uint64_t>(bytes);
    ++requests_;
    return busy_until_ + static_cast<uint64_t>(cfg_.latency);
  }
  uint64_t bytes_read() const { return bytes_read_; }
  uint64_t texture_bytes(int texture) const { return texture_bytes_[static_cast<size_t>(texture)]; }
  uint64_t requests() const { return requests_; }

 private:
  MemoryConfig cfg_;
  std::vector<uint64_t> texture_bytes_;
  uint64_t busy_until_ = 0, bytes_read_ = 0, requests_ = 0;
};

}  // namespace tfu::rtl
