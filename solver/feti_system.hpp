#pragma once
// The FETI interface operators, applied implicitly subdomain by subdomain and never
// assembled (docs/METHODS.md 2):
//   F = sum_j B_j K_j^+ B_j'      d = t sum_j B_j K_j^+ f_j - c
//   G = [R_j' B_j']_j             e = t [R_j' f_j]_j
//
// Distribution (MPI): the subdomains are partitioned over the processes
// (partition.hpp); each process assembles and factorizes only its own K_j, and holds the
// dual vectors on its local rows (dual_space.hpp). Applying F is one local solve per own
// subdomain, then one exchange of partial row sums with the neighbouring processes
// (DualSpace::complete_rows). Vectors over the rigid-body modes (G lambda, e, alpha) are
// small and replicated: each process computes the entries of its own subdomains and
// all_gather assembles them (assemble_modes). In one process the same code runs with
// nothing to exchange.
//
// Every row sum adds the partial sums of the subdomains it joins in subdomain order, so
// one process and many compute the same bits; only scalar products (summed per process,
// then in rank order) differ in rounding with the number of processes.

#include <vector>

#include <Eigen/Core>

#include "solver/communicator.hpp"
#include "solver/decomposition.hpp"
#include "solver/dual_space.hpp"
#include "solver/generalized_inverse.hpp"
#include "solver/local_memory.hpp"
#include "solver/method.hpp"
#include "solver/partition.hpp"
#include "solver/row_term_sum.hpp"

namespace fetic::solver {

struct Incidence {
  int row = 0;  // local row (DualSpace)
  int dof = 0;  // subdomain-local
  double value = 0.0;
};

struct SubdomainOperator {
  int index = 0;      // global subdomain index
  SparseMatrix K;     // empty after FetiSystem::release_stiffness()
  Eigen::MatrixXd R;  // rigid-body modes, dof_count x mode_count
  GeneralizedInverse K_plus;
  std::vector<Incidence> incidence;  // the entries of B_j, by row
  // Per entry of `incidence`, for F's fused pass (FetiSystem::solve_subdomains): where
  // its DOF is in the vector K_plus's lean factor solves in place (-1: a fixed DOF), and
  // its term among the local rows' sums. No positions: K_plus solves through apply().
  std::vector<int> positions;
  std::vector<int> terms;
};

// Time spent in each part of the operators (for the benchmark's split of an iteration).
struct OperatorTimes {
  double local_solves = 0.0;      // K_j^+ applications and B's gathers (F, d, the residual)
  double coarse = 0.0;            // coarse problem: factorizations and solves
  double preconditioner = 0.0;    // M^-1 applications (their local solves and B products)
  double mode_products = 0.0;     // G v and G' a of the coarse projections
  double range_projection = 0.0;  // project_onto_range_of_B
};

// Wall time of the set-up's parts (FetiSystem's own; the preconditioner and the coarse
// problem keep theirs).
struct SetupTimes {
  double decomposition = 0.0;  // subdomains, rows of B, the partition and the dual space
  double incidence = 0.0;      // B's entries per subdomain and per row
  double factorization = 0.0;  // assembling K_j, R_j and factorizing K_j (all subdomains)
  double coarse_space = 0.0;   // G, |G| and the redundant rows' groups
};

class FetiSystem {
 public:
  // Builds and factorizes this process' subdomains; throws SolverError naming the strut
  // when a subdomain (of any process) is singular beyond its rigid-body modes.
  // `interior_first`: factorize each K_j's interior block K_ii too, for the Dirichlet
  // preconditioner (GeneralizedInverse), and keep only K_j's boundary columns after.
  // corner_clusters: 0 FETI-1 (every box a subdomain); otherwise FETI-DP, the boxes joined
  // by their corners (corners.hpp): -1 into clusters as large as the corners make them,
  // N > 0 into clusters of about N boxes.
  // `single_factors`: the subdomain factors' entries kept as floats (SolveOptions);
  // `single_interior`: K_ii's factors (interior_first) kept as floats.
  // `edge_averages`: FETI-DP with the plane model's edge averages primal (edge_averages.hpp).
  // `boundary_last` (interior_first): one factor per subdomain with the boundary last where
  // it can (GeneralizedInverse::factorize), instead of K_j's and K_ii's.
  explicit FetiSystem(const Model& model, const Communicator& communicator = Communicator::self(),
                      bool interior_first = false, int corner_clusters = 0,
                      bool single_factors = false, bool single_interior = true,
                      bool edge_averages = false, bool boundary_last = true);
  FetiSystem(const FetiSystem&) = delete;
  FetiSystem& operator=(const FetiSystem&) = delete;

