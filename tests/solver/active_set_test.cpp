// Behaviour of the primal active-set method beyond agreement with the reference: the
// thesis scene's active contacts, floating struts, unboundedness, warm starts.

#include <catch2/catch.hpp>

#include "solver/active_set.hpp"
#include "tests/support/solve_helpers.hpp"

using namespace fetic;
using fetic::solver::MethodKind;

TEST_CASE("thesis scene: active contacts lie in the middle of the set, not at the smallest gaps") {
  const auto solved = testing::solve(testing::bundled_scene("thesis.toml"), MethodKind::ActiveSet);
  REQUIRE(solved->state.status == solver::Status::Converged);
  const auto& active = solved->state.in_working_set;
  REQUIRE(active.size() == 50);
  int first = -1, last = -1, count = 0;
  for (int k = 0; k < 50; ++k)
    if (active[k]) {
      if (first < 0) first = k;
      last = k;
      ++count;
    }
  CHECK(count >= 8);
  CHECK(first > 5);
  CHECK(last < 44);  // the smallest gaps are at the top (k = 49)
  CHECK(solved->model.pairs[49].gap < solved->model.pairs[first].gap);
  // The method adds one contact per iteration: at least as many iterations as contacts.
  CHECK(solved->state.iteration >= count);
  // Complementarity: forces only on active pairs, and only compressive.
  for (int k = 0; k < 50; ++k) {
    CHECK(solved->state.force[k] >= 0.0);
    if (!active[k]) CHECK(solved->state.force[k] == 0.0);
  }
}

TEST_CASE("a floating strut held only by contacts is solved by the active-set method") {
  const auto solved = testing::solve(testing::bundled_scene("chain.toml"), MethodKind::ActiveSet);
  REQUIRE(solved->state.status == solver::Status::Converged);
  // The middle strut (pushed right) rests on the right strut; the tail rests on the base.
  CHECK_FALSE(solved->state.in_working_set[0]);
  CHECK(solved->state.in_working_set[1]);
  CHECK(solved->state.in_working_set[2]);
  CHECK(solved->state.force[1] == Approx(60000.0));
  CHECK(solved->state.force[2] == Approx(25000.0));
}

TEST_CASE("a floating strut pushed away from every contact is reported as unbounded") {
  const std::string text = R"(
model = "bar"
[[strut]]
name = "base"
from = [0.0, 0.0]
to = [1.0, 0.0]
fixed = ["from"]
E = 2e11
area = 1e-4
elements = 2
[[strut]]
name = "runaway"
from = [1.001, 0.0]
to = [2.0, 0.0]
E = 2e11
area = 1e-4
elements = 2
[[load]]
strut = "runaway"
at = "to"
force = [500.0, 0.0]
[[contact]]
a = "base.to"
b = "runaway.from"
)";
  const auto solved = testing::solve_text(text, MethodKind::ActiveSet);
  CHECK(solved->state.status == solver::Status::Failed);
  CHECK_THAT(solved->state.message, Catch::Contains("unbounded") && Catch::Contains("'runaway'"));
  // Pushed the other way, it is held by the contact.
  const auto held = testing::solve_text(text, MethodKind::ActiveSet, -1.0);
  CHECK(held->state.status == solver::Status::Converged);
  CHECK(held->state.force[0] == Approx(500.0));
}

TEST_CASE("active set: a warm start after a small load change needs fewer iterations") {
  const auto scene = testing::bundled_scene("thesis.toml");
  const auto model = solver::build_model(scene);
  solver::ActiveSet method(model, {});
  method.start(1.0);
  solver::run_to_end(method);
  REQUIRE(method.status() == solver::Status::Converged);
  const solver::Snapshot previous = method.snapshot();
  const int cold_iterations = previous.iteration;

  method.start(1.05, &previous);
  solver::run_to_end(method);
  REQUIRE(method.status() == solver::Status::Converged);
  const int warm_iterations = method.iteration();
  const auto warm_state = method.snapshot();

  method.start(1.05);
  solver::run_to_end(method);
  const auto cold_state = method.snapshot();
  CHECK(warm_iterations < method.iteration());
  CHECK(warm_iterations < cold_iterations);
  CHECK((warm_state.primal - cold_state.primal).norm() <= 1e-10 * cold_state.primal.norm());
}
