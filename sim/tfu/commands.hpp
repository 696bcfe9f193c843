// Subcommands of the `tfu` command-line tool. Each lives in its own cmd_*.cpp file and adds
// itself to the CLI11 application; main.cpp only wires them together and maps errors to exit codes.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace tfu::cli {

void register_kernel_error(CLI::App& app);  // cmd_kernel_error.cpp: Hadwiger Table 3.5
void register_rom(CLI::App& app);           // cmd_rom.cpp: dump tile / direction ROMs as CSV or hex
void register_formats(CLI::App& app);       // cmd_formats.cpp: number-format error bounds
void register_sample(CLI::App& app);        // cmd_sample.cpp: golden sampler on a request trace
void register_report(CLI::App& app);        // cmd_report.cpp: every scene x mode, montages, results.md
void register_mipmap(CLI::App& app);        // cmd_mipmap.cpp: MIP chain generation
void register_compare(CLI::App& app);       // cmd_compare.cpp: `compare` (PSNR, SSIM, heat map) and `montage`
void register_sim(CLI::App& app);           // cmd_sim.cpp: cycle model vs golden, statistics
void register_render(CLI::App& app);        // cmd_render.cpp: scene renderer (images, traces, ground truth)
void register_descriptors(CLI::App& app);   // cmd_descriptors.cpp: descriptor register layouts
void register_aniso_compare(CLI::App& app); // cmd_aniso_compare.cpp: anisotropic filtering vs OpenImageIO
void register_sweep(CLI::App& app);         // cmd_sweep.cpp: `sweep` (design-space sweeps, Slurm) and `plot`
void register_compress(CLI::App& app);       // cmd_compress.cpp: `compress` and `decompress` (DDS, KTX, .astc files)

// A command's closing summary on stderr ("tfu render: 1024 triangles ..."), after its outputs: stdout
// is flushed and checked first, so that when it fails (a full disk, a closed pipe) the error is the
// only line on stderr, not the second (TFU-S E14). Throws InputError("cannot write to standard output").
void print_summary_line(const std::string& line);

// Output files go through tfu::OutputFiles (cmodel/output_files.hpp), input files through
// cmodel/input_file.hpp: one place each for every command.

}  // namespace tfu::cli
