// tfu: command-line front end of the texture filter unit model.
//
// Exit codes: 0 success, 1 a check failed (e.g. a golden compare mismatch), 2 bad input
// (unknown option or value, unreadable file, malformed data). Every error is one line on stderr
// that names the offending input.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "cmodel/error.hpp"
#include "sim/sweep/provenance.hpp"
#include "sim/sweep/version.hpp"
#include "sim/tfu/commands.hpp"

int main(int argc, char** argv) {
  tfu::set_command_line(argc, argv);  // recorded in every statistics file (provenance)
  CLI::App app{"tfu: texture filter unit model (golden reference, cycle model, ROM and error tools)"};
  app.set_version_flag("--version", std::string("tfu ") + tfu::tool_version());
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "tfu: error: %s\n", e.what());
    return tfu::kExitBadInput;
  } catch (const tfu::InputError& e) {
    std::fprintf(stderr, "tfu: error: %s\n", e.what());
    return tfu::kExitBadInput;
  } catch (const tfu::CheckFailed& e) {
    std::fprintf(stderr, "tfu: check failed: %s\n", e.what());
    return tfu::kExitCheckFailed;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tfu: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
