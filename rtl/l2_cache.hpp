// l2_cache: the second-level cache shared by every texture filter unit of a scene, between the
// units' texel-cache (L1) misses and the memory (rtl/memory_model.hpp, a DRAM part or the ideal
// memory; docs/memory-system.md, "The L2 and units together").
//
// Ports:
//   in  req: unit[7:0], issue cycle, address[63:0], bytes[15:0], texture[11:0]   one L1 miss per call
//   out done_cycle[63:0]                                      cycle at which the L1 line is in
//   mem line read requests of line_bytes to the memory model behind it
// Organisation: capacity_bytes = sets x ways x banks x line_bytes. An L2 line address
// L = address / line_bytes goes to bank L mod banks, set (L / banks) mod sets; an L1 request covers
// the L2 lines of its bytes (one when the L2's lines are at least the L1's), each a request of its own.
// Timing of one L2 line request issued at cycle t (the order of calls is the service order, fixed
// by the arbiter in rtl/shared_memory.hpp):
//   input   the L2 takes requests_per_cycle requests per cycle: the request enters at the first
//           cycle e >= t with a free input slot (earlier requests fill the slots in call order);
//   bank    each bank looks up one request per cycle: the lookup is at s = max(e, the bank's
//           previous lookup + 1); s > e is a bank conflict; s - t cycles are counted as queueing;
//   hit     the data is out at max(s + hit_latency, the line's fill cycle) (a hit on a line whose
//           fill is still under way waits for it, as on an MSHR merge);
//   miss    the line is allocated at once (a victim chosen by `replacement` among the set's ways,
//           an invalid way first: LRU, the least recently looked-up; FIFO, the earliest filled), and
//           read from memory at s; the data is out at max(memory's done cycle, s + hit_latency).
// No write-back (textures are read only), no line locking: an in-flight line may be evicted, its
// waiting hits keep their fill cycle. Counters per requesting unit.
#pragma once

#include <cstdint>
#include <vector>

#include "rtl/memory_model.hpp"

namespace tfu::rtl {

enum class L2Replacement { Lru, Fifo };

struct L2Config {
  int capacity_bytes = 0;      // 0: no L2 (the default)
  int line_bytes = 128;        // bytes per L2 line
  int ways = 16;               // associativity
  int banks = 4;               // tag/data banks, one lookup per cycle each
  int hit_latency = 20;        // cycles from lookup to data out on a hit
  int requests_per_cycle = 4;  // requests the L2 takes per cycle from all units together
  int replacement = 0;         // L2Replacement
  bool enabled() const { return capacity_bytes > 0; }
  int sets() const { return capacity_bytes / (line_bytes * ways * banks); }
  void validate() const;  // InputError naming the l2.* key
  friend bool operator==(const L2Config&, const L2Config&) = default;
};

class L2Cache {
 public:
  // Counters of one requesting unit (or of all, summed).
  struct Counters {
    uint64_t requests = 0;        // L2 line requests
    uint64_t hits = 0, misses = 0;
    uint64_t bank_conflicts = 0;  // requests whose bank was busy in their input cycle
    uint64_t queue_cycles = 0;    // cycles from issue to lookup, summed (input slots and banks)
    void add(const Counters& o) {
      requests += o.requests;
      hits += o.hits;
      misses += o.misses;
      bank_conflicts += o.bank_conflicts;
      queue_cycles += o.queue_cycles;
    }
  };

  L2Cache(const L2Config& cfg, int units);
  // The L1 miss of `unit` issued at `now` reading `bytes` at `address`, through the L2 and, for
  // its missing lines, the memory `below`; returns the cycle its data is out. Calls must come in
  // nondecreasing `now` (the arbiter's order).
  uint64_t read(int unit, uint64_t now, int bytes, int texture, uint64_t address, MemoryModel& below);
  const Counters& unit_counters(int unit) const { return units_[static_cast<size_t>(unit)]; }
  Counters total() const;
  const L2Config& config() const { return cfg_; }

 private:
  struct Way {
    uint64_t line = UINT64_MAX;  // L2 line address; UINT64_MAX: invalid
    uint64_t stamp = 0;          // LRU: last lookup; FIFO: fill order
    uint64_t ready = 0;          // cycle the line's fill is in
  };
  L2Config cfg_;
  int sets_;
  std::vector<Way> ways_;           // bank-major: ((bank * sets) + set) * ways + way
  std::vector<uint64_t> bank_free_; // first cycle each bank can look up again
  uint64_t input_cycle_ = 0;        // the cycle input slots are being given out in
  int input_used_ = 0;              // slots given out in input_cycle_
  uint64_t stamp_ = 0;
  std::vector<Counters> units_;
};

}  // namespace tfu::rtl
