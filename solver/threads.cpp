#include "solver/threads.hpp"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>

#include <Eigen/Core>
#include <omp.h>

namespace fetic::solver {
namespace {

int cores_available() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1, omp_get_num_procs());
}

int initial_budget() {
  if (std::getenv("OMP_NUM_THREADS")) return std::max(1, omp_get_max_threads());
  return cores_available();
}

int budget = initial_budget();

}  // namespace

int thread_budget() { return budget; }

void set_thread_budget(int threads) {
  budget = std::max(1, threads);
  Eigen::setNbThreads(budget);  // Eigen's dense products (the active set's Schur complement)
}

void set_thread_budget_for(int processes_per_node) {
  if (std::getenv("OMP_NUM_THREADS")) {
    set_thread_budget(omp_get_max_threads());
    return;
  }
  // A process bound to fewer cores than the machine has (mpirun's binding) uses them all;
  // unbound processes share the machine's cores.
  const int cores = cores_available();
  const bool bound = cores < std::max(1L, sysconf(_SC_NPROCESSORS_ONLN));
  set_thread_budget(bound ? cores : std::max(1, cores / std::max(1, processes_per_node)));
}

int threads_for(long long work) {
  if (budget <= 1 || work < 2 * kWorkPerThread) return 1;
  return static_cast<int>(std::min<long long>(budget, work / kWorkPerThread));
}

}  // namespace fetic::solver
