#pragma once
// The projector onto ker G_F for a face F (the equality rows and the contact rows off
// their bound), without factorizing G_F G_F' for each face:
//
//   P_F v = v - G_F'(G_F G_F')^-1 G_F v,
//   G_F G_F' = G_E G_E' + sum over free contact rows k of g_k g_k'   (g_k: column k of G).
//
// G_E G_E' is the equality rows' coarse matrix, factorized once (CoarseProblem); the sum
// touches only the rigid-body modes of subdomains that contact rows reach (the set C),
// so by Woodbury, with X = (G_E G_E')^-1, U = [e_m for m in C] and S = S_CC(F) the sum,
//
//   (X^-1 + U S U')^-1 = X - X U (I + S U'X U)^-1 S U'X.
//
// X U is computed once (|C| coarse solves); a new face costs one dense LU of size |C| -
// the modes next to contacts, a few hundred at a million unknowns - and an application
// one coarse solve and two dense products. For bar groups the equality rows leave free
// to translate, CoarseProblem regularizes X along their translation z; the result then
// keeps a part of those directions, which is what SMALBE needs to balance the groups.
//
// Distributed: every process holds the columns g_k of all contact rows (a few numbers
// each) and forms the same S in global row order, so S, the correction and every
// projection are the same bits for any number of processes.

#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "solver/coarse_problem.hpp"
#include "solver/feti_system.hpp"

namespace fetic::solver {

class FaceProjector {
 public:
  // `equality` must hold the coarse problem of exactly the equality rows.
  FaceProjector(const FetiSystem& system, const CoarseProblem& equality);

  // The face: per local row, nonzero for the equality rows and the free contact rows.
  // Collective (one reduction; one gather when the face changed on any process).
  void set_face(const std::vector<char>& face);
  // v <- P_F v; v must vanish outside the face (so must the result).
  void project(Eigen::VectorXd& v) const;
  // The modes next to contacts: the size of the dense correction.
  int correction_size() const { return static_cast<int>(XU_.cols()); }

 private:
  struct Column {
    int row = 0;                                  // global contact row
    std::vector<std::pair<int, double>> entries;  // (mode, value)
  };

  const FetiSystem& system_;
  const CoarseProblem& equality_;
  std::vector<Column> columns_;     // of every contact row, in global row order
  std::vector<int> column_of_row_;  // per global row: its column, or -1
  std::vector<int> contact_modes_;  // C
  std::vector<int> position_;       // per mode: its index in C, or -1
  Eigen::MatrixXd XU_, UXU_;
  bool has_face_ = false;
  std::vector<char> face_;
  Eigen::MatrixXd S_;
  Eigen::FullPivLU<Eigen::MatrixXd> correction_;  // I + S U'X U
};

}  // namespace fetic::solver
