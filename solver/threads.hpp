#pragma once
// How many OpenMP threads a parallel loop gets. Threads cost more than they bring on
// small work: a team's start and its barriers wait for every thread, and on a shared
// machine a thread whose core another process holds makes each barrier wait for the
// scheduler (a 500-unknown solve took 100 ms instead of 1.4 ms with one core busy). So
// a loop runs on one thread below kWorkPerThread units of work (about a microsecond
// each: a DOF of a local solve, a row), and never on more threads than the budget.
//
// The budget: OMP_NUM_THREADS when set; otherwise the cores this process may run on
// (its CPU affinity mask), divided among the processes of one solve that share the
// machine (MPI ranks on one node). A process that mpirun bound to one core thus gets
// one thread.

namespace fetic::solver {

constexpr long long kWorkPerThread = 20000;

int thread_budget();
// Sets the budget from the environment for `processes_per_node` processes on this machine.
void set_thread_budget_for(int processes_per_node);
void set_thread_budget(int threads);
// Threads for a loop doing `work` units.
int threads_for(long long work);

}  // namespace fetic::solver
