// The supernodal factorization into CompactFactor's layout (solver/supernodal_factorization
// .hpp, CholmodFactor::factorize(A, true)) against CHOLMOD's own factor of the same
// matrix: random sparse SPD matrices of several shapes (order 1, diagonal, dense,
// disconnected blocks, 2D fill up to 3,000 rows, a plane-stress subdomain's stiffness),
// in double and single precision, and the column a non-positive-definite matrix fails at.

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "scenes/generate_scene.hpp"
#include "solver/cholmod_factor.hpp"
#include "solver/elimination_tree.hpp"
#include "solver/feti_system.hpp"
#include "solver/model.hpp"
#include "solver/supernodal_factorization.hpp"

#include <cholmod.h>

using namespace fetic;

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

solver::SparseMatrix from_triplets(int n, const Triplets& entries) {
  solver::SparseMatrix A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  A.makeCompressed();
  return A;
}

// M M' + n I for a random sparse M (unit diagonal, `density` of its strict lower triangle),
// its order `n` split into `blocks` independent diagonal blocks.
solver::SparseMatrix random_spd(int n, double density, int blocks, std::mt19937& random) {
  std::uniform_real_distribution<double> value(-1.0, 1.0), coin(0.0, 1.0);
  solver::SparseMatrix M(n, n);
  Triplets entries;
  const int size = (n + blocks - 1) / blocks;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 1.0);
    for (int j = i / size * size; j < i; ++j)
      if (coin(random) < density) entries.emplace_back(i, j, value(random));
  }
  M.setFromTriplets(entries.begin(), entries.end());
  solver::SparseMatrix I(n, n);
  I.setIdentity();
  solver::SparseMatrix A = M * M.transpose() + static_cast<double>(n) * I;
  A.makeCompressed();
  return A;
}

