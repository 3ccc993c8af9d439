#include "solver/communicator.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <mpi.h>

#include "solver/stopwatch.hpp"

namespace fetic::solver {
namespace {

bool mpi_running = false;

template <class T>
MPI_Datatype mpi_type();
template <>
MPI_Datatype mpi_type<double>() {
  return MPI_DOUBLE;
}
template <>
MPI_Datatype mpi_type<int>() {
  return MPI_INT;
}

// Counts and displacements of a gather of `local_count` items from each process.
std::vector<int> gather_counts(int local_count, int size) {
  std::vector<int> counts(size);
  MPI_Allgather(&local_count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  return counts;
}

std::vector<int> offsets_of(const std::vector<int>& counts) {
  std::vector<int> offsets(counts.size(), 0);
  for (size_t q = 1; q < counts.size(); ++q)
    offsets[q] = offsets[q - 1] + counts[q - 1];
  return offsets;
}

template <class T>
std::vector<T> all_gather_impl(const std::vector<T>& local, int size, CommunicationStats& stats) {
  Stopwatch timer(stats.gather_seconds);
  ++stats.gathers;
  stats.gathered_bytes += static_cast<std::int64_t>(local.size() * sizeof(T));
  const std::vector<int> counts = gather_counts(static_cast<int>(local.size()), size);
  const std::vector<int> offsets = offsets_of(counts);
  std::vector<T> all(static_cast<size_t>(offsets.back() + counts.back()));
  MPI_Allgatherv(local.data(), static_cast<int>(local.size()), mpi_type<T>(), all.data(),
                 counts.data(), offsets.data(), mpi_type<T>(), MPI_COMM_WORLD);
  return all;
}

template <class T>
std::vector<T> gather_to_root_impl(const std::vector<T>& local, int rank, int size,
                                   CommunicationStats& stats) {
  Stopwatch timer(stats.gather_seconds);
  ++stats.gathers;
  stats.gathered_bytes += static_cast<std::int64_t>(local.size() * sizeof(T));
  const int count = static_cast<int>(local.size());
  std::vector<int> counts(rank == 0 ? size : 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<T> all;
  std::vector<int> offsets;
  if (rank == 0) {
    offsets = offsets_of(counts);
    all.resize(static_cast<size_t>(offsets.back() + counts.back()));
  }
  MPI_Gatherv(local.data(), count, mpi_type<T>(), all.data(), counts.data(), offsets.data(),
              mpi_type<T>(), 0, MPI_COMM_WORLD);
  return all;
}

}  // namespace

const Communicator& Communicator::self() {
  static const Communicator one(0, 1);
  return one;
}

const Communicator& Communicator::world() {
  if (!mpi_running) throw std::logic_error("Communicator::world() before mpi_start()");
  static const Communicator world = [] {
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    return Communicator(rank, size);
  }();
  return world;
}

void Communicator::sum(double* values, int count) const {
  if (size_ == 1) return;
  Stopwatch timer(stats_.reduction_seconds);
  ++stats_.reductions;
  // Gather every process' partials and add them in rank order: the same bits everywhere
  // (MPI_Allreduce may combine in an order that differs between processes).
  std::vector<double> all(static_cast<size_t>(count) * size_);
  MPI_Allgather(values, count, MPI_DOUBLE, all.data(), count, MPI_DOUBLE, MPI_COMM_WORLD);
  for (int i = 0; i < count; ++i) {
    double total = 0.0;
    for (int q = 0; q < size_; ++q)
      total += all[static_cast<size_t>(q) * count + i];
    values[i] = total;
  }
}

void Communicator::sum(ExactSum* sums, int count) const {
  if (size_ == 1) return;
  Stopwatch timer(stats_.reduction_seconds);
  ++stats_.reductions;
  std::vector<std::int64_t> words(static_cast<size_t>(count) * ExactSum::kWords);
  for (int i = 0; i < count; ++i)
    sums[i].to_words(words.data() + static_cast<size_t>(i) * ExactSum::kWords);
  // Integer addition is exact in any order, so MPI_Allreduce is safe here.
  MPI_Allreduce(MPI_IN_PLACE, words.data(), static_cast<int>(words.size()), MPI_INT64_T, MPI_SUM,
                MPI_COMM_WORLD);
  for (int i = 0; i < count; ++i)
    sums[i].from_words(words.data() + static_cast<size_t>(i) * ExactSum::kWords);
}

double Communicator::sum(double value) const {
  sum(&value, 1);
  return value;
}

double Communicator::max(double value) const {
  if (size_ == 1) return value;
  Stopwatch timer(stats_.reduction_seconds);
  ++stats_.reductions;
  double result = value;
  MPI_Allreduce(&value, &result, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);  // exact: max
  return result;
}

long long Communicator::sum(long long value) const {
  if (size_ == 1) return value;
  Stopwatch timer(stats_.reduction_seconds);
  ++stats_.reductions;
  long long result = value;
  MPI_Allreduce(&value, &result, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);  // exact: integers
  return result;
}

bool Communicator::any(bool value) const {
  if (size_ == 1) return value;
  Stopwatch timer(stats_.reduction_seconds);
  ++stats_.reductions;
  int local = value ? 1 : 0, result = 0;
  MPI_Allreduce(&local, &result, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
  return result != 0;
}

std::vector<double> Communicator::all_gather(const std::vector<double>& local) const {
  if (size_ == 1) return local;
  return all_gather_impl(local, size_, stats_);
}

std::vector<int> Communicator::all_gather(const std::vector<int>& local) const {
  if (size_ == 1) return local;
  return all_gather_impl(local, size_, stats_);
}

std::vector<double> Communicator::gather_to_root(const std::vector<double>& local) const {
  if (size_ == 1) return local;
  return gather_to_root_impl(local, rank_, size_, stats_);
}

std::vector<int> Communicator::gather_to_root(const std::vector<int>& local) const {
  if (size_ == 1) return local;
  return gather_to_root_impl(local, rank_, size_, stats_);
}

void Communicator::broadcast(std::string& text, int root) const {
  if (size_ == 1) return;
  unsigned long long length = text.size();
  MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, root, MPI_COMM_WORLD);
  text.resize(length);
  if (length > 0) MPI_Bcast(text.data(), static_cast<int>(length), MPI_CHAR, root, MPI_COMM_WORLD);
}

void Communicator::broadcast(double& value, int root) const {
  if (size_ == 1) return;
  MPI_Bcast(&value, 1, MPI_DOUBLE, root, MPI_COMM_WORLD);
}

std::string Communicator::first_error(int key, const std::string& message) const {
  constexpr int kNone = std::numeric_limits<int>::max();
  if (size_ == 1) return key == kNone ? std::string() : message;
  const std::vector<int> keys = all_gather(std::vector<int>{key});
  int holder = -1;
  for (int q = 0; q < size_; ++q)
    if (keys[q] != kNone && (holder < 0 || keys[q] < keys[holder])) holder = q;
  if (holder < 0) return {};
  std::string text = message;
  broadcast(text, holder);
  return text;
}

void Communicator::barrier() const {
  if (size_ > 1) MPI_Barrier(MPI_COMM_WORLD);
}

void Communicator::exchange(const std::vector<ExchangePeer>& peers, const std::vector<double>& send,
                            std::vector<double>& receive) const {
  if (peers.empty()) return;
  Stopwatch timer(stats_.exchange_seconds);
  ++stats_.exchanges;
  std::vector<MPI_Request> requests(2 * peers.size());
  int offset = 0;
  for (size_t p = 0; p < peers.size(); ++p) {
    MPI_Irecv(receive.data() + offset, peers[p].count, MPI_DOUBLE, peers[p].rank, 0, MPI_COMM_WORLD,
              &requests[2 * p]);
    MPI_Isend(send.data() + offset, peers[p].count, MPI_DOUBLE, peers[p].rank, 0, MPI_COMM_WORLD,
              &requests[2 * p + 1]);
    offset += peers[p].count;
    ++stats_.messages;
    stats_.bytes += static_cast<std::int64_t>(peers[p].count) * 8;
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

std::vector<std::vector<double>> Communicator::all_to_all(
    const std::vector<std::vector<double>>& send) const {
  if (size_ == 1) return send;
  std::vector<int> send_counts(size_), receive_counts(size_);
  for (int q = 0; q < size_; ++q)
    send_counts[q] = static_cast<int>(send[q].size());
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  const std::vector<int> send_offsets = offsets_of(send_counts);
  const std::vector<int> receive_offsets = offsets_of(receive_counts);
  std::vector<double> flat_send;
  for (const auto& part : send)
    flat_send.insert(flat_send.end(), part.begin(), part.end());
  std::vector<double> flat_receive(
      static_cast<size_t>(receive_offsets.back() + receive_counts.back()));
  MPI_Alltoallv(flat_send.data(), send_counts.data(), send_offsets.data(), MPI_DOUBLE,
                flat_receive.data(), receive_counts.data(), receive_offsets.data(), MPI_DOUBLE,
                MPI_COMM_WORLD);
  std::vector<std::vector<double>> received(size_);
  for (int q = 0; q < size_; ++q)
    received[q].assign(flat_receive.begin() + receive_offsets[q],
                       flat_receive.begin() + receive_offsets[q] + receive_counts[q]);
  return received;
}

bool started_by_mpi_launcher() {
  // Open MPI's mpirun sets OMPI_COMM_WORLD_SIZE; PMIx- and PMI-based launchers (srun,
  // MPICH's hydra) set PMIX_RANK or PMI_SIZE.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

bool mpi_start(int* argc, char*** argv) {
  if (mpi_running) return true;
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) return false;
  mpi_running = true;
  return true;
}

void mpi_finish() {
  if (!mpi_running) return;
  MPI_Finalize();
  mpi_running = false;
}

void mpi_abort(int status) {
  if (mpi_running) MPI_Abort(MPI_COMM_WORLD, status);
  std::_Exit(status);
}

}  // namespace fetic::solver
