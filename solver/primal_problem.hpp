#pragma once
// The assembled, undecomposed problem of the primal methods (SD, CG, active set):
//   minimize 1/2 u'K u - t f'u  subject to  A u <= c
// over the free DOFs (clamped DOFs removed). K is block diagonal, one block per strut,
// each factorized once (CHOLMOD); a strut held only by contacts (bar model) keeps its
// axial translation as the kernel of its block and gets a generalized inverse.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "solver/generalized_inverse.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"

namespace fetic::solver {

using RowSparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

struct StrutBlock {
  int strut = 0;
  int offset = 0;  // first global DOF
  int size = 0;
  std::vector<int> strut_dofs;  // strut-local DOF of each block DOF
  Eigen::MatrixXd kernel;       // size x modes; no columns when the strut is clamped
  GeneralizedInverse inverse;
};

class PrimalProblem {
 public:
  // Assembles and (unless factorize_blocks is false) factorizes every strut block;
  // throws SolverError for a singular strut.
  explicit PrimalProblem(const Model& model, bool factorize_blocks = true);

  int size() const { return size_; }
  const SparseMatrix& stiffness() const { return K_; }
  const Eigen::VectorXd& load() const { return f_; }          // at load factor 1
  const RowSparseMatrix& contact_rows() const { return A_; }  // one row per contact pair
  const Eigen::VectorXd& gaps() const { return c_; }
  const std::vector<StrutBlock>& blocks() const { return blocks_; }
  // Rigid-body modes of the floating struts, one column each (global DOFs).
  const SparseMatrix& kernel() const { return R_; }
  const std::vector<int>& kernel_struts() const { return kernel_struts_; }

  // y = K^+ x, block by block (in parallel).
  void apply_pseudo_inverse(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  // The displacements of u as one piece per strut.
  std::vector<Piece> pieces(const Eigen::VectorXd& u) const;

 private:
  const Model& model_;
  int size_ = 0;
  SparseMatrix K_;
  Eigen::VectorXd f_;
  RowSparseMatrix A_;
  Eigen::VectorXd c_;
  std::vector<StrutBlock> blocks_;
  SparseMatrix R_;
  std::vector<int> kernel_struts_;
};

// Message for a stiffness that could not be factorized.
std::string singular_message(const Model& model, int strut, CholmodFactor::Result result,
                             const std::string& part);

}  // namespace fetic::solver
