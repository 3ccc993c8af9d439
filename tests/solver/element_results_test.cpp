// Stress recovery, axial forces and support reactions against closed forms: two opposing
// bars (stresses -lambda/A and (P - lambda)/A, reactions lambda and P - lambda), a
// plane strut in uniaxial tension at any angle (nu = 0: the bilinear elements are exact),
// and the balance of reactions and loads on the bundled scenes.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "solver/element_results.hpp"
#include "tests/support/solve_helpers.hpp"

using namespace fetic;
using fetic::solver::MethodKind;

namespace {

constexpr double kTolerance = 1e-8;

bool near(double value, double expected, double scale) {
  return std::abs(value - expected) <= kTolerance * scale;
}

const solver::NamedValues& field(const std::vector<solver::NamedValues>& fields,
                                 const std::string& name) {
  for (const auto& f : fields)
    if (f.name == name) return f;
  FAIL("no field " << name);
  return fields.front();
}

}  // namespace

TEST_CASE("two bars: element stresses, axial forces and reactions match the closed form") {
  // scenes/two_bars.toml: EA = 2.1e7 N, L = 1 m, gap 1 mm, P = 63 kN at t = 1.
  const double EA = 2.1e11 * 1e-4, A = 1e-4, P = 63000.0, L = 1.0, gap = 0.001;
  const double lambda = std::max(0.0, (P * L / EA - gap) / (2 * L / EA));
  for (MethodKind kind : {MethodKind::ActiveSet, MethodKind::FetiC}) {
    INFO(solver::to_string(kind));
    const auto solved = testing::solve(testing::bundled_scene("two_bars.toml"), kind);
    REQUIRE(solved->state.status == solver::Status::Converged);
    REQUIRE(solved->state.force.at(0) == Approx(lambda).epsilon(1e-8));
    const auto elements = solver::element_results(solved->model, solved->state);
    REQUIRE(elements.size() == 2);
    for (int s = 0; s < 2; ++s) {
      const solver::StrutElements& e = elements[static_cast<size_t>(s)];
      CHECK(e.nodes_per_element == 2);
      REQUIRE(e.element_count() == 4);
      // The left bar is pushed against its clamp (compression); the load pulls the right
      // bar's free end away from its clamp, the contact takes part of it (tension).
      const double force = s == 0 ? -lambda : P - lambda;
      for (int k = 0; k < 4; ++k) {
        CHECK(e.connectivity[static_cast<size_t>(2 * k)] == k);
        CHECK(e.connectivity[static_cast<size_t>(2 * k + 1)] == k + 1);
        CHECK(e.subdomain[static_cast<size_t>(k)] == 2 * s + k / 2);  // 2 subdomains per strut
        CHECK(near(field(e.stress, "axial").values[static_cast<size_t>(k)], force / A, P / A));
        CHECK(near(field(e.resultants, "axial_force").values[static_cast<size_t>(k)], force, P));
      }
    }
    const auto reactions = solver::support_reactions(solved->model, solved->state);
    REQUIRE(reactions.size() == 2);
    CHECK(reactions[0].strut == 0);
    CHECK(reactions[0].end == scenes::StrutEnd::From);
    CHECK(reactions[0].nodes == std::vector<int>{0});
    CHECK(near(reactions[0].force.x(), lambda, P));
    CHECK(reactions[1].strut == 1);
    CHECK(reactions[1].end == scenes::StrutEnd::To);
    CHECK(near(reactions[1].force.x(), P - lambda, P));
    CHECK(std::abs(reactions[0].force.y()) + std::abs(reactions[1].force.y()) == 0.0);
    // Clamped nodes are exactly at rest (total FETI leaves ~1e-19 there otherwise).
    const auto u = solver::strut_displacements(solved->model, solved->state);
    CHECK(u[0][0].norm() == 0.0);
    CHECK(u[1][4].norm() == 0.0);
  }
}

