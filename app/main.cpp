// fetic: frictionless contact of elastic struts solved by dual domain decomposition.
// The command line only wires the layers together; each command lives in its own file.

#include <iostream>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "app/processes.hpp"

namespace {

// Under mpirun only `fetic solve` runs distributed; every other command is refused
// before anything is loaded, with one message (rank 0) and status 1 on every process.
bool refuse_under_mpi(int argc, char** argv) {
  if (!fetic::app::processes().distributed()) return false;
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "solve" || command == "--help" || command == "-h" || command == "--version")
    return false;
  std::cerr << "fetic " << command << " runs in one process: start it without mpirun "
            << "(under mpirun only 'fetic solve' runs, distributed over the processes)\n";
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (!fetic::app::start_processes(&argc, &argv)) return fetic::app::kExitUsage;
  const int status = [&] {
    if (refuse_under_mpi(argc, argv)) return static_cast<int>(fetic::app::kExitUsage);
    return fetic::app::run_command_line(argc, argv);
  }();
  fetic::app::finish_processes(status);
  return status;
}

int fetic::app::run_command_line(int argc, char** argv) {
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? fetic::app::kExitOk : fetic::app::kExitUsage;
  }
  return exit_code;
}
