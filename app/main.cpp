// fetic: frictionless contact of elastic struts solved by dual domain decomposition.
// The command line only wires the layers together; each command lives in its own file.

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include "app/exit_codes.hpp"
#include "app/processes.hpp"
#include "app/run_command_line.hpp"
#include "scenes/scene_error.hpp"

namespace {

// Under mpirun only `fetic solve` runs distributed; every other command is refused
// before anything is loaded, with one message (rank 0) and status 1 on every process.
bool refuse_under_mpi(int argc, char** argv) {
  if (!fetic::app::processes().distributed()) return false;
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "solve" || command == "--help" || command == "-h" || command == "--version" ||
      command == "-v")
    return false;
  std::cerr << "fetic " << fetic::scenes::printable(command)
            << " runs in one process: start it without mpirun "
            << "(under mpirun only 'fetic solve' runs, distributed over the processes)\n";
  return true;
}

}  // namespace

// libgomp's threads spin at every barrier unless OMP_WAIT_POLICY says otherwise, and on a
// shared machine a spinning thread whose partner's core another process holds waits for
// the scheduler at every barrier: 30 warm-started FETI-C solves of a 2,000-pair bar scene
// (8,000 tiny subdomains, many short parallel loops) took 2.4-8.2 s with the default
// against 1.5 s passive while another process held a core; the window's own render threads
// are such a process. libgomp reads the variable while the program is loaded, before
// main() runs (and the C library's start-up discards an environment changed earlier), so
// fetic sets it and executes itself again, once: about 20 ms. A policy the user set wins.
// When the executable cannot be run again, the run goes on with libgomp's default.
void use_passive_openmp_threads(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY")) return;
  // Under valgrind the new program would run outside it (valgrind follows no exec by
  // default): keep the process it watches.
  if (const char* preload = std::getenv("LD_PRELOAD"); preload && std::strstr(preload, "vgpreload"))
    return;
  char path[4096];
  const ssize_t length = ::readlink("/proc/self/exe", path, sizeof path - 1);
  if (length <= 0) return;
  path[length] = '\0';  // the file itself, not /proc/self/exe: ps and top then say "fetic"
  ::setenv("OMP_WAIT_POLICY", "passive", 1);
  ::execv(path, argv);
  ::unsetenv("OMP_WAIT_POLICY");  // not run again: libgomp keeps its default
}

int main(int argc, char** argv) {
  use_passive_openmp_threads(argv);
  if (!fetic::app::start_processes(&argc, &argv)) return fetic::app::kExitUsage;
  const int status = [&] {
    if (refuse_under_mpi(argc, argv)) return static_cast<int>(fetic::app::kExitUsage);
    return fetic::app::run_command_line(argc, argv);
  }();
  fetic::app::finish_processes(status);
  return status;
}
