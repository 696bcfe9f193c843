// Parsing of an option whose value is one of a fixed set of names, shared by the subcommands.
// An unknown value throws InputError "unknown OPTION 'VALUE' (valid: a, b, ...)".
#pragma once

#include <map>
#include <string>

#include "cmodel/error.hpp"

namespace tfu::cli {

template <typename E>
E parse_choice(const std::string& option, const std::string& value, const std::map<std::string, E>& choices) {
  const auto it = choices.find(value);
  if (it != choices.end()) return it->second;
  std::string valid;
  for (const auto& [name, unused] : choices) valid += (valid.empty() ? "" : ", ") + name;
  throw InputError("unknown " + option + " '" + quote_input(value) + "' (valid: " + valid + ")");
}

}  // namespace tfu::cli
