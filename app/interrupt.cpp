#include "app/interrupt.hpp"

#include <csignal>

#include "solver/interruption.hpp"

namespace fetic::app {
namespace {

volatile std::sig_atomic_t received = 0;

extern "C" void on_signal(int signal) { received = signal; }

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  // The solver's long set-up loops ask the same flag (solver/interruption.hpp).
  solver::set_stop_check([] { return received != 0; });
}

bool interrupted() { return received != 0; }

int interrupt_signal() { return received; }

const char* interrupt_name() { return signal_name(received); }

const char* signal_name(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "";
  }
}

}  // namespace fetic::app
