// Subcommands of the `tfu` command-line tool. Each lives in its own cmd_*.cpp file and adds
// itself to the CLI11 application; main.cpp only wires them together and maps errors to exit codes.
#pragma once

#include <CLI/CLI.hpp>

namespace tfu::cli {

void register_kernel_error(CLI::App& app);  // cmd_kernel_error.cpp: Hadwiger Table 3.5
void register_rom(CLI::App& app);           // cmd_rom.cpp: dump tile / direction ROMs as CSV or hex
void register_formats(CLI::App& app);       // cmd_formats.cpp: number-format error bounds

}  // namespace tfu::cli
