#include "rtl/shared_memory.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu::rtl {

SharedMemorySystem::SharedMemorySystem(const UnitConfig& u, size_t textures, int units, int running)
    : units_(static_cast<size_t>(units)), max_running_(std::max(running, 1)), memory_(u.memory, textures) {
  if (units < 1 || units > 256) throw InputError(fmt::format("units {} must be in 1..256", units));
  if (u.l2.enabled()) l2_.emplace(u.l2, units);
}

bool SharedMemorySystem::before(int a, int b) const {
  const UnitState& x = units_[static_cast<size_t>(a)];
  const UnitState& y = units_[static_cast<size_t>(b)];
  if (x.cycle != y.cycle) return x.cycle < y.cycle;
  return rank(a, x.cycle) < rank(b, y.cycle);
}

int SharedMemorySystem::first() const {
  int best = -1;
  for (int k = 0; k < static_cast<int>(units_.size()); ++k)
    if (units_[static_cast<size_t>(k)].state != State::Done && (best < 0 || before(k, best))) best = k;
  return best;
}

// Who may go on: the unit whose next miss comes first, if it waits (for its turn, or to start) and
// a thread slot is free; and, while slots are free, units not started yet (in index order).
void SharedMemorySystem::wake() {
  if (running_ >= max_running_) return;
  const int f = first();
  if (f >= 0 && units_[static_cast<size_t>(f)].state != State::Running) {
    units_[static_cast<size_t>(f)].turn.notify_one();
    if (running_ + 1 >= max_running_) return;
  }
  for (UnitState& s : units_)
    if (s.state == State::NotStarted) {
      s.turn.notify_one();
      return;
    }
}

void SharedMemorySystem::start(int unit) {
  std::unique_lock lock(mutex_);
  UnitState& s = units_[static_cast<size_t>(unit)];
  s.turn.wait(lock, [&] { return running_ < max_running_; });
  s.state = State::Running;
  ++running_;
  wake();
}

void SharedMemorySystem::finish(int unit) {
  std::unique_lock lock(mutex_);
  UnitState& s = units_[static_cast<size_t>(unit)];
  if (s.state == State::Done) return;
  if (s.state == State::Running) --running_;
  s.state = State::Done;
  wake();
}

uint64_t SharedMemorySystem::read(int unit, uint64_t now, int bytes, int texture, uint64_t address) {
  std::unique_lock lock(mutex_);
  UnitState& s = units_[static_cast<size_t>(unit)];
  s.state = State::Waiting;
  s.cycle = now;
  --running_;
  wake();
  s.turn.wait(lock, [&] { return running_ < max_running_ && first() == unit; });
  s.state = State::Running;
  ++running_;
  return l2_ ? l2_->read(unit, now, bytes, texture, address, memory_) : memory_.read(now, bytes, texture, address);
}

}  // namespace tfu::rtl
