#pragma once
// The FETI interface operators, applied implicitly subdomain by subdomain and never
// assembled (ALGORITHMS.md section 2):
//   F = sum_j B_j K_j^+ B_j'      d = t sum_j B_j K_j^+ f_j - c
//   G = [R_j' B_j']_j             e = t [R_j' f_j]_j
// Every K_j^+ is factorized once, when the system is built (in parallel). An application
// costs one forward/backward solve per subdomain; subdomains are processed in parallel
// (OpenMP), each with its own CHOLMOD factor and workspace.

#include <vector>

#include <Eigen/Core>

#include "solver/decomposition.hpp"
#include "solver/dual_space.hpp"
#include "solver/generalized_inverse.hpp"
#include "solver/method.hpp"

namespace fetic::solver {

struct Incidence {
  int row = 0;
  int dof = 0;  // subdomain-local
  double value = 0.0;
};

struct SubdomainOperator {
  SparseMatrix K;
  Eigen::MatrixXd R;  // rigid-body modes, dof_count x mode_count
  GeneralizedInverse K_plus;
  std::vector<Incidence> incidence;  // the entries of B_j, by row
};

class FetiSystem {
 public:
  // Builds and factorizes every subdomain; throws SolverError naming the strut when a
  // subdomain is singular beyond its rigid-body modes.
  explicit FetiSystem(const Model& model);
  FetiSystem(const FetiSystem&) = delete;
  FetiSystem& operator=(const FetiSystem&) = delete;

  const Model& model() const { return model_; }
  const Decomposition& decomposition() const { return decomposition_; }
  // The rows this process holds and the reductions over all of them (dual_space.hpp).
  const DualSpace& space() const { return space_; }
  const std::vector<SubdomainOperator>& subdomains() const { return subdomains_; }
  int rows() const { return decomposition_.row_count(); }
  int modes() const { return decomposition_.total_modes; }
  const Eigen::VectorXd& rhs() const { return c_; }  // c: gaps on contact rows, 0 elsewhere
  const SparseMatrix& G() const { return G_; }       // modes x rows

  // out = B K^+ (t f - B' lambda) - c, i.e. d - F lambda: the dual residual, one pass.
  void residual(const Eigen::VectorXd& lambda, double load_factor, Eigen::VectorXd& out) const;
  // out = F p.
  void apply_F(const Eigen::VectorXd& p, Eigen::VectorXd& out) const;
  // d = t B K^+ f - c.
  Eigen::VectorXd d(double load_factor) const;
  // e = t R' f.
  Eigen::VectorXd e(double load_factor) const;
  // v <- its orthogonal projection onto range(B). Redundant gluing rows make F singular
  // on ker B'; rounding drifts into that kernel, which F cannot reduce, so the iterations
  // keep w and the directions in range(B). For the rows of a node with m copies (one
  // per pair) the projection is (1/m) B_g B_g'.
  void project_onto_range_of_B(Eigen::VectorXd& v) const;

  // Primal displacements u_j = K_j^+ (t f_j - B_j' lambda) + R_j alpha_j as pieces.
  std::vector<Piece> pieces(const Eigen::VectorXd& lambda, const Eigen::VectorXd& alpha,
                            double load_factor) const;
  // The same as one vector of all subdomain DOFs (concatenated).
  Eigen::VectorXd subdomain_displacements(const Eigen::VectorXd& lambda,
                                          const Eigen::VectorXd& alpha, double load_factor) const;

  // Peak memory of the subdomain factors in bytes (CHOLMOD's own accounting).
  std::size_t factor_memory() const;
  // Applications of F so far (apply_F and residual), the dual methods' measure of cost.
  long long f_applications() const { return f_applications_; }

 private:
  // Y_j = K_j^+ (t f_j + s B_j' lambda) for every subdomain, into y_ (concatenated).
  void solve_subdomains(const Eigen::VectorXd* lambda, double s, double load_factor) const;
  // out_r = sum over B's entries of row r of value * y_(subdomain, dof).
  void gather_rows(Eigen::VectorXd& out) const;

  const Model& model_;
  Decomposition decomposition_;
  DualSpace space_;
  std::vector<SubdomainOperator> subdomains_;
  Eigen::VectorXd c_;
  SparseMatrix G_;
  mutable Eigen::VectorXd x_, y_;  // workspaces over all subdomain DOFs
  mutable long long f_applications_ = 0;
};

}  // namespace fetic::solver