  const Model& model() const { return model_; }
  const Communicator& communicator() const { return space_.communicator(); }
  // The whole decomposition (replicated metadata: subdomain boxes, rows and their entries).
  const Decomposition& decomposition() const { return decomposition_; }
  const Partition& partition() const { return partition_; }
  // The rows this process holds and the reductions over all of them (dual_space.hpp).
  const DualSpace& space() const { return space_; }
  // This process' subdomains, in increasing global index.
  const std::vector<SubdomainOperator>& subdomains() const { return subdomains_; }
  int rows() const { return space_.rows(); }  // local rows
  int modes() const { return decomposition_.total_modes; }
  const Eigen::VectorXd& rhs() const { return c_; }  // c on the local rows
  // The columns of G for the local rows (modes x local rows); a column holds the rigid
  // motions of every subdomain its row joins, own or not.
  const SparseMatrix& G() const { return G_; }
  OperatorTimes& times() const { return times_; }
  // Applications of F so far (apply_F, residual and d each count one).
  long long f_applications() const { return f_applications_; }
  // Passes of K^+ over all own subdomains so far (F, d, the residual, the displacements):
  // the work a method does per iteration, counted for tests of its growth.
  long long subdomain_passes() const { return subdomain_passes_; }

  // out = B K^+ (t f - B' lambda) - c, i.e. d - F lambda: the dual residual, one pass.
  void residual(const Eigen::VectorXd& lambda, double load_factor, Eigen::VectorXd& out) const;
  // out = F p.
  void apply_F(const Eigen::VectorXd& p, Eigen::VectorXd& out) const;
  // d = t B K^+ f - c.
  Eigen::VectorXd d(double load_factor) const;
  // e = t R' f (replicated).
  Eigen::VectorXd e(double load_factor) const;
  // G^ v for the rows with mask[r] != 0 (all rows without a mask), replicated.
  Eigen::VectorXd apply_G(const Eigen::VectorXd& v, const std::vector<char>* mask = nullptr) const;
  // v -= G' a on the local rows with mask[r] != 0 (all rows without a mask), in place:
  // each row's sum as G' a forms it, so the same bits as v - G' a.
  void subtract_Gt(const Eigen::VectorXd& a, Eigen::VectorXd& v,
                   const std::vector<char>* mask = nullptr) const;
  // The same for |G| |v| (a scale for G v), replicated.
  Eigen::VectorXd apply_abs_G(const Eigen::VectorXd& v) const;
  // out = B u for u over the own subdomains' DOFs (as subdomain_displacements), local rows.
  void apply_B(const Eigen::VectorXd& u, Eigen::VectorXd& out) const;
  // A replicated vector over all modes from the entries of this process' own subdomains
  // (concatenated in the order of subdomains()).
  Eigen::VectorXd assemble_modes(const std::vector<double>& own) const;
  // v <- its orthogonal projection onto range(B). Redundant gluing rows make F singular
  // on ker B'; rounding drifts into that kernel, which F cannot reduce, so the iterations
  // keep w and the directions in range(B). For the rows of a node with m copies (one
  // per pair) the projection is (1/m) B_g B_g'.
  void project_onto_range_of_B(Eigen::VectorXd& v) const;

  // Primal displacements u_j = K_j^+ (t f_j - B_j' lambda) + R_j alpha_j of the own
  // subdomains, as pieces.
  std::vector<Piece> pieces(const Eigen::VectorXd& lambda, const Eigen::VectorXd& alpha,
                            double load_factor) const;
  // The same as one vector of the own subdomains' DOFs (concatenated; dof_offset()).
  Eigen::VectorXd subdomain_displacements(const Eigen::VectorXd& lambda,
                                          const Eigen::VectorXd& alpha, double load_factor) const;
  // Position of own subdomain i's DOFs in the vectors above.
  int dof_offset(int i) const { return dof_offsets_[i]; }
  // Own subdomain position of a global subdomain, or -1.
  int own_index(int subdomain) const { return own_index_[subdomain]; }
  // Indices into row.entries of its entries on own subdomains, grouped by subdomain in
  // increasing order (one subdomain's in the row's order): the order of the row's terms.
  void own_entries_in_order(const Row& row, std::vector<int>& out) const;
  // The terms of the local rows' sums, row after row: row r's are [first_term(r),
  // first_term(r + 1)), in own_entries_in_order(); SubdomainOperator::terms index them.
  int first_term(int r) const {
    return r < space_.rows() ? row_parts_[r].first : static_cast<int>(part_entries_.size());
  }
  const RowTerm& term(int t) const { return part_entries_[t]; }

