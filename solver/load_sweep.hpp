#pragma once
// The one load-sweep driver: solving at a sequence of load factors, each solve
// warm-started from the previous ones. `fetic solve`, `fetic render` (render::run_frames),
// the window's solver thread, `fetic bench` and the tests all drive their sweeps through
// SweepDriver, so they all see the same iterations (docs/ARCHITECTURE.md).
//
// The warm start: for the FETI methods the dual iterate is affine in the load factor as
// long as the working set does not change, so once the last two solves converged with the
// same working set the next start is their secant extrapolation (the method makes it
// feasible); otherwise the next solve starts from the last state reached, converged,
// failed or stopped early.

#include <functional>
#include <optional>
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
  Snapshot state;  // final state at this load factor (status Running: stopped early)
  std::vector<HistoryEntry> history;
};

struct SweepHooks {
  std::function<void(double)> before_start;  // e.g. to set a reference
  // Sees each finished step; may replace its state (fetic solve under mpirun puts the
  // whole state gathered on rank 0 in place of the process' own).
  std::function<void(SweepStep&)> on_step;
  std::function<bool()> keep_going;                         // false stops the sweep
  std::function<void(double, const Method&)> on_iteration;  // after start and every step
  // sweep(): a stop between two load factors (or before the first) still starts the next
  // solve, which becomes the last step, stopped at iteration 0 - so that the outputs of
  // an interrupted sweep say "interrupted" (docs/COMMANDS.md). Off: the sweep just ends.
  bool record_stop = true;
};

// Drives one method through load factors, keeping what the next warm start needs.
class SweepDriver {
 public:
  explicit SweepDriver(Method& method) : method_(method) {}

  // One solve at `load_factor`, warm from the earlier ones: before_start, start,
  // on_iteration after the start and after every iteration, keep_going before every
  // iteration (false stops the solve where it is), on_step with the final state.
  SweepStep solve(double load_factor, const SweepHooks& hooks = {});
  // The next solve starts cold.
  void forget();
  // What the next warm start would be for `load_factor` (nullopt: a cold start).
  std::optional<Snapshot> warm_start(double load_factor) const;

 private:
  Method& method_;
  std::optional<Snapshot> older_, newer_;  // the last two states reached
};

// Runs `method` at every load factor through a SweepDriver; keep_going is also asked
// before each load factor. A step stopped by keep_going (status Running) is the last one
// returned; see SweepHooks::record_stop.
std::vector<SweepStep> sweep(Method& method, const std::vector<double>& load_factors,
                             const SweepHooks& hooks = {});

}  // namespace fetic::solver
