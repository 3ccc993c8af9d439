// The lean subdomain factors: a compacted CHOLMOD factor solves as CHOLMOD's did, and the
// Dirichlet preconditioner through the interior factors FetiSystem makes beside K_j's
// equals the one that factorizes K_ii itself.

#include <catch2/catch.hpp>

#include <random>

#include "scenes/generate_scene.hpp"
#include "solver/cholmod_factor.hpp"
#include "solver/feti_preconditioner.hpp"
#include "solver/feti_system.hpp"
#include "solver/model.hpp"
#include "tests/support/solve_helpers.hpp"

using namespace fetic;

namespace {

// The largest node displacement of `a` and the largest difference between the two
// solutions' node displacements.
std::pair<double, double> displacement_gap(const testing::Solved& a, const testing::Solved& b) {
  const auto ua = solver::strut_displacements(a.model, a.state);
  const auto ub = solver::strut_displacements(b.model, b.state);
  double largest = 0.0, difference = 0.0;
  for (size_t s = 0; s < ua.size(); ++s)
    for (size_t k = 0; k < ua[s].size(); ++k) {
      largest = std::max(largest, ua[s][k].norm());
      difference = std::max(difference, (ua[s][k] - ub[s][k]).norm());
    }
  return {largest, difference};
}

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
  return scenes::generate_scene({.model = scenes::ModelKind::Plane,
                                 .pairs = 2,
                                 .elements = 24,
                                 .elements_across = 8,
                                 .subdomains = 4,
                                 .subdomains_across = 2});
}

// The scenes the precision tests solve: a generated plane and six bundled scenes.
std::vector<std::pair<std::string, scenes::Scene>> named_scenes() {
  std::vector<std::pair<std::string, scenes::Scene>> named = {{"generated plane", small_plane()}};
  for (const char* name : {"thesis.toml", "plane_pair.toml", "two_bars.toml", "chain.toml",
                           "cantilevers.toml", "frame_scaffold.toml"})
    named.emplace_back(name, testing::bundled_scene(name));
  return named;
}

// Both option sets converge, to displacements within `bound` of the largest, in about
// the same iterations.
void check_same_answer(const std::string& name, const scenes::Scene& scene, solver::MethodKind kind,
                       const solver::SolveOptions& first, const solver::SolveOptions& second,
                       double bound) {
  CAPTURE(name, solver::to_string(kind));
  const auto a = testing::solve(scene, kind, 1.0, first);
  const auto b = testing::solve(scene, kind, 1.0, second);
  REQUIRE(a->method->status() == solver::Status::Converged);
  REQUIRE(b->method->status() == solver::Status::Converged);
  const auto [largest, difference] = displacement_gap(*a, *b);
  const int it_a = a->method->iteration(), it_b = b->method->iteration();
  CAPTURE(largest, difference, it_a, it_b);
  CHECK(largest > 0.0);
  CHECK(difference <= bound * largest);
  CHECK(std::abs(it_a - it_b) <= 1 + it_a / 10);
  WARN(name << " (" << solver::to_string(kind) << "): difference " << difference / largest
            << ", iterations " << it_a << " / " << it_b);
}

}  // namespace

TEST_CASE("A compacted factor solves as CHOLMOD's factor did, in fewer bytes") {
  // 12x9: CHOLMOD chooses a simplicial factor; 40x30: a supernodal one.
  for (const auto& [nx, ny] : {std::pair{12, 9}, std::pair{40, 30}}) {
    CAPTURE(nx, ny);
    const solver::SparseMatrix A = grid_matrix(nx, ny);
    const int n = static_cast<int>(A.rows());
    solver::CholmodFactor factor;
    REQUIRE(factor.factorize(A) == solver::CholmodFactor::Result::Ok);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    Eigen::MatrixXd b(n, 2);
    for (int k = 0; k < 2 * n; ++k)
      b.data()[k] = value(random);
    Eigen::MatrixXd before(n, 2), after(n, 2);
    factor.solve(b.data(), before.data(), 2);
    const double rcond = factor.rcond();
    const std::size_t bytes = factor.memory_in_use();
    REQUIRE(factor.compact());
    REQUIRE(factor.compacted());
    factor.solve(b.data(), after.data(), 2);
    CHECK((after - before).norm() <= 1e-13 * before.norm());
    CHECK((A * after - b).norm() <= 1e-12 * b.norm());  // against A itself, not CHOLMOD
    CHECK(factor.rcond() == Approx(rcond).epsilon(1e-12));
    CHECK(factor.memory_in_use() < bytes);
    CHECK_THROWS_AS(factor.refactorize(A), std::logic_error);
  }
}

TEST_CASE("A compacted simplicial factor leaves out the entries that cancelled to zero") {
  // ones(3) + diag(0, 1, 1): L = [1 0 0; 1 1 0; 1 0 1], its entry (2, 1) an exact zero
  // that CHOLMOD keeps (A's pattern has it); the compact copy, read from CHOLMOD's arrays
  // in place, drops it and still solves A. (factorize(A, true)'s own supernodal factor
  // keeps such zeros: tests/solver/supernodal_factorization_test.cpp.)
  Eigen::MatrixXd dense = Eigen::MatrixXd::Ones(3, 3);
  dense(1, 1) = dense(2, 2) = 2.0;
  const solver::SparseMatrix A = dense.sparseView();
  solver::CholmodFactor factor;
  REQUIRE(factor.factorize(A) == solver::CholmodFactor::Result::Ok);
  REQUIRE(factor.factor_nonzeros() == 6);
  REQUIRE(factor.compact());
  CHECK(factor.factor_nonzeros() == 5);
  const Eigen::Vector3d b(1.0, -2.0, 0.5);
  Eigen::Vector3d x;
  factor.solve(b.data(), x.data());
  CHECK((dense * x - b).norm() <= 1e-14 * b.norm());
}

