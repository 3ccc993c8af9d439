// The supernodal compact factor (solver/compact_factor.hpp) against a dense solve: random
// SPD matrices of a few shapes - 1x1, diagonal, dense, sparse with 2D-like fill - given
// as the nonzeros of Eigen's dense Cholesky factor under a random permutation, solved
// with one and with several right-hand sides, in double and in single precision.

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "solver/compact_factor.hpp"

using namespace fetic;

namespace {

// A random SPD matrix of order n with the given pattern density (1: dense, 0: diagonal):
// M M' + n I for a sparse random M with unit diagonal.
Eigen::MatrixXd random_spd(int n, double density, std::mt19937& random) {
  std::uniform_real_distribution<double> value(-1.0, 1.0), coin(0.0, 1.0);
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < i; ++j)
      if (coin(random) < density) M(i, j) = value(random);
  return M * M.transpose() + n * Eigen::MatrixXd::Identity(n, n);
}

// The dense Cholesky factor of P A P' (row k of P A P' is row perm[k] of A).
Eigen::MatrixXd permuted_factor(const Eigen::MatrixXd& A, const std::vector<int>& perm) {
  const int n = static_cast<int>(A.rows());
  Eigen::MatrixXd PAP(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      PAP(i, j) = A(perm[i], perm[j]);
  return PAP.llt().matrixL();
}

// The CompactFactor of P A P' from the exact nonzeros of its dense Cholesky factor.
solver::CompactFactor compact_of(const Eigen::MatrixXd& A, const std::vector<int>& perm,
                                 bool single) {
  const Eigen::MatrixXd L = permuted_factor(A, perm);
  const int n = static_cast<int>(A.rows());
  solver::CompactFactor factor(n, perm.data(), 0, single);
  for (int j = 0; j < n; ++j) {
    factor.start_column(L(j, j));
    for (int i = j + 1; i < n; ++i)
      if (L(i, j) != 0.0) factor.add(i, L(i, j));
  }
  factor.finish();
  return factor;
}

// The given nonzeros of L for the same matrix (to bound the relaxed supernodes' zeros).
std::size_t factor_nonzeros(const Eigen::MatrixXd& A, const std::vector<int>& perm) {
  return static_cast<std::size_t>((permuted_factor(A, perm).array() != 0.0).count());
}

struct Shape {
  const char* name;
  int n;
  double density;
};

}  // namespace

TEST_CASE("A supernodal compact factor solves as a dense solve does") {
  std::mt19937 random(25);
  for (const Shape& shape :
       {Shape{"1x1", 1, 0.0}, Shape{"diagonal", 17, 0.0}, Shape{"dense", 40, 1.0},
        Shape{"sparse", 120, 0.03}, Shape{"sparser", 300, 0.008}}) {
    CAPTURE(shape.name);
    const Eigen::MatrixXd A = random_spd(shape.n, shape.density, random);
    std::vector<int> perm(static_cast<std::size_t>(shape.n));
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), random);
    const int columns = 3;
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    Eigen::MatrixXd b(shape.n, columns);
    for (int k = 0; k < b.size(); ++k)
      b.data()[k] = value(random);
    const Eigen::MatrixXd truth = A.llt().solve(b);
    for (const bool single : {false, true}) {
      CAPTURE(single);
      const solver::CompactFactor factor = compact_of(A, perm, single);
      Eigen::MatrixXd x(shape.n, columns), x1(shape.n, 1);
      factor.solve(b.data(), x.data(), columns);
      factor.solve(b.data() + shape.n, x1.data());  // one column alone: the same numbers
      CHECK((x.col(1) - x1.col(0)).norm() == 0.0);
      // In place on the right-hand side gathered into the factor's order: the same bits.
      Eigen::MatrixXd y(shape.n, columns);
      for (int c = 0; c < columns; ++c)
        for (int k = 0; k < shape.n; ++k)
          y(k, c) = b(factor.permutation()[k], c);
      factor.solve_in_place(y.data(), columns);
      for (int c = 0; c < columns; ++c)
        for (int k = 0; k < shape.n; ++k)
          CHECK(y(k, c) == x(factor.permutation()[k], c));
      const double error = (x - truth).norm() / truth.norm();
      CHECK(error <= (single ? 1e-6 : 1e-13));
      // Relaxed supernodes store at most 10% explicit zeros (the diagonal apart).
      const auto given = factor_nonzeros(A, perm);
      CHECK(factor.nonzeros() >= given);
      CHECK(static_cast<double>(factor.nonzeros() - given) <=
            solver::CompactFactor::kRelaxedZeros * static_cast<double>(factor.nonzeros()));
    }
    if (shape.density == 0.0) CHECK(compact_of(A, perm, false).supernodes() == shape.n);
    if (shape.density == 1.0) CHECK(compact_of(A, perm, false).supernodes() == 1);
  }
}

