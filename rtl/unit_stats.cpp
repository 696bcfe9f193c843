#include "rtl/unit_stats.hpp"

#include <fmt/format.h>

namespace tfu::rtl {

std::string stat_key(UnitStat s, int level) { return fmt::format("{}{}", stat_key(s), level); }

std::string unit_stats_markdown() {
  std::string md = "| key | kind | meaning |\n|---|---|---|\n";
  for (const UnitStatField& f : kUnitStatFields) {
    md +=
        fmt::format("| `{}{}` | {} | {} |\n", f.key, f.per_level() ? "N" : "", kStatKindNames.name(f.kind), f.meaning);
  }
  return md;
}

}  // namespace tfu::rtl
