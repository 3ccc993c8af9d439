// Element and assembly checks against exact strain energies and rigid-body motions.

#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>

#include "scenes/load_scene.hpp"
#include "solver/model.hpp"
#include "solver/rigid_modes.hpp"
#include "solver/stiffness.hpp"
#include "tests/support/scene_toml.hpp"

using namespace fetic::solver;
using fetic::testing::SceneToml;

namespace {

Eigen::Matrix<double, 4, 2> unit_square() {
  Eigen::Matrix<double, 4, 2> x;
  x << 0, 0, 1, 0, 1, 1, 0, 1;
  return x;
}

// Nodal DOFs of the linear field u(x, y) = (a x + b y, c x + d y) on the corners.
Eigen::Matrix<double, 8, 1> linear_field(const Eigen::Matrix<double, 4, 2>& x, double a, double b,
                                         double c, double d) {
  Eigen::Matrix<double, 8, 1> u;
  for (int n = 0; n < 4; ++n) {
    u(2 * n) = a * x(n, 0) + b * x(n, 1);
    u(2 * n + 1) = c * x(n, 0) + d * x(n, 1);
  }
  return u;
}

// The mesh of a one-strut plane scene.
StrutMesh plane_strut(const fetic::testing::TomlPoint& from, const fetic::testing::TomlPoint& to,
                      const std::string& keys) {
  const std::string text = SceneToml("plane").strut("P", from, to, keys);
  return build_strut_mesh(fetic::scenes::parse_scene(text, "plane.toml"), 0);
}

}  // namespace

TEST_CASE("bilinear quadrilateral reproduces exact strain energies of linear fields") {
  const double E = 2.0e11, nu = 0.3, t = 0.01;
  const auto x = unit_square();
  const auto K = quad_stiffness(x, E, nu, t);
  const double c = E / (1 - nu * nu);
  // Uniaxial strain exx = 1: energy 1/2 * c * area * t.
  auto u = linear_field(x, 1, 0, 0, 0);
  CHECK(0.5 * u.dot(K * u) == Approx(0.5 * c * t).epsilon(1e-12));
  // Pure shear gamma_xy = 1: energy 1/2 * G * area * t with G = E / (2 (1 + nu)).
  u = linear_field(x, 0, 1, 0, 0);
  CHECK(0.5 * u.dot(K * u) == Approx(0.5 * E / (2 * (1 + nu)) * t).epsilon(1e-12));
  // Biaxial exx = eyy = 1: energy 1/2 * c * (2 + 2 nu) * t.
  u = linear_field(x, 1, 0, 0, 1);
  CHECK(0.5 * u.dot(K * u) == Approx(0.5 * c * (2 + 2 * nu) * t).epsilon(1e-12));
}

TEST_CASE("bilinear quadrilateral: three rigid-body modes span its kernel, rotated or not") {
  for (double angle : {0.0, 0.3, 1.2, 2.9}) {
    Eigen::Matrix2d rotation;
    rotation << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    Eigen::Matrix<double, 4, 2> x;
    x << 0, 0, 2, 0, 2, 0.5, 0, 0.5;  // a 2 x 0.5 rectangle
    x = (x * rotation.transpose()).eval();
    const auto K = quad_stiffness(x, 1e9, 0.25, 1.0);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 8, 8>> eigen(K);
    const auto& values = eigen.eigenvalues();
    CHECK(std::abs(values(2)) < 1e-9 * values(7));
    CHECK(values(3) > 1e-3 * values(7));
    for (int m = 0; m < 3; ++m) {
      // translation x, translation y, rotation about the origin
      Eigen::Matrix<double, 8, 1> r;
      for (int n = 0; n < 4; ++n) {
        r(2 * n) = m == 0 ? 1 : (m == 1 ? 0 : -x(n, 1));
        r(2 * n + 1) = m == 0 ? 0 : (m == 1 ? 1 : x(n, 0));
      }
      CHECK((K * r).norm() < 1e-9 * K.norm() * r.norm());
    }
  }
}

TEST_CASE("assembled plane strut: rigid_body_modes lie in the kernel of every subdomain box") {
  const StrutMesh mesh = plane_strut(
      {0.2, 0.1}, {1.4, 0.9},
      "E = 7e10, elements = 6, subdomains = 2, height = 0.1, thickness = 0.02, nu = 0.33, "
      "elements_across = 3, fixed = ['from']");
  for (NodeBox box : {whole_strut(mesh), NodeBox{0, 3, 0, 3}, NodeBox{3, 6, 1, 2}}) {
    const SparseMatrix K = assemble_stiffness(mesh, box);
    const Eigen::MatrixXd R = rigid_body_modes(mesh, box);
    CHECK(R.cols() == 3);
    CHECK((K * R).norm() < 1e-10 * Eigen::MatrixXd(K).norm() * R.norm());
  }
}

