// MPRGP against the active-set method and FETI-C on the bundled scenes, floating struts
// held only by contacts, unboundedness, warm starts; and what the preconditioners and the
// count of F applications report. The random scenes against CGAL's exact QP solver are
// FETI-C's: feti_c_test.cpp (250 bar scenes) and plane_test.cpp (100 plane pairs) check
// MPRGP beside FETI-C.

#include <catch2/catch.hpp>

#include <array>
#include <filesystem>

#include "solver/mprgp.hpp"
#include "tests/support/solve_helpers.hpp"

using namespace fetic;
using fetic::solver::MethodKind;
using fetic::solver::Preconditioner;

namespace {

solver::SolveOptions with(Preconditioner preconditioner) {
  solver::SolveOptions options;
  options.preconditioner = preconditioner;
  return options;
}

constexpr std::array kPreconditioners{Preconditioner::Dirichlet, Preconditioner::Lumped,
                                      Preconditioner::None};

}  // namespace

TEST_CASE("MPRGP agrees with FETI-C and the active-set method on every bundled scene") {
  int scenes_with_contacts = 0;
  for (const auto& entry : std::filesystem::directory_iterator(FETIC_BUNDLED_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    const scenes::Scene scene = scenes::load_scene_file(entry.path().string());
    if (scene.contacts.empty()) continue;
    ++scenes_with_contacts;
    const auto active_set = testing::solve(scene, MethodKind::ActiveSet);
    REQUIRE(active_set->state.status == solver::Status::Converged);
    const auto exact = solver::strut_displacements(active_set->model, active_set->state);
    for (Preconditioner p : kPreconditioners) {
      INFO(entry.path().filename().string() << " / " << solver::to_string(p));
      const auto mprgp = testing::solve(scene, MethodKind::Mprgp, 1.0, with(p));
      INFO(mprgp->state.message);
      REQUIRE(mprgp->state.status == solver::Status::Converged);
      CHECK(solver::relative_error(solver::strut_displacements(mprgp->model, mprgp->state),
                                   exact) <= 1e-8);
      const auto feti_c = testing::solve(scene, MethodKind::FetiC, 1.0, with(p));
      REQUIRE(feti_c->state.status == solver::Status::Converged);
      for (size_t k = 0; k < mprgp->state.force.size(); ++k)
        CHECK(mprgp->state.force[k] ==
              Approx(feti_c->state.force[k]).margin(1e-8 * testing::load_scale(mprgp->model)));
    }
  }
  CHECK(scenes_with_contacts >= 4);
}

TEST_CASE("MPRGP: floating struts held only by contacts, and one pushed away from them") {
  const auto escaping = testing::solve_text(testing::floating_chain(500.0), MethodKind::Mprgp);
  CHECK(escaping->state.status == solver::Status::Failed);
  CHECK_THAT(escaping->state.message, Catch::Contains("unbounded") && Catch::Contains("'tip'"));
  // Pushed back, the tip rests on the middle strut, which rests on the base.
  for (Preconditioner p : kPreconditioners) {
    const auto held =
        testing::solve_text(testing::floating_chain(-500.0), MethodKind::Mprgp, 1.0, with(p));
    INFO(solver::to_string(p) << ": " << held->state.message);
    REQUIRE(held->state.status == solver::Status::Converged);
    CHECK(held->state.force[0] == Approx(1300.0));
    CHECK(held->state.force[1] == Approx(500.0));
  }
}

TEST_CASE("MPRGP: a warm start after a 5% load change needs fewer iterations than a cold one") {
  const auto model = solver::build_model(testing::bundled_scene("plane_pair.toml"));
  solver::Mprgp method(model, {});
  testing::check_warm_start(method, model);
}

TEST_CASE("MPRGP counts applications of F, and preconditioning in face reduces them") {
  const auto model = solver::build_model(testing::bundled_scene("plane_pair.toml"));
  long long count[3] = {};
  for (int i = 0; i < 3; ++i) {
    solver::Mprgp method(model, with(kPreconditioners[i]));
    const long long before = method.system().f_applications();
    method.start(1.0);
    solver::run_to_end(method);
    REQUIRE(method.status() == solver::Status::Converged);
    const auto& history = method.history();
    // Every iteration applies F at least once; the history's count is the operator's own.
    CHECK(history.back().f_applications == method.system().f_applications() - before);
    CHECK(history.back().f_applications >= method.iteration());
    for (size_t k = 1; k < history.size(); ++k)
      CHECK(history[k].f_applications > history[k - 1].f_applications);
    CHECK(method.setup_f_applications() > 0);
    count[i] = history.back().f_applications;
  }
  // Dirichlet < lumped < none on the plane pair (measured: 26, 43, 71).
  CHECK(count[0] < count[1]);
  CHECK(count[1] < count[2]);
}

// Issue 27 item 2: the balance of groups held only by contacts is kept per block of groups
// that share rows (solver/group_balance.hpp), not by a Gram-Schmidt over all of them,
// which was cubic in the number of floating bodies. Copies that do not touch each other
// must each carry what one beam alone carries.
TEST_CASE("MPRGP: many copies of a beam held only by contacts each carry what one carries") {
  const auto copies_of_beam = [](int copies) {
    std::string text =
        "model = \"frame\"\n[defaults]\nE = 2.1e11\narea = 2.0e-3\ninertia = 8.0e-6\n";
    for (int i = 0; i < copies; ++i) {
      const std::string n = std::to_string(i), y = std::to_string(3 * i),
                        top = std::to_string(3 * i + 1);
      const auto strut = [&](const std::string& name, const std::string& from,
                             const std::string& to, const std::string& rest) {
        text += "[[strut]]\nname = \"" + name + n + "\"\nfrom = [" + from + "]\nto = [" + to +
                "]\n" + rest;
      };
      strut("beam", "0.0, " + top + ".002", "4.0, " + top + ".002",
            "elements = 16\nsubdomains = 4\n");
      strut("postL", "0.5, " + y, "0.5, " + top, "elements = 4\nfixed = [\"from\"]\n");
      strut("postR", "3.5, " + y, "3.5, " + top, "elements = 4\nfixed = [\"from\"]\n");
      strut("wall", "-0.5, " + top + ".002", "-0.003, " + top + ".002",
            "elements = 2\nfixed = [\"from\"]\n");
      text += "[[load]]\nstrut = \"beam" + n + "\"\nper_length = [0.0, -1.5e4]\n";
      text += "[[load]]\nstrut = \"beam" + n + "\"\nat = \"to\"\nforce = [-5.0e3, 0.0]\n";
      text += "[[contact]]\na = \"postL" + n + ".to\"\nb = \"beam" + n + "@2\"\n";
      text += "[[contact]]\na = \"postR" + n + ".to\"\nb = \"beam" + n + "@14\"\n";
      text += "[[contact]]\na = \"wall" + n + ".to\"\nb = \"beam" + n + ".from\"\n";
    }
    return text;
  };
  const auto one = testing::solve_text(copies_of_beam(1), MethodKind::ActiveSet);
  REQUIRE(one->state.status == solver::Status::Converged);
  REQUIRE(one->state.force.size() == 3);
  constexpr int kCopies = 60;
  const auto many = testing::solve_text(copies_of_beam(kCopies), MethodKind::Mprgp);
  INFO(many->state.message);
  REQUIRE(many->state.status == solver::Status::Converged);
  REQUIRE(many->state.force.size() == 3 * kCopies);
  for (int i = 0; i < kCopies; ++i)
    for (int k = 0; k < 3; ++k)
      CHECK(many->state.force[3 * i + k] ==
            Approx(one->state.force[k]).margin(1e-7 * testing::load_scale(one->model)));
}

TEST_CASE("MPRGP refuses more than 1,000 linked groups in one block, naming other methods") {
  // A fixed base, then a row of free bars each resting on the next: every contact row
  // links two groups, so all of them form one block of the balance (group_balance.hpp).
  const auto chain = [](int floating) {
    testing::SceneToml scene("bar", "[defaults]", "E = 2e11, area = 1e-4, elements = 1");
    scene.strut("s0", {0.0, 0.0}, {1.0, 0.0}, "fixed = ['from']");
    for (int i = 1; i <= floating; ++i) {
      const double x = 1.001 * i;
      scene.strut("s" + std::to_string(i), {x, 0.0}, {x + 1.0, 0.0});
      scene.contact("s" + std::to_string(i - 1) + ".to", "s" + std::to_string(i) + ".from");
    }
    scene.load("s" + std::to_string(floating), "to", {-100.0, 0.0});
    return solver::build_model(scenes::parse_scene(scene.str(), "chain.toml"));
  };
  constexpr int kLimit = solver::GroupBalance::kMaxBlock;
  const solver::Model refused = chain(kLimit + 1);
  REQUIRE_THROWS_WITH(solver::Mprgp(refused, {}),
                      Catch::Contains(std::to_string(kLimit + 1) + " free motions") &&
                          Catch::Contains("feti-c") && Catch::Contains("active-set"));
  // One group fewer is balanced and solved (the chain rests on the base).
  const solver::Model held = chain(kLimit);
  solver::Mprgp accepted(held, {});
  accepted.start(1.0);
  CHECK(accepted.iteration() == 0);
}
