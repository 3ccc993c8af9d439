#pragma once
// The primal active-set method (docs/METHODS.md 4.4, Nocedal & Wright Alg. 16.3) on the
// assembled problem. K is factorized once, strut by strut; each working-set subproblem
//   min 1/2 p'K p + g'p  s.t.  a_k'p = 0 (k in W),   g = K x - t f
// is solved through the small dense saddle system of the Schur complement S = A K^+ A'
// (precomputed once) and the rigid-body modes R of floating struts:
//   p = -K^+(g + A_W' mu) + R beta,   A_W p = 0,   R'(g + A_W' mu) = 0.
// A floating strut the working set does not hold moves as a rigid body along its load
// until a contact blocks it; with nothing to block it the scene is unbounded.
// The working set changes by one row per iteration; the subproblem is solved per group of
// strut blocks the working set links (rows of S and C couple no others). Residual of an
// iteration: the size of the step to the subproblem minimizer relative to the
// displacement scale, or of the most negative multiplier relative to the load when the
// step is zero.

#include <vector>

#include <Eigen/Core>

#include "solver/method.hpp"
#include "solver/primal_problem.hpp"

namespace fetic::solver {

class ActiveSet final : public Method {
 public:
  ActiveSet(const Model& model, const SolveOptions& options);
  void begin(const Snapshot* warm) override;
  void advance() override;
  Snapshot snapshot() const override;
  std::vector<char> working_set() const override;

  const PrimalProblem& problem() const { return problem_; }

 private:
  enum class Move { Step, RigidMotion, Drop, Done };
  // Rows of W (positions in working_) and rigid-body modes of blocks that W links.
  struct Component {
    std::vector<int> rows;
    std::vector<int> modes;
  };
  std::vector<Component> components() const;

  // Per component of W: the modes W holds, the rows x modes block C = A_W R and R'g (for
  // the saddle system), and the rigid motion of the modes it does not hold.
  struct ModeSplit {
    std::vector<Eigen::MatrixXd> held, C;
    std::vector<Eigen::VectorXd> rg;
    Eigen::VectorXd amplitudes;  // of the rigid motion, per mode
    bool pushed = false;         // a free mode is pushed by the load
  };

  // One subproblem on the working set W, in three steps (below), which sets move_.
  void solve_subproblem();
  ModeSplit split_modes(const std::vector<Component>& parts) const;
  void take_rigid_motion(const Eigen::VectorXd& amplitudes);
  Eigen::VectorXd solve_saddle_systems(const std::vector<Component>& parts, const ModeSplit& split);
  void choose_move(const Eigen::VectorXd& beta_modes);
  void record_move();
  double slack(int row) const;
  // Smallest step along p_ (at most `limit`) that keeps rows outside W feasible; sets
  // blocking_ to the row that stops it, or -1.
  double ratio_test(double limit);

  PrimalProblem problem_;
  SparseMatrix S_;                            // A K^+ A'
  SparseMatrix AR_;                           // A R
  std::vector<std::vector<int>> row_blocks_;  // per contact row: the blocks it touches
  std::vector<int> mode_block_;               // per rigid-body mode: its block
  double u_scale_ = 1.0;
  double f_scale_ = 1.0;

  Eigen::VectorXd x_;
  Eigen::VectorXd g_;               // K x - t f
  std::vector<int> working_;        // rows in W, in the order they entered
  std::vector<double> multiplier_;  // per row of W, from the last subproblem
  Move move_ = Move::Done;
  Eigen::VectorXd p_;
  int drop_ = -1;                   // position in working_ of the row to drop
  int blocking_ = -1;               // row that blocks the step
  std::vector<int> moving_struts_;  // floating struts of a rigid motion
};

}  // namespace fetic::solver
