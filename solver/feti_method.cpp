#include "solver/feti_method.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fetic::solver {

FetiMethod::FetiMethod(const Model& model, const SolveOptions& options, int default_max_iterations)
    : Method(model, options, default_max_iterations),
      system_(model),
      preconditioner_(system_, options.preconditioner, options.scaling),
      coarse_(system_) {}

Eigen::VectorXd FetiMethod::rigid_amplitudes() const {
  // alpha = (G^G^')^+ G^ (F lambda - d) = -(G^G^')^+ G^ r.
  Eigen::VectorXd alpha = -coarse_.amplitudes(r_);
  if (coarse_.unheld().empty()) return alpha;

  // A group the active rows leave free carries no load (else lambda would not balance
  // it): any translation that keeps its gaps open is a solution. Choose the one that
  // moves it least, i.e. keep it where it is unless a neighbour pushes it.
  const Decomposition& d = system_.decomposition();
  const SparseMatrix& G = system_.G();
  for (const UnheldGroup& group : coarse_.unheld()) {
    const Eigen::VectorXd u = system_.subdomain_displacements(lambda_, alpha, load_factor_);
    // Gap of every row under the current placement, and its rate of change per unit
    // translation s of the group along its direction z: gap(s) = gap(0) - s (G'z)_k.
    const Eigen::VectorXd rate = G.transpose() * group.direction;
    double low = -std::numeric_limits<double>::infinity();
    double high = std::numeric_limits<double>::infinity();
    for (int r = d.equality_rows; r < d.row_count(); ++r) {
      if (rate(r) == 0.0) continue;
      double bu = 0.0;
      for (const RowEntry& entry : d.rows[r].entries)
        bu += entry.value * u(d.subdomains[entry.subdomain].dof_offset + entry.dof);
      const double gap = std::max(0.0, d.rows[r].rhs - bu);
      if (rate(r) > 0.0)
        high = std::min(high, gap / rate(r));
      else
        low = std::max(low, gap / rate(r));
    }
    // Displacement of the group per unit s, and the s that minimizes its norm.
    double along = 0.0, size = 0.0;
    for (int j : group.subdomains) {
      const Subdomain& sub = d.subdomains[j];
      const Eigen::VectorXd motion =
          system_.subdomains()[j].R * group.direction.segment(sub.mode_offset, sub.mode_count);
      along += motion.dot(u.segment(sub.dof_offset, sub.dof_count));
      size += motion.squaredNorm();
    }
    const double s = size > 0.0 ? std::clamp(-along / size, std::min(low, high), high) : 0.0;
    alpha += s * group.direction;
  }
  return alpha;
}

void FetiMethod::update_residual(double a, const Eigen::VectorXd& q) {
  if (iteration_ % kResidualReplacement == 0)
    system_.residual(lambda_, load_factor_, r_);
  else
    r_ -= a * q;
}

void FetiMethod::reset_watch() {
  best_residual_ = std::numeric_limits<double>::infinity();
  best_iteration_ = 0;
}

void FetiMethod::watch_stagnation(double residual) {
  if (residual < best_residual_) {
    best_residual_ = residual;
    best_iteration_ = iteration_;
  } else if (iteration_ - best_iteration_ >= kStagnationWindow) {
    fail("stagnated: the relative residual has not gone below " + format_number(best_residual_) +
         " (iteration " + std::to_string(best_iteration_) + ") in " +
         std::to_string(kStagnationWindow) + " iterations; the tolerance " +
         format_number(options_.tolerance) + " is probably below what rounding allows here");
  }
}

void FetiMethod::fail_breakdown(double yw, double pq) {
  fail(std::string(to_string(kind())) + " broke down at iteration " + std::to_string(iteration_) +
       ": the search direction has no curvature (y'w = " + format_number(yw) +
       ", p'F p = " + format_number(pq) + ") at relative residual " +
       format_number(history().empty() ? 0.0 : history().back().residual) +
       "; if that is tiny, the tolerance is below what rounding allows here");
}

void FetiMethod::fill_contacts(Snapshot& s) const {
  const Decomposition& d = system_.decomposition();
  const int pairs = static_cast<int>(model_.pairs.size());
  s.force.assign(pairs, 0.0);
  s.in_working_set.assign(pairs, 0);
  const auto& active = coarse_.active_rows();
  for (int k = 0; k < pairs; ++k) {
    const int row = d.pair_row[k];
    if (row < 0) continue;
    s.force[k] = std::max(0.0, lambda_(row));
    s.in_working_set[k] = !active.empty() && active[row] ? 1 : 0;
  }
}

Snapshot FetiMethod::snapshot() const {
  Snapshot s;
  s.method = kind();
  s.iteration = iteration_;
  s.status = status();
  s.message = message();
  s.load_factor = load_factor_;
  s.residual = history().empty() ? 0.0 : history().back().residual;
  if (lambda_.size() == system_.rows()) {
    s.pieces = system_.pieces(lambda_, rigid_amplitudes(), load_factor_);
    s.dual = lambda_;
  }
  fill_contacts(s);
  return s;
}

}  // namespace fetic::solver
