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

// Thrown when a self-check of the model fails (a measured error above its bound, a golden compare
// mismatch). The CLI prints the one-line message and exits with kExitCheckFailed.
class CheckFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace tfu
