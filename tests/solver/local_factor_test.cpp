// One factor per subdomain for K^+ and the Dirichlet preconditioner: the leading block of
// a constrained-ordered CHOLMOD factor solves with the interior block exactly, and the
// preconditioner through it is the preconditioner with its own interior factors.

#include <catch2/catch.hpp>

#include <random>

#include <Eigen/SparseCholesky>

#include "scenes/generate_scene.hpp"
#include "solver/cholmod_factor.hpp"
#include "solver/feti_preconditioner.hpp"
#include "solver/feti_system.hpp"
#include "solver/model.hpp"
#include "tests/support/solve_helpers.hpp"

using namespace fetic;

namespace {

// The 5-point Laplacian of an nx x ny grid plus a small shift: sparse, SPD, 2D fill.
solver::SparseMatrix grid_matrix(int nx, int ny) {
  std::vector<Eigen::Triplet<double>> entries;
  const auto at = [&](int i, int j) { return i * ny + j; };
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      entries.emplace_back(at(i, j), at(i, j), 4.01);
      if (i + 1 < nx) {
        entries.emplace_back(at(i + 1, j), at(i, j), -1.0);
        entries.emplace_back(at(i, j), at(i + 1, j), -1.0);
      }
      if (j + 1 < ny) {
        entries.emplace_back(at(i, j + 1), at(i, j), -1.0);
        entries.emplace_back(at(i, j), at(i, j + 1), -1.0);
      }
    }
  solver::SparseMatrix A(nx * ny, nx * ny);
  A.setFromTriplets(entries.begin(), entries.end());
  A.makeCompressed();
  return A;
}

scenes::Scene small_plane() {
  scenes::GenerateOptions o;
  o.model = scenes::ModelKind::Plane;
  o.pairs = 2;
  o.elements = 24;
  o.elements_across = 8;
  o.subdomains = 4;
  o.subdomains_across = 2;
  return scenes::generate_scene(o);
}

}  // namespace

TEST_CASE("A factor's leading block solves with the leading rows' submatrix") {
  const solver::SparseMatrix A = grid_matrix(12, 9);
  const int n = static_cast<int>(A.rows());
  // The grid's outer ring last, as a subdomain's boundary is.
  std::vector<char> leading(n, 1);
  std::vector<int> inner;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 9; ++j)
      if (i == 0 || j == 0 || i == 11 || j == 8)
        leading[i * 9 + j] = 0;
      else
        inner.push_back(i * 9 + j);
  solver::CholmodFactor factor;
  REQUIRE(factor.factorize(A, leading) == solver::CholmodFactor::Result::Ok);
  REQUIRE(factor.has_leading());

  // Independent truth: Eigen's own Cholesky of the submatrix.
  const int m = static_cast<int>(inner.size());
  solver::SparseMatrix A_ll(m, m);
  std::vector<Eigen::Triplet<double>> entries;
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b)
      if (A.coeff(inner[a], inner[b]) != 0.0)
        entries.emplace_back(a, b, A.coeff(inner[a], inner[b]));
  A_ll.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLLT<solver::SparseMatrix> reference(A_ll);
  REQUIRE(reference.info() == Eigen::Success);

  std::mt19937 random(3);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd b(n), x(n), b_l(m);
  for (int k = 0; k < n; ++k)
    b(k) = value(random);  // entries off the leading rows must be ignored
  for (int a = 0; a < m; ++a)
    b_l(a) = b(inner[a]);
  factor.solve_leading(b.data(), x.data());
  const Eigen::VectorXd expected = reference.solve(b_l);
  for (int a = 0; a < m; ++a)
    CHECK(x(inner[a]) == Approx(expected(a)).margin(1e-12));
  for (int k = 0; k < n; ++k)
    if (!leading[k]) CHECK(x(k) == 0.0);
  // The whole factor still solves with A.
  Eigen::VectorXd y(n);
  factor.solve(b.data(), y.data());
  CHECK((A * y - b).norm() <= 1e-12 * b.norm());
}

