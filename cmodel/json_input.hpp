// JSON input files (scenes, unit configurations): one parser entry point, so that every JSON error
// is an InputError naming the file, the position and, where the parser was inside an object, the
// key path: "scene.json: line 3, column 27: at meshes[0].corners[1]: number overflow parsing '1e400'".
// Numbers outside the range of double (1e400), malformed text and nesting deeper than
// kMaxJsonDepth are all such errors (never a library exception).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace tfu {

inline constexpr int kMaxJsonDepth = 64;

nlohmann::json parse_json_input(const std::string& text, const std::string& source);

// The value of an integer field as the file spells it (18446744073709551615 stays that, never -1).
std::string json_number_text(const nlohmann::json& v);

}  // namespace tfu
