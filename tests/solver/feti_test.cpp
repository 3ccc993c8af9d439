// FETI-1 (PCPG) on scenes without contact agrees with a direct solve, for every
// preconditioner, and refuses contact scenes.

#include <catch2/catch.hpp>

#include <array>
#include <random>

#include "tests/support/random_scenes.hpp"
#include "tests/support/solve_helpers.hpp"

using namespace fetic;
using fetic::solver::MethodKind;
using fetic::solver::Preconditioner;

TEST_CASE("FETI-1 agrees with a direct solve on the contact-free scene, every preconditioner") {
  const auto scene = testing::bundled_scene("cantilevers.toml");
  for (Preconditioner p :
       {Preconditioner::None, Preconditioner::Lumped, Preconditioner::Dirichlet}) {
    for (bool scaling : {false, true}) {
      solver::SolveOptions options;
      options.preconditioner = p;
      options.scaling = scaling;
      options.tolerance = 1e-12;
      const auto solved = testing::solve(scene, MethodKind::Feti, 1.0, options);
      REQUIRE(solved->state.status == solver::Status::Converged);
      const auto u = solver::strut_displacements(solved->model, solved->state);
      CHECK(solver::relative_error(u, testing::direct_displacements(solved->model)) <= 1e-9);
    }
  }
}

TEST_CASE("FETI-1 agrees with a direct solve on 40 random contact-free scenes") {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 40; ++trial) {
    const std::string text = testing::random_contact_free_scene(rng);
    INFO(text);
    solver::SolveOptions options;
    options.preconditioner = std::array{Preconditioner::Dirichlet, Preconditioner::Lumped,
                                        Preconditioner::None}[trial % 3];
    options.tolerance = 1e-12;
    const auto solved = testing::solve_text(text, MethodKind::Feti, 1.0, options);
    REQUIRE(solved->state.status == solver::Status::Converged);
    const auto u = solver::strut_displacements(solved->model, solved->state);
    CHECK(solver::relative_error(u, testing::direct_displacements(solved->model)) <= 1e-9);
  }
}

TEST_CASE("FETI-1 refuses scenes with contacts, pointing to FETI-C") {
  const auto model = solver::build_model(testing::bundled_scene("two_bars.toml"));
  CHECK_THROWS_WITH(solver::make_method(MethodKind::Feti, model, {}),
                    Catch::Contains("--method feti-c"));
}
