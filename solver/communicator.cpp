#include "solver/communicator.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <thread>

#include <mpi.h>

#include "solver/interruption.hpp"
#include "solver/stopwatch.hpp"

namespace fetic::solver {
namespace {

bool mpi_running = false;

// ---- stopping together ----
// A process asked to stop (a signal; the app's flag) sends one notice, the signal's
// number, to every other process on a communicator of its own (so that no exchange can
// ever receive it); a process that finds a notice stops as if the signal had reached it.
// Only the thread that started MPI calls MPI (MPI_THREAD_FUNNELED).

constexpr int kStopTag = 1;
MPI_Comm notice_comm = MPI_COMM_NULL;
std::thread::id mpi_thread;
bool stop_known = false;  // this process sent its notice or received one
int notice_payload = 0;   // what this process sent (the buffer must outlive the sends)
std::vector<MPI_Request> notice_sends;

void send_stop_notice(int signal) {
  int rank = 0, size = 1;
  MPI_Comm_rank(notice_comm, &rank);
  MPI_Comm_size(notice_comm, &size);
  notice_payload = signal;
  for (int q = 0; q < size; ++q)
    if (q != rank) {
      notice_sends.emplace_back();
      MPI_Isend(&notice_payload, 1, MPI_INT, q, kStopTag, notice_comm, &notice_sends.back());
    }
}

// Receives every notice that has arrived; returns the last signal named (0: none).
int receive_stop_notices() {
  int signal = 0;
  while (true) {
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, kStopTag, notice_comm, &arrived, &status);
    if (!arrived) return signal;
    int payload = 0;
    MPI_Recv(&payload, 1, MPI_INT, status.MPI_SOURCE, kStopTag, notice_comm, MPI_STATUS_IGNORE);
    signal = payload;
  }
}

void poll_stop_notices() {
  if (!mpi_running || std::this_thread::get_id() != mpi_thread) return;
  if (const int received = receive_stop_notices(); received != 0 && !stop_known) {
    stop_known = true;  // every process was told by the sender: no need to tell them again
    receive_stop_notice(received);
  }
  if (stop_known) return;
  if (const int own = own_stop_signal(); own != 0) {
    stop_known = true;
    send_stop_notice(own);
  }
}

// Waits for `count` requests of a collective or an exchange without spinning for long:
// first a short while (2 ms) of tests that yield the processor in between - most waits end
// there, and a sleep's wake-up would add its delay to every iteration's messages -, then
// sleeps a little longer each round (up to 1 ms), looking for stop notices between tests,
// so that a process waiting here for one that is stuck elsewhere (rank 0 on a FIFO without
// a reader) takes no processor and still passes its signal on.
void wait_all(int count, MPI_Request* requests) {
  int done = 0;
  MPI_Testall(count, requests, &done, MPI_STATUSES_IGNORE);
  if (done) return;
  using Clock = std::chrono::steady_clock;
  const Clock::time_point yield_until = Clock::now() + std::chrono::milliseconds(2);
  for (int round = 1;; ++round) {
    if ((round & 63) == 0) {
      poll_stop_notices();
      if (Clock::now() > yield_until) break;
    }
    std::this_thread::yield();
    MPI_Testall(count, requests, &done, MPI_STATUSES_IGNORE);
    if (done) return;
  }
  auto pause = std::chrono::microseconds(50);
  while (true) {
    poll_stop_notices();
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(1000));
    MPI_Testall(count, requests, &done, MPI_STATUSES_IGNORE);
    if (done) return;
  }
}

void wait_one(MPI_Request& request) {
  wait_all(1, &request);
}

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
  MPI_Request request;
  MPI_Iallgather(&local_count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD, &request);
  wait_one(request);
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
  MPI_Request request;
  MPI_Iallgatherv(local.data(), static_cast<int>(local.size()), mpi_type<T>(), all.data(),
                  counts.data(), offsets.data(), mpi_type<T>(), MPI_COMM_WORLD, &request);
  wait_one(request);
  return all;
}

// The start of a gather to rank 0: counted in `stats`, and every process' item count
// brought to rank 0 (the others get none).
std::vector<int> counts_at_root(int count, std::size_t item_bytes, int rank, int size,
                                CommunicationStats& stats) {
  ++stats.gathers;
  stats.gathered_bytes += static_cast<std::int64_t>(static_cast<std::size_t>(count) * item_bytes);
  std::vector<int> counts(rank == 0 ? size : 0);
  MPI_Request request;
  MPI_Igather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  wait_one(request);
  return counts;
}

template <class T>
std::vector<T> gather_to_root_impl(const std::vector<T>& local, int rank, int size,
                                   CommunicationStats& stats) {
  Stopwatch timer(stats.gather_seconds);
  const int count = static_cast<int>(local.size());
  const std::vector<int> counts = counts_at_root(count, sizeof(T), rank, size, stats);
  MPI_Request request;
  std::vector<T> all;
  std::vector<int> offsets;
  if (rank == 0) {
    offsets = offsets_of(counts);
    all.resize(static_cast<size_t>(offsets.back() + counts.back()));
  }
  MPI_Igatherv(local.data(), count, mpi_type<T>(), all.data(), counts.data(), offsets.data(),
               mpi_type<T>(), 0, MPI_COMM_WORLD, &request);
  wait_one(request);
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
  MPI_Request request;
  MPI_Iallgather(values, count, MPI_DOUBLE, all.data(), count, MPI_DOUBLE, MPI_COMM_WORLD,
                 &request);
  wait_one(request);
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
  MPI_Request request;
  MPI_Iallreduce(MPI_IN_PLACE, words.data(), static_cast<int>(words.size()), MPI_INT64_T, MPI_SUM,
                 MPI_COMM_WORLD, &request);
  wait_one(request);
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
  MPI_Request request;
  MPI_Iallreduce(&value, &result, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD, &request);  // exact
  wait_one(request);
  return result;
}

