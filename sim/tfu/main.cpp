// tfu: command-line front end of the texture filter unit model.
//
// Exit codes (README "Exit codes", `tfu --help`): 0 success; 1 an output differs from the golden
// model or a measured value fails its threshold; 2 bad input or usage; 3 internal error (a bug:
// please report it); 4 deadlock of the cycle model. Every error is one line on stderr of at most 300
// characters that names the offending input (cmodel/error_report.hpp).
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "cmodel/error.hpp"
#include "cmodel/error_report.hpp"
#include "cmodel/run_files.hpp"
#include "sim/sweep/provenance.hpp"
#include "sim/sweep/version.hpp"
#include "sim/tfu/commands.hpp"

namespace {

constexpr const char* kExitCodeHelp =
    "Exit codes: 0 success; 1 an output differs from the golden model (or a measured value fails its threshold); "
    "2 bad input or usage; 3 internal error (a bug: please report it); 4 deadlock of the cycle model. "
    "Every error is one line on stderr that names the input.\n";

// stdout is the last output: a full disk or a closed pipe behind it is an error too.
int check_stdout(int code) {
  std::cout.flush();
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  if (failed && code == tfu::kExitSuccess) {
    tfu::print_error_line(stderr, "error", "cannot write to standard output");
    return tfu::kExitBadInput;
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  tfu::set_command_line(argc, argv);  // recorded in every statistics file (provenance)
  tfu::track_run_files(true);         // an output never replaces an input of this run (cmodel/run_files.hpp)
  CLI::App app{"tfu: texture filter unit model (golden reference, cycle model, ROM and error tools)"};
  app.set_version_flag("--version", std::string("tfu ") + tfu::tool_version());
  app.footer(kExitCodeHelp);
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Print help for every subcommand");
  tfu::cli::register_kernel_error(app);
  tfu::cli::register_rom(app);
  tfu::cli::register_formats(app);
  tfu::cli::register_sample(app);
  tfu::cli::register_mipmap(app);
  tfu::cli::register_report(app);
  tfu::cli::register_compare(app);
  tfu::cli::register_render(app);
  tfu::cli::register_sim(app);
  tfu::cli::register_descriptors(app);
  tfu::cli::register_aniso_compare(app);
  tfu::cli::register_sweep(app);
  int code = tfu::kExitSuccess;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return check_stdout(app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return check_stdout(app.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return check_stdout(app.exit(e));
  } catch (const CLI::ParseError& e) {
    tfu::print_error_line(stderr, "error", e.what());
    code = tfu::kExitBadInput;
  } catch (...) {
    code = tfu::report_error(std::current_exception());
  }
  return check_stdout(code);
}
