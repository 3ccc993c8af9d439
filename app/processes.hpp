#pragma once
// The processes fetic runs as. Started by mpirun (or another MPI launcher) it initializes
// MPI and `fetic solve` distributes the dual methods over the processes; started
// directly it is one process and never touches MPI (MPI_Init alone costs 0.5 s here).
//
// Under MPI only rank 0 speaks: the other processes' standard output and error are
// silenced at start, and every message a solve prints comes from rank 0 after the
// processes have agreed on it (a failure on any process is reported once, by rank 0,
// and every process exits with the same status).

#include <string>

#include "solver/communicator.hpp"

namespace fetic::app {

// Initializes MPI when a launcher started this process, sets the thread budget per
// process, silences ranks other than 0. Returns false (after saying why) when MPI could
// not start.
bool start_processes(int* argc, char*** argv);
// MPI_Finalize when MPI runs. After an interrupt (status 130) it exits at once instead:
// mpirun is then tearing the job down, and MPI_Finalize would wait for it (seconds).
void finish_processes(int status);
// The processes of this run: Communicator::world() under MPI, else self().
const solver::Communicator& processes();
// Prints `message` on this process' own standard error even when it is not rank 0 (for
// a failure only this process saw, which ends the whole run through mpi_abort).
void report_from_any_rank(const std::string& message);

}  // namespace fetic::app
