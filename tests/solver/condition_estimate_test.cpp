// solver/condition_estimate.hpp: Lanczos eigenvalue estimates from CG coefficients, against
// the known spectrum of the matrix the CG ran on.

#include <catch2/catch.hpp>

#include <Eigen/Core>

#include "solver/condition_estimate.hpp"

using fetic::solver::ConditionEstimate;
using fetic::solver::ConditionRecord;

namespace {

// Runs `steps` steps of plain CG on diag(eigenvalues) x = 1 from x = 0, recording them.
void run_cg(const Eigen::VectorXd& eigenvalues, int steps, ConditionRecord& record) {
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(eigenvalues.size());
  Eigen::VectorXd r = b, p = r;
  double rr = r.squaredNorm(), beta = 0.0;
  for (int k = 0; k < steps; ++k) {
    const Eigen::VectorXd q = eigenvalues.cwiseProduct(p);
    const double a = rr / p.dot(q);
    record.add(a, beta);
    r -= a * q;
    const double rr_next = r.squaredNorm();
    beta = rr_next / rr;
    rr = rr_next;
    p = r + beta * p;
  }
}

}  // namespace

TEST_CASE("condition estimate: the extreme eigenvalues from CG's coefficients") {
  Eigen::VectorXd eigenvalues(12);
  for (int k = 0; k < 12; ++k)
    eigenvalues(k) = 0.5 + 4.0 * k * k;  // 0.5 .. 484.5
  ConditionRecord record;
  SECTION("a whole CG run finds the spectrum's ends") {
    run_cg(eigenvalues, 12, record);
    const ConditionEstimate e = record.estimate();
    CHECK(e.steps == 12);
    CHECK(e.lambda_min == Approx(0.5).epsilon(1e-6));
    CHECK(e.lambda_max == Approx(484.5).epsilon(1e-6));
    CHECK(e.kappa() == Approx(969.0).epsilon(1e-6));
  }
  SECTION("a short run's Ritz values lie inside the spectrum") {
    run_cg(eigenvalues, 4, record);
    const ConditionEstimate e = record.estimate();
    CHECK(e.steps == 4);
    CHECK(e.lambda_min >= 0.5 * (1 - 1e-12));
    CHECK(e.lambda_max <= 484.5 * (1 + 1e-12));
    CHECK(e.kappa() > 10.0);
  }
  SECTION("the longest run counts, a restart starts a new one, clear forgets") {
    run_cg(eigenvalues, 12, record);
    record.restart();
    run_cg(eigenvalues.head(3), 3, record);  // a shorter run on another operator
    CHECK(record.estimate().steps == 12);
    CHECK(record.estimate().lambda_max == Approx(484.5).epsilon(1e-6));
    record.clear();
    CHECK(record.estimate().steps == 0);
    CHECK(record.estimate().kappa() == 0.0);
    run_cg(eigenvalues.head(3), 3, record);
    CHECK(record.estimate().lambda_max == Approx(16.5).epsilon(1e-6));
  }
}
