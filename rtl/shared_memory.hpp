// shared_memory: one memory system behind every unit of a scene (docs/memory-system.md, "The L2 and
// units together"): the L2 (rtl/l2_cache.hpp) when l2.capacity_bytes > 0, and one memory model
// (memory.*: one interface and one DRAM, one set of channels) for all units, instead of each unit's
// own. Each unit keeps its own texel cache (L1); its L1 misses come here through its memory port
// (MemoryModel bound to this system).
//
// Arbitration and order. The units run as they do alone, each on its own thread, and each L1 miss
// is served here at its issue cycle, in one global order: by issue cycle, and within a cycle by a
// rotating priority, unit (t mod N) first at cycle t, then t + 1 mod N, ... (a unit's misses of one
// cycle stay together, in its own order). A unit's misses issue in nondecreasing cycles (its texel
// cache looks up footprints in order, at increasing cycles), and a miss's answer is known when it
// is served, so the order is causal: the miss of unit u at cycle t is served once every other unit
// has finished, or waits with a later miss, or has been served at a cycle whose later misses all
// come after (t, u) (a conservative parallel discrete-event simulation). The result is one
// function of the units' traces and configuration, whatever the thread count or scheduling; both
// engines issue the same misses at the same cycles, so both give it (tested).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "rtl/l2_cache.hpp"
#include "rtl/memory_model.hpp"
#include "rtl/unit_config.hpp"

namespace tfu::rtl {

class SharedMemorySystem final : public SharedMemoryPort {
 public:
  // `units` units of configuration `u` (its l2.* and memory.* fields), `textures` texture descriptors;
  // at most `running` units run at once (the others wait for a turn).
  SharedMemorySystem(const UnitConfig& u, size_t textures, int units, int running);
  // The unit's thread, before its run (waits for a turn) and after it (also when it threw, or had
  // nothing to run; a second finish does nothing).
  void start(int unit);
  void finish(int unit);
  uint64_t read(int unit, uint64_t now, int bytes, int texture, uint64_t address) override;

  const MemoryModel& memory() const { return memory_; }
  const L2Cache* l2() const { return l2_ ? &*l2_ : nullptr; }
  int units() const override { return static_cast<int>(units_.size()); }

 private:
  enum class State { NotStarted, Running, Waiting, Done };
  struct UnitState {
    State state = State::NotStarted;
    uint64_t cycle = 0;  // Waiting: the miss's issue cycle; NotStarted, Running: a bound below its next miss's
    std::condition_variable turn;
  };
  // The arbitration key of a miss of `unit` at `cycle`: (cycle, rotating priority).
  uint64_t rank(int unit, uint64_t cycle) const {
    const auto n = static_cast<uint64_t>(units_.size());
    return (static_cast<uint64_t>(unit) + n - cycle % n) % n;
  }
  bool before(int a, int b) const;  // unit a's (bound on its) next miss comes before unit b's
  int first() const;                // the unit whose next miss comes first; -1 when all are done
  void wake();                      // called with the lock held, after any change of state
  std::mutex mutex_;
  std::vector<UnitState> units_;
  int running_ = 0, max_running_;
  std::optional<L2Cache> l2_;
  MemoryModel memory_;
};

}  // namespace tfu::rtl
