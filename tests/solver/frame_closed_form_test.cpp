// Frame model against closed forms (Hermite beam elements are nodally exact for point
// loads, two-node bars for axial force): a cantilever's tip, a post pushed onto a
// clamped-clamped beam, a symmetric two-leg pinned truss.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "tests/support/random_draws.hpp"
#include "tests/support/solve_helpers.hpp"

using namespace fetic;
using fetic::solver::MethodKind;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The displacement and rotation of node `node` of strut `strut`.
struct NodeState {
  solver::Vec2 u;
  double rotation;
};
NodeState node_state(const testing::Solved& solved, int strut, int node) {
  return {solver::strut_displacements(solved.model, solved.state)[strut][node],
          solver::strut_rotations(solved.model, solved.state)[strut][node]};
}

}  // namespace

TEST_CASE("frame: a cantilever's tip deflects P L^3 / (3 E I) and turns P L^2 / (2 E I)") {
  const double L = 1.7, E = 2.1e11, I = 3.0e-6, P = 4.0e3;
  for (const double angle : {0.0, 0.7, 2.9}) {
    const double c = std::cos(angle), s = std::sin(angle);
    // The load across the axis (+90 degrees): the tip moves that way and turns
    // counter-clockwise.
    const std::string text = testing::SceneToml("frame")
                                 .strut("C", {0.0, 0.0}, {L * c, L * s}, testing::kCantileverKeys)
                                 .load("C", "to", {-P * s, P * c});
    for (MethodKind kind : {MethodKind::ActiveSet, MethodKind::ConjugateGradient, MethodKind::Feti,
                            MethodKind::FetiC}) {
      INFO("angle " << angle << ", method " << solver::to_string(kind));
      const auto solved = testing::solve_text(text, kind);
      REQUIRE(solved->state.status == solver::Status::Converged);
      const NodeState tip = node_state(*solved, 0, 8);
      const double deflection = tip.u.dot(solver::Vec2(-s, c));
      const double along = tip.u.dot(solver::Vec2(c, s));
      CHECK(deflection == Approx(P * L * L * L / (3.0 * E * I)).epsilon(1e-8));
      CHECK(tip.rotation == Approx(P * L * L / (2.0 * E * I)).epsilon(1e-8));
      CHECK(std::abs(along) <= 1e-8 * deflection);
    }
  }
}

namespace {

// A post (clamped at its top) whose tip is `gap` above the middle of a clamped-clamped
// beam, pushed down by P at the tip.
std::string post_on_beam(double P, double gap, double angle, const char* normal) {
  const double c = std::cos(angle), s = std::sin(angle);
  auto at = [&](double x, double y) { return testing::toml_point(c * x - s * y, s * x + c * y); };
  return "model = \"frame\"\n[defaults]\nE = 2.0e11\n"
         "[[strut]]\nname = \"beam\"\nfrom = " +
         at(0.0, 0.0) + "\nto = " + at(2.4, 0.0) +
         "\narea = 3.0e-3\ninertia = 1.5e-5\nelements = 6\nsubdomains = 2\nfixed = [\"from\", "
         "\"to\"]\n"
         "[[strut]]\nname = \"post\"\nfrom = " +
         at(1.2, 1.3) + "\nto = " + at(1.2, gap) +
         "\narea = 8.0e-4\ninertia = 4.0e-7\nelements = 4\nsubdomains = 2\nfixed = [\"from\"]\n"
         "[[load]]\nstrut = \"post\"\nat = \"to\"\nforce = " +
         at(0.0, -P) +
         "\n"
         "[[contact]]\na = \"beam@3\"\nb = \"post.to\"\n" +
         normal;
}

}  // namespace