// The 5-point Laplacian of an nx x ny grid, shifted: SPD with 2D fill.
solver::SparseMatrix grid_matrix(int nx, int ny, double diagonal = 4.01) {
  Triplets entries;
  constexpr int kSteps[5][2] = {{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  for (int node = 0; node < nx * ny; ++node)
    for (const auto& [di, dj] : kSteps) {
      const int i = node / ny + di, j = node % ny + dj;
      if (i < 0 || i >= nx || j < 0 || j >= ny) continue;
      entries.emplace_back(i * ny + j, node, di == 0 && dj == 0 ? diagonal : -1.0);
    }
  return from_triplets(nx * ny, entries);
}

// A floating subdomain's stiffness of a generated plane scene, made regular by a small
// shift: the pattern (two DOFs a node, bilinear elements) the factorization is for.
solver::SparseMatrix plane_subdomain() {
  const scenes::Scene scene = scenes::generate_scene({.model = scenes::ModelKind::Plane,
                                                      .pairs = 1,
                                                      .elements = 24,
                                                      .elements_across = 16,
                                                      .subdomains = 2,
                                                      .subdomains_across = 1});
  const solver::Model model = solver::build_model(scene);
  const solver::FetiSystem system(model, solver::Communicator::self(), false);
  solver::SparseMatrix K = system.subdomains().front().K;
  double largest = 0.0;
  for (int j = 0; j < K.cols(); ++j)
    largest = std::max(largest, K.coeff(j, j));
  for (int j = 0; j < K.cols(); ++j)
    K.coeffRef(j, j) += 1e-3 * largest;
  K.makeCompressed();
  return K;
}

// CHOLMOD's own simplicial LL' of A: the row of A whose column of P A P' it stopped at
// (Perm[minor]), -1 when A is definite.
int cholmod_ll_failed_row(const solver::SparseMatrix& A) {
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  common.supernodal = CHOLMOD_SIMPLICIAL;
  common.final_ll = 1;
  const auto n = static_cast<size_t>(A.rows()), nonzeros = static_cast<size_t>(A.nonZeros());
  cholmod_sparse* B = cholmod_allocate_sparse(n, n, nonzeros, 1, 1, -1, CHOLMOD_REAL, &common);
  std::copy_n(A.outerIndexPtr(), n + 1, static_cast<int*>(B->p));
  std::copy_n(A.innerIndexPtr(), nonzeros, static_cast<int*>(B->i));
  std::copy_n(A.valuePtr(), nonzeros, static_cast<double*>(B->x));
  cholmod_factor* L = cholmod_analyze(B, &common);
  cholmod_factorize(B, L, &common);
  const auto minor = static_cast<std::size_t>(L->minor);
  const int row = minor < n ? static_cast<const int*>(L->Perm)[minor] : -1;
  cholmod_free_factor(&L, &common);
  cholmod_free_sparse(&B, &common);
  cholmod_finish(&common);
  return row;
}

Eigen::MatrixXd random_columns(int n, int columns, std::mt19937& random) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::MatrixXd b(n, columns);
  for (int k = 0; k < n * columns; ++k)
    b.data()[k] = value(random);
  return b;
}

// Factorized both ways, both solve A; the supernodal factor to CHOLMOD's rounding (double)
// or to float's (single).
void check_against_cholmod(const std::string& name, const solver::SparseMatrix& A, bool single) {
  CAPTURE(name, single);
  const int n = static_cast<int>(A.rows());
  std::mt19937 random(3);
  const Eigen::MatrixXd b = random_columns(n, 3, random);
  solver::CholmodFactor reference, factor;
  REQUIRE(reference.factorize(A) == solver::CholmodFactor::Result::Ok);
  REQUIRE(factor.factorize(A, /*to_compact=*/true) == solver::CholmodFactor::Result::Ok);
  CHECK(factor.rcond() == Approx(reference.rcond()).epsilon(1e-10));
  REQUIRE(factor.compact(single));
  REQUIRE(factor.compacted());
  Eigen::MatrixXd x_reference(n, 3), x(n, 3);
  reference.solve(b.data(), x_reference.data(), 3);
  factor.solve(b.data(), x.data(), 3);
  const double residual = (A * x - b).norm() / b.norm();
  const double difference = (x - x_reference).norm() / x_reference.norm();
  CAPTURE(residual, difference, n);
  CHECK(residual <= (single ? 1e-6 : 1e-13));
  CHECK(difference <= (single ? 1e-5 : 1e-12));
  // The entries below the diagonal really are floats (a diagonal matrix has none).
  if (single && factor.factor_nonzeros() > static_cast<std::size_t>(n)) CHECK(residual > 1e-12);
  // At most CompactFactor::kRelaxedZeros zeros in each supernode (and CHOLMOD's simplicial
  // factor stores its whole pattern): about as many entries as CHOLMOD's.
  CHECK(static_cast<double>(factor.factor_nonzeros()) <= 1.15 * reference.factor_nonzeros());
}

// The shapes the tests factorize: order 1, diagonal, dense, sparse, disconnected blocks, 2D
// fill up to 3,000 rows, a plane-stress subdomain's stiffness.
std::vector<std::pair<std::string, solver::SparseMatrix>> test_matrices(std::mt19937& random) {
  return {{"order 1", random_spd(1, 0.0, 1, random)},
          {"diagonal", random_spd(50, 0.0, 1, random)},
          {"dense", random_spd(60, 1.0, 1, random)},
          {"sparse", random_spd(300, 0.02, 1, random)},
          {"disconnected blocks", random_spd(240, 0.1, 6, random)},
          {"grid 12x9", grid_matrix(12, 9)},
          {"grid 60x50", grid_matrix(60, 50)},
          {"plane-stress subdomain", plane_subdomain()}};
}

}  // namespace

TEST_CASE("The supernodal factorization solves as CHOLMOD's factor of random SPD matrices") {
  std::mt19937 random(17);
  for (const auto& [name, A] : test_matrices(random))
    for (const bool single : {false, true})
      check_against_cholmod(name, A, single);
}

TEST_CASE("The supernodal factorization fails at the row CHOLMOD's LL' fails at") {
  // A negative diagonal entry: the pivot of its column is the first not positive, whatever
  // the order (the pivots before it do not see it).
  for (const int dof : {0, 37, 59}) {
    CAPTURE(dof);
    solver::SparseMatrix A = grid_matrix(10, 6);
    A.coeffRef(dof, dof) = -1.0;
    REQUIRE(cholmod_ll_failed_row(A) == dof);
    solver::SupernodalFactorization direct;
    const int column = direct.factorize(A);
    REQUIRE(column >= 0);
    CHECK(direct.permutation()[static_cast<std::size_t>(column)] == dof);
    solver::CholmodFactor factor;
    REQUIRE(factor.factorize(A, true) == solver::CholmodFactor::Result::NotPositiveDefinite);
    CHECK(factor.failed_column() == column);
    CHECK_THROWS(factor.solve(nullptr, nullptr));  // no factor to solve with
  }
}

