// FETI-C (and MPRGP on the same random scenes) against the independent QP solver and the
// active-set method, and the behaviour the thesis reports: few iterations on its test
// problem, far fewer than the active-set method; floating struts; unboundedness; warm
// starts.

#include <catch2/catch.hpp>

#include <random>

#include "solver/feti_c.hpp"
#include "tests/support/random_scenes.hpp"
#include "tests/support/random_trials.hpp"
#include "tests/support/scene_toml.hpp"
#include "tests/support/solve_helpers.hpp"

using namespace fetic;
using fetic::solver::MethodKind;
using fetic::solver::Preconditioner;

namespace {

solver::SolveOptions with(Preconditioner preconditioner, bool scaling = true) {
  solver::SolveOptions options;
  options.preconditioner = preconditioner;
  options.scaling = scaling;
  return options;
}

}  // namespace

// MPRGP is checked on the same scenes, so that the reference solves are made once.
TEST_CASE(
    "FETI-C and MPRGP agree with CGAL's exact QP solver and the active-set method on 250 random "
    "scenes") {
  std::mt19937 rng(97);
  int active = 0, floating = 0;
  for (int trial = 0; trial < testing::random_trials(250); ++trial) {
    const std::string text = testing::random_bar_scene(rng);
    const double load_factor = std::uniform_real_distribution<double>(0.2, 1.5)(rng);
    const Preconditioner preconditioner = std::array{
        Preconditioner::Dirichlet, Preconditioner::Lumped, Preconditioner::None}[trial % 3];
    const scenes::Scene scene = scenes::parse_scene(text, "random.toml");
    INFO(text);
    INFO("load factor " << load_factor << ", preconditioner " << solver::to_string(preconditioner));
    const auto feti_c = testing::solve(scene, MethodKind::FetiC, load_factor, with(preconditioner));
    INFO("message: " << feti_c->state.message);
    REQUIRE(feti_c->state.status == solver::Status::Converged);
    const auto reference = testing::solve_reference_qp(scene, load_factor);
    REQUIRE(reference.optimal);
    const double force_scale = 1e-12 * testing::load_scale(feti_c->model);
    CHECK(testing::displacement_error(*feti_c, reference) <= 1e-8);
    CHECK(testing::force_error(*feti_c, reference, force_scale) <= 1e-8);

    const auto active_set = testing::solve(scene, MethodKind::ActiveSet, load_factor);
    REQUIRE(active_set->state.status == solver::Status::Converged);
    const auto u = solver::strut_displacements(feti_c->model, feti_c->state);
    const auto v = solver::strut_displacements(active_set->model, active_set->state);
    CHECK(solver::relative_error(u, v) <= 1e-8);
    CHECK(feti_c->state.in_working_set == active_set->state.in_working_set);

    const auto mprgp = testing::solve(scene, MethodKind::Mprgp, load_factor, with(preconditioner));
    INFO("MPRGP: " << mprgp->state.message);
    REQUIRE(mprgp->state.status == solver::Status::Converged);
    CHECK(testing::displacement_error(*mprgp, reference) <= 1e-8);
    CHECK(testing::force_error(*mprgp, reference, force_scale) <= 1e-8);
    CHECK(solver::relative_error(solver::strut_displacements(mprgp->model, mprgp->state), v) <=
          1e-8);
    CHECK(mprgp->state.in_working_set == active_set->state.in_working_set);
    active += feti_c->state.active_set_size();
    for (size_t s = 0; s < feti_c->model.struts.size(); ++s)
      floating += feti_c->model.floating(s);
  }
  CHECK(active > 150);
  CHECK(floating > 100);
}

TEST_CASE("FETI-C on the thesis scene: the reference to 1e-6 within 10 iterations") {
  const scenes::Scene scene = testing::bundled_scene("thesis.toml");
  const auto reference_solve = testing::solve(scene, MethodKind::ActiveSet);
  const auto reference =
      solver::strut_displacements(reference_solve->model, reference_solve->state);
  for (Preconditioner p :
       {Preconditioner::Dirichlet, Preconditioner::Lumped, Preconditioner::None}) {
    INFO(solver::to_string(p));
    const auto model = solver::build_model(scene);
    solver::FetiC method(model, with(p));
    method.set_reference(reference);
    method.start(1.0);
    solver::run_to_end(method);
    REQUIRE(method.status() == solver::Status::Converged);
    int reached = -1;
    for (const auto& entry : method.history())
      if (reached < 0 && entry.error <= 1e-6) reached = entry.iteration;
    CHECK(reached >= 0);
    CHECK(reached <= 10);
    // The primal active-set method changes W one contact at a time and needs more.
    CHECK(reference_solve->state.iteration > method.iteration());
  }
}