TEST_CASE(
    "frame: a post pushed onto a clamped-clamped beam: force max(0, (P/k_p - g) / (1/k_p + "
    "1/k_b))") {
  const double E = 2.0e11, L_beam = 2.4, I = 1.5e-5, A_post = 8.0e-4;
  const double k_b = 192.0 * E * I / (L_beam * L_beam * L_beam);
  int touching = 0;
  for (const double gap : {0.0, 4e-4, 1.5e-3}) {
    const double L_post = 1.3 - gap, k_p = E * A_post / L_post;
    for (const double P : {5.0e4, 2.0e5, 6.0e5}) {
      const double expected = std::max(0.0, (P / k_p - gap) / (1.0 / k_p + 1.0 / k_b));
      touching += expected > 0.0;
      // Where the nodes coincide the normal must be given (any turn of it, with the scene).
      const double angle = gap == 0.0 ? 0.4 : 0.0;
      const std::string normal =
          gap == 0.0 ? "normal = " + testing::toml_point(-std::sin(angle), std::cos(angle)) + "\n"
                     : "";
      for (MethodKind kind : {MethodKind::ActiveSet, MethodKind::FetiC}) {
        INFO("gap " << gap << ", P " << P << ", method " << solver::to_string(kind));
        const auto solved = testing::solve_text(post_on_beam(P, gap, angle, normal.c_str()), kind);
        REQUIRE(solved->state.status == solver::Status::Converged);
        CHECK(solved->state.force[0] == Approx(expected).epsilon(1e-8).margin(1e-9 * P));
        // The beam's middle moves down by force / k_b.
        const double sag =
            -node_state(*solved, 0, 3).u.dot(solver::Vec2(-std::sin(angle), std::cos(angle)));
        CHECK(sag == Approx(expected / k_b).epsilon(1e-8).margin(1e-12));
      }
    }
  }
  CHECK(touching >= 5);
}

TEST_CASE("frame: a symmetric two-leg pinned truss: apex deflection P L / (2 E A sin^2 a)") {
  const double E = 2.1e11, A = 6.0e-4, P = 7.0e4, L = 1.9;
  for (const double a : {0.5, 0.9, 1.2}) {
    const double w = L * std::cos(a), h = L * std::sin(a);
    const std::string text =
        "model = \"frame\"\n[defaults]\nE = 2.1e11\narea = 6.0e-4\ninertia = 2.0e-7\n"
        "elements = 5\nsubdomains = 2\npinned = [\"from\"]\n"
        "[[strut]]\nname = \"left\"\nfrom = " +
        testing::toml_point(-w, 0.0) + "\nto = " + testing::toml_point(0.0, h) +
        "\n"
        "[[strut]]\nname = \"right\"\nfrom = " +
        testing::toml_point(w, 0.0) + "\nto = " + testing::toml_point(0.0, h) +
        "\n"
        "[[joint]]\nends = [\"left.to\", \"right.to\"]\nkind = \"pinned\"\n"
        "[[load]]\nstrut = \"right\"\nat = 5\nforce = [0.0, " +
        std::to_string(-P) + "]\n";
    for (MethodKind kind : {MethodKind::ActiveSet, MethodKind::ConjugateGradient, MethodKind::Feti,
                            MethodKind::FetiC}) {
      INFO("angle " << a << ", method " << solver::to_string(kind));
      const auto solved = testing::solve_text(text, kind);
      REQUIRE(solved->state.status == solver::Status::Converged);
      const double expected = P * L / (2.0 * E * A * std::sin(a) * std::sin(a));
      for (int strut : {0, 1}) {
        const NodeState apex = node_state(*solved, strut, 5);
        CHECK(-apex.u.y() == Approx(expected).epsilon(1e-8));
        CHECK(std::abs(apex.u.x()) <= 1e-8 * expected);
      }
      // Pinned at both ends and loaded only there, the legs do not bend: the rotations
      // are those of a rigid turn, the same all along each leg.
      const auto rotations = solver::strut_rotations(solved->model, solved->state);
      CHECK(rotations[0][0] == Approx(rotations[0][5]).epsilon(1e-7));
      CHECK(rotations[0][2] == Approx(-rotations[1][2]).epsilon(1e-7));
    }
  }
}
