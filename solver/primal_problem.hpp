#pragma once
// The assembled, undecomposed problem of the primal methods (SD, CG, active set):
//   minimize 1/2 u'K u - t f'u  subject to  A u <= c
// over the free DOFs (held DOFs removed). K is block diagonal, one block per strut -
// in the frame model one per group of struts that joints connect: the ends of a joint
// share one global DOF per shared component (ux, uy and, rigid, the rotation), so a
// joint needs no constraint row. Each block is factorized once (CHOLMOD); a block that
// supports do not hold keeps its free motions as its kernel (bar: the axial
// translation; frame: the rigid and mechanism motions of scenes/frame_kinematics) and
// gets a generalized inverse.

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
  int strut = 0;            // the first of its struts
  std::vector<int> struts;  // one strut, or (frame model) a group joined by joints
  int offset = 0;           // first global DOF
  int size = 0;
  Eigen::MatrixXd kernel;  // size x modes; no columns when supports hold the block
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
  // The struts each column of kernel() moves.
  const std::vector<std::vector<int>>& kernel_struts() const { return kernel_struts_; }
  // Global DOF of each strut DOF (node * dofs_per_node + component), -1 where held.
  const std::vector<std::vector<int>>& global_dofs() const { return global_of_; }

  // y = K^+ x, block by block (in parallel).
  void apply_pseudo_inverse(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  // The displacements of u as one piece per strut.
  std::vector<Piece> pieces(const Eigen::VectorXd& u) const;

 private:
  // Frame model: the group's free motions as columns over the block's DOFs; records the
  // struts each moves in kernel_struts_.
  // The constructor's steps: the free DOFs numbered group by group (global_of_, blocks_,
  // size_); K, R, f and each block's kernel and factor; the contact rows A, c.
  void number_free_dofs();
  void assemble_blocks(bool factorize_blocks);
  void build_contact_rows();
  Eigen::MatrixXd frame_kernel(const std::vector<int>& motions, const StrutBlock& block);

  const Model& model_;
  int size_ = 0;
  SparseMatrix K_;
  Eigen::VectorXd f_;
  RowSparseMatrix A_;
  Eigen::VectorXd c_;
  std::vector<StrutBlock> blocks_;
  SparseMatrix R_;
  std::vector<std::vector<int>> kernel_struts_;
  std::vector<std::vector<int>> global_of_;
};

// Message for a stiffness that could not be factorized.
std::string singular_message(const Model& model, int strut, CholmodFactor::Result result,
                             const std::string& part);

}  // namespace fetic::solver
