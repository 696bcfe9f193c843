// Test helper: the message of the InputError that f() throws, or "(no InputError)" when it throws none.
#pragma once

#include <string>

#include "cmodel/error.hpp"

namespace tfu {

template <typename F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

}  // namespace tfu