  // Peak memory of this process' subdomain factors in bytes (CHOLMOD's own accounting).
  std::size_t factor_memory() const;
  // Bytes held now for the own subdomains, by kind (the preconditioner adds its own).
  LocalMemory memory() const;
  // Bytes one application of F reads of the own subdomains' factors: each lean factor's
  // trailing columns (boundary last) or reached part twice (forward, back;
  // CompactFactor::trailing_bytes, reached_bytes), others whole.
  double f_bytes_read() const;
  const SetupTimes& setup_times() const { return setup_times_; }
  // Frees every K_j: after the preconditioner's set-up nothing reads them (the factors
  // and the preconditioner's blocks hold what the iterations need).
  void release_stiffness();

 private:
  // Y_j = K_j^+ (t f_j + s B_j' lambda) for every own subdomain: its values at B's
  // entries into boundary_y_ and, with `whole` (or without a lean factor), all of it into
  // y_ (concatenated).
  void solve_subdomains(const Eigen::VectorXd* lambda, double s, double load_factor,
                        bool whole = false) const;
  // Own subdomain i's part of it through the lean factor in one pass: B_i' lambda
  // gathered straight into the factor's order, the solve, B's values read out of it.
  void solve_subdomain_fused(int i, const Eigen::VectorXd* lambda, double s) const;
  // out_r = sum over B's entries of row r of value * Y(subdomain, dof), all processes.
  void gather_rows(Eigen::VectorXd& out) const;
  void build_incidence();
  void fill_terms_and_incidence();
  void write_row_terms(int r, const int*& next, std::vector<int>& at);
  struct FactorOptions {
    bool interior_first, single_factors, single_interior, boundary_last;
  };
  void factorize_subdomains(const FactorOptions& options);
  // M v over the own subdomains' modes (M: modes x local rows, like G), replicated.
  Eigen::VectorXd own_modes_product(const SparseMatrix& M, const Eigen::VectorXd& v,
                                    const std::vector<char>* mask) const;
  // out_r = sum over the own entries of row r of value * values(entry), all processes.
  void sum_rows(const Eigen::VectorXd& values, Eigen::VectorXd& out) const;
  void build_G();
  void build_redundant_groups();
  void project_groups(const Eigen::VectorXd& v, Eigen::VectorXd& partial) const;

  // Per local row, the entries on own subdomains, grouped by subdomain in increasing order.
  struct RowPart {
    int first = 0;  // into part_entries_
    int end = 0;
  };
  using PartEntry = RowTerm;  // y: index into y_
  // A redundant group as this process sees it.
  struct LocalGroup {
    int copies = 0;
    std::vector<int> own_copies;            // copy indices whose subdomain is own
    std::vector<int> rows;                  // local rows of the group (-1: not held)
    std::vector<std::pair<int, int>> ends;  // (i, j) per row
    std::vector<char> own_end;              // per copy: its subdomain is own
  };

  const Model& model_;
  SetupTimes setup_times_;  // before decomposition_, whose construction it times
  Decomposition decomposition_;
  Partition partition_;
  DualSpace space_;
  std::vector<SubdomainOperator> subdomains_;
  std::vector<int> own_index_;
  std::vector<int> dof_offsets_;
  std::vector<RowPart> row_parts_;
  std::vector<PartEntry> part_entries_;
  std::vector<LocalGroup> groups_;
  bool groups_disjoint_ = true;  // no local row in two groups
  Eigen::VectorXd c_;
  SparseMatrix G_;
  SparseMatrix G_abs_;
  mutable Eigen::VectorXd x_, y_;           // workspaces over the own subdomains' DOFs
  mutable std::vector<double> boundary_y_;  // Y at B's entries, per term of part_entries_
  mutable OperatorTimes times_;
  mutable long long f_applications_ = 0;
  mutable long long subdomain_passes_ = 0;
};

}  // namespace fetic::solver
