#pragma once
// The coarse problem of FETI on a set of active rows (equality rows plus the contact rows
// of the working set): G^ keeps the columns of G for those rows, G^ G^' is factorized
// once per set (CHOLMOD) and gives
//   P^ v = v - G^'(G^ G^')^+ G^ v       (projector onto ker G^, section 3)
//   G^'(G^ G^')^+ e                     (the particular multipliers, (6.45), (8.25))
//   (G^ G^')^+ G^ r                     (rigid-body amplitudes, (6.50))
//
// Distribution (MPI): G^ G^' is small (rigid-body modes x modes) and replicated - every
// process holds and factorizes all of it, so a solve needs no communication. Each
// process computes the block rows of its own subdomains (from the rows of B they touch,
// all local to it) and one all_gather assembles the matrix. Its nonzero pattern is that
// of all rows and never changes: a working-set change only changes values, and the
// factorization keeps CHOLMOD's ordering and symbolic analysis. The working set itself
// (which contact rows are active) is replicated too: each process contributes its
// owned contact rows and every process applies the same changes, so all refactorize at
// the same moment with the same numbers.
//
// A working-set change of a few rows updates the factor instead (CHOLMOD's rank-k
// update/downdate by the rows' columns of G: G^ G^' = sum over active rows of g g'),
// which costs a fraction of a numeric refactorization - 97 refactorizations were a third
// of FETI-C's solve at 32x16 subdomains per strut. After 64 updated rows, or when a
// group is left unheld, it refactorizes from scratch.
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
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "solver/cholmod_factor.hpp"
#include "solver/default_init.hpp"
#include "solver/feti_system.hpp"

namespace fetic::solver {

struct UnheldGroup {
  std::vector<int> subdomains;
  // Over all modes, unit length; sparse, as it is nonzero only in the group (dense, a
  // thousand floating beams' directions took gigabytes).
  Eigen::SparseVector<double> direction;
};

class FreeMotionSpace;

class CoarseProblem {
 public:
  explicit CoarseProblem(const FetiSystem& system);
  // Another coarse problem of the same system, all rows active, sharing `other`'s pattern
  // and products (fixed; building them was 0.3 s of set-up at 984,900 unknowns, and they
  // are most of its memory): MPRGP's face projector.
  struct SamePattern {};
  CoarseProblem(const CoarseProblem& other, SamePattern);

  // Makes the rows with active[r] != 0 (local rows) the rows of G^; equality rows are
  // always active. Collective: every process must call it at the same point. Factorizes
  // G^ G^' again when the set of active rows (over all processes) changed, and returns
  // whether it did.
  bool set_active_rows(const std::vector<char>& active);
  const std::vector<char>& active_rows() const { return active_; }  // local rows
  // Whether contact row `k` (global contact index: global row - equality rows) is active,
  // known alike on every process.
  bool contact_active(int k) const { return contact_active_[k] != 0; }

  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;     // (G^ G^')^+ b
  Eigen::VectorXd apply_G(const Eigen::VectorXd& v) const;   // G^ v (replicated)
  Eigen::VectorXd apply_Gt(const Eigen::VectorXd& a) const;  // G^' a (local rows; 0 if inactive)
  void project(Eigen::VectorXd& v) const;                    // v <- P^ v
  void subtract_Gt(const Eigen::VectorXd& a, Eigen::VectorXd& v) const {  // v -= G^' a
    system_.subtract_Gt(a, v, &active_);
  }
  Eigen::VectorXd particular(const Eigen::VectorXd& e) const;
  Eigen::VectorXd amplitudes(const Eigen::VectorXd& r) const;  // (G^ G^')^+ G^ r

  const std::vector<UnheldGroup>& unheld() const { return unheld_; }
  // Pins these directions in every factorization, instead of those of the groups the
  // active rows leave unheld (which must lie in their span): G^ G^' + sum z z'. MPRGP's
  // face projector pins the groups of the equality rows, so that its projection keeps
  // the part of their motion that SMALBE balances (face_projector.hpp).
  void pin_always(std::vector<UnheldGroup> groups) {
    pinned_ = std::move(groups);
    factorized_ = false;
  }
  std::size_t factor_memory() const { return factor_.peak_memory(); }
  int size() const { return system_.modes(); }
  // Nonzeros of G G' (the stored lower triangle) and how often it was factorized.
  std::size_t matrix_nonzeros() const { return static_cast<std::size_t>(matrix_.nonZeros()); }
  int factorizations() const { return factorizations_; }
  // The next set_active_rows() factorizes from scratch, whatever the rows: a solve then
  // does not depend, in its last bits, on the updates of the solves before it.
  void forget_updates() { factorized_ = false; }
  // How often a working-set change updated the factor instead (update_factor).
  int updates() const { return updates_; }

 private:
  void build_pattern();
  void factorize();
  bool update_factor(const std::vector<int>& own_changes, std::size_t all_changes);
  void find_unheld_groups();
  bool row_active(int global_row) const;
  // Entry of G for (mode of `subdomain`, global row): bar model only (find_unheld_groups).
  double g(int global_row, int subdomain) const;

  const FetiSystem& system_;
  std::vector<char> active_;          // per local row
  std::vector<char> contact_active_;  // per contact row of the whole problem (replicated)
  bool factorized_ = false;

  // This process' block rows of G G': per own subdomain, its local rows; each row's
  // products g_a g_b go to value positions of the block rows.
  // No default values: the pattern's arrays of them are sized unwritten (DefaultInitVector)
  // and then written on both cores (a zeroing resize was a serial pass over them).
  struct Product {
    int value;  // into own_values_
    int a, b;   // positions of the two factors in the row's column of G
  };
  struct RowProducts {
    int row;         // local row
    int first, end;  // into Pattern::products
  };
  // This process' products and where their sums go: fixed, shared by SamePattern copies.
  struct Pattern {
    // in increasing local row, grouped by own subdomain
    DefaultInitVector<RowProducts> row_products;
    DefaultInitVector<Product> products;
    std::size_t own_values = 0;
    std::vector<int> value_slot;  // per gathered value: its position in matrix_ (or -1)
  };
  std::vector<std::pair<int, int>> own_entries(const SubdomainOperator& op,
                                               const Subdomain& sub) const;
  void write_products(const SubdomainOperator& op, const Subdomain& sub,
                      const std::vector<std::pair<int, int>>& entries, int first_value,
                      Product* product, RowProducts* row, int first_product) const;
  void count_products(std::vector<int>& products, std::vector<int>& rows) const;
  std::shared_ptr<const Pattern> pattern_;
  std::vector<double> own_values_;
  SparseMatrix matrix_;  // lower triangle of G^ G^', fixed pattern
  std::vector<UnheldGroup> unheld_;
  std::vector<UnheldGroup> pinned_;                       // pin_always()
  std::shared_ptr<const FreeMotionSpace> frame_motions_;  // frame model
  CholmodFactor factor_;
  // factor_ must be analysed anew: it holds G^G^' + zz' (a pattern of its own) or was
  // updated (a simplicial LDL' then, slower to refactorize than the supernodal LL').
  bool reanalyse_ = false;
  int factorizations_ = 0;
  // Rank updates of the factor (update_factor): allowed while the last factorization was
  // of G^ G^' alone; rows changed since that factorization.
  bool updatable_ = false;
  int rows_updated_ = 0;
  int updates_ = 0;
};

}  // namespace fetic::solver