TEST_CASE("Single precision supernodes hold about half the bytes of double ones") {
  std::mt19937 random(7);
  const Eigen::MatrixXd A = random_spd(200, 0.02, random);
  std::vector<int> perm(200);
  std::iota(perm.begin(), perm.end(), 0);
  const solver::CompactFactor full = compact_of(A, perm, false);
  const solver::CompactFactor single = compact_of(A, perm, true);
  CHECK(single.nonzeros() == full.nonzeros());
  CHECK(static_cast<double>(single.bytes()) <= 0.7 * static_cast<double>(full.bytes()));
  // Fewer supernodes than columns: the fill makes columns nest.
  CHECK(full.supernodes() < 200);
}

TEST_CASE("A compact factor refuses entries that are not below the diagonal in order") {
  const std::vector<int> perm{0, 1, 2};
  solver::CompactFactor factor(3, perm.data(), 3);
  CHECK_THROWS_AS(factor.add(1, 0.5), std::logic_error);  // before any column
  factor.start_column(2.0);
  CHECK_THROWS_AS(factor.add(0, 0.5), std::logic_error);  // the diagonal itself
  factor.add(2, 0.5);
  CHECK_THROWS_AS(factor.add(1, 0.5), std::logic_error);  // rows not increasing
  factor.start_column(2.0);
  CHECK_THROWS_AS(factor.add(3, 0.5), std::logic_error);  // beyond the order
  factor.add(2, 0.25);
  factor.start_column(2.0);
  factor.finish();
  std::vector<double> b{1.0, 1.0, 1.0}, x(3);
  factor.solve(b.data(), x.data());
  // The entries kept: L(2,0) = 0.5 and L(2,1) = 0.25.
  const Eigen::Matrix3d L = (Eigen::Matrix3d() << 2, 0, 0, 0, 2, 0, 0.5, 0.25, 2).finished();
  const Eigen::Vector3d expected = (L * L.transpose()).ldlt().solve(Eigen::Vector3d::Ones());
  for (int i = 0; i < 3; ++i)
    CHECK(x[i] == Approx(expected[i]).epsilon(1e-14));
}

// F and the Dirichlet preconditioner solve with right-hand sides on a few rows and read
// only those rows: reach_first() stores the supernodes such a solve needs first, and
// solve_reached_in_place() visits them alone. Those rows come out with the same bits as a
// whole solve's (and as a dense solve's to round-off), a whole solve is unchanged by the
// new layout, and a sparse factor leaves supernodes out (else nothing was saved).
TEST_CASE("A compact factor solves on the supernodes a few rows reach as on all of them") {
  std::mt19937 random(11);
  const int n = 300;
  const Eigen::MatrixXd A = random_spd(n, 0.004, random);
  std::vector<int> perm(static_cast<std::size_t>(n));
  std::iota(perm.begin(), perm.end(), 0);
  const std::vector<int> rows{3, 40, 41, 150, 299};
  for (const bool single : {false, true}) {
    CAPTURE(single);
    solver::CompactFactor factor = compact_of(A, perm, single);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
    for (int row : rows)
      b(row) = 1.0 + row;
    Eigen::VectorXd whole = b;
    factor.solve_in_place(whole.data());
    factor.reach_first(rows);
    CHECK(factor.reached_nonzeros() < factor.nonzeros());
    Eigen::VectorXd after = b, reached = b;
    factor.solve_in_place(after.data());
    factor.solve_reached_in_place(reached.data());
    CHECK((after - whole).norm() == 0.0);
    const Eigen::VectorXd truth = A.llt().solve(b);
    for (int row : rows) {
      CAPTURE(row);
      CHECK(factor.reached(row));
      CHECK(reached(row) == whole(row));
      CHECK(std::abs(reached(row) - truth(row)) <= (single ? 1e-6 : 1e-13) * truth.norm());
    }
  }
}
