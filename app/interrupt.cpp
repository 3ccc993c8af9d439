#include "app/interrupt.hpp"

#include <csignal>

#include "solver/interruption.hpp"

namespace fetic::app {
namespace {

volatile std::sig_atomic_t received = 0;

extern "C" void on_signal(int signal) {
  received = signal;
}

// Under MPI: another process was asked to stop; this one stops as if it had been too.
void on_stop_notice(int signal) {
  if (received == 0) received = signal;
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  // The solver's long set-up loops ask the same flag (solver/interruption.hpp).
  // Under MPI a notice from another process counts as this process' own signal.
  solver::set_stop_check([] { return static_cast<int>(received); });
  solver::set_stop_notice_handler(on_stop_notice);
}

// Each asks the solver, which first looks for other processes' notices under MPI.
bool interrupted() {
  return solver::stop_signal() != 0;
}

int interrupt_signal() {
  return solver::stop_signal();
}

const char* interrupt_name() {
  return signal_name(interrupt_signal());
}

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "";
  }
}

}  // namespace fetic::app
