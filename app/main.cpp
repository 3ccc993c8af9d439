// fetic: frictionless contact of elastic struts solved by dual domain decomposition.
// The command line only wires the layers together; each command lives in its own file.

#include <iostream>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/help_text.hpp"
#include "app/interrupt.hpp"

int main(int argc, char** argv) {
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? fetic::app::kExitOk : fetic::app::kExitUsage;
  }
  return exit_code;
}
