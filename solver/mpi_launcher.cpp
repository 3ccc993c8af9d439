// Whether an MPI launcher started this process: asked by the app whether or not fetic was
// built with MPI (without it, the app then refuses to run: communicator_serial.cpp).
#include <cstdlib>

#include "solver/communicator.hpp"

namespace fetic::solver {

bool started_by_mpi_launcher() {
  // Open MPI's mpirun sets OMPI_COMM_WORLD_SIZE; PMIx- and PMI-based launchers (srun,
  // MPICH's hydra) set PMIX_RANK or PMI_SIZE.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

}  // namespace fetic::solver
