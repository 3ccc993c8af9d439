#include "solver/mprgp.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "solver/boundedness.hpp"
#include "solver/interruption.hpp"

namespace fetic::solver {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Iterations without a new lowest residual before the solve is declared stagnated. Longer
// than FETI-C's window: within one SMALBE outer iteration the residual, which includes
// the groups' imbalance, may rest while MPRGP drives the projected gradient down.
constexpr int kMprgpStagnationWindow = 200;

}  // namespace

Mprgp::Mprgp(const Model& model, const SolveOptions& options, const Communicator& communicator,
             MprgpParameters parameters)
    : FetiMethod(model, options, 0, communicator), parameters_(parameters) {
  if (options.max_iterations <= 0) max_iterations_ = 10 * space().global_rows() + 1000;
  std::vector<char> equality_rows(space().rows(), 0);
  for (int k = 0; k < space().rows(); ++k)
    equality_rows[k] = !space().is_contact(k);
  coarse_.set_active_rows(equality_rows);
  face_.emplace(system_, coarse_.unheld());
  find_group_constraints();
  estimate_operator_norm();
}

// Groups of struts the equality rows leave free: their balance z'G x = 0 involves only
// contact rows, c = G'z (group_balance.hpp).
void Mprgp::find_group_constraints() {
  groups_ = GroupBalance(system_, coarse_.unheld());
}

Eigen::VectorXd Mprgp::to_multipliers(const Eigen::VectorXd& x) const {
  return x - coarse_.apply_Gt(coarse_.solve(system_.apply_G(x)));
}

Eigen::VectorXd Mprgp::to_gradient(const Eigen::VectorXd& w) const {
  return w - system_.G().transpose() * coarse_.solve(coarse_.apply_G(w));
}

