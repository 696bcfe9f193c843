// How a failed run reports itself: one line on stderr, an exit code (cmodel/error.hpp). `tfu`'s
// main() sends every exception here; so do the fuzz targets' harnesses.
//
//   InputError, std::filesystem::error, out of memory  "tfu: error: MSG"                exit 2
//   CheckFailed                                        "tfu: check failed: MSG"         exit 1
//   DeadlockError                                      "tfu: deadlock: MSG; ... FILE"   exit 4
//                                                      (the per-stage dump goes to FILE, a new file
//                                                      in the temporary directory)
//   anything else                                      "tfu: internal error: MSG ..."   exit 3
// Every line is cut to kMaxLineChars characters with control characters removed (one_line), the
// last guard behind each message's own quoting.
#pragma once

#include <cstdio>
#include <exception>
#include <string>

namespace tfu {

inline constexpr size_t kMaxLineChars = 300;

// Prints "tfu: KIND: MESSAGE" as one line of at most kMaxLineChars characters.
void print_error_line(std::FILE* out, const std::string& kind, const std::string& message);

// Reports `e` on `out` and returns the exit code.
int report_error(std::exception_ptr e, std::FILE* out = stderr);

// Writes a deadlock dump to a new file "tfu-deadlock-PID-N.txt" in the temporary directory
// ($TMPDIR or /tmp) and returns its path; throws std::runtime_error if it cannot.
std::string write_deadlock_dump(const std::string& dump);

}  // namespace tfu
