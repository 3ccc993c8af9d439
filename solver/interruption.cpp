#include "solver/interruption.hpp"

#include <atomic>

namespace fetic::solver {
namespace {

std::atomic<int (*)()> stop_check{nullptr};
std::atomic<void (*)(int)> notice_handler{nullptr};
std::atomic<void (*)()> notice_poll{nullptr};

}  // namespace

void set_stop_check(int (*check)()) {
  stop_check.store(check);
}

int own_stop_signal() {
  int (*check)() = stop_check.load();
  return check ? check() : 0;
}

int stop_signal() {
  if (void (*poll)() = notice_poll.load()) poll();
  return own_stop_signal();
}

bool stop_requested() {
  return stop_signal() != 0;
}

void throw_if_stopped(const char* during) {
  if (stop_requested()) throw SetupInterrupted(during);
}

void set_stop_notice_handler(void (*handler)(int)) {
  notice_handler.store(handler);
}

void set_stop_notice_poll(void (*poll)()) {
  notice_poll.store(poll);
}

void receive_stop_notice(int signal) {
  if (void (*handler)(int) = notice_handler.load()) handler(signal);
}

}  // namespace fetic::solver
