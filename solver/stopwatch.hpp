#pragma once
// Adds the seconds between its construction and its destruction to a running total: the
// time split of the solver's profile (local solves, coarse problem, communication) and of
// the outputs.

#include <chrono>

namespace fetic::solver {

class Stopwatch {
 public:
  explicit Stopwatch(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~Stopwatch() {
    total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  Stopwatch(const Stopwatch&) = delete;
  Stopwatch& operator=(const Stopwatch&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace fetic::solver
