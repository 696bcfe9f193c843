// The cluster runner (tfu sweep --slurm): one Slurm job array whose tasks run this same binary on
// their share of the points (point index modulo the task count) into DIR, which must be on a file
// system every node sees; `tfu sweep --collect DIR` then writes results.csv and summary.md.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace tfu::sweep {

struct SlurmJob {
  std::string tfu;                        // absolute path of the tfu binary the tasks run
  std::string dir;                        // absolute sweep directory
  size_t tasks = 1;                       // array tasks (0 .. tasks-1)
  int cpus_per_task = 1;                  // each task's worker threads
  std::vector<std::string> sbatch_args;   // passed to sbatch before the script (e.g. --partition=x)
};

// The batch script (bash, #SBATCH lines for the array, log files DIR/slurm/task-%a.log and the CPUs
// per task; the task line runs `tfu sweep --run-task $SLURM_ARRAY_TASK_ID --tasks N --out DIR`).
// Every value in it is single-quoted by shell_quote; InputError (check_script_value) for a value
// with a newline or carriage return. The log path is an sbatch filename pattern: a '%' of DIR is
// written %%, and a DIR with a backslash (which turns sbatch's replacements off) is refused.
std::string batch_script(const SlurmJob& job);
// sbatch --parsable [sbatch_args...] SCRIPT
std::vector<std::string> sbatch_command(const SlurmJob& job, const std::string& script_path);
// Submits: InputError with sbatch's first error line if it fails; returns the job id.
std::string submit(const SlurmJob& job, const std::string& script_path);

// The absolute path of the running binary (/proc/self/exe).
std::string self_executable();
// Single-quoted for bash ('\'' for a quote inside): every value placed in a generated script.
std::string shell_quote(const std::string& s);
// InputError naming WHAT when `value` holds a newline or carriage return (it would end a line of a
// generated script, or of the dry run's printed command); batch_script and sbatch_command check every value.
void check_script_value(const std::string& what, const std::string& value);

}  // namespace tfu::sweep
