#pragma once
// MPRGP (Dostal's modified proportioning with reduced gradient projections; docs/METHODS.md
// 4.6, Dostal 2009, PERMON's MPGP, ESPRESO's MPRGP) on the dual problem of section 2,
// with the same FETI operators and subdomains as FETI-C:
//
//   min 1/2 lambda'F lambda - lambda'd   s.t.  G lambda = e,  lambda_I >= 0.
//
// The equality constraints by a projector that leaves the bounds alone. With lambda =
// lambda0 + mu (G lambda0 = e), G mu = 0 reads G_E mu_E + G_I mu_I = 0: the rigid-body
// modes of every subdomain are fixed by its equality rows E (gluing, Dirichlet), so the
// contact part mu_I can be anything and mu_E follows. The variables are x = (x_E, x_I)
// with x_E in ker G_E and x_I >= l_I = -lambda0_I - a box in a subspace - and
//
//   mu = T x = x - G_E'(G_E G_E')^+ G x        (T: onto ker G, contact rows untouched)
//
// so MPRGP runs on  min 1/2 x'H x - b'x,  H = T'F T,  b = T'(d - F lambda0)  over that
// set, and the projection onto it is the orthogonal projector P_E of the equality rows
// (on x_E) and clipping (on x_I): they act on different rows, so they commute. The
// gradient on a contact row, (T'(F lambda - d))_k, is the row's gap with the rigid-body
// motion the equality rows give the subdomains - FETI-C's gap with G_E instead of G^.
// G_E G_E' is factorized once (CoarseProblem on the equality rows) and never changes.
//
// Bar struts held only by contacts: their rigid translation z is not fixed by G_E; the
// balance of such a group is z'G x = 0, a constraint on the contact rows, enforced by
// SMALBE (augmented Lagrangian, PERMON's SMALXE) with penalty rho on these few rows:
// A = H + rho Q_C, Q_C the projector onto span{G'z}. Plane struts are always clamped,
// so plane scenes need no outer iterations.
//
// Each step of the stepper is one MPRGP iteration: a conjugate gradient step in the face
// of the free rows, an expansion step (to the first bound, then a projected gradient
// step of fixed length alpha_bar) or a proportioning step (along the chopped gradient,
// releasing contact rows whose multiplier should grow). Preconditioning in face (Dirichlet
// or lumped): the CG directions come from z = Z P_E M^-1 P_E Z g_free, Z the restriction
// to the free rows: on the face the masked M^-1 is the FETI preconditioner of the face's
// rows (as FETI-C's), and P_E does not mix free and bound rows. Expansion and
// proportioning steps stay unpreconditioned, so they keep feasibility and descent.

#include <optional>
#include <vector>

#include "solver/face_projector.hpp"
#include "solver/feti_method.hpp"
#include "solver/group_balance.hpp"

namespace fetic::solver {

// The parameters, the values used and why (docs/METHODS.md has the measurements).
struct MprgpParameters {
  // Proportioning when ||g_chopped||^2 > gamma^2 g_reduced'g_free: gamma while a face is
  // new (fewer than settle_steps CG steps since the last restart), settled_gamma after.
  double gamma = 10.0;
  double settled_gamma = 1.0;
  int settle_steps = 3;
  double alpha_factor = 1.9;      // expansion step alpha_bar = alpha_factor / ||A||, < 2
  double rho_factor = 10.0;       // SMALBE penalty rho = rho_factor ||H|| for the groups
  double m_factor = 100.0;        // initial M = m_factor ||A|| (PERMON)
  double m_divisor = 2.0;         // M /= m_divisor when the Lagrangian grows too little
  double eta_factor = 0.1;        // eta = eta_factor ||b|| (PERMON)
  double power_tolerance = 1e-3;  // power method for ||H||: relative change
  int power_iterations = 10;      // and its cap
};

class Mprgp final : public FetiMethod {
 public:
  Mprgp(const Model& model, const SolveOptions& options,
        const Communicator& communicator = Communicator::self(), MprgpParameters parameters = {});
  MethodKind kind() const override { return MethodKind::Mprgp; }
  Snapshot snapshot() const override;
  // The contact rows off their bound (collective: gathers the flags of all processes).
  std::vector<char> working_set() const override;

  // ||H|| as estimated at set-up, and the applications of F that took.
  double operator_norm() const { return norm_H_; }
  int setup_f_applications() const { return power_steps_; }
  // Steps of each kind in the current solve, and SMALBE outer iterations.
  struct Counts {
    int cg = 0, expansion = 0, proportioning = 0, outer = 0;
  };
  const Counts& counts() const { return counts_; }

 private:
  void begin(const Snapshot* warm) override;
  void advance() override;

  void find_group_constraints();
  void estimate_operator_norm();
  Eigen::VectorXd to_multipliers(const Eigen::VectorXd& x) const;  // T x
  Eigen::VectorXd to_gradient(const Eigen::VectorXd& w) const;     // T'w
  // out = A x, with F T x (for the residual) and Q_C x.
  void apply_A(const Eigen::VectorXd& x, Eigen::VectorXd& out, Eigen::VectorXd& ftx,
               Eigen::VectorXd& qx) const;
  void recompute_gradient();  // g = A x - b + C nu, one application of F
  void split_gradient();      // free set, free, chopped and reduced free gradients
  void precondition_free_gradient(Eigen::VectorXd& z);
  double feasible_step(const Eigen::VectorXd& p) const;  // largest a keeping x - a p feasible
  void step_to_bound(double a, const Eigen::VectorXd& p);
  void conjugate_gradient_or_expansion();
  void expand(double a_cg, double a_feasible, const Eigen::VectorXd& Ap);
  void proportioning();
  void restart_direction();
  void finish_iteration();
  void repeat_outer_update(double tolerance);
  double lagrangian() const;
  int free_contact_rows() const;
  Eigen::VectorXd solution_amplitudes() const;

  MprgpParameters parameters_;
  std::optional<FaceProjector> face_;  // projector of the current face, for preconditioning
  double norm_H_ = 0.0, norm_A_ = 0.0, rho_ = 0.0, alpha_bar_ = 0.0;
  int power_steps_ = 0;
  // Balance of the groups held only by contacts: C = [G'z] and Q_C.
  GroupBalance groups_;

  // Per solve.
  Eigen::VectorXd lambda0_, r0_, lower_, b_;
  Eigen::VectorXd x_, g_, ftx_, qx_;  // iterate, gradient, F T x, Q_C x
  Eigen::VectorXd c_nu_;              // C nu, the SMALBE multiplier's term in the gradient
  Eigen::VectorXd p_, z_;
  std::vector<char> free_;
  Eigen::VectorXd g_free_, g_chopped_, g_reduced_;
  double m_ = 0.0, eta_ = 0.0, lagrangian_previous_ = 0.0;
  Counts counts_;
  int face_steps_ = 0;  // CG steps since the direction was last restarted
};

}  // namespace fetic::solver
