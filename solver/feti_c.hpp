#pragma once
// FETI-C (docs/METHODS.md 4.5, thesis Def. 8.5, Dureisseix & Farhat 2001): PCPG on the
// equality rows and the working set W of contact rows, with the planning procedure
// PLAN keeping lambda_W >= 0 and G^ lambda = e after every step.
//
//   W = all contact rows; lambda = PLAN(G'(GG')^-1 e); r = d - F lambda
//   loop: w^ = P^ r on E and W; on a contact row outside W the true gap decides:
//           w^_k = max(0, -gap_k),  gap = F lambda - d - G'alpha  (full G: a floating
//           tip's rigid motion counts, which P^ r alone misses)
//         stop when ||w^|| <= tol ||d||
//         A = E + W + {rows outside W that penetrate (w^_k > 0)}
//         w = P_A r; z = M^-1 w (on A); y = P_A z; p = y + beta p
//         lambda = PLAN(lambda + a p),  a = y'w / p'F p
//         r -= a F p if PLAN changed nothing, else r = d - F lambda
//
// Difference from the thesis (and docs/METHODS.md 4.5), and why: there the direction is
// z = M^-1 w^ projected with P^ of E and W only, so the components on penetrating rows
// outside W leave ker G: p'F p can then vanish (F is only definite on ker G) and the
// step a = y'w / p'F p explodes - it does on random scenes with floating struts. Here
// each step is a plain PCPG step on the face A, the working set widened by the rows
// that penetrate: it stays in ker G_A, so p'F p > 0 and y'w >= 0, and PLAN then keeps
// the rows whose multipliers came out positive. Stopping test and optimality
// conditions are the thesis' own.
//
// When A changes, conjugacy is lost and the next step restarts (beta = 0). A warm start
// takes lambda and W from a previous snapshot and re-plans them for the new load.

#include <string>
#include <vector>

#include "solver/feti_method.hpp"

namespace fetic::solver {

class FetiC final : public FetiMethod {
 public:
  FetiC(const Model& model, const SolveOptions& options,
        const Communicator& communicator = Communicator::self());

 private:
  void begin(const Snapshot* warm) override;
  void advance() override;
  // The planning procedure (Def. 8.4): clip lambda_k <= 0 out of W, restore G^ lambda = e,
  // repeat until both hold. Returns true when W changed (on any process).
  bool plan(Eigen::VectorXd& lambda);
  // Collective: every process calls it at the same point.
  void set_working_set(const std::vector<char>& active);
  bool hold_loaded_groups();
  bool balanced(const Eigen::VectorXd& lambda) const;
  void compute_search_residual();
  void record_state();

  std::vector<char> active_;  // per row: equality rows always; contact rows in W
  std::vector<char> face_;    // A: rows of the current step
  std::vector<char> previous_face_;
  Eigen::VectorXd w_hat_, p_, q_;
  std::vector<double> along_;  // hold_loaded_groups' scratch
  double yw_previous_ = 0.0;
  bool restart_ = true;
};

}  // namespace fetic::solver
