// Extreme magnitudes: the two-bar closed form must hold whatever the units - moduli of
// 1e-12 and 1e30, gaps of a femtometre, loads of 1e-20, kilometre-long struts - for every
// contact method and preconditioner. Relative tolerances everywhere make this possible;
// these cases once exposed an absolute test hidden in a "relative" one.

#include <catch2/catch.hpp>

#include <cstdio>

#include "tests/support/solve_helpers.hpp"

using namespace fetic;
using fetic::solver::MethodKind;
using fetic::solver::Preconditioner;

namespace {

struct Case {
  const char* what;
  double E, area, length, gap, push;
};

std::string two_bars(const Case& c) {
  char text[1024];
  std::snprintf(text, sizeof text, R"(
model = "bar"
[defaults]
E = %.17g
area = %.17g
elements = 4
subdomains = 2
[[strut]]
name = "left"
from = [0.0, 0.0]
to = [%.17g, 0.0]
fixed = ["from"]
[[strut]]
name = "right"
from = [%.17g, 0.0]
to = [%.17g, 0.0]
fixed = ["to"]
[[load]]
strut = "right"
at = "from"
force = [%.17g, 0.0]
[[contact]]
a = "left.to"
b = "right.from"
)",
                c.E, c.area, c.length, c.length + c.gap, 2 * c.length + c.gap, -c.push);
  return text;
}

}  // namespace

TEST_CASE("two bars at extreme magnitudes: every contact method matches the closed form") {
  const Case cases[] = {
      {"E = 1e-12", 1e-12, 1e-4, 1.0, 1e-3, 3e-19},
      {"E = 1e30", 1e30, 1e-4, 1.0, 1e-3, 3e27},
      {"gap at the resolution of the coordinates", 2.1e11, 1e-4, 1.0, 1e-15, 1e-6},
      {"load 1e-20 on a zero gap", 2.1e11, 1e-4, 1.0, 0.0, 1e-20},
      {"struts 1000 km long", 2.1e11, 1e-4, 1e6, 1.0, 1e12},
      {"micrometre struts", 2.1e11, 1e-12, 1e-6, 1e-9, 1e-3},
      {"pulled apart", 2.1e11, 1e-4, 1.0, 1e-3, -5e4},
      // The edges of the range the scene layer accepts (element stiffness and forces within
      // 1e-60..1e60): displacements of 1e117 and 1e-118 are still exact.
      {"softest accepted stiffness, largest force", 2.5e-60, 1.0, 1.0, 0.0, 1e59},
      {"stiffest accepted stiffness, smallest force", 2.4e59, 1.0, 1.0, 0.0, 1e-59},
  };
  for (const Case& c : cases) {
    const auto scene = scenes::parse_scene(two_bars(c), "extreme.toml");
    const auto model = solver::build_model(scene);
    // The model's gap is what the coordinates give (1 + 1e-15 is not exact in binary).
    const double gap = model.pairs[0].gap;
    const double compliance = c.length / (c.E * c.area);
    const double expected = std::max(0.0, (c.push * compliance - gap) / (2 * compliance));
    for (MethodKind kind : {MethodKind::ActiveSet, MethodKind::FetiC, MethodKind::Mprgp}) {
      for (Preconditioner p :
           {Preconditioner::Dirichlet, Preconditioner::Lumped, Preconditioner::None}) {
        if (kind == MethodKind::ActiveSet && p != Preconditioner::Dirichlet) continue;
        INFO(c.what << ", " << solver::to_string(kind) << "/" << solver::to_string(p));
        solver::SolveOptions options;
        options.preconditioner = p;
        const auto solved = testing::solve(scene, kind, 1.0, options);
        INFO(solved->state.message);
        REQUIRE(solved->state.status == solver::Status::Converged);
        CHECK(solved->state.force[0] ==
              Approx(expected).epsilon(1e-8).margin(1e-8 * std::abs(c.push)));
        const auto u = solver::strut_displacements(solved->model, solved->state);
        const double tip = (c.push - expected) * compliance;  // shortening of the right bar
        CHECK(u[1][0].x() ==
              Approx(-tip).epsilon(1e-8).margin(1e-8 * std::abs(c.push) * compliance));
      }
    }
  }
}
