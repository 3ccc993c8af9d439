#include "solver/feti_c.hpp"

#include <algorithm>
#include <cmath>

#include "solver/boundedness.hpp"

namespace fetic::solver {

FetiC::FetiC(const Model& model, const SolveOptions& options, const Communicator& communicator)
    : FetiMethod(MethodKind::FetiC, model, options, 0, communicator) {
  if (options.max_iterations <= 0) max_iterations_ = 10 * system_.space().global_rows() + 1000;
}

void FetiC::set_working_set(const std::vector<char>& active) {
  active_ = active;
  coarse_.set_active_rows(active_);
}

bool FetiC::balanced(const Eigen::VectorXd& lambda) const {
  const Eigen::VectorXd imbalance = coarse_.apply_G(lambda) - e_;
  const double scale =
      e_.lpNorm<Eigen::Infinity>() + system_.apply_abs_G(lambda).lpNorm<Eigen::Infinity>();
  return imbalance.lpNorm<Eigen::Infinity>() <= 1e-12 * scale;
}

bool FetiC::plan(Eigen::VectorXd& lambda) {
  const int first_contact = space().first_contact();
  const int rows = system_.rows();
  bool changed = false;
  for (int pass = 0; pass <= space().global_rows(); ++pass) {
    std::vector<char> active = active_;
    for (int k = first_contact; k < rows; ++k) {
      if (lambda(k) <= 0.0) lambda(k) = 0.0;
      active[k] = lambda(k) > 0.0;
    }
    if (space().any(active != active_)) changed = true;
    set_working_set(active);
    if (hold_loaded_groups()) changed = true;
    if (balanced(lambda)) return changed;
    // Restore equilibrium on the new working set (8.25).
    coarse_.project(lambda);
    lambda += coarse_.particular(e_);
    bool negative = false;
    for (int k = first_contact; k < rows; ++k)
      if (active_[k] && lambda(k) < 0.0) negative = true;
    if (!space().any(negative)) return changed;
  }
  return changed;
}

// Clipping may leave a group of floating struts with no active row although a load
// pushes it: G^ lambda = e has no solution then. The rows in front of the push (those
// whose force opposes it) re-enter W with lambda = 0; the projection gives them the force.
// Per group only the rows its modes reach (the columns of G' in the group's direction): the
// whole of G'z for every group cost groups x rows (1,000 floating beams).
bool FetiC::hold_loaded_groups() {
  const int first_contact = space().first_contact();
  const double negligible = 1e-12 * (e_.lpNorm<1>() + 1e-300);
  std::vector<double>& along = along_;  // (G'z)_k on the rows in `reached`, else 0
  along.assign(static_cast<size_t>(system_.rows()), 0.0);
  std::vector<int> reached;
  bool added = false;
  for (int round = 0; round < space().global_rows() && !coarse_.unheld().empty(); ++round) {
    std::vector<char> active = active_;
    bool any = false;
    for (const UnheldGroup& group : coarse_.unheld()) {
      const double push = group.direction.dot(e_);
      if (std::abs(push) <= negligible) continue;
      reached.clear();
      for (Eigen::SparseVector<double>::InnerIterator mode(group.direction); mode; ++mode)
        for (SparseMatrix::InnerIterator row(Gt(), mode.index()); row; ++row) {
          if (along[static_cast<size_t>(row.index())] == 0.0) reached.push_back(row.index());
          along[static_cast<size_t>(row.index())] += row.value() * mode.value();
        }
      std::sort(reached.begin(), reached.end());
      reached.erase(std::unique(reached.begin(), reached.end()), reached.end());
      for (int k : reached) {
        if (k >= first_contact && !active[k] && along[static_cast<size_t>(k)] * push > 0.0) {
          active[k] = 1;
          any = true;
        }
        along[static_cast<size_t>(k)] = 0.0;
      }
    }
    if (!space().any(any)) break;
    added = true;
    set_working_set(active);
  }
  return added;
}

void FetiC::compute_search_residual() {
  const int first_contact = space().first_contact();
  const int rows = system_.rows();
  w_hat_ = r_;
  coarse_.project(w_hat_);
  system_.project_onto_range_of_B(w_hat_);
  // Gaps of the rows outside W from the true rigid-body amplitudes.
  const Eigen::VectorXd rigid = system_.G().transpose() * rigid_amplitudes();
  face_.assign(rows, 0);
  for (int k = 0; k < rows; ++k) {
    if (k >= first_contact && !active_[k]) {
      const double gap = -r_(k) - rigid(k);
      w_hat_(k) = gap < 0.0 ? -gap : 0.0;
    }
    face_[k] = active_[k] || w_hat_(k) != 0.0;
  }
}

void FetiC::record_state() {
  compute_search_residual();
  const double residual = stopping_test(space().norm(w_hat_));
  long long working = 0;
  for (int k = space().first_contact(); k < system_.rows(); ++k)
    working += active_[k] && space().owned(k) ? 1 : 0;
  record(residual, static_cast<int>(space().communicator().sum(working)));
}

void FetiC::begin(const Snapshot* warm) {
  d_ = system_.d(load_factor_);
  e_ = system_.e(load_factor_);
  const int rows = system_.rows();
  const int first_contact = space().first_contact();
  std::vector<char> active(rows, 1);
  const bool use_warm = !space().any(!(warm && warm->dual.size() == rows));
  if (use_warm)
    for (int k = first_contact; k < rows; ++k)
      active[k] = warm->dual(k) > 0.0;
  active_.clear();
  coarse_.forget_updates();
  set_working_set(active);
  lambda_ = use_warm ? warm->dual : coarse_.particular(e_);
  restart_ = true;
  yw_previous_ = 0.0;
  reset_watch();
  previous_face_.clear();

  const std::string unbounded = unbounded_struts(model_, load_factor_);
  if (!unbounded.empty()) {
    lambda_.setZero();
    system_.residual(lambda_, load_factor_, r_);
    set_scale();
    w_hat_ = r_;
    record(relative(space().norm(r_)), 0);
    fail(unbounded);
    return;
  }
  plan(lambda_);
  system_.residual(lambda_, load_factor_, r_);
  set_scale();
  record_state();
}

void FetiC::advance() {
  // A PCPG step on the face A = E + W + penetrating rows.
  coarse_.set_active_rows(face_);
  if (space().any(face_ != previous_face_)) restart_ = true;
  previous_face_ = face_;
  Eigen::VectorXd w = r_;
  coarse_.project(w);
  system_.project_onto_range_of_B(w);
  for (int k = 0; k < system_.rows(); ++k)
    if (!face_[k]) w(k) = 0.0;
  const PcpgStep step = pcpg_step(w, &face_, restart_, yw_previous_, p_, q_);
  if (!step.ok) return;
  const double a = step.a;
  const Eigen::VectorXd trial = lambda_ + a * p_;
  Eigen::VectorXd planned = trial;
  const bool changed = plan(planned);
  const bool modified = changed || space().any(planned != trial);
  lambda_ = planned;
  if (modified)
    system_.residual(lambda_, load_factor_, r_);
  else
    update_residual(a, q_);
  restart_ = modified;
  yw_previous_ = step.yw;
  record_state();
}

}  // namespace fetic::solver
