// tfu: command-line front end of the texture filter unit model.
//
// Exit codes (README "Exit codes", `tfu --help`): 0 success; 1 an output differs from the golden
// model or a measured value fails its threshold; 2 bad input or usage; 3 internal error (a bug:
// please report it); 4 deadlock of the cycle model. Every error is one line on stderr of at most 300
// characters that names the offending input (cmodel/error_report.hpp).
#include <csignal>
#include <cstdio>
#include <exception>
#include <iostream>
#include <regex>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cmodel/error.hpp"
#include "cmodel/error_report.hpp"
#include "cmodel/memory_budget.hpp"
#include "cmodel/nearest_name.hpp"
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

// No option takes an empty value (TFU-S E12): an empty string is what "not given" is held as, so
// `--out ''` drew to the default path and `--scene ''` rendered the default scene. Every option of
// every subcommand that takes a value gets the check, so a new option cannot forget it.
void refuse_empty_values(CLI::App& app) {
  const CLI::Validator non_empty([](std::string& text) { return text.empty() ? std::string("an empty value names nothing") : std::string(); },
                                 "");
  for (CLI::Option* opt : app.get_options([](CLI::Option* o) { return o->get_type_size_max() > 0; })) opt->check(non_empty);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) refuse_empty_values(*sub);
}

// --memory-budget SIZE on every subcommand (cmodel/memory_budget.hpp; TFU-S E11).
void add_memory_budget_option(CLI::App& app) {
  const std::string help = fmt::format("Memory budget for decoded texels and request traces, e.g. 8G or 512M (default: 3/4 of "
                                       "this machine's memory and limits, here {})",
                                       tfu::memory_size_text(tfu::default_memory_budget()));
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    sub->add_option_function<std::string>(
           "--memory-budget", [](const std::string& text) { tfu::set_memory_budget(tfu::parse_memory_size(text, "--memory-budget")); },
           help)
        ->check(CLI::Validator(
            [](std::string& text) {
              try {
                (void)tfu::parse_memory_size(text, "--memory-budget");
              } catch (const tfu::InputError& e) {
                const std::string m = e.what();
                return m.substr(m.find(": ") + 2);
              }
              return std::string();
            },
            ""))
        ->type_name("SIZE");
}

std::vector<std::string> command_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
  return names;
}

// A usage error in words that help (the user's next step, a near name), from CLI11's exception and
// the command line. CLI11's own text is kept where nothing better is known.
std::string usage_error_text(const CLI::App& app, int argc, char** argv, const CLI::ParseError& e) {
  const std::vector<std::string> commands = command_names(app);
  const std::string command_list = fmt::format("{}", fmt::join(commands, ", "));
  std::vector<CLI::App*> parsed = const_cast<CLI::App&>(app).get_subcommands();
  if (parsed.empty()) {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a.empty() || a[0] == '-') continue;
      return fmt::format("unknown command '{}' ({}commands: {}; `tfu help COMMAND` shows a command's options)",
                         tfu::quote_input(a, 40), tfu::did_you_mean(a, commands), command_list);
    }
    return fmt::format("a command is required (commands: {}; `tfu help COMMAND` shows a command's options)", command_list);
  }
  const CLI::App& sub = *parsed.front();
  std::vector<std::string> options;
  for (const CLI::Option* o : sub.get_options({}))
    for (const std::string& n : o->get_lnames()) options.push_back("--" + n);
  if (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr) {
    for (int i = 1; i < argc; ++i) {
      std::string a = argv[i];
      if (a.rfind("--", 0) != 0 || a == "--") continue;
      a = a.substr(0, a.find('='));
      if (const_cast<CLI::App&>(sub).get_option_no_throw(a) != nullptr) continue;
      return fmt::format("unknown option '{}' of tfu {} ({}`tfu help {}` lists its options)", tfu::quote_input(a, 40),
                         sub.get_name(), tfu::did_you_mean(a, options), sub.get_name());
    }
  }
  if (dynamic_cast<const CLI::ConversionError*>(&e) != nullptr) {
    // CLI11 2.1: "Could not convert: --width = 1280x720"
    static const std::regex form("Could not convert: (--[A-Za-z0-9-]+) = (.*)");
    std::smatch m;
    const std::string what = e.what();
    if (std::regex_match(what, m, form)) {
      const std::string name = m[1], value = m[2];
      const CLI::Option* o = const_cast<CLI::App&>(sub).get_option_no_throw(name);
      const std::string type = o != nullptr ? o->get_type_name() : std::string();
      std::string text = fmt::format("{} '{}': expected {}", name, tfu::quote_input(value, 40),
                                     type == "UINT" ? "an integer >= 0" : type == "INT" ? "an integer" : "a number");
      static const std::regex size_form("([0-9]+)[xX*]([0-9]+)");
      std::smatch sz;
      if ((name == "--width" || name == "--height") && std::regex_match(value, sz, size_form))
        text += fmt::format(" (a size is two options: --width {} --height {})", sz[1].str(), sz[2].str());
      return text;
    }
  }
  return e.what();
}

// `tfu help [COMMAND]`: the help of the tool or of one command, as --help prints it.
int print_help(const CLI::App& app, int argc, char** argv) {
  if (argc <= 2) {
    std::cout << app.help();
    return tfu::kExitSuccess;
  }
  const std::string name = argv[2];
  for (const CLI::App* sub : app.get_subcommands({}))
    if (sub->get_name() == name) {
      std::cout << sub->help();
      return tfu::kExitSuccess;
    }
  const std::vector<std::string> commands = command_names(app);
  tfu::print_error_line(stderr, "error", fmt::format("unknown command '{}' ({}commands: {})", tfu::quote_input(name, 40),
                                                     tfu::did_you_mean(name, commands), fmt::join(commands, ", ")));
  return tfu::kExitBadInput;
}

}  // namespace

namespace tfu::cli {

void print_summary_line(const std::string& line) {
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) throw InputError("cannot write to standard output");
  std::fputs((line + "\n").c_str(), stderr);
}

}  // namespace tfu::cli

int main(int argc, char** argv) {
  // A closed pipe behind stdout (`tfu rom --tile 4 | head -1`) is reported as every output error is
  // (check_stdout: exit 2, one line), not by SIGPIPE's exit 141 (TFU-S E15).
  std::signal(SIGPIPE, SIG_IGN);
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
  tfu::cli::register_compress(app);
  tfu::cli::register_report(app);
  tfu::cli::register_compare(app);
  tfu::cli::register_render(app);
  tfu::cli::register_sim(app);
  tfu::cli::register_descriptors(app);
  tfu::cli::register_aniso_compare(app);
  tfu::cli::register_sweep(app);
  add_memory_budget_option(app);
  refuse_empty_values(app);
  if (argc >= 2 && std::string(argv[1]) == "help") return check_stdout(print_help(app, argc, argv));
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
    tfu::print_error_line(stderr, "error", usage_error_text(app, argc, argv, e));
    code = tfu::kExitBadInput;
  } catch (...) {
    code = tfu::report_error(std::current_exception());
  }
  return check_stdout(code);
}
