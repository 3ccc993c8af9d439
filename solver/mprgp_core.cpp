#include "solver/mprgp_core.hpp"

#include <algorithm>
#include <limits>

namespace fetic::solver {

void MprgpCore::place(const Eigen::VectorXd& b, const Eigen::VectorXd& lower,
                      const Eigen::VectorXd& x) {
  const auto rows = x.size();
  b_ = b;
  lower_ = lower;
  x_ = x;
  c_.setZero(rows);
  qx_.setZero(rows);
  steps_ = {};
  condition_.clear();
}

void MprgpCore::start() {
  recompute_gradient();
  restart();
}

void MprgpCore::recompute_gradient() {
  problem_.apply_A(x_, g_, ftx_, qx_);
  g_ += c_ - b_;
}

void MprgpCore::split_gradient() {
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

double MprgpCore::feasible_step(const Eigen::VectorXd& p) const {
  double step = std::numeric_limits<double>::infinity();
  for (int k = 0; k < space().rows(); ++k)
    if (space().is_contact(k) && p(k) > 0.0) step = std::min(step, (x_(k) - lower_(k)) / p(k));
  return -space().max(-step);
}

void MprgpCore::step_to_bound(double a, const Eigen::VectorXd& p) {
  for (int k = 0; k < space().rows(); ++k) {
    if (space().is_contact(k) && p(k) > 0.0 && x_(k) - lower_(k) <= a * p(k))
      x_(k) = lower_(k);
    else
      x_(k) -= a * p(k);
  }
}

void MprgpCore::restart() {
  face_steps_ = 0;
  condition_.restart();
  beta_ = 0.0;
  split_gradient();
  problem_.precondition(g_free_, free_, z_);
  p_ = z_;
}

void MprgpCore::shift_offset(const Eigen::VectorXd& delta) {
  c_ += delta;
  g_ += delta;
}

double MprgpCore::projected_gradient() const {
  return space().norm(g_free_ + g_chopped_);
}

double MprgpCore::lagrangian() const {
  // With g = A x - b + c:  L = 1/2 x'A x - b'x + c'x = 1/2 x'(g - b + c).
  return 0.5 * space().dot(x_, g_ - b_ + c_);
}

std::optional<MprgpCore::Breakdown> MprgpCore::step() {
  const double chopped = space().dot(g_chopped_, g_chopped_);
  const double proportional = space().dot(g_reduced_, g_free_);
  // A new face is explored before its bound rows are judged (a large gamma: releasing
  // rows early costs expansions); once CG has run on it, a bound row whose chopped
  // gradient rivals the free one is released at once instead of waiting for the free
  // gradient to fall tenfold below it (docs/METHODS.md, "Parameters").
  const double gamma =
      face_steps_ >= parameters_.settle_steps ? parameters_.settled_gamma : parameters_.gamma;
  if (chopped <= gamma * gamma * proportional) return conjugate_gradient_or_expansion();
  return proportioning();
}

std::optional<MprgpCore::Breakdown> MprgpCore::conjugate_gradient_or_expansion() {
  Eigen::VectorXd Ap, ftp, qp;
  problem_.apply_A(p_, Ap, ftp, qp);
  const double pAp = space().dot(p_, Ap);
  const double gp = space().dot(g_, p_);
  if (!(pAp > 0.0)) return Breakdown{gp, pAp};
  if (!(gp > 0.0)) {
    // Rounding has spoilt the conjugacy so that p no longer descends: restart from z.
    ++steps_.cg;
    restart();
    return std::nullopt;
  }
  const double a_cg = gp / pAp;
  const double a_feasible = feasible_step(p_);
  if (a_cg <= a_feasible) {
    ++steps_.cg;
    ++face_steps_;
    condition_.add(a_cg, beta_);
    x_ -= a_cg * p_;
    g_ -= a_cg * Ap;
    ftx_ -= a_cg * ftp;
    if (qp.size() != 0) qx_ -= a_cg * qp;
    split_gradient();
    problem_.precondition(g_free_, free_, z_);
    const double beta = space().dot(z_, Ap) / pAp;
    p_ = z_ - beta * p_;
    beta_ = -beta;
    return std::nullopt;
  }
  expand(a_cg, a_feasible, Ap);
  return std::nullopt;
}

// Expansion. First the whole CG step with the rows it would take below their bound put
// on it (ESPRESO's "mixed" step): kept when L decreased, which it mostly does, and it
// changes many rows at once. Else Dostal's: to the first bound, then a projected gradient
// step of fixed length alpha_bar, halved for good should it not decrease L (the
// estimate of ||A|| was too low for 2 / ||A||).
void MprgpCore::expand(double a_cg, double a_feasible, const Eigen::VectorXd& Ap) {
  ++steps_.expansion;
  const double before = lagrangian();
  const Eigen::VectorXd x_kept = x_, g_kept = g_;
  x_ = (x_ - a_cg * p_).cwiseMax(lower_);
  recompute_gradient();
  if (lagrangian() < before) {
    restart();
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
  restart();
}

std::optional<MprgpCore::Breakdown> MprgpCore::proportioning() {
  ++steps_.proportioning;
  const Eigen::VectorXd d = g_chopped_;
  Eigen::VectorXd Ad, ftd, qd;
  problem_.apply_A(d, Ad, ftd, qd);
  const double dAd = space().dot(d, Ad);
  const double gd = space().dot(g_, d);
  if (!(dAd > 0.0)) return Breakdown{gd, dAd};
  const double a = gd / dAd;
  x_ -= a * d;  // d <= 0 on rows at their bound: they move up, off it
  g_ -= a * Ad;
  ftx_ -= a * ftd;
  if (qd.size() != 0) qx_ -= a * qd;
  restart();
  return std::nullopt;
}

}  // namespace fetic::solver
