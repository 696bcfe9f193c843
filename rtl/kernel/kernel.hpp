// Cycle simulation kernel: SystemC-like modules, clocked registers and valid/ready channels in plain
// C++ (../shared/FIELD-NOTES.md, outside the repository: the real SystemC kernel measured ~10x slower for the same pipeline).
//
// Two-phase clocking. Every cycle the simulator calls evaluate() on every module, then commit() on
// every channel. evaluate() may read of other blocks only committed channel state (front, can_*)
// and may write only next state (push, pop), so the order in which modules are evaluated cannot
// change any result (tested by evaluating in forward and reverse order).
//
// Channels are FIFOs with skid buffering: can_push() looks at the committed occupancy, so the
// ready signal is registered and never forms a combinational path across stages. A depth of 2
// sustains one transfer per cycle under back-pressure-free flow.
#pragma once

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cmodel/error_kinds.hpp"

namespace tfu::sim {

// Anything with next state that becomes current at the clock edge.
class Clocked {
 public:
  virtual ~Clocked() = default;
  virtual void commit() = 0;
  virtual void reset() = 0;  // synchronous reset: back to the reset value at the next edge
};

// Blocks talk only through channels: what one block produces for another travels in a channel,
// whose valid/ready and payload change only at the edge (commit). A block's own state (the pixel it
// holds, the cache's miss FIFO, its counters) is read and written by that block's evaluate() alone,
// so it needs no second phase: no other block can observe it within a cycle.

// The occupancy state every channel shares, whatever its payload: the simulator commits all
// channels in one loop without a virtual call per channel (commit_state() is inline). The state is
// two free-running 32-bit counters, pushes (write) and pops (read): occupancy = write - read
// (modulo 2^32), the ring slot of an entry its counter masked. A push or pop of this cycle moves
// the `next` counters; the edge copies them into the committed ones.
class ChannelBase : public Clocked {
 public:
  size_t depth() const { return depth_; }
  size_t size() const { return now_.write - now_.read; }
  bool can_push() const { return now_.write - now_.read < depth_; }  // ready, registered
  bool can_pop() const { return now_.write != now_.read; }           // valid
  // Items pushed and popped so far, committed (modulo 2^32): for observers between cycles.
  uint32_t pushes() const { return now_.write; }
  uint32_t pops() const { return now_.read; }
  void commit_state() {  // two 32-bit copies, each load forwarded from its own store
    now_.write = next_.write;
    now_.read = next_.read;
  }
  void commit() final { commit_state(); }
  void reset() final { now_ = next_ = {}; }

 protected:
  // Ring slots: the power of two >= depth + 1, so that a push into a full-at-commit ring never
  // overwrites the head and ring indices wrap with a mask.
  explicit ChannelBase(size_t depth)
      : depth_(static_cast<uint32_t>(depth)), mask_(static_cast<uint32_t>(std::bit_ceil(std::min<size_t>(depth, 4096) + 1) - 1)) {}
  size_t slots() const { return size_t{mask_} + 1; }
  struct Counters {
    uint32_t write = 0, read = 0;
  };
  Counters now_, next_;  // committed, and after this cycle's transfers (at most one push, one pop)
  uint32_t depth_;
  uint32_t mask_;
  bool pushed() const { return next_.write != now_.write; }
  bool popped() const { return next_.read != now_.read; }
};

// Valid/ready channel with a FIFO of `depth` entries (skid buffer), one producer and one consumer.
// Storage is a preallocated ring: push() writes the tail slot, which becomes visible at commit().
template <typename T>
class Channel : public ChannelBase {
 public:
  Channel(std::string name, size_t depth) : ChannelBase(depth), name_(std::move(name)) {
    if (depth == 0 || depth > 4096) throw InputError(fmt::format("channel {}: depth {} must be in 1..4096", name_, depth));
    ring_.resize(slots());
  }
  const std::string& name() const { return name_; }
  // Producer side.
  void push(const T& v) { push_slot() = v; }
  // push() without the copy: the producer fills the returned slot during this evaluate().
  T& push_slot() {
    if (!can_push() || pushed()) throw CheckFailed(fmt::format("channel {}: push while not ready", name_));
    next_.write = now_.write + 1;
    return ring_[now_.write & mask_];
  }
  // Consumer side.
  const T& front() const { return ring_[now_.read & mask_]; }
  void pop() {
    if (!can_pop() || popped()) throw CheckFailed(fmt::format("channel {}: pop while not valid", name_));
    next_.read = now_.read + 1;
  }
  std::string state() const { return fmt::format("{} {}/{}{}", name_, size(), depth_, can_push() ? "" : " full"); }