TEST_CASE("FETI-C: a floating tip pushed away from every contact is reported as unbounded") {
  // The middle strut is pushed onto the base, the tip is pulled away from the middle.
  const auto escaping = testing::solve_text(testing::floating_chain(500.0), MethodKind::FetiC);
  CHECK(escaping->state.status == solver::Status::Failed);
  CHECK_THAT(escaping->state.message, Catch::Contains("unbounded") && Catch::Contains("'tip'") &&
                                          !Catch::Contains("'middle'"));
  // Reversed, the two together are pushed away (net 300 N outward).
  const auto both = testing::solve_text(testing::floating_chain(500.0), MethodKind::FetiC, -1.0);
  CHECK(both->state.status == solver::Status::Failed);
  CHECK_THAT(both->state.message, Catch::Contains("'middle', 'tip'"));
  // Pushed back, the tip rests on the middle strut, which rests on the base.
  const auto held = testing::solve_text(testing::floating_chain(-500.0), MethodKind::FetiC);
  INFO(held->state.message);
  REQUIRE(held->state.status == solver::Status::Converged);
  CHECK(held->state.force[0] == Approx(1300.0));
  CHECK(held->state.force[1] == Approx(500.0));
}

// Each iteration places the groups of floating struts that no active row holds (they
// carry no load) as close to where they are as their gaps allow. That placement once cost
// a pass over every subdomain per group (groups x subdomains per iteration: minutes for
// a thousand floating beams); it must cost a fixed number of passes, whatever the groups.
TEST_CASE("FETI-C: the placement of unheld floating groups costs no pass per group") {
  // Three pairs of opposing bars pushed together (the thesis' test problem in small),
  // beside `idle` unloaded free bars, each facing a clamped stop across an open gap: every
  // idle bar is a group that no row holds.
  const auto scene = [](int idle) {
    testing::SceneToml toml("bar", "[defaults]",
                            "E = 2.1e11, area = 7e-5, elements = 4, subdomains = 2");
    for (int p = 0; p < 3; ++p) {
      const std::string n = std::to_string(p);
      const double y = -1.0 - p;
      toml.strut("L" + n, {0.0, y}, {0.996, y},
                 "area = " + std::to_string(6e-5 + 2e-5 * p) + ", fixed = ['from']")
          .strut("R" + n, {1.0, y}, {2.0, y}, "fixed = ['to']")
          .contact("L" + n + ".to", "R" + n + ".from")
          .load("R" + n, "from", {-1e5 - 5e4 * p, 0.0});
    }
    for (int i = 0; i < idle; ++i) {
      const std::string n = std::to_string(i);
      const double y = 1.0 + i;
      toml.strut("stop" + n, {0.0, y}, {1.0, y}, "fixed = ['from'], elements = 1, subdomains = 1")
          .strut("idle" + n, {1.002, y}, {2.0, y}, "elements = 1, subdomains = 1")
          .contact("stop" + n + ".to", "idle" + n + ".from");
    }
    return solver::build_model(scenes::parse_scene(toml.str(), "idle.toml"));
  };
  const auto passes_per_iteration = [&](int idle) {
    const solver::Model model = scene(idle);
    solver::FetiC method(model, {});
    method.start(1.0);
    solver::run_to_end(method);
    INFO(idle << " idle bars: " << method.message());
    REQUIRE(method.status() == solver::Status::Converged);
    REQUIRE(method.iteration() >= 1);
    const solver::Snapshot state = method.snapshot();
    for (int p = 0; p < 3; ++p)
      CHECK(state.force[static_cast<size_t>(p)] > 0.0);
    for (int i = 3; i < 3 + idle; ++i)
      CHECK(state.force[static_cast<size_t>(i)] == 0.0);
    return static_cast<double>(method.system().subdomain_passes()) / method.iteration();
  };
  const double few = passes_per_iteration(2), many = passes_per_iteration(300);
  INFO("passes per iteration: " << few << " with 2 idle bars, " << many << " with 300");
  CHECK(many <= few + 1.0);
}

TEST_CASE("FETI-C: a warm start after a 5% load change needs fewer iterations than a cold one") {
  const auto model = solver::build_model(testing::bundled_scene("thesis.toml"));
  solver::FetiC method(model, {});
  testing::check_warm_start(method, model);
}

TEST_CASE("FETI-C: the displacements are torn across subdomains until lambda converges") {
  const auto model = solver::build_model(testing::bundled_scene("thesis.toml"));
  solver::FetiC method(model, {});
  method.start(1.0);
  auto jump = [&](const solver::Snapshot& s) {
    // Largest difference between two pieces of the same strut at a shared node.
    double largest = 0.0;
    for (size_t a = 0; a < s.pieces.size(); ++a)
      for (size_t b = a + 1; b < s.pieces.size(); ++b) {
        const auto& p = s.pieces[a];
        const auto& q = s.pieces[b];
        if (p.strut != q.strut || p.box.i1 != q.box.i0) continue;
        largest = std::max(largest, (p.displacement.back() - q.displacement.front()).norm());
      }
    return largest;
  };
  const solver::Snapshot first = method.snapshot();
  REQUIRE(first.pieces.size() == 200);  // 2 subdomains per bar
  solver::run_to_end(method);
  const solver::Snapshot last = method.snapshot();
  CHECK(jump(first) > 1e-6);
  CHECK(jump(last) < 1e-12);
}
