// Checks of option values shared by the subcommands:
//   * parse_choice: a value that is one of a fixed set of names; an unknown value throws InputError
//     "unknown OPTION 'VALUE' (valid: a, b, ...)";
//   * unsigned_integer: the CLI11 check of an option held in an unsigned type. CLI11 converts "-1"
//     to such a type by wrapping it (to 2^64 - 1), so the text is checked before: decimal digits
//     only (TFU-S E12: `--vcd-from -1` and `--tasks -1` were taken as huge numbers).
#pragma once

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/nearest_name.hpp"

namespace tfu::cli {

template <typename E>
E parse_choice(const std::string& option, const std::string& value, const std::map<std::string, E>& choices) {
  const auto it = choices.find(value);
  if (it != choices.end()) return it->second;
  std::string valid;
  for (const auto& [name, unused] : choices) valid += (valid.empty() ? "" : ", ") + name;
  std::vector<std::string> names;
  for (const auto& [name, unused] : choices) names.push_back(name);
  throw InputError("unknown " + option + " '" + quote_input(value) + "' (" + did_you_mean(value, names) + "valid: " + valid + ")");
}

inline CLI::Validator unsigned_integer(uint64_t max = UINT64_MAX) {
  return CLI::Validator(
      [max](std::string& text) -> std::string {
        const bool digits = !text.empty() && text.size() <= 20 && text.find_first_not_of("0123456789") == std::string::npos;
        errno = 0;
        const unsigned long long v = digits ? std::strtoull(text.c_str(), nullptr, 10) : 0;
        if (!digits || errno == ERANGE || v > max)
          return fmt::format("must be an integer in 0..{}, got '{}'", max, quote_input(text, 40));
        return {};
      },
      "");
}

}  // namespace tfu::cli
