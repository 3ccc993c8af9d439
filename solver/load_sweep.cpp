#include "solver/load_sweep.hpp"

#include <cmath>

namespace fetic::solver {

std::vector<double> load_steps(double first, double last, int count) {
  std::vector<double> values;
  if (count <= 1) return {first};
  // last - first overflows for ends near the largest double (-1e308:1e308): then the
  // weighted mean, which cannot.
  const double span = last - first;
  for (int i = 0; i < count; ++i) {
    const double s = static_cast<double>(i) / (count - 1);
    values.push_back(std::isfinite(span) ? first + span * s : first * (1.0 - s) + last * s);
  }
  values.back() = last;
  return values;
}

Snapshot predict_warm_start(const Snapshot* older, const Snapshot& newer, double load_factor) {
  Snapshot warm = newer;
  if (!older || older->dual.size() != newer.dual.size() || newer.dual.size() == 0 ||
      older->in_working_set != newer.in_working_set || older->load_factor == newer.load_factor ||
      older->status != Status::Converged || newer.status != Status::Converged)
    return warm;
  const double s = (load_factor - newer.load_factor) / (newer.load_factor - older->load_factor);
  warm.dual = newer.dual + s * (newer.dual - older->dual);
  return warm;
}

std::vector<SweepStep> sweep(Method& method, const std::vector<double>& load_factors,
                             const SweepHooks& hooks) {
  std::vector<SweepStep> steps;
  for (double t : load_factors) {
    if (hooks.keep_going && !hooks.keep_going()) break;
    if (hooks.before_start) hooks.before_start(t);
    if (steps.empty()) {
      method.start(t);
    } else {
      const Snapshot* older = steps.size() >= 2 ? &steps[steps.size() - 2].state : nullptr;
      const Snapshot warm = predict_warm_start(older, steps.back().state, t);
      method.start(t, &warm);
    }
    if (hooks.on_iteration) {
      hooks.on_iteration(t, method);
      while (method.status() == Status::Running && (!hooks.keep_going || hooks.keep_going())) {
        method.step();
        hooks.on_iteration(t, method);
      }
    } else {
      run_to_end(method, hooks.keep_going);
    }
    steps.push_back({t, method.snapshot(), method.history()});
    if (hooks.on_step) hooks.on_step(steps.back());
  }
  return steps;
}

}  // namespace fetic::solver
