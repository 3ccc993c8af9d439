#pragma once
// Steepest descent (docs/METHODS.md 4.1) and conjugate gradients (4.2) on K u = t f for
// scenes without contacts. Residual: ||t f - K u|| / ||t f||.

#include <memory>

#include "solver/method.hpp"
#include "solver/primal_problem.hpp"

namespace fetic::solver {

class GradientMethod : public Method {
 public:
  void begin(const Snapshot* warm) override;
  Snapshot snapshot() const override;

 protected:
  GradientMethod(const Model& model, const SolveOptions& options, int default_max_iterations,
                 MethodKind kind);
  // Records the residual of the current iterate; converges when it is small enough.
  void record_residual();

  PrimalProblem problem_;
  Eigen::VectorXd x_;  // iterate
  Eigen::VectorXd r_;  // residual t f - K x
  double rhs_norm_ = 0.0;
};

class SteepestDescent final : public GradientMethod {
 public:
  SteepestDescent(const Model& model, const SolveOptions& options);
  void advance() override;
};

class ConjugateGradient final : public GradientMethod {
 public:
  ConjugateGradient(const Model& model, const SolveOptions& options);
  void begin(const Snapshot* warm) override;
  void advance() override;

 private:
  Eigen::VectorXd direction_;
};

}  // namespace fetic::solver
