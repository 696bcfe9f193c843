#include "cmodel/memory_budget.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <fstream>
#include <string_view>

#include <fmt/format.h>

namespace tfu {
namespace {

constexpr uint64_t kUnlimited = UINT64_MAX;

std::atomic<uint64_t> g_budget{0};  // 0: not set, default_memory_budget()
std::atomic<uint64_t> g_in_use{0};

// The cgroup v2 limit of this process: memory.max of its cgroup (from /proc/self/cgroup, "0::/PATH"),
// else of the root; "max" or no file: none.
uint64_t cgroup_limit() {
  std::string path;
  if (std::ifstream cg("/proc/self/cgroup"); cg) {
    std::string line;
    while (std::getline(cg, line))
      if (line.rfind("0::", 0) == 0) path = line.substr(3);
  }
  for (const std::string& dir : {"/sys/fs/cgroup" + path, std::string("/sys/fs/cgroup")}) {
    std::ifstream f(dir + "/memory.max");
    std::string text;
    if (f >> text && !text.empty() && std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isdigit(c); }))
      return std::stoull(text);
  }
  return kUnlimited;
}

uint64_t rlimit_of(int resource) {
  rlimit r{};
  if (getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return kUnlimited;
  return static_cast<uint64_t>(r.rlim_cur);
}

}  // namespace

uint64_t default_memory_budget() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  uint64_t m = pages > 0 && page > 0 ? static_cast<uint64_t>(pages) * static_cast<uint64_t>(page) : kUnlimited;
  m = std::min({m, cgroup_limit(), rlimit_of(RLIMIT_AS), rlimit_of(RLIMIT_DATA)});
  return m == kUnlimited ? kUnlimited : m / 4 * 3;
}

uint64_t memory_budget() {
  const uint64_t b = g_budget.load();
  if (b != 0) return b;
  static const uint64_t d = default_memory_budget();
  return d;
}

void set_memory_budget(uint64_t bytes) { g_budget.store(std::max<uint64_t>(bytes, 1)); }

uint64_t memory_in_use() { return g_in_use.load(); }

uint64_t parse_memory_size(const std::string& text, const std::string& option) {
  const auto bad = [&] {
    return InputError(fmt::format("{}: '{}' is not a memory size (a number of bytes, or with K, M, G or T: 512M, 8G)", option,
                                  quote_input(text, 40)));
  };
  size_t digits = 0;
  while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits]))) ++digits;
  if (digits == 0 || digits > 19) throw bad();
  const uint64_t n = std::stoull(text.substr(0, digits));
  std::string_view unit(text);
  unit.remove_prefix(digits);
  int shift = 0;
  if (unit == "K" || unit == "KiB") shift = 10;
  else if (unit == "M" || unit == "MiB") shift = 20;
  else if (unit == "G" || unit == "GiB") shift = 30;
  else if (unit == "T" || unit == "TiB") shift = 40;
  else if (!unit.empty()) throw bad();
  if (n == 0) throw InputError(fmt::format("{}: the memory budget must be more than 0 bytes", option));
  if (n > (kUnlimited >> shift)) throw bad();
  return n << shift;
}

std::string memory_size_text(uint64_t bytes) {
  const double b = static_cast<double>(bytes);
  if (bytes >= uint64_t{1} << 30) return fmt::format("{:.1f} GiB", b / (1 << 30));
  if (bytes >= uint64_t{1} << 20) return fmt::format("{:.1f} MiB", b / (1 << 20));
  if (bytes >= uint64_t{1} << 10) return fmt::format("{:.1f} KiB", b / (1 << 10));
  return fmt::format("{} bytes", bytes);
}

uint64_t mip_chain_bytes(int w, int h) {
  uint64_t sum = 0;
  uint64_t x = static_cast<uint64_t>(std::max(w, 1)), y = static_cast<uint64_t>(std::max(h, 1));
  for (;;) {
    sum += x * y * 4;
    if (x == 1 && y == 1) return sum;
    x = std::max<uint64_t>(x / 2, 1);
    y = std::max<uint64_t>(y / 2, 1);
  }
}

MemoryCharge::MemoryCharge(uint64_t bytes, std::string what, std::string kind) : what_(std::move(what)), kind_(std::move(kind)) {
  add(bytes);
}

MemoryCharge::~MemoryCharge() { g_in_use.fetch_sub(bytes_); }

void MemoryCharge::add(uint64_t bytes) {
  const uint64_t budget = memory_budget();
  uint64_t in_use = g_in_use.load();
  do {
    if (bytes > budget || in_use > budget - bytes)
      throw InputError(fmt::format("{}: {} of about {} would pass the memory budget of {} ({} in use; --memory-budget SIZE, "
                                   "default 3/4 of this machine's memory)",
                                   what_, kind_, memory_size_text(bytes_ + bytes), memory_size_text(budget),
                                   memory_size_text(in_use)));
  } while (!g_in_use.compare_exchange_weak(in_use, in_use + bytes));
  bytes_ += bytes;
}

}  // namespace tfu
