// tfu descriptors: the register layout of the texture and sampler descriptors (fields, words, bits,
// reset values) as Markdown, from the field tables of cmodel/descriptors.cpp (docs/descriptors.md
// shows this output).
#include <iostream>

#include "cmodel/descriptors.hpp"
#include "sim/tfu/commands.hpp"

namespace tfu::cli {

void register_descriptors(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("descriptors", "Print the texture and sampler descriptor register layouts (Markdown)");
  cmd->callback([] { std::cout << descriptor_tables_markdown(); });
}

}  // namespace tfu::cli
