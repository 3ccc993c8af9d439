#pragma once
// Preconditioners M^-1 ~ F^-1 of the FETI interface problem (docs/METHODS.md 3),
// applied subdomain by subdomain like F:
//   lumped:    M^-1 = sum_j B_j K_j B_j'
//   Dirichlet: M^-1 = sum_j B_j [0 0; 0 S_j] B_j',  S_j = K_bb - K_bi K_ii^-1 K_ib
//   none:      M^-1 = I
// b: the DOFs of subdomain j that rows of B touch; i: the others. S_j is applied
// implicitly: from the trailing block of K_j's one factor with the boundary last
// (GeneralizedInverse::apply_boundary_schur, solver/boundary_last.hpp), or where that
// factor is not made, through a factor of K_ii (one interior solve per application).
// Stiffness scaling (optional): in a row shared by subdomains a and b, B_j's entry is
// weighted by k_other / (k_a + k_b), k the diagonal stiffness at the DOF; this is the
// multiplicity scaling 1/2 for equal neighbours and follows jumps in stiffness.
// An optional row mask restricts input and output to the rows FETI-C works on.
//
// Distributed like F (feti_system.hpp): each process holds the blocks of its own
// subdomains; the diagonal stiffness of a neighbour's DOF, which the scaling needs, is
// asked of its process once, at set-up.

#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "solver/cholmod_factor.hpp"
#include "solver/feti_system.hpp"
#include "solver/row_term_sum.hpp"

namespace fetic::solver {

class FetiPreconditioner {
 public:
  FetiPreconditioner(const FetiSystem& system, Preconditioner kind, bool scaled);

  Preconditioner kind() const { return kind_; }
  std::size_t factor_memory() const;  // CHOLMOD's peak for the interior factors, bytes
  // Adds the bytes held now for the own subdomains' blocks, by kind.
  void add_memory(LocalMemory& memory) const;
  double setup_seconds() const { return setup_seconds_; }
  long long applications() const { return applications_; }
  // Bytes one application reads of the own subdomains' blocks: with one boundary-last
  // factor its trailing columns once; else K_ii's factors (their reached parts) forward
  // and back, K_ib twice (K_ib x, K_ib' y), K_bb once.
  double bytes_read() const;
  // z = M^-1 w, using and producing only rows with mask[r] != 0 (all rows without a mask).
  void apply(const Eigen::VectorXd& w, const std::vector<char>* mask, Eigen::VectorXd& z) const;

 private:
  struct Local {
    std::vector<int> boundary;         // subdomain DOFs touched by B
    std::vector<Incidence> incidence;  // B's entries, dof = position in `boundary`,
                                       // value already scaled
    SparseMatrix K_bb, K_ib;
    // Own factor only when K_j's factor cannot solve with K_ii: made only then (a
    // CholmodFactor holds CHOLMOD's 2.7 KB workspace header: 26 MB and 0.1 s at 1e7).
    std::unique_ptr<CholmodFactor> K_ii;
    const GeneralizedInverse* interior = nullptr;  // K_j's K^+, which also holds K_ii's factor
    // K_j's K^+ when its one factor applies S_j from its trailing block (boundary_last.hpp):
    // then no K_bb, K_ib or K_ii factor.
    const GeneralizedInverse* schur = nullptr;
    // K_ii's lean factor, if it has one: K_ib's rows are then renumbered into its order,
    // so that M^-1 solves in place (CompactFactor::solve_in_place).
    const CompactFactor* interior_factor = nullptr;
    // Whether its reach_first() layout covers K_ib's rows: solves on those alone.
    bool reached_only = false;
    int offset = 0;          // of its boundary among all subdomains'
    std::vector<int> terms;  // per entry of `incidence`: its term among the rows' sums
  };
  // One term of a row's sum: y_(index) * value.
  using Term = RowTerm;

  // The boundary, K_bb and (Dirichlet) K_ib and the factor of K_ii of one subdomain;
  // false when K_ii is singular. b_position: per DOF its place in the boundary or -1.
  bool set_up_local(const SubdomainOperator& op, Local& local, std::vector<int>& b_position) const;
  // y = S_j x for one subdomain (x, y over its boundary DOFs; y sized).
  static void apply_local(const Local& local, const Eigen::VectorXd& x, Eigen::VectorXd& y);
  // The scaling weights of every local row's own entries, at their terms
  // (FetiSystem::first_term).
  std::vector<double> scaling_weights(bool scaled) const;
  using DofKey = std::pair<int, int>;  // (subdomain, subdomain-local DOF)
  template <class Stiffness>
  static void row_weights(const Row& row, bool scaled, const Stiffness& stiffness,
                          std::vector<std::pair<DofKey, double>>& side, const std::vector<int>& own,
                          double* weight);

  double setup_seconds_ = 0.0;  // before the members whose construction it times
  const FetiSystem& system_;
  Preconditioner kind_;
  std::vector<Local> local_;
  std::vector<int> row_first_;  // per local row, into terms_ (size rows + 1)
  std::vector<Term> terms_;
  int boundary_dofs_ = 0;  // of all own subdomains
  // Each subdomain's S_j B_j' w at its terms of the rows' sums (in the order of terms_),
  // so that the sums read it in order.
  mutable std::vector<double> term_values_;
  mutable long long applications_ = 0;
};

}  // namespace fetic::solver