long long Communicator::sum(long long value) const {
  if (size_ == 1) return value;
  Stopwatch timer(stats_.reduction_seconds);
  ++stats_.reductions;
  long long result = value;
  MPI_Request request;
  MPI_Iallreduce(&value, &result, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD, &request);  // exact
  wait_one(request);
  return result;
}

bool Communicator::any(bool value) const {
  if (size_ == 1) return value;
  Stopwatch timer(stats_.reduction_seconds);
  ++stats_.reductions;
  int local = value ? 1 : 0, result = 0;
  MPI_Request request;
  MPI_Iallreduce(&local, &result, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD, &request);
  wait_one(request);
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

void Communicator::gather_to_root_each(
    const std::vector<double>& local,
    const std::function<void(int, const std::vector<double>&)>& take) const {
  if (size_ == 1) {
    take(0, local);
    return;
  }
  Stopwatch timer(stats_.gather_seconds);
  const int count = static_cast<int>(local.size());
  const std::vector<int> counts = counts_at_root(count, sizeof(double), rank_, size_, stats_);
  MPI_Request request;
  constexpr int kGatherEachTag = 1;  // exchanges use tag 0
  if (rank_ != 0) {
    MPI_Isend(local.data(), count, MPI_DOUBLE, 0, kGatherEachTag, MPI_COMM_WORLD, &request);
    wait_one(request);
    return;
  }
  take(0, local);
  std::vector<double> values;
  for (int q = 1; q < size_; ++q) {
    values.resize(static_cast<size_t>(counts[q]));
    MPI_Irecv(values.data(), counts[q], MPI_DOUBLE, q, kGatherEachTag, MPI_COMM_WORLD, &request);
    wait_one(request);
    take(q, values);
    std::vector<double>().swap(values);  // one process' values at a time
  }
}

void Communicator::broadcast(std::string& text, int root) const {
  if (size_ == 1) return;
  unsigned long long length = text.size();
  MPI_Request request;
  MPI_Ibcast(&length, 1, MPI_UNSIGNED_LONG_LONG, root, MPI_COMM_WORLD, &request);
  wait_one(request);
  text.resize(length);
  if (length == 0) return;
  MPI_Ibcast(text.data(), static_cast<int>(length), MPI_CHAR, root, MPI_COMM_WORLD, &request);
  wait_one(request);
}

void Communicator::broadcast(double& value, int root) const {
  if (size_ == 1) return;
  MPI_Request request;
  MPI_Ibcast(&value, 1, MPI_DOUBLE, root, MPI_COMM_WORLD, &request);
  wait_one(request);
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
  if (size_ == 1) return;
  MPI_Request request;
  MPI_Ibarrier(MPI_COMM_WORLD, &request);
  wait_one(request);
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
  wait_all(static_cast<int>(requests.size()), requests.data());
}

std::vector<std::vector<double>> Communicator::all_to_all(
    const std::vector<std::vector<double>>& send) const {
  if (size_ == 1) return send;
  std::vector<int> send_counts(size_), receive_counts(size_);
  for (int q = 0; q < size_; ++q)
    send_counts[q] = static_cast<int>(send[q].size());
  MPI_Request request;
  MPI_Ialltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, MPI_COMM_WORLD,
                &request);
  wait_one(request);
  const std::vector<int> send_offsets = offsets_of(send_counts);
  const std::vector<int> receive_offsets = offsets_of(receive_counts);
  std::vector<double> flat_send;
  for (const auto& part : send)
    flat_send.insert(flat_send.end(), part.begin(), part.end());
  std::vector<double> flat_receive(
      static_cast<size_t>(receive_offsets.back() + receive_counts.back()));
  MPI_Ialltoallv(flat_send.data(), send_counts.data(), send_offsets.data(), MPI_DOUBLE,
                 flat_receive.data(), receive_counts.data(), receive_offsets.data(), MPI_DOUBLE,
                 MPI_COMM_WORLD, &request);
  wait_one(request);
  std::vector<std::vector<double>> received(size_);
  for (int q = 0; q < size_; ++q)
    received[q].assign(flat_receive.begin() + receive_offsets[q],
                       flat_receive.begin() + receive_offsets[q] + receive_counts[q]);
  return received;
}

bool mpi_built_in() {
  return true;
}

bool mpi_start(int* argc, char*** argv) {
  if (mpi_running) return true;
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) return false;
  mpi_running = true;
  mpi_thread = std::this_thread::get_id();
  MPI_Comm_dup(MPI_COMM_WORLD, &notice_comm);
  set_stop_notice_poll(poll_stop_notices);
  return true;
}

void mpi_finish() {
  if (!mpi_running) return;
  set_stop_notice_poll(nullptr);
  // Notices (one integer each, sent at once) complete; take in those that arrived.
  if (!notice_sends.empty())
    MPI_Waitall(static_cast<int>(notice_sends.size()), notice_sends.data(), MPI_STATUSES_IGNORE);
  receive_stop_notices();
  MPI_Comm_free(&notice_comm);
  MPI_Finalize();
  mpi_running = false;
}

void mpi_abort(int status) {
  if (mpi_running) MPI_Abort(MPI_COMM_WORLD, status);
  std::_Exit(status);
}

}  // namespace fetic::solver