 private:
  std::string name_;
  std::vector<T> ring_;
};

// A block-internal FIFO (no clocking of its own: the owning block's evaluate() is its only user),
// preallocated ring of `depth` entries.
template <typename T>
class Fifo {
 public:
  explicit Fifo(size_t depth) : ring_(depth) {}
  bool empty() const { return count_ == 0; }
  bool full() const { return count_ == ring_.size(); }
  size_t size() const { return count_; }
  size_t depth() const { return ring_.size(); }
  T& front() { return ring_[head_]; }
  const T& front() const { return ring_[head_]; }
  T& push_back() {  // the new tail slot, to be filled by the caller
    const size_t i = head_ + count_;
    T& slot = ring_[i >= ring_.size() ? i - ring_.size() : i];
    ++count_;
    return slot;
  }
  void pop_front() {
    head_ = head_ + 1 == ring_.size() ? 0 : head_ + 1;
    --count_;
  }

 private:
  std::vector<T> ring_;
  size_t head_ = 0, count_ = 0;
};

// Named counters, values, histograms and tables (rows of counters under a label, e.g. one row per
// texture), written as JSON.
class Stats {
 public:
  struct Table {
    std::vector<std::string> columns;
    std::vector<std::pair<std::string, std::vector<uint64_t>>> rows;  // label, one counter per column
  };
  void add(const std::string& name, uint64_t n = 1) { counters_[name] += n; }
  void set(const std::string& name, double v) { values_[name] = v; }
  void sample(const std::string& histogram, size_t bucket) {
    auto& h = histograms_[histogram];
    if (h.size() <= bucket) h.resize(bucket + 1);
    ++h[bucket];
  }
  void set_histogram(const std::string& name, std::vector<uint64_t> buckets) { histograms_[name] = std::move(buckets); }
  const std::vector<uint64_t>* histogram(const std::string& name) const {
    const auto it = histograms_.find(name);
    return it == histograms_.end() ? nullptr : &it->second;
  }
  double value(const std::string& name) const {
    const auto it = values_.find(name);
    return it == values_.end() ? 0.0 : it->second;
  }
  uint64_t counter(const std::string& name) const {
    const auto it = counters_.find(name);
    return it == counters_.end() ? 0 : it->second;
  }
  const std::map<std::string, uint64_t>& counters() const { return counters_; }
  void set_table(const std::string& name, Table t) { tables_[name] = std::move(t); }
  const Table* table(const std::string& name) const {
    const auto it = tables_.find(name);
    return it == tables_.end() ? nullptr : &it->second;
  }
  // Groups: the same statistics for a part of the run, e.g. one material stage or one texture, each
  // a Stats of its own under a breakdown ("stage", "texture") and a label ("stage 1", "3 name").
  struct Group;
  Stats& group(const std::string& breakdown, const std::string& label);  // created empty if absent
  const Stats* find_group(const std::string& breakdown, const std::string& label) const;
  std::vector<Group>& groups() { return groups_; }
  const std::vector<Group>& groups() const { return groups_; }
  // Adds `from`'s counters, histograms and table rows (rows with equal labels summed) into this,
  // and its groups (each merged whole, counters too, whatever `add_counters`; values not at all:
  // they are derived, again after a merge).
  void merge(const Stats& from, bool add_counters = true);
  void write_json(std::ostream& os) const;
  // The same as a JSON object (to embed in a larger document); the groups under "groups":
  // {breakdown: {label: {counters, values, histograms}}}.
  std::string json_text() const;

