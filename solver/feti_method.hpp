#pragma once
// What FETI-1 (PCPG) and FETI-C share: the interface system, the preconditioner, the
// coarse problem, the dual iterate lambda with its residual r = d - F lambda, and the
// reconstruction of the primal displacements from the current lambda - torn across
// subdomain interfaces until lambda has converged.

#include <algorithm>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "solver/coarse_problem.hpp"
#include "solver/condition_estimate.hpp"
#include "solver/feti_preconditioner.hpp"
#include "solver/feti_system.hpp"
#include "solver/method.hpp"

namespace fetic::solver {

// What one process did and holds, cumulative since the method was made (subtract two
// readings for a phase). For the benchmark of the distributed solve.
struct ProcessProfile {
  int subdomains = 0;
  long long unknowns = 0;  // DOFs of the own subdomains
  int rows = 0;            // local rows of B
  int shared_rows = 0;     // of which also held by another process
  long long f_applications = 0;
  double local_seconds = 0.0;             // local solves and B's gathers (F, d, residual)
  double coarse_seconds = 0.0;            // coarse factorizations and solves
  double preconditioner_seconds = 0.0;    // M^-1 applications
  double mode_product_seconds = 0.0;      // G v and G' a of the coarse projections
  double range_projection_seconds = 0.0;  // projections onto range(B)
  double exchange_seconds = 0.0;          // neighbour exchanges
  double reduction_seconds = 0.0;         // scalar reductions
  double gather_seconds = 0.0;            // gathers (coarse vectors and matrix)
  CommunicationStats communication;
  int coarse_size = 0;
  long long coarse_nonzeros = 0;
  int coarse_factorizations = 0;
  int coarse_updates = 0;         // working-set changes that updated the factor instead
  std::size_t coarse_memory = 0;  // CHOLMOD's peak for the replicated coarse factor
  std::size_t factor_memory = 0;  // own subdomain and preconditioner factors
  LocalMemory memory;             // bytes held for the own subdomains, by kind
  SetupTimes setup;               // the subdomain operators' set-up, by part
  double preconditioner_setup_seconds = 0.0;
  double coarse_setup_seconds = 0.0;  // the coarse problem's pattern (CoarseProblem)
  long long preconditioner_applications = 0;
  double f_bytes_read = 0.0;               // per application of F (FetiSystem::f_bytes_read)
  double preconditioner_bytes_read = 0.0;  // per application of M^-1
};

class FetiMethod : public Method {
 public:
  ProcessProfile profile() const;
  // The condition number of the preconditioned dual operator, from the coefficients of the
  // longest run of CG steps in the last solve (the same on every process).
  virtual ConditionEstimate condition_estimate() const { return condition_.estimate(); }
  // This process' part of the state: its subdomains' pieces, the forces of the contact
  // pairs whose rows it holds, the working set of all pairs, its local multipliers.
  Snapshot snapshot() const override;
  // The whole state on rank 0 (collective; the same as snapshot() in one process).
  Snapshot gathered(Snapshot local) const override;
  const FetiSystem& system() const { return system_; }
  const FetiPreconditioner& preconditioner() const { return preconditioner_; }
  // Bytes CHOLMOD holds at its peak for the subdomain, preconditioner and coarse factors.
  std::size_t factor_memory() const {
    return system_.factor_memory() + preconditioner_.factor_memory() + coarse_.factor_memory();
  }

 protected:
  FetiMethod(MethodKind kind, const Model& model, const SolveOptions& options,
             int default_max_iterations, const Communicator& communicator);
  // The kind a core with FETI-1's subdomains reports: feti-dp once they are joined by
  // their corners (make_method runs FETI-DP as PCPG without contacts, MPRGP with them).
  static MethodKind kind_of(MethodKind core, const SolveOptions& options) {
    return options.corner_clusters != 0 ? MethodKind::FetiDp : core;
  }
  double reference_error() const override;
  long long f_applications() const override { return system_.f_applications(); }

  const SparseMatrix& Gt() const {
    if (!Gt_) Gt_.emplace(system_.G().transpose());
    return *Gt_;
  }
  // Rigid-body amplitudes alpha = (G^ G^')^+ G^ (F lambda - d) for the current rows,
  // with groups of floating struts the active rows leave free placed as close to where
  // they started as the gaps allow.
  Eigen::VectorXd rigid_amplitudes() const;
  // ||w|| relative to the scale of the problem (docs/METHODS.md 4.3/4.5 use ||d||).
  double relative(double norm) const { return scale_ > 0.0 ? norm / scale_ : norm; }
  // Sets the scale from r = d - F lambda at the starting lambda: max(||d||, ||F lambda||).
  // ||d|| alone depends on the generalized inverse: when K^+ f happens to vanish (a load
  // on a fixed DOF) and the gaps are zero, d = 0 and the test would turn absolute;
  // F lambda_0, the interface displacement of multipliers that balance the loads, does not.
  void set_scale() { scale_ = std::max(space().norm(d_), space().norm(d_ - r_)); }
  // Scalar products and norms of dual vectors over all rows (of every process).
  const DualSpace& space() const { return system_.space(); }
  // Force and working-set flags per contact pair from lambda and the active rows.
  void fill_contacts(Snapshot& s) const;
  // r <- r - a q after a step a p (q = F p); every kResidualReplacement iterations r is
  // recomputed as d - F lambda instead, so that rounding in the recursion cannot pile up.
  void update_residual(double a, const Eigen::VectorXd& q);
  // Call before recording a residual: fails the solve when it has not reached a new low
  // for `window` iterations (the tolerance is below what rounding allows).
  void watch_stagnation(double residual, int window = kStagnationWindow);
  // The stopping test of PCPG and FETI-C (docs/METHODS.md 4.3, 4.5) on the norm of the
  // projected residual: converges when it is within the tolerance relative to the scale
  // (or exactly zero), else watches for stagnation. Returns the relative residual.
  double stopping_test(double norm);
  // Fails for a vanishing or negative curvature p'F p, explaining the likely cause.
  void fail_breakdown(double yw, double pq);
  // One PCPG step's direction and length (PCPG and FETI-C): y = P M^-1 w preconditioned on
  // the rows of `face` (all when null) and projected onto range B and ker G of the current
  // rows; p = y + beta p (beta = 0 on a restart); q = F p; a = y'w / p'F p. Counts the
  // iteration; on a breakdown fails the solve and returns ok = false.
  struct PcpgStep {
    double a = 0.0, yw = 0.0;
    bool ok = false;
  };
  PcpgStep pcpg_step(const Eigen::VectorXd& w, const std::vector<char>* face, bool restart,
                     double yw_previous, Eigen::VectorXd& p, Eigen::VectorXd& q);
  void reset_watch();

  static constexpr int kResidualReplacement = 25;
  static constexpr int kStagnationWindow = 60;
  double best_residual_ = 0.0;
  int best_iteration_ = 0;

  ConditionRecord condition_;  // pcpg_step's coefficients
  FetiSystem system_;
  FetiPreconditioner preconditioner_;
  double coarse_setup_seconds_ = 0.0;  // before coarse_, whose construction it times
  CoarseProblem coarse_;
  // G' (local rows x modes): a column per mode, the rows it reaches. Made on first use: only
  // groups of subdomains the active rows leave free read it (the serial transposition
  // was a part of every set-up).
  mutable std::optional<SparseMatrix> Gt_;
  Eigen::VectorXd d_;
  Eigen::VectorXd e_;
  double scale_ = 0.0;
  Eigen::VectorXd lambda_;
  Eigen::VectorXd r_;  // d - F lambda
};

}  // namespace fetic::solver
