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
// SMALBE (solver/smalbe.hpp) with penalty rho on these few rows: A = H + rho Q_C, Q_C the
// projector onto span{G'z}. Plane struts are always clamped, so plane scenes need no
// outer iterations.
//
// The parts: this class sets up the problem (T, b, the bounds, ||H||) and is the
// stepper; the MPRGP core (solver/mprgp_core.hpp) iterates on it; with groups, SMALBE
// holds that core as its inner solver and updates the groups' multiplier between its
// iterations. Each step of the stepper is one MPRGP iteration (and, when due, one SMALBE
// outer iteration after it). Preconditioning in face (Dirichlet or lumped): the CG
// directions come from z = Z P_E M^-1 P_E Z g_free, Z the restriction to the free rows:
// on the face the masked M^-1 is the FETI preconditioner of the face's rows (as
// FETI-C's), and P_E does not mix free and bound rows.

#include <optional>
#include <vector>

#include "solver/contact_coarse.hpp"
#include "solver/face_projector.hpp"
#include "solver/feti_method.hpp"
#include "solver/group_balance.hpp"
#include "solver/mprgp_core.hpp"
#include "solver/smalbe.hpp"

namespace fetic::solver {

class Mprgp final : public FetiMethod, private MprgpProblem {
 public:
  Mprgp(const Model& model, const SolveOptions& options,
        const Communicator& communicator = Communicator::self(), MprgpParameters parameters = {});
  Snapshot snapshot() const override;
  // The contact rows off their bound (collective: gathers the flags of all processes).
  std::vector<char> working_set() const override;

  // ||H|| as estimated at set-up, and the applications of F the set-up took (the
  // estimate's, Lanczos, and, for FETI-DP, one per batch of columns of the contact faces' coarse
  // space).
  double operator_norm() const { return norm_H_; }
  int setup_f_applications() const {
    return norm_products_ + (contact_coarse_ ? contact_coarse_->applications() : 0);
  }
  // Columns of FETI-DP's coarse space of the contact faces (0: none).
  int contact_columns() const { return contact_coarse_ ? contact_coarse_->columns() : 0; }
  // Steps of each kind in the current solve, and SMALBE outer iterations.
  struct Counts {
    int cg = 0, expansion = 0, proportioning = 0, outer = 0;
  };
  Counts counts() const;
  ConditionEstimate condition_estimate() const override { return inner_.condition().estimate(); }

 private:
  void begin(const Snapshot* warm) override;
  void advance() override;

  // MprgpProblem: the operator A = T'F T (+ rho Q_C) and the preconditioner in face.
  void apply_A(const Eigen::VectorXd& x, Eigen::VectorXd& out, Eigen::VectorXd& ftx,
               Eigen::VectorXd& qx) const override;
  void precondition(const Eigen::VectorXd& g_free, const std::vector<char>& free,
                    Eigen::VectorXd& z) override;
  const DualSpace& dual_space() const override { return space(); }

  void find_group_constraints();
  void precondition_in_face(const Eigen::VectorXd& g_free, const std::vector<char>& free,
                            Eigen::VectorXd& z);
  void estimate_operator_norm();
  Eigen::VectorXd to_multipliers(const Eigen::VectorXd& x) const;  // T x
  Eigen::VectorXd to_gradient(const Eigen::VectorXd& w) const;     // T'w
  void finish_iteration();
  int free_contact_rows() const;
  Eigen::VectorXd solution_amplitudes() const;

  MprgpParameters parameters_;
  std::optional<FaceProjector> face_;  // projector of the current face, for preconditioning
  // FETI-DP with contacts, preconditioned: the contact faces' modes, balanced (the hybrid:
  // only between clusters without modes).
  std::optional<ContactCoarseSpace> contact_coarse_;
  double norm_H_ = 0.0, norm_A_ = 0.0, rho_ = 0.0;
  int norm_products_ = 0;
  // Balance of the groups held only by contacts: C = [G'z] and Q_C.
  GroupBalance groups_;
  MprgpCore inner_{*this, parameters_};
  std::optional<Smalbe> outer_;  // with groups: SMALBE, holding inner_

  // Per solve.
  Eigen::VectorXd lambda0_, r0_;
};

}  // namespace fetic::solver
