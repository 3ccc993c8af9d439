// fetic: frictionless contact of elastic struts solved by dual domain decomposition.
// The command line only wires the layers together; each command lives in its own file.

#include <iostream>
#include <new>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/help_text.hpp"
#include "app/interrupt.hpp"
#include "app/out_of_memory.hpp"
#include "app/standard_streams.hpp"
#include "scenes/scene_error.hpp"

namespace {

// CLI11 reports an unknown command as "A subcommand is required": name it instead.
bool known_command(const CLI::App& app, const std::string& word) {
  for (const CLI::App* command : app.get_subcommands({}))
    if (command->check_name(word)) return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  fetic::app::guard_standard_streams();
  fetic::app::install_out_of_memory_handler();
  CLI::App app{"fetic - frictionless contact of elastic struts by FETI and FETI-C"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "fetic 0.1.0");
  fetic::app::install_interrupt_handlers();
  int exit_code = fetic::app::kExitOk;
  fetic::app::register_solve(app, exit_code);
  fetic::app::register_bench(app, exit_code);
  fetic::app::register_generate(app, exit_code);
  fetic::app::register_render(app, exit_code);
  fetic::app::register_figures(app, exit_code);
  fetic::app::register_bench_render(app, exit_code);
  fetic::app::register_gui(app, exit_code);
  fetic::app::add_help_footers(app);
  if (argc > 1 && argv[1][0] != '-' && !known_command(app, argv[1])) {
    std::string commands;
    for (const CLI::App* command : app.get_subcommands({}))
      commands += (commands.empty() ? "" : ", ") + command->get_name();
    std::cerr << "fetic: unknown command '" << fetic::scenes::printable(argv[1])
              << "' (commands: " << commands << "; fetic --help)\n";
    return fetic::app::kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return fetic::app::finish_standard_output(code == 0 ? fetic::app::kExitOk
                                                        : fetic::app::kExitUsage);
  } catch (const std::bad_alloc&) {
    return fetic::app::finish_standard_output(fetic::app::report_out_of_memory());
  }
  return fetic::app::finish_standard_output(exit_code);
}