 private:
  std::map<std::string, uint64_t> counters_;
  std::map<std::string, double> values_;
  std::map<std::string, std::vector<uint64_t>> histograms_;
  std::map<std::string, Table> tables_;
  std::vector<Group> groups_;  // in order of creation
};

struct Stats::Group {
  std::string breakdown, label;
  Stats stats;
};

class Simulator;

// Simulator::run's progress bar (stderr, runs over ~2 s) on or off for the whole process: a sweep
// running many simulations on worker threads shows its own progress instead.
void set_progress_bars(bool on);

// The progress bar of a simulation (Simulator::run, and the unit's timing recurrences): stderr,
// after ~2 s, at most every 0.5 s, `done()` of `total` work items and the cycle reached; nothing
// when total is 0, `done` is empty or set_progress_bars(false).
class ProgressBar {
 public:
  ProgressBar(const std::function<uint64_t()>& done, uint64_t total);
  void update(uint64_t cycle);
  void finish(uint64_t cycle) const;

 private:
  const std::function<uint64_t()>& done_;
  uint64_t total_;
  std::chrono::steady_clock::time_point t0_, last_;
  bool printed_ = false;
};

// A hardware block; its name is the one deadlock dumps give it.
class Module {
 public:
  Module(Simulator& sim, std::string name);
  virtual ~Module() = default;
  Module(const Module&) = delete;
  Module& operator=(const Module&) = delete;
  const std::string& name() const { return name_; }
  virtual void evaluate() = 0;
  // Idle-cycle skipping. After a cycle in which no block made progress, nothing changes until a
  // time-based event (a memory return, a bank port freeing): wake_cycle(now) is the first cycle
  // >= now at which this block could act (kNever: it waits only on channels, i.e. on other blocks),
  // and skip_cycles(n) accounts the n skipped cycles exactly as n evaluate() calls would have
  // (stall counters). The simulator then jumps to the earliest wake cycle.
  static constexpr uint64_t kNever = UINT64_MAX;
  virtual uint64_t wake_cycle(uint64_t /*now*/) const { return kNever; }
  virtual void skip_cycles(uint64_t /*n*/) {}
  // One line for deadlock dumps: the valid/ready state of the block's ports.
  virtual std::string state() const { return {}; }

 protected:
  Simulator& sim_;

 private:
  std::string name_;
};

// Value-change dump of chosen signals (opens in GTKWave). Signals are sampled after each edge.
class VcdWriter {
 public:
  VcdWriter(std::ostream& out, std::string timescale = "1ns") : out_(out), timescale_(std::move(timescale)) {}
  // `path` is hierarchical, separated by '.', e.g. "tfu.lod.valid".
  void add(const std::string& path, int width, std::function<uint64_t()> value);
  // A 1-bit clock `path`: the dump's time unit becomes half a cycle; cycle c's values are at time
  // 2c with the clock high, and the clock falls at 2c + 1. Before the first sample.
  void add_clock(const std::string& path);
  // Only cycles from..to (inclusive) are dumped; the first of them dumps every signal.
  void set_window(uint64_t from, uint64_t to);
  // Only the signals a pattern selects are dumped (before the first add; none given: every
  // signal); the clock always. A pattern selects a path it matches as a glob ('*' any characters,
  // dots included; '?' one; [...] a set: POSIX fnmatch without flags) and every path under a scope
  // it matches ("tfu.texel_cache" selects tfu.texel_cache.*).
  void select(std::vector<std::string> patterns);
  static bool selects(const std::string& pattern, const std::string& path);
  // The patterns that selected none of the signals offered to add() so far, and every path
  // offered (selected or not): for the caller's error line.
  std::vector<std::string> unmatched_patterns() const;
  const std::vector<std::string>& offered() const { return offered_; }
  void sample(uint64_t cycle);

