#pragma once
// FETI-1 solved by the preconditioned conjugate projected gradient (docs/METHODS.md 4.3),
// for scenes without contacts:
//   lambda = G'(GG')^-1 e,  r = d - F lambda
//   loop: w = P r (stop when ||w|| <= tol ||d||); z = M^-1 w; y = P z;
//         p = y + beta p; a = y'w / p'F p; lambda += a p; r -= a F p.

#include "solver/feti_method.hpp"

namespace fetic::solver {

class Pcpg final : public FetiMethod {
 public:
  // Made by make_method, for feti and for feti-dp without contacts.
  Pcpg(const Model& model, const SolveOptions& options, const Communicator& communicator);

 private:
  void begin(const Snapshot* warm) override;
  void advance() override;
  void record_residual();

  Eigen::VectorXd w_, p_, q_;
  double yw_previous_ = 0.0;
};

}  // namespace fetic::solver
