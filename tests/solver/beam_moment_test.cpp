// Bending moments of frame beams (solver::strut_moments, piece_moments) against closed
// forms. Hermite elements are nodally exact for point loads and M is linear between the
// nodes, so the recovered moment is exact everywhere: a cantilever with a tip force
// (M = -P (L - x), sagging positive) and a clamped-clamped beam with a central point load
// (M = -P L / 8 at the ends, +P L / 8 at midspan).

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <functional>

#include "solver/element_results.hpp"
#include "tests/support/random_draws.hpp"
#include "tests/support/solve_helpers.hpp"

using namespace fetic;
using fetic::solver::MethodKind;

namespace {

// Checks every element of `moments` against `expected` (a function of the distance from
// the strut's start) at both ends and at xi = 0.3, to `tolerance` of `scale`.
void check_moments(const solver::BeamMoments& moments, double h,
                   const std::function<double(double)>& expected, double scale) {
  REQUIRE_FALSE(moments.empty());
  for (int k = 0; k < static_cast<int>(moments.ends.size()); ++k) {
    const int e = moments.first_element + k;
    for (const double xi : {0.0, 0.3, 1.0}) {
      INFO("element " << e << ", xi " << xi);
      CHECK(moments.at(e, xi) == Approx(expected((e + xi) * h)).margin(1e-8 * scale));
    }
  }
}

}  // namespace

TEST_CASE("frame moments: a cantilever with a tip force P has M = -P (L - x)") {
  const double L = 1.7, P = 4.0e3;
  const int elements = 8;
  for (const double angle : {0.0, 0.7, 2.9}) {
    const double c = std::cos(angle), s = std::sin(angle);
    // The force against e2 (the axis turned +90 degrees): the strut hogs, M <= 0.
    const std::string text = testing::SceneToml("frame")
                                 .strut("C", {0.0, 0.0}, {L * c, L * s}, testing::kCantileverKeys)
                                 .load("C", "to", {P * s, -P * c});
    const auto expected = [&](double x) { return -P * (L - x); };
    for (MethodKind kind : {MethodKind::ActiveSet, MethodKind::FetiC}) {
      INFO("angle " << angle << ", method " << solver::to_string(kind));
      const auto solved = testing::solve_text(text, kind);
      REQUIRE(solved->state.status == solver::Status::Converged);
      const auto moments = solver::strut_moments(solved->model, solved->state);
      REQUIRE(moments.size() == 1);
      REQUIRE(moments[0].ends.size() == elements);
      check_moments(moments[0], L / elements, expected, P * L);
      // The named values: -P L at the clamped end, zero at the tip.
      CHECK(moments[0].at(0, 0.0) == Approx(-P * L).epsilon(1e-8));
      CHECK(std::abs(moments[0].at(elements - 1, 1.0)) <= 1e-8 * P * L);
      // Each subdomain's own moments agree at convergence.
      const auto pieces = solver::piece_moments(solved->model, solved->state);
      REQUIRE(pieces.size() == solved->state.pieces.size());
      for (const solver::BeamMoments& piece : pieces)
        check_moments(piece, L / elements, expected, P * L);
    }
  }
}

TEST_CASE(
    "frame moments: a clamped-clamped beam with a central load: -P L/8 at the ends, "
    "+P L/8 at midspan") {
  const double L = 2.4, P = 6.0e4;
  const int elements = 8;
  const std::string text =
      "model = \"frame\"\n[[strut]]\nname = \"B\"\nfrom = [0.0, 0.0]\nto = " +
      testing::toml_point(L, 0.0) +
      "\nE = 2.0e11\narea = 3.0e-3\ninertia = 1.5e-5\nelements = 8\nsubdomains = 2\n"
      "fixed = [\"from\", \"to\"]\n[[load]]\nstrut = \"B\"\nat = 4\nforce = " +
      testing::toml_point(0.0, -P) + "\n";
  // Symmetric halves, each linear from -P L / 8 to +P L / 8.
  const auto expected = [&](double x) {
    const double from_end = std::min(x, L - x);
    return -P * L / 8.0 + P * from_end / 2.0;
  };
  for (MethodKind kind : {MethodKind::ActiveSet, MethodKind::FetiC}) {
    INFO(solver::to_string(kind));
    const auto solved = testing::solve_text(text, kind);
    REQUIRE(solved->state.status == solver::Status::Converged);
    const auto moments = solver::strut_moments(solved->model, solved->state);
    REQUIRE(moments.size() == 1);
    check_moments(moments[0], L / elements, expected, P * L);
    CHECK(moments[0].at(0, 0.0) == Approx(-P * L / 8.0).epsilon(1e-8));
    CHECK(moments[0].at(elements - 1, 1.0) == Approx(-P * L / 8.0).epsilon(1e-8));
    CHECK(moments[0].at(3, 1.0) == Approx(P * L / 8.0).epsilon(1e-8));
    CHECK(moments[0].at(4, 0.0) == Approx(P * L / 8.0).epsilon(1e-8));
    for (const solver::BeamMoments& piece : solver::piece_moments(solved->model, solved->state))
      check_moments(piece, L / elements, expected, P * L);
  }
}

TEST_CASE("frame moments: struts without bending stiffness have none") {
  const auto solved =
      testing::solve(testing::bundled_scene("two_bars.toml"), MethodKind::ActiveSet);
  for (const solver::BeamMoments& m : solver::strut_moments(solved->model, solved->state))
    CHECK(m.empty());
  for (const solver::BeamMoments& m : solver::piece_moments(solved->model, solved->state))
    CHECK(m.empty());
}
