#include "rtl/l2_cache.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu::rtl {

void L2Config::validate() const {
  if (!enabled()) return;
  const auto power_of_two = [](int v) { return v > 0 && (v & (v - 1)) == 0; };
  if (!power_of_two(line_bytes) || line_bytes < 16 || line_bytes > 4096)
    throw InputError(fmt::format("l2.line_bytes {} must be a power of two in 16..4096", line_bytes));
  if (ways < 1 || ways > 64) throw InputError(fmt::format("l2.ways {} must be in 1..64", ways));
  if (banks < 1 || banks > 64) throw InputError(fmt::format("l2.banks {} must be in 1..64", banks));
  const int64_t set_bytes = int64_t{line_bytes} * ways * banks;
  if (capacity_bytes % set_bytes != 0)
    throw InputError(fmt::format("l2.capacity_bytes {} must be a whole number of sets: a multiple of line_bytes x ways x banks = {}",
                                 capacity_bytes, set_bytes));
  if (hit_latency < 1 || hit_latency > 10000) throw InputError(fmt::format("l2.hit_latency {} must be in 1..10000", hit_latency));
  if (requests_per_cycle < 1 || requests_per_cycle > 256)
    throw InputError(fmt::format("l2.requests_per_cycle {} must be in 1..256", requests_per_cycle));
  if (replacement < 0 || replacement > 1) throw InputError(fmt::format("l2.replacement {} must be 0 (lru) or 1 (fifo)", replacement));
}

L2Cache::L2Cache(const L2Config& cfg, int units)
    : cfg_(cfg),
      sets_(cfg.sets()),
      ways_(static_cast<size_t>(cfg.capacity_bytes / cfg.line_bytes)),
      bank_free_(static_cast<size_t>(cfg.banks), 0),
      units_(static_cast<size_t>(units)) {
  cfg_.validate();
}

uint64_t L2Cache::read(int unit, uint64_t now, int bytes, int texture, uint64_t address, MemoryModel& below) {
  Counters& c = units_[static_cast<size_t>(unit)];
  const auto line_bytes = static_cast<uint64_t>(cfg_.line_bytes);
  const auto banks = static_cast<uint64_t>(cfg_.banks), sets = static_cast<uint64_t>(sets_);
  const uint64_t first = address / line_bytes, last = (address + static_cast<uint64_t>(bytes) - 1) / line_bytes;
  uint64_t done = now;
  for (uint64_t line = first; line <= last; ++line) {
    // Input: requests_per_cycle slots per cycle, given out in call order.
    if (now > input_cycle_) {
      input_cycle_ = now;
      input_used_ = 0;
    }
    if (input_used_ == cfg_.requests_per_cycle) {
      ++input_cycle_;
      input_used_ = 0;
    }
    ++input_used_;
    const uint64_t entered = input_cycle_;
    // Bank: one lookup per cycle.
    const uint64_t bank = line % banks;
    uint64_t& bank_free = bank_free_[static_cast<size_t>(bank)];
    const uint64_t lookup = std::max(entered, bank_free);
    if (lookup > entered) ++c.bank_conflicts;
    bank_free = lookup + 1;
    c.queue_cycles += lookup - now;
    ++c.requests;
    // Tags: the set's ways; a hit, or a victim (an invalid way first, then the oldest stamp).
    Way* set = &ways_[static_cast<size_t>((bank * sets + (line / banks) % sets) * static_cast<uint64_t>(cfg_.ways))];
    Way* hit = nullptr;
    Way* victim = set;
    for (int w = 0; w < cfg_.ways; ++w) {
      Way& way = set[w];
      if (way.line == line) {
        hit = &way;
        break;
      }
      if (victim->line != UINT64_MAX && (way.line == UINT64_MAX || way.stamp < victim->stamp)) victim = &way;
    }
    const uint64_t out = lookup + static_cast<uint64_t>(cfg_.hit_latency);
    if (hit != nullptr) {
      ++c.hits;
      if (cfg_.replacement == static_cast<int>(L2Replacement::Lru)) hit->stamp = ++stamp_;
      done = std::max({done, out, hit->ready});
    } else {
      ++c.misses;
      victim->line = line;
      victim->stamp = ++stamp_;
      victim->ready = std::max(below.read(lookup, cfg_.line_bytes, texture, line * line_bytes), out);
      done = std::max(done, victim->ready);
    }
  }
  return done;
}

L2Cache::Counters L2Cache::total() const {
  Counters t;
  for (const Counters& c : units_) t.add(c);
  return t;
}

}  // namespace tfu::rtl
