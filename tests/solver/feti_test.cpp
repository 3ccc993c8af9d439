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

namespace {

solver::SolveOptions feti1_options(Preconditioner preconditioner, bool scaling) {
  solver::SolveOptions options;
  options.preconditioner = preconditioner;
  options.scaling = scaling;
  options.tolerance = 1e-12;
  return options;
}

void check_feti1_against_direct(const testing::Solved& solved) {
  REQUIRE(solved.state.status == solver::Status::Converged);
  const auto u = solver::strut_displacements(solved.model, solved.state);
  CHECK(solver::relative_error(u, testing::direct_displacements(solved.model)) <= 1e-9);
}

}  // namespace

TEST_CASE("FETI-1 agrees with a direct solve on the contact-free scene, every preconditioner") {
  const auto scene = testing::bundled_scene("cantilevers.toml");
  for (Preconditioner p :
       {Preconditioner::None, Preconditioner::Lumped, Preconditioner::Dirichlet}) {
    for (bool scaling : {false, true}) {
      check_feti1_against_direct(
          *testing::solve(scene, MethodKind::Feti, 1.0, feti1_options(p, scaling)));
    }
  }
}

TEST_CASE("FETI-1 agrees with a direct solve on 40 random contact-free scenes") {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 40; ++trial) {
    const std::string text = testing::random_contact_free_scene(rng);
    INFO(text);
    const Preconditioner p = std::array{Preconditioner::Dirichlet, Preconditioner::Lumped,
                                        Preconditioner::None}[trial % 3];
    check_feti1_against_direct(
        *testing::solve_text(text, MethodKind::Feti, 1.0, feti1_options(p, true)));
  }
}

TEST_CASE("FETI-1 refuses scenes with contacts, pointing to FETI-C") {
  const auto model = solver::build_model(testing::bundled_scene("two_bars.toml"));
  CHECK_THROWS_WITH(solver::make_method(MethodKind::Feti, model, {}),
                    Catch::Contains("--method feti-c"));
}