TEST_CASE("An indefinite matrix is not positive definite, from CHOLMOD's LDL' as from its LL'") {
  // The grid matrix with one diagonal entry negative: e_k' A e_k < 0, so A is indefinite
  // whatever its other pivots. 12x9: CHOLMOD's default is a simplicial LDL', which
  // factorizes through negative pivots; 40x30: a supernodal LL', which stops at one.
  for (const auto& [nx, ny] : {std::pair{12, 9}, std::pair{40, 30}}) {
    CAPTURE(nx, ny);
    const solver::SparseMatrix A = grid_matrix(nx, ny);
    solver::SparseMatrix indefinite = A;
    indefinite.coeffRef(nx * ny / 2, nx * ny / 2) = -4.0;
    const int n = static_cast<int>(A.rows());
    solver::CholmodFactor factor;
    CHECK(factor.factorize(indefinite) == solver::CholmodFactor::Result::NotPositiveDefinite);
    CHECK(factor.failed_column() >= 0);
    CHECK(factor.failed_column() < n);
    // The same pattern factorized anew (the kept analysis), first definite, then not.
    REQUIRE(factor.factorize(A) == solver::CholmodFactor::Result::Ok);
    CHECK(factor.failed_column() == -1);
    CHECK(factor.refactorize(indefinite) == solver::CholmodFactor::Result::NotPositiveDefinite);
    CHECK(factor.failed_column() >= 0);
  }
}

TEST_CASE("A factor kept in single precision solves A to its rounding, in 40% fewer bytes") {
  const solver::SparseMatrix A = grid_matrix(40, 30);  // supernodal, condition about 800
  const int n = static_cast<int>(A.rows());
  solver::CholmodFactor full, single;
  REQUIRE(full.factorize(A) == solver::CholmodFactor::Result::Ok);
  REQUIRE(single.factorize(A) == solver::CholmodFactor::Result::Ok);
  REQUIRE(full.compact());
  REQUIRE(single.compact(true));
  std::mt19937 random(11);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd b(n), x_full(n), x_single(n);
  for (int k = 0; k < n; ++k)
    b(k) = value(random);
  full.solve(b.data(), x_full.data());
  single.solve(b.data(), x_single.data());
  // Exact for A + E, |E| ~ 6e-8 |L||L'|: the residual is that size, not double's 1e-16.
  const double residual = (A * x_single - b).norm() / b.norm();
  CHECK(residual <= 1e-6);
  CHECK(residual > 1e-12);  // the entries really are floats
  CHECK((x_single - x_full).norm() <= 1e-5 * x_full.norm());
  CHECK(static_cast<double>(single.memory_in_use()) <= 0.7 * full.memory_in_use());
  CHECK(single.factor_nonzeros() == full.factor_nonzeros());
}

TEST_CASE("The Dirichlet preconditioner through K_j's factor equals it with its own K_ii") {
  const scenes::Scene scene = small_plane();
  const solver::Model model = solver::build_model(scene);
  // K_ii's factor in double here, as the preconditioner's own is: the same operator. The
  // two-factor path (not one factor with the boundary last: tests/solver/boundary_last_test.cpp).
  const solver::FetiSystem shared(model, solver::Communicator::self(), true, 0, false, false, false,
                                  false);
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
  const auto [largest, difference] = displacement_gap(*a, *b);
  CHECK(largest > 0.0);
  CHECK(difference <= 1e-6 * largest);
}

TEST_CASE("MPRGP with single precision factors reaches the double factors' solution") {
  solver::SolveOptions double_factors, single_factors;
  single_factors.single_factors = true;
  for (const auto& [name, scene] : named_scenes())
    check_same_answer(name, scene, solver::MethodKind::Mprgp, double_factors, single_factors, 1e-6);
}

TEST_CASE("Single precision interior factors move the preconditioner, not the answer") {
  // K_ii's factors serve only the Dirichlet preconditioner: in floats they hold 40% fewer
  // bytes, and the methods converge to the answer of the double ones - to far closer than
  // single precision K_j factors come (1e-7 of the largest displacement on these scenes),
  // since the problem solved is the same.
  const solver::Model plane = solver::build_model(small_plane());
  // (The two-factor path: one factor with the boundary last has no K_ii factor.)
  const solver::FetiSystem doubles(plane, solver::Communicator::self(), true, 0, false, false,
                                   false, false);
  const solver::FetiSystem singles(plane, solver::Communicator::self(), true, 0, false, true, false,
                                   false);
  const double double_bytes = doubles.memory().preconditioner_factor;
  CHECK(double_bytes > 0.0);
  CHECK(singles.memory().preconditioner_factor <= 0.7 * double_bytes);
  CHECK(singles.memory().factor == doubles.memory().factor);

  solver::SolveOptions double_interior, single_interior;
  double_interior.single_interior_factors = false;
  double_interior.boundary_last_factor = single_interior.boundary_last_factor = false;
  for (const auto kind : {solver::MethodKind::Mprgp, solver::MethodKind::FetiC})
    for (const auto& [name, scene] : named_scenes())
      check_same_answer(name, scene, kind, double_interior, single_interior, 1e-8);
}
