#pragma once
// Frame model: the motions of the subdomains that the equality rows of B (gluing,
// joints, supports) leave free are exactly the structure's free motions
// (scenes/frame_kinematics): every strut moves rigidly, so each of its subdomains by
// the same rigid motion. In subdomain-mode coordinates (rotation, x- and y-translation
// of each subdomain at its centre) they are the columns of Z. Which of them a set of
// active contact rows W leaves free is then the null space of the small matrix
// (G'Z)_W - the change of each active row per unit of each motion - computed per
// cluster of motions that contact rows link (SVD, threshold 1e-9). This replaces the
// bar model's walk along chains of floating struts (CoarseProblem::find_unheld_groups)
// and needs no rank decision on G^ G^' itself.

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "solver/coarse_problem.hpp"
#include "solver/feti_system.hpp"

namespace fetic::solver {

class FreeMotionSpace {
 public:
  explicit FreeMotionSpace(const FetiSystem& system);

  // Orthonormal directions over all modes that no active contact row stops (the equality
  // rows never do), one group each (with the subdomains it moves). `active`: one flag per
  // contact row of the decomposition, in global order (replicated, so that every process
  // finds the same directions).
  std::vector<UnheldGroup> unheld(const std::vector<char>& active) const;

 private:
  struct Cluster {
    std::vector<int> motions;
    std::vector<int> rows;        // contact rows (from 0) some motion of the cluster changes
    std::vector<int> modes;       // modes some motion of the cluster moves
    std::vector<int> subdomains;  // of the struts its motions move
  };

  const FetiSystem& system_;
  Eigen::SparseMatrix<double> Z_;                    // modes x motions
  Eigen::SparseMatrix<double, Eigen::RowMajor> GZ_;  // contact rows x motions: G'Z
  std::vector<Cluster> clusters_;
};

}  // namespace fetic::solver