TEST_CASE("assembled plane box equals the sum of its element blocks bit for bit") {
  // The assembly writes compressed columns directly; the truth here is the definition:
  // every element's 8x8 block added at its nodes' DOFs (by triplets, summed in element
  // order). Boxes one element across (two nodes: the neighbour offsets must not alias),
  // offset from the strut's origin, the whole strut, and one without elements.
  const StrutMesh mesh = plane_strut(
      {0.0, 0.0}, {2.0, 0.3},
      "E = 7e10, elements = 7, subdomains = 1, height = 0.2, thickness = 0.02, nu = 0.31, "
      "elements_across = 4, fixed = ['from']");
  Eigen::Matrix<double, 4, 2> corners;
  for (int a = 0; a < 4; ++a) {
    const int i = a == 1 || a == 2 ? 1 : 0, k = a >= 2 ? 1 : 0;
    corners.row(a) = mesh.nodes[mesh.node(i, k)].transpose();
  }
  const auto Ke = quad_stiffness(corners, mesh.E, mesh.nu, mesh.thickness);
  for (NodeBox box : {whole_strut(mesh), NodeBox{2, 3, 1, 2}, NodeBox{0, 7, 3, 4},
                      NodeBox{5, 6, 0, 4}, NodeBox{1, 4, 2, 4}, NodeBox{3, 3, 0, 4}}) {
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = box.i0; i < box.i1; ++i)
      for (int k = box.k0; k < box.k1; ++k) {
        const int nodes[4] = {box.local(i, k), box.local(i + 1, k), box.local(i + 1, k + 1),
                              box.local(i, k + 1)};
        for (int a = 0; a < 8; ++a)
          for (int b = 0; b < 8; ++b)
            entries.emplace_back(2 * nodes[a / 2] + a % 2, 2 * nodes[b / 2] + b % 2, Ke(a, b));
      }
    SparseMatrix expected(2 * box.node_count(), 2 * box.node_count());
    expected.setFromTriplets(entries.begin(), entries.end());
    const SparseMatrix K = assemble_stiffness(mesh, box);
    REQUIRE(K.isCompressed());
    REQUIRE(K.rows() == expected.rows());
    REQUIRE(K.nonZeros() == expected.nonZeros());
    for (int col = 0; col <= K.cols(); ++col)
      REQUIRE(K.outerIndexPtr()[col] == expected.outerIndexPtr()[col]);
    for (Eigen::Index e = 0; e < K.nonZeros(); ++e) {
      REQUIRE(K.innerIndexPtr()[e] == expected.innerIndexPtr()[e]);
      REQUIRE(K.valuePtr()[e] == expected.valuePtr()[e]);
    }
  }
}

TEST_CASE("bar loads: end forces and distributed loads give consistent nodal forces") {
  const std::string text = SceneToml("bar")
                               .strut("B", {0.0, 0.0}, {0.0, 2.0},
                                      "E = 1e9, area = 1e-4, elements = 4, fixed = ['from']")
                               .load("B", "to", {5.0, 30.0})
                               .per_length("B", {100.0, -8.0});
  const auto scene = fetic::scenes::parse_scene(text, "bar.toml");
  const Model model = build_model(scene);
  const Eigen::VectorXd& f = model.loads[0];
  REQUIRE(f.size() == 5);
  // Axis is +y: only the y components count; h = 0.5, so h/2 * (-8) = -2 per element end.
  CHECK(f(0) == Approx(-2.0));
  CHECK(f(1) == Approx(-4.0));
  CHECK(f(3) == Approx(-4.0));
  CHECK(f(4) == Approx(30.0 - 2.0));
  CHECK(f.sum() == Approx(30.0 - 8.0 * 2.0));
}

TEST_CASE("plane loads: end traction and body force follow the contract's shares") {
  const std::string text = SceneToml("plane")
                               .strut("P", {0.0, 0.0}, {3.0, 0.0},
                                      "E = 1e9, elements = 3, height = 0.4, thickness = 0.1, "
                                      "nu = 0.3, elements_across = 2, fixed = ['from']")
                               .load("P", "to", {12.0, -4.0})
                               .per_length("P", {0.0, -6.0});
  const auto scene = fetic::scenes::parse_scene(text, "plane.toml");
  const Model model = build_model(scene);
  const StrutMesh& mesh = model.struts[0];
  const Eigen::VectorXd& f = model.loads[0];
  // End face at i = 3: nodes k = 0, 1, 2 get 1/4, 1/2, 1/4 of the end force.
  CHECK(f(2 * mesh.node(3, 0)) == Approx(3.0));
  CHECK(f(2 * mesh.node(3, 1)) == Approx(6.0));
  CHECK(f(2 * mesh.node(3, 2)) == Approx(3.0));
  // Body force: total -6 * 3 = -18 in y, each of 6 elements gives -3 / 4 to each corner.
  // An interior node (1, 1) touches 4 elements: -3; a corner (0, 0) touches 1: -0.75.
  CHECK(f(2 * mesh.node(1, 1) + 1) == Approx(-3.0));
  CHECK(f(2 * mesh.node(0, 0) + 1) == Approx(-0.75));
  CHECK(f(2 * mesh.node(3, 1) + 1) == Approx(-2.0 - 1.5));
  double fy = 0.0;
  for (int n = 0; n < mesh.node_count(); ++n)
    fy += f(2 * n + 1);
  CHECK(fy == Approx(-4.0 - 18.0));
}
