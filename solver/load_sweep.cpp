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

std::optional<Snapshot> SweepDriver::warm_start(double load_factor) const {
  if (!newer_) return std::nullopt;
  return predict_warm_start(older_ ? &*older_ : nullptr, *newer_, load_factor);
}

void SweepDriver::forget() {
  older_.reset();
  newer_.reset();
}

SweepStep SweepDriver::solve(double load_factor, const SweepHooks& hooks) {
  if (hooks.before_start) hooks.before_start(load_factor);
  if (const std::optional<Snapshot> warm = warm_start(load_factor))
    method_.start(load_factor, &*warm);
  else
    method_.start(load_factor);
  if (hooks.on_iteration) hooks.on_iteration(load_factor, method_);
  while (method_.status() == Status::Running && (!hooks.keep_going || hooks.keep_going())) {
    method_.step();
    if (hooks.on_iteration) hooks.on_iteration(load_factor, method_);
  }
  SweepStep step{load_factor, method_.snapshot(), method_.history()};
  // A secant needs two converged solves (predict_warm_start checks); any other state
  // reached is the next start as it is.
  if (step.state.status == Status::Converged && newer_)
    older_ = std::move(newer_);
  else
    older_.reset();
  // Kept for the next warm start: all but the displacements, which Method::start never
  // reads and which are as large as the model (77 MB at ten million unknowns).
  std::vector<Piece> pieces = std::move(step.state.pieces);
  newer_ = step.state;
  step.state.pieces = std::move(pieces);
  if (hooks.on_step) hooks.on_step(step);
  return step;
}

std::vector<SweepStep> sweep(Method& method, const std::vector<double>& load_factors,
                             const SweepHooks& hooks) {
  SweepDriver driver(method);
  std::vector<SweepStep> steps;
  for (double t : load_factors) {
    // Stopped before this load factor: its start (iteration 0, stopped) is the last
    // step, so that what the sweep reports says it was interrupted, not converged.
    const bool stopped = hooks.keep_going && !hooks.keep_going();
    if (stopped && !hooks.record_stop) break;
    steps.push_back(driver.solve(t, hooks));
    if (stopped || steps.back().state.status == Status::Running) break;
  }
  return steps;
}

}  // namespace fetic::solver
