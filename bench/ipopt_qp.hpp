#pragma once
// The primal contact QP  min 1/2 u'K u - t f'u  s.t.  A u <= c  handed to Ipopt (an
// interior-point solver from Debian's coinor-libipopt, MUMPS inside): what a user would
// otherwise reach for. Used only by the scale benchmark.

#include <string>

#include <Eigen/Core>

#include "solver/model.hpp"

namespace fetic::bench {

struct IpoptResult {
  bool solved = false;
  std::string status;
  int iterations = 0;
  double seconds = 0.0;
  Eigen::VectorXd u;  // free DOFs, PrimalProblem numbering
};

IpoptResult solve_with_ipopt(const solver::Model& model, double load_factor, double tolerance);

}  // namespace fetic::bench
