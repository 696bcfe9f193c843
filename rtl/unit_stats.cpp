#include "rtl/unit_stats.hpp"

#include <fmt/format.h>

namespace tfu::rtl {

std::string stat_key(UnitStat s, int level) { return fmt::format("{}{}", stat_key(s), level); }

std::string stage_group_label(int stage) { return fmt::format("stage {}", stage); }

std::string unit_stats_markdown() {
  std::string md = "| key | kind | meaning | per stage and texture |\n|---|---|---|---|\n";
  for (const UnitStatField& f : kUnitStatFields) {
    const std::string group = f.in_group == nullptr ? "no"
                              : *f.in_group == 0    ? "yes"
                                                    : fmt::format("yes: {}", f.in_group);
    md += fmt::format("| `{}{}` | {} | {} | {} |\n", f.key, f.per_level() ? "N" : "", kStatKindNames.name(f.kind),
                      f.meaning, group);
  }
  return md;
}

}  // namespace tfu::rtl
