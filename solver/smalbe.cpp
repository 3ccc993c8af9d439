#include "solver/smalbe.hpp"

#include <algorithm>
#include <limits>

namespace fetic::solver {

void Smalbe::start(double norm_A, double eta) {
  eta_ = eta;
  m_ = parameters_.m_factor * norm_A;
  lagrangian_previous_ = -std::numeric_limits<double>::infinity();
  outer_ = 0;
}

bool Smalbe::outer_step(double imbalance, double tolerance) {
  const double lagrangian_now = inner_.lagrangian();
  if (lagrangian_now < lagrangian_previous_ + 0.5 * rho_ * imbalance * imbalance)
    m_ /= parameters_.m_divisor;
  lagrangian_previous_ = lagrangian_now;
  inner_.shift_offset(rho_ * inner_.qx());
  ++outer_;
  inner_.restart();
  if (inner_.projected_gradient() <= tolerance) return repeat_outer_step(tolerance);
  return true;
}

// With the projected gradient within the tolerance, the inner problem is solved as far
// as rounding allows, and the next outer iterations would not move x: each adds
// rho Q_C x to the gradient again, until it leaves the tolerance (a contact row at its
// bound gets a negative gradient, or a free row a gradient to follow). Take them at
// once, doubling their number.
bool Smalbe::repeat_outer_step(double tolerance) {
  const Eigen::VectorXd step = rho_ * inner_.qx();
  double updates = 1.0;
  for (int round = 0; round < 200; ++round) {
    inner_.shift_offset(updates * step);
    outer_ += static_cast<int>(std::min(updates, 1e9));
    if (inner_.split_and_measure() > tolerance) {
      inner_.restart();
      return true;
    }
    updates *= 2.0;
  }
  return false;
}

}  // namespace fetic::solver
