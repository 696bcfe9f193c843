// The error kinds and exit codes of the model and its tools, in one header with no dependency:
// the golden model (cmodel/error.hpp, which adds the message helpers) and the simulation kernel
// (rtl/kernel/) both throw these.
//
// Exit codes of `tfu` (README, `tfu --help`):
//   0 success
//   1 an output differs from the golden model, or a measured value fails its threshold (CheckFailed)
//   2 bad input or usage: one line on stderr names the input (InputError, CLI11 parse errors)
//   3 internal error: a bug in tfu (any other exception); please report it
//   4 deadlock: the cycle model stopped making progress (DeadlockError); one summary line names a
//     file that holds the full per-stage dump
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace tfu {

inline constexpr int kExitSuccess = 0;
inline constexpr int kExitCheckFailed = 1;  // a comparison or self-check failed
inline constexpr int kExitBadInput = 2;     // the user's input is wrong: one line says which
inline constexpr int kExitInternal = 3;     // a bug: an exception the program did not expect
inline constexpr int kExitDeadlock = 4;     // the cycle model made no progress (DeadlockError)

// Longest error message line (without the "tfu: error: " prefix the CLI adds it stays below 300).
inline constexpr size_t kMaxMessageChars = 280;
// Longest piece of the user's input quoted in a message (quote_input).
inline constexpr size_t kMaxQuotedChars = 60;

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

// Thrown by the simulation kernel when no block made progress for the watchdog's number of cycles.
// what() is one summary line; dump() holds every block's state (the CLI writes it to a file).
class DeadlockError : public std::runtime_error {
 public:
  DeadlockError(const std::string& summary, std::string dump) : std::runtime_error(summary), dump_(std::move(dump)) {}
  const std::string& dump() const { return dump_; }

 private:
  std::string dump_;
};

}  // namespace tfu
