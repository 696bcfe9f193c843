// Runs another program (the plot script, sbatch) with an argument vector (no shell), waits for it,
// and returns its exit status with what it printed.
#pragma once

#include <string>
#include <vector>

namespace tfu::sweep {

struct ProcessResult {
  int status = -1;           // exit code; 128 + signal if killed by one; -1 if it could not start
  std::string out, err;      // its standard output and standard error
};

// argv[0] is the program (a path, or a name looked up in PATH).
ProcessResult run_process(const std::vector<std::string>& argv);

// The first non-empty line of `text`, at most `max` characters.
std::string first_line(const std::string& text, size_t max = 200);
// Why a child failed, from its standard error: the first non-empty line, or, when that opens a Python
// traceback, the traceback's last non-empty line (the exception); control characters as spaces, at
// most `max` characters (TFU-S E7: "Traceback (most recent call last):" was the error line).
std::string failure_line(const std::string& err, size_t max = 200);

}  // namespace tfu::sweep
