// The run's memory budget (docs/inputs-outputs.md "Memory budget"; TFU-S E11). Each input has a
// bound of its own (a file's bytes, a texture's sides), but small inputs can still ask for more
// memory than the machine has: a 33 KB PNG of 16384 x 16384 one-bit texels decodes to 1.3 GiB with
// its MIP chain, and a scene may name it in 24 stages with distinct keys. What the inputs make a run
// hold is charged here before it is allocated, and a charge beyond the budget is one line naming
// the input and the figures, exit 2, instead of the kernel's OOM killer or bad_alloc's line that
// names nothing:
//   * decoded texels: 4 bytes per texel of every level of a texture's complete MIP chain (charged
//     whole when level 0 is known, whether the levels are read or generated): file textures, MIP
//     directories, procedural textures, a level's textures and light maps;
//   * request traces: the bytes of each request held (sizeof(TraceRequest)), charged as they are read.
// A charge is held by what it pays for (a Texture's or Trace's `memory`, shared by its copies) and
// given back when the last of them goes. The budget is `--memory-budget SIZE` (every command), else
// default_memory_budget(); a single thread-safe account per process.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "cmodel/error.hpp"

namespace tfu {

// 3/4 of the least of: physical memory, the cgroup's memory.max, RLIMIT_AS and RLIMIT_DATA (what
// the machine, its container and the shell's ulimit let the process have); the rest is left for what
// the budget does not count (the texel memory's tiled copies, images rendered, the program).
uint64_t default_memory_budget();
// The budget in force: set_memory_budget's, else default_memory_budget().
uint64_t memory_budget();
void set_memory_budget(uint64_t bytes);
// Bytes charged and not yet given back.
uint64_t memory_in_use();

// "8G", "512M", "64K", "1T" (binary multiples) or a number of bytes; InputError naming `option`.
uint64_t parse_memory_size(const std::string& text, const std::string& option);
// 1.5 GiB, 512.0 MiB, 900 bytes: a size for messages.
std::string memory_size_text(uint64_t bytes);

// Bytes of the complete MIP chain of a w x h texture at 4 bytes per texel.
uint64_t mip_chain_bytes(int w, int h);

// A charge against the budget, given back by the destructor. `what` names the input as messages do
// (a quoted path, "trace 'x.txt'"); `kind` says what is charged ("decoded texels", "requests").
class MemoryCharge {
 public:
  // Throws InputError when `bytes` more would pass the budget:
  //   WHAT: KIND of about N would pass the memory budget of B (U in use; --memory-budget SIZE, default 3/4 of this machine's memory)
  MemoryCharge(uint64_t bytes, std::string what, std::string kind);
  ~MemoryCharge();
  MemoryCharge(const MemoryCharge&) = delete;
  MemoryCharge& operator=(const MemoryCharge&) = delete;
  // Charges `bytes` more (the same check).
  void add(uint64_t bytes);
  uint64_t bytes() const { return bytes_; }

 private:
  uint64_t bytes_ = 0;
  std::string what_, kind_;
};

}  // namespace tfu
