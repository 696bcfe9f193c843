// Error conventions shared by the model and its tools.
#pragma once

#include <stdexcept>
#include <string>

namespace tfu {

inline constexpr int kExitCheckFailed = 1;  // a comparison or self-check failed
inline constexpr int kExitBadInput = 2;     // the user's input is wrong: one line says which

// Thrown for anything the user supplied that cannot be used (unknown name, value out of range,
// unreadable file). The message is a single line that names the input.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace tfu
