// The JSON text the project writes (statistics, unit configurations, run records, sweep points and
// reports, ids and fingerprints): every writer goes through json_dump.
//
// JSON text is UTF-8. A name taken from a file system or an archive may hold bytes that are not
// UTF-8 (a Latin-1 file name, a pk3 entry): nlohmann's dump() throws on them, which ended a run as
// an internal error (exit 3) after its work was done. json_dump writes each such byte as U+FFFD
// instead (docs/inputs-outputs.md, "Names"), so the output stays valid JSON; names that are UTF-8
// are written exactly.
#pragma once

#include <string>

namespace tfu {

// `j` an nlohmann::json or ordered_json; indent as dump()'s (-1: one line).
template <typename Json>
std::string json_dump(const Json& j, int indent = -1) {
  return j.dump(indent, ' ', false, Json::error_handler_t::replace);
}

}  // namespace tfu
