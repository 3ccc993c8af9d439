#pragma once
// The MPRGP core (Dostal's modified proportioning with reduced gradient projections;
// docs/METHODS.md 4.6, PERMON's MPGP): one bound-constrained quadratic problem
//
//   min 1/2 x'A x - b'x + c'x   s.t.  x_I >= l_I  (I: the contact rows),
//
// a step at a time. The problem (solver/mprgp.hpp) supplies A and the preconditioner in
// face; the offset c is the outer solver's (solver/smalbe.hpp: C nu, the multiplier of the
// groups' balance), zero without one. Each step is a conjugate gradient step in the face of
// the free rows, an expansion step (to the first bound, then a projected gradient step of
// fixed length alpha_bar) or a proportioning step (along the chopped gradient, releasing
// contact rows whose multiplier should grow). Expansion and proportioning steps stay
// unpreconditioned, so they keep feasibility and descent.

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "solver/condition_estimate.hpp"
#include "solver/dual_space.hpp"

namespace fetic::solver {

// The parameters, the values used and why (docs/METHODS.md has the measurements).
struct MprgpParameters {
  // Proportioning when ||g_chopped||^2 > gamma^2 g_reduced'g_free: gamma while a face is
  // new (fewer than settle_steps CG steps since the last restart), settled_gamma after.
  double gamma = 10.0;
  double settled_gamma = 1.0;
  int settle_steps = 3;
  double alpha_factor = 1.9;  // expansion step alpha_bar = alpha_factor / ||A||, < 2
  double rho_factor = 10.0;   // SMALBE penalty rho = rho_factor ||H|| for the groups
  double m_factor = 100.0;    // initial M = m_factor ||A|| (PERMON)
  double m_divisor = 2.0;     // M /= m_divisor when the Lagrangian grows too little
  double eta_factor = 0.1;    // eta = eta_factor ||b|| (PERMON)
  // Lanczos for ||H|| (largest_eigenvalue.hpp): stops when the Ritz value's residual is
  // within norm_tolerance of it (not before norm_min_products applications of F), else
  // after norm_products. 5%: alpha_factor's margin below 2.
  double norm_tolerance = 0.05;
  int norm_min_products = 3;
  int norm_products = 10;
};

// What the core needs of the problem it runs on.
class MprgpProblem {
 public:
  virtual ~MprgpProblem() = default;
  // out = A x, with the parts of it the outer solver reads: ftx = F T x (the residual)
  // and qx = Q_C x (the groups' balance; left as it is without groups).
  virtual void apply_A(const Eigen::VectorXd& x, Eigen::VectorXd& out, Eigen::VectorXd& ftx,
                       Eigen::VectorXd& qx) const = 0;
  // z from the free gradient on the face `free` (z = g_free unpreconditioned).
  virtual void precondition(const Eigen::VectorXd& g_free, const std::vector<char>& free,
                            Eigen::VectorXd& z) = 0;
  virtual const DualSpace& dual_space() const = 0;
};

class MprgpCore {
 public:
  // Steps of each kind in the current solve.
  struct Steps {
    int cg = 0, expansion = 0, proportioning = 0;
  };
  // A step whose curvature d'A d vanished: the numbers for the message.
  struct Breakdown {
    double gd = 0.0, dAd = 0.0;
  };

  MprgpCore(MprgpProblem& problem, const MprgpParameters& parameters)
      : problem_(problem), parameters_(parameters) {}
  // alpha_bar = alpha_factor / ||A|| (halved for good when a step finds it too long).
  void set_norm(double norm_A) { alpha_bar_ = parameters_.alpha_factor / norm_A; }

  // A new solve from `x` (within the bounds): the offset and the step counts cleared.
  // Computes nothing; start() takes the gradient.
  void place(const Eigen::VectorXd& b, const Eigen::VectorXd& lower, const Eigen::VectorXd& x);
  // g = A x - b + c (one application of A) and a fresh direction.
  void start();
  // One step; a breakdown leaves the iterate where it was.
  std::optional<Breakdown> step();

  // The outer solver's interface: c += delta (and the gradient with it); then restart().
  void shift_offset(const Eigen::VectorXd& delta);
  void restart();
  // ||g_P||: the projected gradient (free and chopped parts).
  double projected_gradient() const;
  // After shift_offset: the gradient split again and ||g_P||, without a new direction.
  double split_and_measure() {
    split_gradient();
    return projected_gradient();
  }
  // L(x) = 1/2 x'A x - b'x + c'x.
  double lagrangian() const;

  const Eigen::VectorXd& x() const { return x_; }
  const Eigen::VectorXd& lower() const { return lower_; }
  const Eigen::VectorXd& offset() const { return c_; }
  const Eigen::VectorXd& ftx() const { return ftx_; }  // F T x
  const Eigen::VectorXd& qx() const { return qx_; }    // Q_C x
  const std::vector<char>& free() const { return free_; }
  const Steps& steps() const { return steps_; }
  // The CG steps' coefficients since place(), run by run (a restart starts a run).
  const ConditionRecord& condition() const { return condition_; }

 private:
  const DualSpace& space() const { return problem_.dual_space(); }
  void recompute_gradient();  // g = A x - b + c, one application of F
  void split_gradient();      // free set, free, chopped and reduced free gradients
  double feasible_step(const Eigen::VectorXd& p) const;  // largest a keeping x - a p feasible
  void step_to_bound(double a, const Eigen::VectorXd& p);
  std::optional<Breakdown> conjugate_gradient_or_expansion();
  void expand(double a_cg, double a_feasible, const Eigen::VectorXd& Ap);
  std::optional<Breakdown> proportioning();

  MprgpProblem& problem_;
  MprgpParameters parameters_;
  double alpha_bar_ = 0.0;
  Eigen::VectorXd b_, lower_, c_;
  Eigen::VectorXd x_, g_, ftx_, qx_;  // iterate, gradient, F T x, Q_C x
  Eigen::VectorXd p_, z_;
  std::vector<char> free_;
  Eigen::VectorXd g_free_, g_chopped_, g_reduced_;
  Steps steps_;
  ConditionRecord condition_;
  double beta_ = 0.0;   // the last direction update, as p = z + beta p (ConditionRecord's sign)
  int face_steps_ = 0;  // CG steps since the direction was last restarted
};

}  // namespace fetic::solver
