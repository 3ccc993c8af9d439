#pragma once
// The condition number of a preconditioned operator estimated from the coefficients of
// conjugate gradient steps (the Lanczos connection): a run of m CG steps with step lengths
// a_k and direction updates p_k = z_k + beta_k p_(k-1) holds the tridiagonal Lanczos matrix
//   T(k,k) = 1/a_k + beta_k/a_(k-1),  T(k,k+1) = sqrt(beta_(k+1))/a_k,
// whose extreme eigenvalues approach those of the preconditioned operator from inside.
// Kept per run (a restart of the directions starts a new one: MPRGP and FETI-C restart
// when the face changes); the estimate is the longest run's, on the operator of its face.

#include <cstddef>
#include <vector>

namespace fetic::solver {

struct ConditionEstimate {
  int steps = 0;  // CG steps of the run it comes from (0: no CG step was taken)
  double lambda_min = 0.0, lambda_max = 0.0;
  double kappa() const { return lambda_min > 0.0 ? lambda_max / lambda_min : 0.0; }
};

class ConditionRecord {
 public:
  // A new solve: every run forgotten.
  void clear();
  // The directions were restarted: the next step starts a new run (beta = 0).
  void restart() { run_start_ = steps_.size(); }
  // One CG step of length a whose direction was p = z + beta p_previous (beta = 0 first).
  void add(double a, double beta);
  // The longest run's extreme Lanczos eigenvalues (the later run on a tie).
  ConditionEstimate estimate() const;

 private:
  struct Step {
    double a, beta;
  };
  std::vector<Step> steps_;  // of this solve, run after run
  std::size_t run_start_ = 0, longest_start_ = 0, longest_size_ = 0;
};

}  // namespace fetic::solver
