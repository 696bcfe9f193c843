// memory_model: texture memory behind the texel cache.
//
// Ports:
//   in  req_valid, req_address[63:0], req_bytes[15:0], req_texture[11:0]   one line request per call
//   out done_cycle[63:0]                              cycle at which the line is in the cache
// Model: requests are served in order; each occupies the memory interface for
// ceil(bytes / bytes_per_cycle) cycles (bandwidth). Then, with the ideal memory (memory.dram ideal,
// the default), the data arrives `latency` cycles later. Several misses can be outstanding: a
// request does not wait for the previous one's latency, only for the interface. With a DRAM part
// (rtl/dram.hpp, docs/memory-system.md) the request goes to that DRAM, the unit's own, at the cycle
// the interface takes it, and arrives when the DRAM has delivered its last burst (`latency` is not
// used). Every byte read is counted, in total and per texture (the texture whose footprint missed
// the line). Bound to a shared memory system (memory.shared, or an L2: rtl/shared_memory.hpp), the
// unit has no interface or DRAM of its own: each request goes to that system at its issue cycle,
// which answers with the cycle its data arrives; the bytes are still counted here, per unit.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "rtl/dram.hpp"

namespace tfu::rtl {

struct MemoryConfig {
  int latency = 100;         // cycles from issue to data (the ideal memory)
  int bytes_per_cycle = 16;  // interface bandwidth
  int dram = 0;              // 0: the ideal memory; k: dram::parts()[k - 1]
  int dram_policy = 0;       // dram::PagePolicy
  int dram_mapping = 0;      // index into dram::kMappings
  int unit_clock_mhz = 1000;  // the unit's clock, for the DRAM's (dram::Config::unit_clock_mhz)
  int shared = 0;             // 1: one memory (interface and DRAM) for all units of a scene (rtl/shared_memory.hpp)
  friend bool operator==(const MemoryConfig&, const MemoryConfig&) = default;
  dram::Config dram_config() const {
    return {std::string(dram::parts()[static_cast<size_t>(dram - 1)].name), static_cast<dram::PagePolicy>(dram_policy),
            dram::kMappings[static_cast<size_t>(dram_mapping)], unit_clock_mhz, true};
  }
  void validate() const {
    if (latency < 0 || latency > 1000000)
      throw InputError(fmt::format("memory latency {} must be in 0..1000000 cycles", latency));
    if (bytes_per_cycle < 1 || bytes_per_cycle > 65536)
      throw InputError(fmt::format("memory bytes_per_cycle {} must be in 1..65536", bytes_per_cycle));
    if (dram < 0 || dram > static_cast<int>(dram::parts().size()))
      throw InputError(fmt::format("memory dram {} must be in 0..{}", dram, dram::parts().size()));
    if (dram_policy < 0 || dram_policy > 1) throw InputError(fmt::format("memory dram_policy {} must be 0 or 1", dram_policy));
    if (dram_mapping < 0 || dram_mapping >= static_cast<int>(dram::kMappings.size()))
      throw InputError(fmt::format("memory dram_mapping {} must be in 0..{}", dram_mapping, dram::kMappings.size() - 1));
    if (unit_clock_mhz < 1 || unit_clock_mhz > 100000)
      throw InputError(fmt::format("memory unit_clock_mhz {} must be in 1..100000", unit_clock_mhz));
    if (shared < 0 || shared > 1) throw InputError(fmt::format("memory shared {} must be 0 or 1", shared));
  }
};

// The memory system several units share (rtl/shared_memory.hpp), as a unit's memory model sees it.
class SharedMemoryPort {
 public:
  // The read of `unit` (MemoryModel::read's arguments); returns the cycle its data has arrived.
  virtual uint64_t read(int unit, uint64_t now, int bytes, int texture, uint64_t address) = 0;
  virtual int units() const = 0;  // the units sharing it

 protected:
  ~SharedMemoryPort() = default;
};
// A unit's binding to a shared memory system: none (port nullptr, the unit's own memory), or unit
// `unit` of `port`.
struct MemoryBinding {
  SharedMemoryPort* port = nullptr;
  int unit = 0;
};

class MemoryModel {
 public:
  MemoryModel(MemoryConfig cfg, size_t textures, MemoryBinding shared = {})
      : cfg_(cfg), shared_(shared), texture_bytes_(textures, 0) {
    cfg_.validate();
    if (cfg_.dram > 0 && shared_.port == nullptr) dram_.emplace(cfg_.dram_config());
  }
  // Issues a read of `bytes` at byte `address` for `texture` at cycle `now`; returns the cycle at
  // which the data has arrived.
  uint64_t read(uint64_t now, int bytes, int texture, uint64_t address) {
    bytes_read_ += static_cast<uint64_t>(bytes);
    texture_bytes_[static_cast<size_t>(texture)] += static_cast<uint64_t>(bytes);
    ++requests_;
    if (shared_.port != nullptr) [[unlikely]]
      return shared_.port->read(shared_.unit, now, bytes, texture, address);
    const uint64_t start = now > busy_until_ ? now : busy_until_;
    busy_until_ = start + static_cast<uint64_t>((bytes + cfg_.bytes_per_cycle - 1) / cfg_.bytes_per_cycle);
    if (dram_) {
      const uint64_t in = dram_->read(start, address, bytes);
      return in > busy_until_ ? in : busy_until_;
    }
    return busy_until_ + static_cast<uint64_t>(cfg_.latency);
  }
  const dram::DramModel* dram() const { return dram_ ? &*dram_ : nullptr; }
  uint64_t bytes_read() const { return bytes_read_; }
  uint64_t texture_bytes(int texture) const { return texture_bytes_[static_cast<size_t>(texture)]; }
  uint64_t requests() const { return requests_; }
  const MemoryBinding& binding() const { return shared_; }

 private:
  MemoryConfig cfg_;
  MemoryBinding shared_;
  std::optional<dram::DramModel> dram_;
  std::vector<uint64_t> texture_bytes_;
  uint64_t busy_until_ = 0, bytes_read_ = 0, requests_ = 0;
};

}  // namespace tfu::rtl
