#include "app/processes.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "app/exit_codes.hpp"
#include "solver/threads.hpp"

namespace fetic::app {
namespace {

bool under_mpi = false;
int own_stderr = 2;  // this process' standard error, kept when it is silenced

int processes_on_this_node() {
  for (const char* name : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS", "SLURM_NTASKS_PER_NODE"})
    if (const char* value = std::getenv(name)) {
      const int n = std::atoi(value);
      if (n > 0) return n;
    }
  return 1;
}

}  // namespace

bool start_processes(int* argc, char*** argv) {
  // FETIC_FORCE_MPI_INIT=1 initializes MPI even without a launcher (a singleton): the
  // benchmark measures what starting MPI always would cost.
  if (!solver::started_by_mpi_launcher() && !std::getenv("FETIC_FORCE_MPI_INIT")) {
    solver::set_thread_budget_for(1);
    return true;
  }
  if (!solver::mpi_built_in()) {
    std::fprintf(stderr,
                 "fetic: started by an MPI launcher, but this fetic was built without MPI "
                 "(each process would solve the whole scene alone); install Open MPI and "
                 "build again: scripts/test.sh does both\n");
    return false;
  }
  if (!solver::mpi_start(argc, argv)) {
    std::fprintf(stderr, "fetic: started by an MPI launcher, but MPI_Init failed\n");
    return false;
  }
  under_mpi = true;
  solver::set_thread_budget_for(processes_on_this_node());
  if (!solver::Communicator::world().root()) {
    // Only rank 0 speaks: the others' standard output and error go to /dev/null (so
    // their writes succeed, and nothing counts as lost).
    std::fflush(nullptr);
    own_stderr = dup(2);
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, 1);
      dup2(null, 2);
      close(null);
    }
  }
  return true;
}

void finish_processes(int status) {
  if (!under_mpi) return;
  if (status == kExitInterrupted) {
    std::cout.flush();
    std::fflush(nullptr);
    std::_Exit(status);
  }
  solver::mpi_finish();
}

const solver::Communicator& processes() {
  return under_mpi ? solver::Communicator::world() : solver::Communicator::self();
}

void report_from_any_rank(const std::string& message) {
  const std::string line = message + "\n";
  if (write(own_stderr, line.data(), line.size()) < 0) {
    // Nowhere left to say it.
  }
}

}  // namespace fetic::app
