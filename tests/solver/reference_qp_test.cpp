// The active-set method against an independent solver: CGAL's exact QP solver on the
// primal problem assembled separately (tests/support/reference_qp.cpp).

#include <catch2/catch.hpp>

#include <random>

#include "tests/support/random_scenes.hpp"
#include "tests/support/random_trials.hpp"
#include "tests/support/solve_helpers.hpp"

using namespace fetic;
using fetic::solver::MethodKind;

namespace {

int compare_with_reference(const std::string& text, MethodKind kind, double load_factor,
                           solver::SolveOptions options = {}) {
  const scenes::Scene scene = scenes::parse_scene(text, "random.toml");
  const auto solved = testing::solve(scene, kind, load_factor, options);
  INFO(text);
  INFO("message: " << solved->state.message);
  REQUIRE(solved->state.status == solver::Status::Converged);
  const testing::ReferenceSolution reference = testing::solve_reference_qp(scene, load_factor);
  REQUIRE(reference.optimal);
  testing::check_against_reference(*solved, reference);
  return solved->state.active_set_size();
}

}  // namespace

TEST_CASE("active set agrees with CGAL's exact QP solver on 150 random bar scenes") {
  std::mt19937 rng(4242);
  int active = 0;
  const int trials = testing::random_trials(150);
  for (int trial = 0; trial < trials; ++trial) {
    const std::string text = testing::random_bar_scene(rng);
    const double load_factor = std::uniform_real_distribution<double>(0.2, 1.5)(rng);
    active += compare_with_reference(text, MethodKind::ActiveSet, load_factor);
  }
  CHECK(active > 100 * trials / 150);  // the scenes really exercise contact
}

TEST_CASE("active set agrees with CGAL on the bundled contact scenes") {
  for (const char* name : {"thesis.toml", "two_bars.toml", "chain.toml"}) {
    INFO(name);
    const scenes::Scene scene = testing::bundled_scene(name);
    const auto solved = testing::solve(scene, MethodKind::ActiveSet);
    REQUIRE(solved->state.status == solver::Status::Converged);
    const auto reference = testing::solve_reference_qp(scene, 1.0);
    REQUIRE(reference.optimal);
    CHECK(testing::displacement_error(*solved, reference) <= 1e-8);
    CHECK(testing::force_error(*solved, reference, 0.0) <= 1e-8);
  }
}
