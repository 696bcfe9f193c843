#include "cmodel/json_keys.hpp"

#include <fmt/format.h>

#include "cmodel/error.hpp"

namespace tfu {

std::string unknown_key_text(const std::string& key) { return fmt::format("unknown key '{}'", quote_input(key)); }

}  // namespace tfu
