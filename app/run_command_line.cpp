// The command line: every command registered on one CLI11 app, parsed, and the errors
// CLI11 leaves to the caller reported. Apart from main.cpp (the process: OpenMP policy,
// MPI start) so that CLI11's header-only code compiles in a unity batch of the app
// library with the other files that use it, not once more for the executable.

#include <iostream>
#include <new>
#include <string>

#include <CLI/CLI.hpp>

#include "app/command_line_help.hpp"
#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/help_text.hpp"
#include "app/interrupt.hpp"
#include "app/out_of_memory.hpp"
#include "app/run_command_line.hpp"
#include "app/standard_streams.hpp"
#include "app/version.hpp"
#include "scenes/scene_error.hpp"
#include "solver/interruption.hpp"

namespace fetic::app {
namespace {

// CLI11 reports an unknown command as "A subcommand is required": name it instead.
bool known_command(const CLI::App& app, const std::string& word) {
  for (const CLI::App* command : app.get_subcommands({}))
    if (command->check_name(word)) return true;
  return false;
}

}  // namespace

int run_command_line(int argc, char** argv) {
  guard_standard_streams();
  install_out_of_memory_handler();
  CLI::App app{"fetic - frictionless contact of elastic struts by FETI and FETI-C"};
  app.require_subcommand(1);
  app.set_version_flag("-v,--version", std::string("fetic ") + fetic_version());
  install_interrupt_handlers();
  int exit_code = kExitOk;
  register_solve(app, exit_code);
  register_bench(app, exit_code);
  register_generate(app, exit_code);
  register_render(app, exit_code);
  register_figures(app, exit_code);
  register_bench_render(app, exit_code);
  register_gui(app, exit_code);
  register_scenes(app, exit_code);
  register_help(app, exit_code);
  add_help_footers(app);
  if (argc > 1 && argv[1][0] != '-' && !known_command(app, argv[1])) {
    std::string commands;
    for (const CLI::App* command : app.get_subcommands({}))
      commands += (commands.empty() ? "" : ", ") + command->get_name();
    std::cerr << "fetic: unknown command '" << scenes::printable(argv[1])
              << "' (commands: " << commands << "; fetic --help)\n";
    return kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ExtrasError& error) {
    const std::string message = unknown_option_message(app, argc, argv);
    if (message.empty()) return finish_standard_output(app.exit(error) == 0 ? kExitOk : kExitUsage);
    std::cerr << message;
    return finish_standard_output(kExitUsage);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return finish_standard_output(code == 0 ? kExitOk : kExitUsage);
  } catch (const std::bad_alloc&) {
    return finish_standard_output(report_out_of_memory());
  } catch (const solver::SetupInterrupted& stop) {
    // Ctrl-C in a set-up step (solver/interruption.hpp): before any output was opened.
    std::cerr << "fetic: interrupted by " << interrupt_name() << " while " << stop.during()
              << "; nothing was written\n";
    return finish_standard_output(kExitInterrupted);
  }
  return finish_standard_output(exit_code);
}

}  // namespace fetic::app
