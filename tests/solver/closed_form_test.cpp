// Closed-form solutions: two opposing bars in contact, and bars under distributed loads
// (linear bar elements are nodally exact in 1D).

#include <catch2/catch.hpp>

#include "tests/support/solve_helpers.hpp"

using namespace fetic;
using fetic::solver::MethodKind;

namespace {

std::string two_bars(double L1, double EA1, double L2, double EA2, double gap, double P,
                     int elements, int subdomains, double angle) {
  const double dx = std::cos(angle), dy = std::sin(angle);
  auto at = [&](double s) { return testing::TomlPoint{s * dx, s * dy}; };
  const std::string mesh = "area = 1.0, elements = " + std::to_string(elements) +
                           ", subdomains = " + std::to_string(subdomains);
  return testing::SceneToml("bar")
      .strut("A", at(0), at(L1),
             "E = " + testing::toml_number(EA1) + ", " + mesh + ", fixed = ['from']")
      .strut("B", at(L1 + gap), at(L1 + gap + L2),
             "E = " + testing::toml_number(EA2) + ", " + mesh + ", fixed = ['to']")
      .load("B", "from", {-P * dx, -P * dy})
      .contact("A.to", "B.from");
}

}  // namespace

TEST_CASE("two opposing bars: contact force max(0, (P L2/EA2 - g) / (L1/EA1 + L2/EA2))") {
  const double L1 = 0.8, L2 = 1.3, EA1 = 3.0e7, EA2 = 1.2e7;
  int case_index = 0, closed = 0;
  for (double gap : {0.0, 1e-4, 1e-3, 5e-3}) {
    for (double P : {-20000.0, 0.0, 5000.0, 20000.0, 80000.0}) {
      for (int elements : {1, 3}) {
        const double angle = 0.7 * case_index++;
        const auto solved = testing::solve_text(
            two_bars(L1, EA1, L2, EA2, gap, P, elements, elements, angle), MethodKind::ActiveSet);
        REQUIRE(solved->state.status == solver::Status::Converged);
        const double expected = std::max(0.0, (P * L2 / EA2 - gap) / (L1 / EA1 + L2 / EA2));
        CHECK(solved->state.force[0] == Approx(expected).margin(1e-9 * std::abs(P)));
        CHECK(static_cast<bool>(solved->state.in_working_set[0]) == (expected > 0.0));
        // Tip of B moves by -(P - lambda) L2 / EA2 along the axis; tip of A by lambda L1/EA1.
        const auto u = solver::strut_displacements(solved->model, solved->state);
        const double tip_b = -(P - expected) * L2 / EA2;
        const double tip_a = -expected * L1 / EA1;
        CHECK(u[1][0].norm() == Approx(std::abs(tip_b)).margin(1e-12));
        CHECK(u[0].back().norm() == Approx(std::abs(tip_a)).margin(1e-12));
        closed += solved->state.in_working_set[0] != 0;
      }
    }
  }
  // Both regimes are exercised: the solver closed some contacts and left others open.
  CHECK(closed > 5);
  CHECK(closed < 35);
}

TEST_CASE("bar under a distributed load: nodal displacements are exact") {
  // Clamped at x = 0, free at x = L, load q per length: u(x) = q/(EA) (L x - x^2 / 2).
  const double L = 2.0, EA = 5.0e6, q = 300.0;
  const std::string text = testing::SceneToml("bar")
                               .strut("B", {0.0, 0.0}, {2.0, 0.0},
                                      "E = 5.0e6, area = 1.0, elements = 7, fixed = ['from']")
                               .per_length("B", {300.0, 0.0});
  for (MethodKind kind : {MethodKind::ActiveSet, MethodKind::ConjugateGradient}) {
    const auto solved = testing::solve_text(text, kind);
    REQUIRE(solved->state.status == solver::Status::Converged);
    const auto u = solver::strut_displacements(solved->model, solved->state);
    for (int i = 0; i <= 7; ++i) {
      const double x = L * i / 7;
      CHECK(u[0][i].x() == Approx(q / EA * (L * x - 0.5 * x * x)).margin(1e-14));
      CHECK(u[0][i].y() == 0.0);
    }
  }
}
