#pragma once
// Set-up steps that can take seconds on a large scene (assembly, the subdomain
// factorizations, the coarse problem, the preconditioner, the power method) ask between
// pieces of work whether the program has been asked to stop, so that Ctrl-C ends the run
// within a fraction of a second. The solver knows no signals: the app installs the
// question (app/interrupt.cpp). Inside OpenMP loops ask stop_requested() and skip the
// remaining work; after the loop, throw_if_stopped().

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

// The question (a plain function, safe to call from any thread); nullptr: never stop.
void set_stop_check(bool (*check)());
bool stop_requested();
// Throws SetupInterrupted(during) when stop_requested().
void throw_if_stopped(const char* during);

}  // namespace fetic::solver