TEST_CASE("A compacted factor solves as CHOLMOD's factor did, in fewer bytes") {
  // 12x9: CHOLMOD chooses a simplicial factor; 40x30: a supernodal one.
  for (const auto& [nx, ny] : {std::pair{12, 9}, std::pair{40, 30}}) {
    CAPTURE(nx, ny);
    const solver::SparseMatrix A = grid_matrix(nx, ny);
    const int n = static_cast<int>(A.rows());
    std::vector<char> leading(n, 1);
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j)
        if (i == 0 || j == 0 || i == nx - 1 || j == ny - 1) leading[i * ny + j] = 0;
    solver::CholmodFactor factor;
    REQUIRE(factor.factorize(A, leading) == solver::CholmodFactor::Result::Ok);
    REQUIRE(factor.has_leading());
    std::mt19937 random(7);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    Eigen::MatrixXd b(n, 2);
    for (int k = 0; k < 2 * n; ++k)
      b.data()[k] = value(random);
    Eigen::MatrixXd before(n, 2), after(n, 2);
    Eigen::VectorXd leading_before(n), leading_after(n);
    factor.solve(b.data(), before.data(), 2);
    factor.solve_leading(b.data(), leading_before.data());
    const double rcond = factor.rcond();
    const std::size_t bytes = factor.memory_in_use();
    REQUIRE(factor.compact());
    REQUIRE(factor.compacted());
    factor.solve(b.data(), after.data(), 2);
    factor.solve_leading(b.data(), leading_after.data());
    CHECK((after - before).norm() <= 1e-13 * before.norm());
    CHECK((leading_after - leading_before).norm() <= 1e-13 * leading_before.norm());
    CHECK((A * after - b).norm() <= 1e-12 * b.norm());  // against A itself, not CHOLMOD
    CHECK(factor.rcond() == Approx(rcond).epsilon(1e-12));
    CHECK(factor.memory_in_use() < bytes);
    CHECK_THROWS_AS(factor.refactorize(A), std::logic_error);
  }
}

TEST_CASE("The Dirichlet preconditioner through K_j's factor equals it with its own K_ii") {
  const scenes::Scene scene = small_plane();
  const solver::Model model = solver::build_model(scene);
  const solver::FetiSystem shared(model, solver::Communicator::self(), true);
  const solver::FetiSystem separate(model, solver::Communicator::self(), false);
  for (const solver::SubdomainOperator& op : shared.subdomains())
    REQUIRE(op.K_plus.has_interior_solve());
  for (const solver::SubdomainOperator& op : separate.subdomains())
    REQUIRE_FALSE(op.K_plus.has_interior_solve());
  const solver::FetiPreconditioner one(shared, solver::Preconditioner::Dirichlet, true);
  const solver::FetiPreconditioner two(separate, solver::Preconditioner::Dirichlet, true);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd w(shared.rows()), z1, z2;
  for (int r = 0; r < w.size(); ++r)
    w(r) = value(random);
  one.apply(w, nullptr, z1);
  two.apply(w, nullptr, z2);
  REQUIRE(z1.size() == z2.size());
  CHECK((z1 - z2).norm() <= 1e-10 * z2.norm());
  CHECK(z2.norm() > 0.0);
}

TEST_CASE("MPRGP with one factor per subdomain reaches the solution of two factors") {
  const scenes::Scene scene = small_plane();
  solver::SolveOptions one, two;
  two.shared_interior_factor = false;
  const auto a = testing::solve(scene, solver::MethodKind::Mprgp, 1.0, one);
  const auto b = testing::solve(scene, solver::MethodKind::Mprgp, 1.0, two);
  REQUIRE(a->method->status() == solver::Status::Converged);
  REQUIRE(b->method->status() == solver::Status::Converged);
  const auto ua = solver::strut_displacements(a->model, a->state);
  const auto ub = solver::strut_displacements(b->model, b->state);
  double largest = 0.0, difference = 0.0;
  for (size_t s = 0; s < ua.size(); ++s)
    for (size_t k = 0; k < ua[s].size(); ++k) {
      largest = std::max(largest, ua[s][k].norm());
      difference = std::max(difference, (ua[s][k] - ub[s][k]).norm());
    }
  CHECK(largest > 0.0);
  CHECK(difference <= 1e-6 * largest);
}
