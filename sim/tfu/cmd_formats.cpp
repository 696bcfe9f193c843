// PLACEHOLDER: replaced by the real subcommand in this same change.
#include "sim/tfu/commands.hpp"
namespace tfu::cli {
void register_formats(CLI::App&) {}
}
