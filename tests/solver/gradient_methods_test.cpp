// Steepest descent and conjugate gradients agree with one direct CHOLMOD solve of K u = f.

#include <catch2/catch.hpp>

#include <random>

#include "solver/cholmod_factor.hpp"
#include "solver/primal_problem.hpp"
#include "tests/support/random_scenes.hpp"
#include "tests/support/solve_helpers.hpp"

using namespace fetic;
using fetic::solver::MethodKind;

namespace {

Eigen::VectorXd direct_solution(const solver::Model& model, double load_factor) {
  solver::PrimalProblem problem(model);
  solver::CholmodFactor factor;
  REQUIRE(factor.factorize(problem.stiffness()) == solver::CholmodFactor::Result::Ok);
  Eigen::VectorXd f = load_factor * problem.load(), u(problem.size());
  factor.solve(f.data(), u.data());
  return u;
}

void check_against_direct(const std::string& text, MethodKind kind, double tolerance) {
  solver::SolveOptions options;
  options.tolerance = tolerance;
  const auto solved = testing::solve_text(text, kind, 1.0, options);
  REQUIRE(solved->state.status == solver::Status::Converged);
  const Eigen::VectorXd u = direct_solution(solved->model, 1.0);
  const Eigen::VectorXd& x = solved->state.primal;
  CHECK((x - u).norm() <= 1e-6 * u.norm());
  // The residual the method reports is the true one.
  CHECK(solved->state.residual <= tolerance);
}

}  // namespace

TEST_CASE("SD and CG agree with a direct solve on the bundled contact-free scene") {
  const auto scene = testing::bundled_scene("cantilevers.toml");
  for (MethodKind kind : {MethodKind::SteepestDescent, MethodKind::ConjugateGradient}) {
    solver::SolveOptions options;
    options.tolerance = 1e-10;
    const auto solved = testing::solve(scene, kind, 1.0, options);
    REQUIRE(solved->state.status == solver::Status::Converged);
    const Eigen::VectorXd u = direct_solution(solved->model, 1.0);
    CHECK((solved->state.primal - u).norm() <= 1e-8 * u.norm());
  }
}

TEST_CASE("SD and CG agree with a direct solve on random contact-free scenes") {
  std::mt19937 rng(20261122);
  for (int trial = 0; trial < 30; ++trial) {
    const std::string text = testing::random_contact_free_scene(rng);
    INFO(text);
    check_against_direct(text, MethodKind::ConjugateGradient, 1e-12);
    check_against_direct(text, MethodKind::SteepestDescent, 1e-10);
  }
}

TEST_CASE("CG converges in at most n steps on a small system, SD needs more") {
  const auto scene = testing::bundled_scene("cantilevers.toml");
  const auto cg = testing::solve(scene, MethodKind::ConjugateGradient);
  const auto sd = testing::solve(scene, MethodKind::SteepestDescent);
  REQUIRE(cg->state.status == solver::Status::Converged);
  REQUIRE(sd->state.status == solver::Status::Converged);
  CHECK(cg->state.iteration < sd->state.iteration);
}

TEST_CASE("SD and CG refuse scenes with contacts, naming the methods that can") {
  const auto scene = testing::bundled_scene("two_bars.toml");
  const auto model = solver::build_model(scene);
  for (MethodKind kind : {MethodKind::SteepestDescent, MethodKind::ConjugateGradient}) {
    try {
      solver::make_method(kind, model, {});
      FAIL("the method accepted a contact scene");
    } catch (const solver::SolverError& error) {
      CHECK_THAT(error.what(),
                 Catch::Contains("without contacts") && Catch::Contains("--method active-set"));
    }
  }
}

TEST_CASE("SD reports no convergence within its iteration cap") {
  solver::SolveOptions options;
  options.max_iterations = 3;
  options.tolerance = 1e-14;
  const auto solved = testing::solve(testing::bundled_scene("cantilevers.toml"),
                                     MethodKind::SteepestDescent, 1.0, options);
  CHECK(solved->state.status == solver::Status::Failed);
  CHECK_THAT(solved->state.message, Catch::Contains("no convergence within 3 iterations"));
  CHECK(solved->method->history().size() == 4);  // initial state + 3 iterations
}
