// The key check of the JSON inputs (scene files, unit configurations, sweep specifications): an
// object may hold only the keys its format knows, checked before any value is read, and an unknown
// key reads the same in every input:
//   first_unknown_key  the first key of the object (in the object's order) that `known` refuses;
//   unknown_key_text   "unknown key 'KEY'", the key cut as every echo of user input (quote_input).
// The callers add the location (file, key path) in their own form: scene.cpp's Obj and
// unit_config.cpp's read_object before the text; sweep_spec.cpp's parse_spec names the key as the
// location and lists the keys it expects ("s.json: extra: unknown key (expected scenes, ...)").
#pragma once

#include <optional>
#include <set>
#include <string>
#include <type_traits>

namespace tfu {

// `j` (an nlohmann::json or ordered_json object); `known` either the set of the object's keys or a
// predicate known(key, value) (a nested object may be a group of dotted keys).
template <typename Json, typename Known>
std::optional<std::string> first_unknown_key(const Json& j, const Known& known) {
  for (const auto& [key, value] : j.items()) {
    if constexpr (std::is_same_v<Known, std::set<std::string>>) {
      if (!known.contains(key)) return key;
    } else {
      if (!known(key, value)) return key;
    }
  }
  return std::nullopt;
}

std::string unknown_key_text(const std::string& key);

}  // namespace tfu
