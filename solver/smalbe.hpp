#pragma once
// SMALBE (Dostal's semi-monotonic augmented Lagrangian for bound and equality
// constraints; docs/METHODS.md 4.6, PERMON's SMALXE): the outer solver of MPRGP's dual
// problem when groups of struts are held only by contacts. Their balance C'x = 0 (a
// constraint on the contact rows, solver/group_balance.hpp) is enforced by the penalty
// rho Q_C inside the inner operator A = H + rho Q_C and by the multiplier term C nu, the
// inner problem's linear offset. SMALBE holds the MPRGP core (solver/mprgp_core.hpp) as
// its inner solver, as PERMON's SMALXE holds an inner QPS: the inner solver runs until its
// projected gradient is below min(M ||Q_C x||, eta); then an outer iteration updates
// C nu += rho Q_C x, halving M when the Lagrangian grew too little.

#include <algorithm>

#include "solver/mprgp_core.hpp"

namespace fetic::solver {

class Smalbe {
 public:
  // `rho`: the penalty inside the inner operator (rho_factor ||H||).
  Smalbe(MprgpCore& inner, const MprgpParameters& parameters, double rho)
      : inner_(inner), parameters_(parameters), rho_(rho) {}

  // A new solve: M = m_factor ||A||, eta, no Lagrangian seen yet, no outer iterations.
  void start(double norm_A, double eta);
  // Whether the inner problem is solved as far as this outer iteration needs: its
  // projected gradient below min(M ||Q_C x||, eta), or within the tolerance (then further
  // inner iterations cannot help; M may have fallen below what rounding allows).
  bool outer_step_due(double gradient, double imbalance, double tolerance) const {
    return gradient <= std::min(m_ * imbalance, eta_) || gradient <= tolerance;
  }
  // The outer iteration: C nu += rho Q_C x and a fresh inner direction. Returns false when
  // the groups cannot be balanced (no contact can take the force they need).
  bool outer_step(double imbalance, double tolerance);
  int outer_iterations() const { return outer_; }

 private:
  bool repeat_outer_step(double tolerance);

  MprgpCore& inner_;
  MprgpParameters parameters_;
  double rho_ = 0.0;
  double m_ = 0.0, eta_ = 0.0, lagrangian_previous_ = 0.0;
  int outer_ = 0;
};

}  // namespace fetic::solver