// ||H|| by the power method on the feasible subspace (PERMON: relative change 1e-4, at
// most 50 steps), from a fixed pseudo-random start so that no symmetry of the scene
// hides the largest eigenvalue. A row's start is drawn from its global index (splitmix64),
// so that every process count starts alike. The estimate approaches ||H|| from below.
void Mprgp::estimate_operator_norm() {
  const int rows = space().rows();
  Eigen::VectorXd v(rows), w, ftv, qv;
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
  double estimate = 0.0;
  const long long before = system_.f_applications();
  for (int step = 0; step < parameters_.power_iterations; ++step) {
    throw_if_stopped("estimating the operator's norm (power method)");
    const double size = space().norm(v);
    if (!(size > 0.0)) break;
    v /= size;
    apply_A(v, w, ftv, qv);
    const double next = space().norm(w);
    const bool settled = std::abs(next - estimate) <= parameters_.power_tolerance * next;
    estimate = next;
    v = w;
    if (settled) break;
  }
  power_steps_ = static_cast<int>(system_.f_applications() - before);
  norm_H_ = estimate > 0.0 ? estimate : 1.0;
  norm_A_ = norm_H_;
  if (!groups_.empty()) {
    rho_ = parameters_.rho_factor * norm_H_;
    norm_A_ = std::max(norm_H_, rho_);
  }
  alpha_bar_ = parameters_.alpha_factor / norm_A_;
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

void Mprgp::recompute_gradient() {
  apply_A(x_, g_, ftx_, qx_);
  g_ += c_nu_ - b_;
}

void Mprgp::split_gradient() {
  const int rows = space().rows();
  free_.assign(rows, 1);
  g_free_ = g_;
  g_chopped_.setZero(rows);
  g_reduced_ = g_;
  for (int k = 0; k < rows; ++k) {
    if (!space().is_contact(k)) continue;
    if (x_(k) > lower_(k)) {
      // Reduced free gradient: a step alpha_bar along it stays feasible.
      g_reduced_(k) = std::min(g_(k), (x_(k) - lower_(k)) / alpha_bar_);
    } else {
      free_[k] = 0;
      g_free_(k) = 0.0;
      g_reduced_(k) = 0.0;
      g_chopped_(k) = std::min(g_(k), 0.0);
    }
  }
}

void Mprgp::precondition_free_gradient(Eigen::VectorXd& z) {
  if (preconditioner_.kind() == Preconditioner::None) {
    z = g_free_;
    return;
  }
  // z = P_E P_F M^-1 P_F g_free on the face (see the header).
  face_->set_face(free_);
  Eigen::VectorXd w = g_free_;
  face_->project(w);
  preconditioner_.apply(w, &free_, z);
  system_.project_onto_range_of_B(z);
  face_->project(z);
  coarse_.project(z);
}

double Mprgp::feasible_step(const Eigen::VectorXd& p) const {
  double step = kInfinity;
  for (int k = 0; k < space().rows(); ++k)
    if (space().is_contact(k) && p(k) > 0.0) step = std::min(step, (x_(k) - lower_(k)) / p(k));
  return -space().max(-step);
}

void Mprgp::step_to_bound(double a, const Eigen::VectorXd& p) {
  for (int k = 0; k < space().rows(); ++k) {
    if (space().is_contact(k) && p(k) > 0.0 && x_(k) - lower_(k) <= a * p(k))
      x_(k) = lower_(k);
    else
      x_(k) -= a * p(k);
  }
}

void Mprgp::restart_direction() {
  face_steps_ = 0;
  split_gradient();
  precondition_free_gradient(z_);
  p_ = z_;
}

void Mprgp::begin(const Snapshot* warm) {
  d_ = system_.d(load_factor_);
  e_ = system_.e(load_factor_);
  const int rows = space().rows();
  counts_ = {};
  reset_watch();
  face_->forget_updates();

  // lambda0: balances the loads through the equality rows, and through the contact rows
  // of the groups they leave free: w = sum_z beta_z c_z with c_y'w = z_y'e.
  lambda0_ = coarse_.particular(e_);
  if (!groups_.empty())
    lambda0_ += to_multipliers(groups_.times(groups_.gram_solve(groups_.direction_dots(e_))));
  system_.residual(lambda0_, load_factor_, r0_);
  b_ = to_gradient(r0_);
  system_.project_onto_range_of_B(b_);
  lower_.setConstant(rows, -kInfinity);
  for (int k = 0; k < rows; ++k)
    if (space().is_contact(k)) lower_(k) = -lambda0_(k);

  c_nu_.setZero(rows);
  qx_.setZero(rows);
  const std::string unbounded = unbounded_struts(model_, load_factor_);
  if (!unbounded.empty()) {
    x_ = lower_.cwiseMax(0.0);
    r_ = d_;
    set_scale();
    record(relative(space().norm(r_)), 0);
    fail(unbounded);
    return;
  }

  // Start: lambda0 with negative contact multipliers clipped; warm, the previous
  // multipliers with the equality rows' part projected onto ker G_E.
  x_.setZero(rows);
  if (!space().any(!(warm && warm->dual.size() == rows))) {
    x_ = warm->dual - lambda0_;
    coarse_.project(x_);
  }
  x_ = x_.cwiseMax(lower_);
  recompute_gradient();
  r_ = r0_ - ftx_;
  set_scale();
  // eta relative to ||b|| (PERMON); b can vanish when lambda0 already minimizes on ker G.
  eta_ = parameters_.eta_factor * std::max(space().norm(b_), scale_);
  m_ = parameters_.m_factor * norm_A_;
  lagrangian_previous_ = -kInfinity;
  restart_direction();
  finish_iteration();
}

void Mprgp::advance() {
  ++iteration_;
  const double chopped = space().dot(g_chopped_, g_chopped_);
  const double proportional = space().dot(g_reduced_, g_free_);
  // A new face is explored before its bound rows are judged (a large gamma: releasing
  // rows early costs expansions); once CG has run on it, a bound row whose chopped
  // gradient rivals the free one is released at once instead of waiting for the free
  // gradient to fall tenfold below it (docs/METHODS.md, "Parameters").
  const double gamma =
      face_steps_ >= parameters_.settle_steps ? parameters_.settled_gamma : parameters_.gamma;
  if (chopped <= gamma * gamma * proportional)
    conjugate_gradient_or_expansion();
  else
    proportioning();
  if (status() == Status::Running) finish_iteration();
}

void Mprgp::conjugate_gradient_or_expansion() {
  Eigen::VectorXd Ap, ftp, qp;
  apply_A(p_, Ap, ftp, qp);
  const double pAp = space().dot(p_, Ap);
  const double gp = space().dot(g_, p_);
  if (!(pAp > 0.0)) {
    fail_breakdown(gp, pAp);
    return;
  }
  if (!(gp > 0.0)) {
    // Rounding has spoilt the conjugacy so that p no longer descends: restart from z.
    ++counts_.cg;
    restart_direction();
    return;
  }
  const double a_cg = gp / pAp;
  const double a_feasible = feasible_step(p_);
  if (a_cg <= a_feasible) {
    ++counts_.cg;
    ++face_steps_;
    x_ -= a_cg * p_;
    g_ -= a_cg * Ap;
    ftx_ -= a_cg * ftp;
    if (!groups_.empty()) qx_ -= a_cg * qp;
    split_gradient();
    precondition_free_gradient(z_);
    const double beta = space().dot(z_, Ap) / pAp;
    p_ = z_ - beta * p_;
    return;
  }
  expand(a_cg, a_feasible, Ap);
}

// Expansion. First the whole CG step with the rows it would take below their bound put
// on it (ESPRESO's "mixed" step): kept when L decreased, which it mostly does, and it
// changes many rows at once. Else Dostal's: to the first bound, then a projected gradient
// step of fixed length alpha_bar, halved for good should it not decrease L (the power
// method's estimate of ||A|| was too low for 2 / ||A||).
void Mprgp::expand(double a_cg, double a_feasible, const Eigen::VectorXd& Ap) {
  ++counts_.expansion;
  const double before = lagrangian();
  const Eigen::VectorXd x_kept = x_, g_kept = g_;
  x_ = (x_ - a_cg * p_).cwiseMax(lower_);
  recompute_gradient();
  if (lagrangian() < before) {
    restart_direction();
    return;
  }
  x_ = x_kept;
  g_ = g_kept;
  step_to_bound(a_feasible, p_);
  g_ -= a_feasible * Ap;
  split_gradient();
  const double halfway = lagrangian();
  const Eigen::VectorXd x_half = x_, g_half = g_;
  for (int attempt = 0; attempt < 30; ++attempt) {
    x_ = (x_half - alpha_bar_ * g_free_).cwiseMax(lower_);
    recompute_gradient();
    if (lagrangian() <= halfway) break;
    alpha_bar_ /= 2.0;
    g_ = g_half;
  }
  restart_direction();
}

void Mprgp::proportioning() {
  ++counts_.proportioning;
  const Eigen::VectorXd d = g_chopped_;
  Eigen::VectorXd Ad, ftd, qd;
  apply_A(d, Ad, ftd, qd);
  const double dAd = space().dot(d, Ad);
  const double gd = space().dot(g_, d);
  if (!(dAd > 0.0)) {
    fail_breakdown(gd, dAd);
    return;
  }
  const double a = gd / dAd;
  x_ -= a * d;  // d <= 0 on rows at their bound: they move up, off it
  g_ -= a * Ad;
  ftx_ -= a * ftd;
  if (!groups_.empty()) qx_ -= a * qd;
  restart_direction();
}

double Mprgp::lagrangian() const {
  // With g = A x - b + C nu:  L = 1/2 x'A x - b'x + nu'C'x = 1/2 x'(g - b + C nu).
  return 0.5 * space().dot(x_, g_ - b_ + c_nu_);
}

int Mprgp::free_contact_rows() const {
  int count = 0;
  for (int k = 0; k < space().rows(); ++k)
    count += space().is_contact(k) && space().owned(k) && free_[k];
  return static_cast<int>(space().sum(static_cast<long long>(count)));
}

void Mprgp::finish_iteration() {
  double gradient = space().norm(g_free_ + g_chopped_);
  const double imbalance = groups_.empty() ? 0.0 : space().norm(qx_);
  const double tolerance = options_.tolerance * scale_;
  r_ = r0_ - ftx_;
  if (gradient <= tolerance && norm_H_ * imbalance <= tolerance) {
    converge();
  } else if (!groups_.empty() &&
             (gradient <= std::min(m_ * imbalance, eta_) || gradient <= tolerance)) {
    // (Once the projected gradient is within the tolerance, further inner iterations
    // cannot help; M may have fallen below what rounding allows.)
    // SMALBE outer iteration: the groups' multiplier, and M when L grew too little.
    const double lagrangian_now = lagrangian();
    if (lagrangian_now < lagrangian_previous_ + 0.5 * rho_ * imbalance * imbalance)
      m_ /= parameters_.m_divisor;
    lagrangian_previous_ = lagrangian_now;
    c_nu_ += rho_ * qx_;
    g_ += rho_ * qx_;
    ++counts_.outer;
    restart_direction();
    gradient = space().norm(g_free_ + g_chopped_);
    if (gradient <= tolerance) repeat_outer_update(tolerance);
    gradient = space().norm(g_free_ + g_chopped_);
  }
  const double residual = relative(std::max(gradient, norm_H_ * imbalance));
  if (status() == Status::Running) watch_stagnation(residual, kMprgpStagnationWindow);
  record(residual, free_contact_rows());
}

// With the projected gradient within the tolerance, the inner problem is solved as far
// as rounding allows, and the next outer iterations would not move x: each adds
// rho Q_C x to the gradient again, until it leaves the tolerance (a contact row at its
// bound gets a negative gradient, or a free row a gradient to follow). Take them at
// once, doubling their number.
void Mprgp::repeat_outer_update(double tolerance) {
  const Eigen::VectorXd step = rho_ * qx_;
  double updates = 1.0;
  for (int round = 0; round < 200; ++round) {
    c_nu_ += updates * step;
    g_ += updates * step;
    counts_.outer += static_cast<int>(std::min(updates, 1e9));
    split_gradient();
    if (space().norm(g_free_ + g_chopped_) > tolerance) {
      restart_direction();
      return;
    }
    updates *= 2.0;
  }
  fail("the groups of struts held only by contacts cannot be balanced at load factor " +
       format_number(load_factor_) + " (no contact can take the force they need)");
}

// alpha = (G_E G_E')^+ G_E (F lambda - d) - sum_z nu_z z: the rigid-body amplitudes of
// the KKT conditions (gap = F lambda - d - G'alpha), nu_z the multiplier of group z's
// balance (C nu = c_nu_).
Eigen::VectorXd Mprgp::solution_amplitudes() const {
  Eigen::VectorXd alpha = -coarse_.amplitudes(r_);
  if (groups_.empty()) return alpha;
  groups_.add_directions(-groups_.gram_solve(groups_.transpose_times(c_nu_)), alpha);
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
  const Eigen::VectorXd lambda = lambda0_ + to_multipliers(x_);
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
    if (row >= 0 && space().owned(row) && x_(row) > lower_(row))
      mine.push_back(static_cast<int>(k));
  }
  for (int k : space().communicator().all_gather(mine))
    set[static_cast<std::size_t>(k)] = 1;
  return set;
}

}  // namespace fetic::solver
