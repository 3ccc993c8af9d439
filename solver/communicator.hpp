#pragma once
// The processes one solve runs on. `Communicator::self()` is a single process and never
// calls MPI (a plain `fetic solve` does not even initialize it); `Communicator::world()`
// is MPI_COMM_WORLD once the app has initialized MPI under mpirun.
//
// Every reduction returns the same bits on every process: sums gather one partial per
// process and add them in rank order, so a decision taken from a reduced number (stop,
// restart, a working-set change) is taken alike everywhere. The counters record what a
// solve costs in communication, for the benchmark's cost model.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "solver/exact_sum.hpp"

namespace fetic::solver {

struct CommunicationStats {
  std::int64_t exchanges = 0;       // neighbour exchanges (one per F or M^-1 application)
  std::int64_t messages = 0;        // point-to-point messages sent
  std::int64_t bytes = 0;           // point-to-point bytes sent
  std::int64_t reductions = 0;      // collective reductions of scalars (dot products, flags)
  std::int64_t gathers = 0;         // collective gathers of vectors (coarse problem)
  std::int64_t gathered_bytes = 0;  // bytes this process contributed to gathers
  double exchange_seconds = 0.0;    // time in neighbour exchanges (incl. waiting)
  double reduction_seconds = 0.0;   // time in reductions (incl. waiting for the slowest)
  double gather_seconds = 0.0;      // time in gathers
};

// One neighbour of a point-to-point exchange: the process and how many doubles go each way.
struct ExchangePeer {
  int rank = 0;
  int count = 0;
};

class Communicator {
 public:
  // One process; no MPI call is ever made.
  static const Communicator& self();
  // MPI_COMM_WORLD; only valid after mpi_start() succeeded.
  static const Communicator& world();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool distributed() const { return size_ > 1; }
  bool root() const { return rank_ == 0; }

  // Sum / max over all processes of one value each (the same bits on every process).
  double sum(double value) const;
  void sum(double* values, int count) const;  // element-wise, `count` values at once
  // Exact sums (exact_sum.hpp) over all processes, `count` at once: the same bits for any
  // number of processes and any split of the addends among them.
  void sum(ExactSum* sums, int count) const;
  double max(double value) const;
  double min(double value) const { return -max(-value); }
  long long sum(long long value) const;
  bool any(bool value) const;

  // Agreement on a failure some processes may have seen: each passes the key of its
  // first failure (any int; INT_MAX when it saw none) and its message; every process
  // returns the message of the lowest key (lowest rank on a tie), or "" when none failed.
  std::string first_error(int key, const std::string& message) const;

  // Every process contributes `local`; all receive the concatenation in rank order.
  std::vector<double> all_gather(const std::vector<double>& local) const;
  std::vector<int> all_gather(const std::vector<int>& local) const;
  // Only rank 0 receives the concatenation (others get an empty vector).
  std::vector<double> gather_to_root(const std::vector<double>& local) const;
  std::vector<int> gather_to_root(const std::vector<int>& local) const;
  // Rank 0 is handed each process' `local` in rank order, its own first: take(rank,
  // values). It holds one other process' values at a time, never the concatenation, so
  // that a whole state built from the parts is not held twice (docs/DISTRIBUTED.md,
  // rank 0's peak). The other processes send theirs; `take` runs on rank 0 only.
  void gather_to_root_each(const std::vector<double>& local,
                           const std::function<void(int, const std::vector<double>&)>& take) const;
  // Rank `root`'s value on every process.
  void broadcast(std::string& text, int root = 0) const;
  void broadcast(double& value, int root = 0) const;
  void barrier() const;

  // Point-to-point exchange with neighbours: send[p] goes to peers[p].rank, receive[p]
  // comes from it (peers[p].count doubles each way, the same lists on both sides).
  void exchange(const std::vector<ExchangePeer>& peers, const std::vector<double>& send,
                std::vector<double>& receive) const;
  // Each process sends send[q] to process q and receives receive[q] from it (setup only).
  std::vector<std::vector<double>> all_to_all(const std::vector<std::vector<double>>& send) const;

  CommunicationStats& stats() const { return stats_; }

 private:
  Communicator(int rank, int size) : rank_(rank), size_(size) {}

  int rank_ = 0;
  int size_ = 1;
  mutable CommunicationStats stats_;
};

// The app's side: MPI is initialized only when a launcher (mpirun) started this process,
// so a plain run pays nothing for it. Returns true when MPI is now running.
bool started_by_mpi_launcher();  // solver/mpi_launcher.cpp
// False when fetic was built without MPI (CMake found none: scripts/setup.sh installs
// only what the program needs; scripts/test.sh adds Open MPI): communicator_serial.cpp.
bool mpi_built_in();
bool mpi_start(int* argc, char*** argv);
void mpi_finish();
// Ends every process at once (a failure on one process that the others cannot learn of).
[[noreturn]] void mpi_abort(int status);

}  // namespace fetic::solver
