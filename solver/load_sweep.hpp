#pragma once
// Solving at a sequence of load factors, each solve warm-started from the previous ones
// (the load slider, offline). For the FETI methods the dual iterate is affine in the
// load factor as long as the working set does not change, so once two solutions share a
// working set the next start is their secant extrapolation; PLAN makes it feasible.

#include <functional>
#include <vector>

#include "solver/method.hpp"

namespace fetic::solver {

// n load factors from first to last inclusive (n = 1: just `first`).
std::vector<double> load_steps(double first, double last, int count);

// The warm start for `load_factor` after `newer` (and `older`, when given): the secant
// prediction of the dual iterate when both share a working set, else `newer` itself.
Snapshot predict_warm_start(const Snapshot* older, const Snapshot& newer, double load_factor);

struct SweepStep {
  double load_factor = 0.0;
  Snapshot state;  // final state at this load factor
  std::vector<HistoryEntry> history;
};

struct SweepHooks {
  std::function<void(double)> before_start;                 // e.g. to set a reference
  std::function<void(const SweepStep&)> on_step;            // sees each finished step
  std::function<bool()> keep_going;                         // false stops the sweep
  std::function<void(double, const Method&)> on_iteration;  // after start and every step
};

// Runs `method` at every load factor, warm-starting each solve from the previous ones.
std::vector<SweepStep> sweep(Method& method, const std::vector<double>& load_factors,
                             const SweepHooks& hooks = {});

}  // namespace fetic::solver
