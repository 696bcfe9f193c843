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

}  // namespace tfu::sweep
