// The Communicator of a fetic built without MPI (CMake found no MPI: scripts/setup.sh
// installs only what the program needs, scripts/test.sh adds Open MPI and builds again).
// Only Communicator::self() exists: every reduction of one process is its own value, every
// gather its own part. Under mpirun such a fetic refuses to run (app/processes.cpp), since
// each process would solve the whole scene alone.
#include <algorithm>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "solver/communicator.hpp"

namespace fetic::solver {

const Communicator& Communicator::self() {
  static const Communicator one(0, 1);
  return one;
}

const Communicator& Communicator::world() {
  throw std::logic_error("Communicator::world(): this fetic was built without MPI");
}

void Communicator::sum(double*, int) const {}
void Communicator::sum(ExactSum*, int) const {}
double Communicator::sum(double value) const {
  return value;
}
double Communicator::max(double value) const {
  return value;
}
long long Communicator::sum(long long value) const {
  return value;
}
bool Communicator::any(bool value) const {
  return value;
}

std::string Communicator::first_error(int key, const std::string& message) const {
  return key == std::numeric_limits<int>::max() ? std::string() : message;
}

std::vector<double> Communicator::all_gather(const std::vector<double>& local) const {
  return local;
}
std::vector<int> Communicator::all_gather(const std::vector<int>& local) const {
  return local;
}
std::vector<double> Communicator::gather_to_root(const std::vector<double>& local) const {
  return local;
}
std::vector<int> Communicator::gather_to_root(const std::vector<int>& local) const {
  return local;
}
void Communicator::gather_to_root_each(
    const std::vector<double>& local,
    const std::function<void(int, const std::vector<double>&)>& take) const {
  take(0, local);
}

void Communicator::broadcast(std::string&, int) const {}
void Communicator::broadcast(double&, int) const {}
void Communicator::barrier() const {}

// The only peer one process can have is itself: what it sends, it receives.
void Communicator::exchange(const std::vector<ExchangePeer>& peers, const std::vector<double>& send,
                            std::vector<double>& receive) const {
  size_t count = 0;
  for (const ExchangePeer& peer : peers)
    count += static_cast<size_t>(peer.count);
  std::copy(send.begin(), send.begin() + static_cast<std::ptrdiff_t>(count), receive.begin());
}

std::vector<std::vector<double>> Communicator::all_to_all(
    const std::vector<std::vector<double>>& send) const {
  return send;
}

bool mpi_built_in() {
  return false;
}
bool mpi_start(int*, char***) {
  return false;
}
void mpi_finish() {}
void mpi_abort(int status) {
  std::_Exit(status);
}

}  // namespace fetic::solver
