#pragma once
// The projector onto ker G_F for a face F of MPRGP (the equality rows and the contact
// rows off their bound), for preconditioning in the face:
//
//   P_F v = v - G_F'(G_F G_F')^+ G_F v.
//
// G_F G_F' is FETI-C's coarse matrix for the working set F (CoarseProblem): a face change
// of a few rows updates its factor by those rows' columns of G (rank-k update/downdate),
// a bigger one refactorizes numerically with CHOLMOD's kept ordering and symbolic
// analysis, and nothing is dense. (An
// earlier version updated the equality rows' factor by Woodbury with a dense matrix over
// the modes next to contacts: a few hundred on plane scenes, but 4,000 on a 2,000-pair bar
// scene, where each face change cost a dense 4,000 x 4,000 LU: 96 s for 7 iterations.)
// Groups of struts the equality rows leave free (bar groups held only by contacts, frame
// mechanisms) stay pinned whatever the face: G_F G_F' + sum z z' over their directions z,
// as the Woodbury form had it. Their motion is then kept in part by the projection, which
// SMALBE needs to balance them (with the exact pseudo-inverse of a face holding none of a
// group's rows, the preconditioned direction loses it and has no curvature).
//
// Distributed like CoarseProblem: replicated, the same bits on every process.

#include <vector>

#include <Eigen/Core>

#include "solver/coarse_problem.hpp"
#include "solver/feti_system.hpp"

namespace fetic::solver {

class FaceProjector {
 public:
  // `equality`: the equality rows' coarse problem, whose pattern it shares; it pins the
  // groups those rows leave free (equality.unheld()).
  explicit FaceProjector(const CoarseProblem& equality)
      : coarse_(equality, CoarseProblem::SamePattern{}) {
    coarse_.pin_always(equality.unheld());
  }

  // The face: per local row, nonzero for the equality rows and the free contact rows.
  // Collective (one all-gather of the changed rows; a refactorization when there are any).
  void set_face(const std::vector<char>& face) { coarse_.set_active_rows(face); }
  // v <- P_F v; v must vanish outside the face (so does the result).
  void project(Eigen::VectorXd& v) const { coarse_.project(v); }
  // See CoarseProblem::forget_updates.
  void forget_updates() { coarse_.forget_updates(); }
  // How often a face change refactorized G_F G_F'.
  int factorizations() const { return coarse_.factorizations(); }

 private:
  CoarseProblem coarse_;
};

}  // namespace fetic::solver