TEST_CASE("The supernodal factorization fails where the leading block stops being definite") {
  // A grid Laplacian shifted below its smallest eigenvalue (indefinite through the fill,
  // at no one entry), under AMD's ordering and random ones: P A P''s leading k x k block
  // is positive definite and its leading (k + 1) x (k + 1) one is not (Eigen's dense
  // LLT), k the column reported.
  std::mt19937 random(23);
  const solver::SparseMatrix A = grid_matrix(9, 8, 3.7);
  const int n = static_cast<int>(A.rows());
  const Eigen::MatrixXd dense = Eigen::MatrixXd(A);
  for (int trial = 0; trial < 5; ++trial) {
    solver::SupernodalFactorization factor;
    std::vector<int> permutation(static_cast<std::size_t>(n));
    int k = -1;
    if (trial == 0) {
      k = factor.factorize(A);
      permutation = factor.permutation();
    } else {
      std::iota(permutation.begin(), permutation.end(), 0);
      std::shuffle(permutation.begin(), permutation.end(), random);
      k = factor.factorize(A, permutation.data());
    }
    CAPTURE(trial, k);
    REQUIRE(k >= 0);
    Eigen::MatrixXd lead(k + 1, k + 1);
    for (int i = 0; i <= k; ++i)
      for (int j = 0; j <= k; ++j)
        lead(i, j) = dense(permutation[i], permutation[j]);
    CHECK(Eigen::LLT<Eigen::MatrixXd>(lead.topLeftCorner(k, k)).info() == Eigen::Success);
    CHECK(Eigen::LLT<Eigen::MatrixXd>(lead).info() == Eigen::NumericalIssue);
  }
}

namespace {

// Column counts of L below the diagonal by eliminating A's pattern (dense, boolean): each
// column's rows below the diagonal connect pairwise in the columns after it.
std::vector<int> counted_by_elimination(const Eigen::MatrixXd& A) {
  const int n = static_cast<int>(A.rows());
  Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic> pattern = A.array() != 0.0;
  std::vector<int> count(static_cast<std::size_t>(n), 0);
  for (int k = 0; k < n; ++k) {
    std::vector<int> below;
    for (int i = k + 1; i < n; ++i)
      if (pattern(i, k) || pattern(k, i)) below.push_back(i);
    count[static_cast<std::size_t>(k)] = static_cast<int>(below.size());
    for (const int i : below)
      for (const int j : below)
        pattern(i, j) = true;
  }
  return count;
}

// The lower triangle's (rows >= j) and strict upper triangle's patterns of P A P' as
// compressed columns, P the permutation `order` (row k: row order[k] of A).
void permuted_patterns(const Eigen::MatrixXd& A, const std::vector<int>& order,
                       std::vector<int>& lower_start, std::vector<int>& lower_rows,
                       std::vector<int>& upper_start, std::vector<int>& upper_rows) {
  const int n = static_cast<int>(A.rows());
  lower_start.assign(1, 0);
  upper_start.assign(1, 0);
  lower_rows.clear();
  upper_rows.clear();
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (A(order[i], order[j]) == 0.0 && i != j) continue;
      (i < j ? upper_rows : lower_rows).push_back(i);
    }
    lower_start.push_back(static_cast<int>(lower_rows.size()));
    upper_start.push_back(static_cast<int>(upper_rows.size()));
  }
}

}  // namespace

TEST_CASE("L's column counts from the row subtrees' leaves equal those of the elimination") {
  std::mt19937 random(29);
  for (const auto& [name, A] : test_matrices(random)) {
    const Eigen::MatrixXd dense = Eigen::MatrixXd(A);
    const int n = static_cast<int>(A.rows());
    for (int trial = 0; trial < 3; ++trial) {
      CAPTURE(name, trial);
      // The natural order, AMD's postordered (the factorization's), a random one.
      std::vector<int> order(static_cast<std::size_t>(n));
      std::iota(order.begin(), order.end(), 0);
      if (trial == 1) {
        solver::SupernodalFactorization factor;
        REQUIRE(factor.factorize(A) == -1);
        order = factor.permutation();
      }
      if (trial == 2) std::shuffle(order.begin(), order.end(), random);
      std::vector<int> lower_start, lower_rows, upper_start, upper_rows, parent, count;
      permuted_patterns(dense, order, lower_start, lower_rows, upper_start, upper_rows);
      solver::elimination_tree(upper_start, upper_rows, n, parent);
      solver::column_counts(lower_start, lower_rows, parent, count);
      if (trial == 1) {  // AMD's order postordered: the counts without a postorder of their own
        std::vector<int> postordered;
        solver::column_counts(lower_start, lower_rows, parent, postordered, true);
        CHECK(postordered == count);
      }
      Eigen::MatrixXd permuted(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          permuted(i, j) = dense(order[i], order[j]);
      CHECK(count == counted_by_elimination(permuted));
    }
  }
}
