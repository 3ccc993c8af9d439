#pragma once
// The coarse problem of FETI on a set of active rows (equality rows plus the contact rows
// of the working set): G^ keeps the columns of G for those rows, G^ G^' is factorized
// once per set (CHOLMOD) and gives
//   P^ v = v - G^'(G^ G^')^+ G^ v       (projector onto ker G^, section 3)
//   G^'(G^ G^')^+ e                     (the particular multipliers, (6.45), (8.25))
//   (G^ G^')^+ G^ r                     (rigid-body amplitudes, (6.50))
//
// G^ G^' is singular exactly when a group of bar struts held only by contacts has none
// of its contact rows active: the group can then translate freely along its axis. Such
// a direction z is found from the structure (subdomains linked by active rows, none of
// them a Dirichlet row) and G^ G^' + z z'/|z|^2 is factorized instead, which gives the
// pseudo-inverse on the range. `unheld()` lists those groups; a load on one of them
// (z'e != 0) means the working set cannot hold it. In the frame model a group may have
// several free directions (translations, rotation, mechanisms); FreeMotionSpace finds
// them as orthonormal directions, one UnheldGroup each.

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "solver/cholmod_factor.hpp"
#include "solver/feti_system.hpp"

namespace fetic::solver {

struct UnheldGroup {
  std::vector<int> subdomains;
  Eigen::VectorXd direction;  // over all modes, unit length, zero outside the group
};

class FreeMotionSpace;

class CoarseProblem {
 public:
  explicit CoarseProblem(const FetiSystem& system);

  // Factorizes G^ G^' for the rows with active[r] != 0.
  void set_active_rows(const std::vector<char>& active);
  const std::vector<char>& active_rows() const { return active_; }

  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;     // (G^ G^')^+ b
  Eigen::VectorXd apply_G(const Eigen::VectorXd& v) const;   // G^ v
  Eigen::VectorXd apply_Gt(const Eigen::VectorXd& a) const;  // G^' a (zero on inactive rows)
  void project(Eigen::VectorXd& v) const;                    // v <- P^ v
  Eigen::VectorXd particular(const Eigen::VectorXd& e) const;
  Eigen::VectorXd amplitudes(const Eigen::VectorXd& r) const;  // (G^ G^')^+ G^ r

  const std::vector<UnheldGroup>& unheld() const { return unheld_; }
  std::size_t factor_memory() const { return factor_.peak_memory(); }

 private:
  void find_unheld_groups();

  const FetiSystem& system_;
  std::vector<char> active_;
  SparseMatrix G_hat_;  // modes x rows, inactive columns removed (kept as zero columns)
  std::vector<UnheldGroup> unheld_;
  std::shared_ptr<const FreeMotionSpace> frame_motions_;  // frame model
  CholmodFactor factor_;
};

}  // namespace fetic::solver
