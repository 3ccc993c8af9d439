// fetic: frictionless contact of elastic struts solved by dual domain decomposition.
// The command line only wires the layers together; each command lives in its own file.

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include "app/exit_codes.hpp"
#include "app/heap_policy.hpp"
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

// glibc's malloc asks for transparent huge pages on its heaps only when the tunable
// glibc.malloc.hugetlb=1 is given, read at start-up like OMP_WAIT_POLICY. On the microVMs
// fetic is measured on (THP "madvise") each first touch of a 4 KiB page costs 10-30 us;
// the kept factors come from solver/huge_pages, but incidence, G, R_j, the preconditioner's
// blocks, the model and the outputs are heap memory: at 984,900 unknowns the tunable takes
// the minor faults from about 67,000 to 27,000 at the same peak (docs/BENCHMARKS.md). A
// hugetlb setting of the user's wins (GLIBC_TUNABLES=glibc.malloc.hugetlb=0 turns it off).
void add_malloc_huge_pages(const std::string& given) {
  if (given.find("glibc.malloc.hugetlb") != std::string::npos) return;
  const std::string tunables =
      given.empty() ? "glibc.malloc.hugetlb=1" : given + ":glibc.malloc.hugetlb=1";
  ::setenv("GLIBC_TUNABLES", tunables.c_str(), 1);
}

// libgomp's threads spin at every barrier unless OMP_WAIT_POLICY says otherwise, and on a
// shared machine a spinning thread whose partner's core another process holds waits for
// the scheduler at every barrier: 30 warm-started FETI-C solves of a 2,000-pair bar scene
// (8,000 tiny subdomains, many short parallel loops) took 2.4-8.2 s with the default
// against 1.5 s passive while another process held a core; the window's own render threads
// are such a process. libgomp reads the variable while the program is loaded, before
// main() runs (and the C library's start-up discards an environment changed earlier), so
// fetic sets it and executes itself again, once: about 20 ms. A policy the user set wins.
// When the executable cannot be run again, the run goes on with libgomp's default.
// The same start sets glibc's malloc tunable (add_malloc_huge_pages).
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
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string given = tunables ? tunables : "";
  ::setenv("OMP_WAIT_POLICY", "passive", 1);
  add_malloc_huge_pages(given);
  ::execv(path, argv);
  ::unsetenv("OMP_WAIT_POLICY");  // not run again: libgomp keeps its default
  if (tunables)
    ::setenv("GLIBC_TUNABLES", given.c_str(), 1);
  else
    ::unsetenv("GLIBC_TUNABLES");
}

int main(int argc, char** argv) {
  use_passive_openmp_threads(argv);
  fetic::app::keep_freed_heap_for_reuse();
  if (!fetic::app::start_processes(&argc, &argv)) return fetic::app::kExitUsage;
  const int status = [&] {
    if (refuse_under_mpi(argc, argv)) return static_cast<int>(fetic::app::kExitUsage);
    return fetic::app::run_command_line(argc, argv);
  }();
  fetic::app::finish_processes(status);
  return status;
}