TEST_CASE("plane strut in uniaxial tension at any angle: stresses in global axes") {
  // nu = 0 and a uniform end traction: u = sigma x / E along the axis is exact for the
  // bilinear elements even at the clamped end.
  const double F = 2.5e5, height = 0.1, thickness = 0.02, E = 7e10;
  const double sigma = F / (height * thickness);
  for (double degrees : {0.0, 30.0, 90.0, 200.0}) {
    INFO("angle " << degrees);
    const double a = degrees * M_PI / 180.0, c = std::cos(a), s = std::sin(a);
    char text[1024];
    std::snprintf(text, sizeof text, R"(
model = "plane"
[[strut]]
name = "S"
from = [0.5, -0.25]
to = [%.17g, %.17g]
E = %.17g
nu = 0.0
height = %.17g
thickness = %.17g
elements = 6
elements_across = 3
subdomains = 3
subdomains_across = 1
fixed = ["from"]
[[load]]
strut = "S"
at = "to"
force = [%.17g, %.17g]
)",
                  0.5 + 1.2 * c, -0.25 + 1.2 * s, E, height, thickness, F * c, F * s);
    for (MethodKind kind : {MethodKind::ActiveSet, MethodKind::Feti}) {
      INFO(solver::to_string(kind));
      const auto solved = testing::solve_text(text, kind);
      REQUIRE(solved->state.status == solver::Status::Converged);
      const auto elements = solver::element_results(solved->model, solved->state);
      const solver::StrutElements& e = elements.at(0);
      CHECK(e.nodes_per_element == 4);
      REQUIRE(e.element_count() == 18);
      for (int k = 0; k < 18; ++k) {
        const auto at = static_cast<size_t>(k);
        CHECK(near(field(e.stress, "axial").values[at], sigma, sigma));
        CHECK(near(field(e.stress, "sxx").values[at], sigma * c * c, sigma));
        CHECK(near(field(e.stress, "syy").values[at], sigma * s * s, sigma));
        CHECK(near(field(e.stress, "sxy").values[at], sigma * c * s, sigma));
        CHECK(near(field(e.stress, "von_mises").values[at], sigma, sigma));
        CHECK(near(field(e.resultants, "axial_force").values[at], F / 3, F));
        CHECK(e.subdomain[at] == k / 6);  // 2 elements along per subdomain, 3 across
      }
      // Counterclockwise quadrilaterals: positive area in (e1, e2).
      const auto& nodes = solved->model.struts[0].nodes;
      const auto q = [&](int corner) {
        return nodes[static_cast<size_t>(e.connectivity[static_cast<size_t>(corner)])];
      };
      const solver::Vec2 d1 = q(2) - q(0), d2 = q(3) - q(1);
      CHECK(d1.x() * d2.y() - d1.y() * d2.x() > 0.0);
      const auto reactions = solver::support_reactions(solved->model, solved->state);
      REQUIRE(reactions.size() == 1);
      CHECK(reactions[0].nodes.size() == 4);
      CHECK(near(reactions[0].force.x(), -F * c, F));
      CHECK(near(reactions[0].force.y(), -F * s, F));
    }
  }
}

TEST_CASE("bundled scenes: the support reactions balance the applied loads") {
  for (const char* name : {"thesis.toml", "chain.toml", "cantilevers.toml", "plane_pair.toml"}) {
    INFO(name);
    solver::SolveOptions options;
    options.tolerance = 1e-12;
    const auto solved =
        testing::solve(testing::bundled_scene(name), MethodKind::FetiC, 1.0, options);
    REQUIRE(solved->state.status == solver::Status::Converged);
    const solver::Model& model = solved->model;
    solver::Vec2 load = solver::Vec2::Zero(), reaction = solver::Vec2::Zero();
    for (size_t s = 0; s < model.struts.size(); ++s)
      for (int n = 0; n < model.struts[s].node_count(); ++n)
        load += solver::node_displacement(
            model.struts[s], model.loads[s].data() + n * model.struts[s].dofs_per_node);
    for (const auto& r : solver::support_reactions(model, solved->state)) {
      solver::Vec2 sum = solver::Vec2::Zero();
      for (const auto& f : r.node_forces)
        sum += f;
      CHECK((sum - r.force).norm() <= 1e-12 * r.force.norm());
      reaction += r.force;
    }
    const double scale = testing::load_scale(model);
    CHECK((reaction + load).norm() <= 1e-7 * scale);
  }
}
