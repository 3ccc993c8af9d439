#pragma once
// Timing on the steady clock: seconds_since for one interval, and Stopwatch, which adds the
// seconds between its construction and its destruction to a running total (the time split
// of the solver's profile - local solves, coarse problem, communication - and of the
// outputs).

#include <chrono>

namespace fetic::solver {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

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
