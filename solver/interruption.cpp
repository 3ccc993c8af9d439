#include "solver/interruption.hpp"

#include <atomic>

namespace fetic::solver {
namespace {

std::atomic<bool (*)()> stop_check{nullptr};

}  // namespace

void set_stop_check(bool (*check)()) { stop_check.store(check); }

bool stop_requested() {
  bool (*check)() = stop_check.load();
  return check && check();
}

void throw_if_stopped(const char* during) {
  if (stop_requested()) throw SetupInterrupted(during);
}

}  // namespace fetic::solver
