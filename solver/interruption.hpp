#pragma once
// Set-up steps that can take seconds on a large scene (assembly, the subdomain
// factorizations, the coarse problem, the preconditioner, the estimate of ||H||) ask between
// pieces of work whether the program has been asked to stop, so that Ctrl-C ends the run
// within a fraction of a second. The solver knows no signals: the app installs the
// question (app/interrupt.cpp). Inside OpenMP loops ask stop_requested() and skip the
// remaining work; after the loop, throw_if_stopped().
//
// Under MPI a stop reaches every process: a process asked to stop sends a notice to the
// others (solver/communicator.cpp), and a notice that arrives is handed to the app's
// notice handler, which treats it as if the signal had reached this process too.

#include <stdexcept>
#include <string>

namespace fetic::solver {

// Thrown by throw_if_stopped(): the set-up was abandoned, nothing usable was made.
class SetupInterrupted : public std::runtime_error {
 public:
  explicit SetupInterrupted(const std::string& during) : std::runtime_error(during) {}
  // What was being done: "factorizing the subdomains", ...
  const char* during() const { return what(); }
};

// The question (a plain function, safe to call from any thread): the signal that asks this
// process to stop, 0 when none; nullptr: never stop.
void set_stop_check(int (*check)());
bool stop_requested();
// The signal behind stop_requested() (SIGINT, SIGTERM), 0 when there is none. Under MPI
// both first look for notices from the other processes (on the thread that runs MPI).
int stop_signal();
// The answer of the app's question alone, without looking for notices.
int own_stop_signal();
// Throws SetupInterrupted(during) when stop_requested().
void throw_if_stopped(const char* during);

// Another process of the run was asked to stop by `signal`: the handler (the app's) makes
// this process stop as well. Without a handler a notice is ignored.
void set_stop_notice_handler(void (*handler)(int signal));
void receive_stop_notice(int signal);
// Looks for notices (set by the communicator while MPI runs; nullptr: nothing to look for).
void set_stop_notice_poll(void (*poll)());

}  // namespace fetic::solver