 private:
  struct Signal {
    std::string path;
    int width;
    std::function<uint64_t()> value;
    std::string id;
    uint64_t last = 0;
    bool dumped = false;
  };
  void header();
  std::ostream& out_;
  std::string timescale_;
  std::vector<Signal> signals_;
  bool header_done_ = false;
  std::string clock_path_, clock_id_;  // empty: no clock
  uint64_t from_ = 0, to_ = UINT64_MAX;
  std::vector<std::string> patterns_;  // empty: every signal
  std::vector<uint8_t> matched_;       // per pattern
  std::vector<std::string> offered_;
};

class Simulator {
 public:
  static constexpr uint64_t kNoCycleLimit = UINT64_MAX;
  explicit Simulator(uint64_t watchdog_cycles = 100000) : watchdog_(watchdog_cycles) {}
  void add_module(Module* m) { modules_.push_back(m); }
  void add_clocked(Clocked* c) { clocked_.push_back(c); }
  void add_clocked(ChannelBase* c) { channels_.push_back(c); }  // committed without a virtual call
  void set_vcd(VcdWriter* v) { vcd_ = v; }
  // Jump over cycles in which no block can act (see Module::wake_cycle); on by default, off while
  // a VCD is written (every cycle is dumped). Results and statistics are identical (tested).
  void set_idle_skip(bool on) { idle_skip_ = on; }
  uint64_t skipped_cycles() const { return skipped_; }
  // Evaluation order (tests use Reverse to show that it does not matter).
  enum class Order { Forward, Reverse };
  void set_order(Order o) { order_ = o; }
  // Modules call this whenever work moves forward (a transfer, an output); the watchdog stops a
  // run that makes no progress for `watchdog_cycles` cycles.
  void progress() { last_progress_ = cycle_; }
  uint64_t cycle() const { return cycle_; }
  Stats& stats() { return stats_; }
  void reset();
  // One clock: every module evaluates, then every channel and register commits (the edge).
  void step() { step_scheduled([this] { evaluate_modules(); }); }
  // Every module's evaluate(), through the module list in the set order (a virtual call each).
  void evaluate_modules() {
    if (order_ == Order::Forward) {
      for (Module* m : modules_) m->evaluate();
    } else {
      for (auto it = modules_.rbegin(); it != modules_.rend(); ++it) (*it)->evaluate();
    }
  }
  // One clock with a static schedule: `evaluate()` must call evaluate() of every registered module
  // once, in any order (a design's own list of its blocks, called directly so that the compiler
  // can inline them: what Verilator's generated eval() is to a netlist). Then the edge.
  template <typename Schedule>
  void step_scheduled(Schedule&& evaluate) {
    evaluate();
    for (ChannelBase* c : channels_) c->commit_state();
    for (Clocked* c : clocked_) c->commit();
    const bool progressed = last_progress_ == cycle_;
    ++cycle_;
    if (vcd_ || (idle_skip_ && !progressed)) after_edge(progressed);
  }
  // Steps until done() is true. Throws DeadlockError (one summary line, dump() = every module's
  // state) if the watchdog fires or max_cycles pass (kNoCycleLimit: only the watchdog). Shows a progress bar on stderr for runs over ~2 s when
  // `work_total` > 0 and `work_done` reports progress. (A template, so that the per-cycle test of
  // done() and the step inline into one loop.)
  template <typename Done>
  void run(Done&& done, uint64_t max_cycles, const std::function<uint64_t()>& work_done = {}, uint64_t work_total = 0) {
    run_scheduled([this] { evaluate_modules(); }, done, max_cycles, work_done, work_total);
  }
  // run() with a static schedule (step_scheduled).
  template <typename Schedule, typename Done>
  void run_scheduled(Schedule&& evaluate, Done&& done, uint64_t max_cycles, const std::function<uint64_t()>& work_done = {},
                     uint64_t work_total = 0) {
    ProgressBar bar(work_done, work_total);
    const uint64_t start = cycle_;
    last_progress_ = cycle_;
    for (uint32_t steps = 1; !done(); ++steps) {
      if (cycle_ - start >= max_cycles || cycle_ - last_progress_ > watchdog_) stop(start, max_cycles);
      step_scheduled(evaluate);
      if ((steps & 0xFFFu) == 0) bar.update(cycle_);
    }
    bar.finish(cycle_);
  }
  std::string dump() const;

 private:
  // After the edge: the VCD sample, or the jump over idle cycles (see Module::wake_cycle).
  void after_edge(bool progressed);
  // Throws the watchdog's or the cycle limit's DeadlockError with the state dump.
  [[noreturn]] void stop(uint64_t start, uint64_t max_cycles) const;
  std::vector<Module*> modules_;
  std::vector<Clocked*> clocked_;
  std::vector<ChannelBase*> channels_;
  VcdWriter* vcd_ = nullptr;
  Order order_ = Order::Forward;
  uint64_t cycle_ = 0, last_progress_ = 0, watchdog_;
  bool idle_skip_ = true;
  uint64_t skipped_ = 0;
  Stats stats_;
};

}  // namespace tfu::sim
