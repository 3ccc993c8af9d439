#include "solver/mprgp.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "solver/boundedness.hpp"
#include "solver/interruption.hpp"
#include "solver/largest_eigenvalue.hpp"

namespace fetic::solver {
namespace {

// Iterations without a new lowest residual before the solve is declared stagnated. Longer
// than FETI-C's window: within one SMALBE outer iteration the residual, which includes
// the groups' imbalance, may rest while MPRGP drives the projected gradient down.
constexpr int kMprgpStagnationWindow = 200;

}  // namespace

Mprgp::Mprgp(const Model& model, const SolveOptions& options, const Communicator& communicator,
             MprgpParameters parameters)
    : FetiMethod(kind_of(MethodKind::Mprgp, options), model, options, 0, communicator),
      parameters_(parameters) {
  if (options.max_iterations <= 0) max_iterations_ = 10 * space().global_rows() + 1000;
  std::vector<char> equality_rows(space().rows(), 0);
  for (int k = 0; k < space().rows(); ++k)
    equality_rows[k] = !space().is_contact(k);
  coarse_.set_active_rows(equality_rows);
  face_.emplace(coarse_);
  find_group_constraints();
  estimate_operator_norm();
  inner_.set_norm(norm_A_);
  if (!groups_.empty()) outer_.emplace(inner_, parameters_, rho_);
  // FETI-DP (not --clusters 1, which is FETI-1): the contact faces' coarse space
  // (contact_coarse.hpp). The hybrid only between clusters without modes: a floating
  // cluster carries its modes in G, and columns there cost more F than they saved
  // (docs/METHODS.md, "FETI-DP").
  const int clusters = options.corner_clusters;
  if ((clusters < 0 || clusters > 1) && options.preconditioner != Preconditioner::None &&
      system_.decomposition().contact_rows() > 0) {
    throw_if_stopped("setting up the contact faces' coarse space");
    contact_coarse_.emplace(
        system_,
        [this](const Eigen::VectorXd& x, Eigen::VectorXd& out) {
          Eigen::VectorXd ftx, qx;
          apply_A(x, out, ftx, qx);
        },
        clusters > 1);
    if (contact_coarse_->columns() == 0) contact_coarse_.reset();
  }
}

// Groups of struts the equality rows leave free: their balance z'G x = 0 involves only
// contact rows, c = G'z (group_balance.hpp).
void Mprgp::find_group_constraints() {
  groups_ = GroupBalance(system_, coarse_.unheld());
}

Eigen::VectorXd Mprgp::to_multipliers(const Eigen::VectorXd& x) const {
  Eigen::VectorXd multipliers = x;
  coarse_.subtract_Gt(coarse_.solve(system_.apply_G(x)), multipliers);
  return multipliers;
}

Eigen::VectorXd Mprgp::to_gradient(const Eigen::VectorXd& w) const {
  Eigen::VectorXd gradient = w;
  system_.subtract_Gt(coarse_.solve(coarse_.apply_G(w)), gradient);
  return gradient;
}

// ||H|| by Lanczos on the feasible subspace (largest_eigenvalue.hpp), from a fixed
// pseudo-random start so that no symmetry of the scene hides the largest eigenvalue. A
// row's start is drawn from its global index (splitmix64), so that every process count
// starts alike. The estimate is the largest Ritz value plus its residual: from above, so
// that alpha_bar = alpha_factor / ||A|| stays below 2 / ||A|| (docs/METHODS.md, "MPRGP").
void Mprgp::estimate_operator_norm() {
  const int rows = space().rows();
  Eigen::VectorXd v(rows);
  for (int k = 0; k < rows; ++k) {
    std::uint64_t state =
        0x9E3779B97F4A7C15ull * (static_cast<std::uint64_t>(space().global_row(k)) + 1);
    state = (state ^ (state >> 30)) * 0xBF58476D1CE4E5B9ull;
    state = (state ^ (state >> 27)) * 0x94D049BB133111EBull;
    state ^= state >> 31;
    v(k) = static_cast<double>(state % 2001) / 1000.0 - 1.0;
  }
  system_.project_onto_range_of_B(v);
  coarse_.project(v);
  rho_ = 0.0;
  const long long before = system_.f_applications();
  LanczosOperator op;
  op.apply = [this](const Eigen::VectorXd& x, Eigen::VectorXd& out) {
    Eigen::VectorXd ftx, qx;
    apply_A(x, out, ftx, qx);
  };
  op.dot = [this](const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return space().dot(a, b); };
  op.before_product = [] { throw_if_stopped("estimating the operator's norm (Lanczos)"); };
  LanczosStop stop{parameters_.norm_tolerance, parameters_.norm_min_products,
                   parameters_.norm_products};
  const EigenvalueEstimate estimate = largest_eigenvalue(op, v, stop);
  norm_products_ = static_cast<int>(system_.f_applications() - before);
  norm_H_ = estimate.upper() > 0.0 ? estimate.upper() : 1.0;
  norm_A_ = norm_H_;
  if (!groups_.empty()) {
    rho_ = parameters_.rho_factor * norm_H_;
    norm_A_ = std::max(norm_H_, rho_);
  }
}

void Mprgp::apply_A(const Eigen::VectorXd& x, Eigen::VectorXd& out, Eigen::VectorXd& ftx,
                    Eigen::VectorXd& qx) const {
  system_.apply_F(to_multipliers(x), ftx);
  out = to_gradient(ftx);
  system_.project_onto_range_of_B(out);
  if (groups_.empty()) return;
  qx = groups_.project(x);
  out += rho_ * qx;
}

void Mprgp::precondition(const Eigen::VectorXd& g_free, const std::vector<char>& free,
                         Eigen::VectorXd& z) {
  if (!contact_coarse_) {
    precondition_in_face(g_free, free, z);
    return;
  }
  contact_coarse_->apply(
      g_free, free,
      [this](const Eigen::VectorXd& g, const std::vector<char>& face, Eigen::VectorXd& out) {
        precondition_in_face(g, face, out);
      },
      z);
}

void Mprgp::precondition_in_face(const Eigen::VectorXd& g_free, const std::vector<char>& free,
                                 Eigen::VectorXd& z) {
  if (preconditioner_.kind() == Preconditioner::None) {
    z = g_free;
    return;
  }
  // z = P_E P_F M^-1 P_F g_free on the face (see the header).
  face_->set_face(free);
  Eigen::VectorXd w = g_free;
  face_->project(w);
  preconditioner_.apply(w, &free, z);
  system_.project_onto_range_of_B(z);
  face_->project(z);
  coarse_.project(z);
}

Mprgp::Counts Mprgp::counts() const {
  const MprgpCore::Steps& steps = inner_.steps();
  return {steps.cg, steps.expansion, steps.proportioning, outer_ ? outer_->outer_iterations() : 0};
}

void Mprgp::begin(const Snapshot* warm) {
  d_ = system_.d(load_factor_);
  e_ = system_.e(load_factor_);
  const int rows = space().rows();
  reset_watch();
  face_->forget_updates();
  if (outer_) outer_->start(norm_A_, 0.0);

  // lambda0: balances the loads through the equality rows, and through the contact rows
  // of the groups they leave free: w = sum_z beta_z c_z with c_y'w = z_y'e.
  lambda0_ = coarse_.particular(e_);
  if (!groups_.empty())
    lambda0_ += to_multipliers(groups_.times(groups_.gram_solve(groups_.direction_dots(e_))));
  system_.residual(lambda0_, load_factor_, r0_);
  Eigen::VectorXd b = to_gradient(r0_);
  system_.project_onto_range_of_B(b);
  Eigen::VectorXd lower = Eigen::VectorXd::Constant(rows, -std::numeric_limits<double>::infinity());
  for (int k = 0; k < rows; ++k)
    if (space().is_contact(k)) lower(k) = -lambda0_(k);

  const std::string unbounded = unbounded_struts(model_, load_factor_);
  if (!unbounded.empty()) {
    inner_.place(b, lower, lower.cwiseMax(0.0));
    r_ = d_;
    set_scale();
    record(relative(space().norm(r_)), 0);
    fail(unbounded);
    return;
  }

  // Start: lambda0 with negative contact multipliers clipped; warm, the previous
  // multipliers with the equality rows' part projected onto ker G_E.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(rows);
  if (!space().any(!(warm && warm->dual.size() == rows))) {
    x = warm->dual - lambda0_;
    coarse_.project(x);
  }
  inner_.place(b, lower, x.cwiseMax(lower));
  inner_.start();
  r_ = r0_ - inner_.ftx();
  set_scale();
  // eta relative to ||b|| (PERMON); b can vanish when lambda0 already minimizes on ker G.
  if (outer_) outer_->start(norm_A_, parameters_.eta_factor * std::max(space().norm(b), scale_));
  finish_iteration();
}

void Mprgp::advance() {
  ++iteration_;
  if (const auto breakdown = inner_.step()) {
    fail_breakdown(breakdown->gd, breakdown->dAd);
    return;
  }
  finish_iteration();
}

int Mprgp::free_contact_rows() const {
  const std::vector<char>& free = inner_.free();
  int count = 0;
  for (int k = 0; k < space().rows(); ++k)
    count += space().is_contact(k) && space().owned(k) && free[k];
  return static_cast<int>(space().sum(static_cast<long long>(count)));
}

// Converged when the projected gradient and the groups' imbalance are within the
// tolerance; else, with groups, SMALBE's outer iteration when the inner solve is far
// enough.
void Mprgp::finish_iteration() {
  double gradient = inner_.projected_gradient();
  const double imbalance = groups_.empty() ? 0.0 : space().norm(inner_.qx());
  const double tolerance = options_.tolerance * scale_;
  r_ = r0_ - inner_.ftx();
  if (gradient <= tolerance && norm_H_ * imbalance <= tolerance) {
    converge();
  } else if (outer_ && outer_->outer_step_due(gradient, imbalance, tolerance)) {
    if (!outer_->outer_step(imbalance, tolerance))
      fail("the groups of struts held only by contacts cannot be balanced at load factor " +
           format_number(load_factor_) + " (no contact can take the force they need)");
    gradient = inner_.projected_gradient();
  }
  const double residual = relative(std::max(gradient, norm_H_ * imbalance));
  if (status() == Status::Running) watch_stagnation(residual, kMprgpStagnationWindow);
  record(residual, free_contact_rows());
}

// alpha = (G_E G_E')^+ G_E (F lambda - d) - sum_z nu_z z: the rigid-body amplitudes of
// the KKT conditions (gap = F lambda - d - G'alpha), nu_z the multiplier of group z's
// balance (C nu, the inner problem's offset).
Eigen::VectorXd Mprgp::solution_amplitudes() const {
  Eigen::VectorXd alpha = -coarse_.amplitudes(r_);
  if (groups_.empty()) return alpha;
  groups_.add_directions(-groups_.gram_solve(groups_.transpose_times(inner_.offset())), alpha);
  return alpha;
}

Snapshot Mprgp::snapshot() const {
  Snapshot s = snapshot_header();
  const Decomposition& d = system_.decomposition();
  const int pairs = static_cast<int>(model_.pairs.size());
  s.force.assign(pairs, 0.0);
  s.in_working_set.assign(pairs, 0);
  // (Alike on every process: the same set-up and iterations.)
  if (history().empty()) return s;
  const Eigen::VectorXd lambda = lambda0_ + to_multipliers(inner_.x());
  s.pieces = system_.pieces(lambda, solution_amplitudes(), load_factor_);
  s.dual = lambda;
  // Forces of the pairs whose rows this process holds (gathered_snapshot() collects the
  // others); the working set of all pairs, as FETI-C's, so that every process takes the
  // same warm-start decisions (predict_warm_start).
  for (int k = 0; k < pairs; ++k) {
    const int row = d.pair_row[k] < 0 ? -1 : space().local_row(d.pair_row[k]);
    if (row >= 0) s.force[k] = std::max(0.0, lambda(row));
  }
  s.in_working_set = working_set();
  return s;
}

std::vector<char> Mprgp::working_set() const {
  const Decomposition& d = system_.decomposition();
  std::vector<char> set(model_.pairs.size(), 0);
  if (history().empty()) return set;
  std::vector<int> mine;
  for (std::size_t k = 0; k < set.size(); ++k) {
    const int row = d.pair_row[k] < 0 ? -1 : space().local_row(d.pair_row[k]);
    if (row >= 0 && space().owned(row) && inner_.x()(row) > inner_.lower()(row))
      mine.push_back(static_cast<int>(k));
  }
  for (int k : space().communicator().all_gather(mine))
    set[static_cast<std::size_t>(k)] = 1;
  return set;
}

}  // namespace fetic::solver
