// One constexpr name table per enum, and everything that follows from it: the name of a value, the
// value of a name (with the one-line InputError that lists the valid names), and the list of valid
// names. A table is typed once, in the .cpp that owns the enum's name functions; nothing else
// spells those names. Tested: EnumNames.* (testbench/test_enum_names.cpp), each table against its
// enum's values and its error line.
//
//   constexpr EnumNames<WrapMode, 4> kWrapModeNames{"wrap mode", {{
//       {WrapMode::Repeat, "repeat"}, {WrapMode::MirroredRepeat, "mirrored-repeat"}, ...}}};
//   kWrapModeNames.name(WrapMode::Repeat)      -> "repeat"
//   kWrapModeNames.from_name("repat")          -> InputError "unknown wrap mode 'repat' (did you mean
//                                                 'repeat'? expected repeat, mirrored-repeat, clamp-to-edge
//                                                 or clamp-to-border)"  (the suggestion: nearest_name.hpp)
//
// An alias (a second name accepted for a value, not listed in the error) follows the listed names
// with `listed = false`; name() returns the first entry of a value.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "cmodel/error.hpp"
#include "cmodel/nearest_name.hpp"

namespace tfu {

template <typename E>
struct EnumName {
  E value;
  const char* name;
  bool listed = true;  // false: an alias, accepted but not offered in the error line
};

template <typename E, size_t N>
struct EnumNames {
  const char* what;  // the quantity, for the error line: "unknown <what> '<input>' (expected ...)"
  std::array<EnumName<E>, N> entries;

  // The value's name ("?" for a value outside the table: a corrupt enum, never a user's input).
  constexpr const char* name(E v) const {
    for (const EnumName<E>& e : entries)
      if (e.value == v) return e.name;
    return "?";
  }
  // The value named `s`, or false.
  constexpr bool find(std::string_view s, E& out) const {
    for (const EnumName<E>& e : entries)
      if (s == e.name) {
        out = e.value;
        return true;
      }
    return false;
  }
  // The value named `s`; InputError naming the input and the valid names otherwise.
  E from_name(std::string_view s) const {
    E v{};
    if (find(s, v)) return v;
    throw InputError(fmt::format("unknown {} '{}' ({}expected {})", what, quote_input(s), did_you_mean(s, all_names()), expected()));
  }
  // The listed names, in table order.
  std::vector<std::string> names() const {
    std::vector<std::string> v;
    for (const EnumName<E>& e : entries)
      if (e.listed) v.emplace_back(e.name);
    return v;
  }
  // Every accepted name, aliases included (what a mistyped name is compared with: nearest_name.hpp).
  std::vector<std::string> all_names() const {
    std::vector<std::string> v;
    for (const EnumName<E>& e : entries) v.emplace_back(e.name);
    return v;
  }
  // "a, b or c": the listed names for a message.
  std::string expected() const {
    const std::vector<std::string> v = names();
    std::string s;
    for (size_t i = 0; i < v.size(); ++i) s += (i == 0 ? "" : i + 1 == v.size() ? " or " : ", ") + v[i];
    return s;
  }
};

}  // namespace tfu
