#pragma once
// The null space of a large sparse constraint matrix - the free motions of a group of
// hundreds or thousands of struts - by SuiteSparseQR's rank-revealing QR of C': the
// columns of Q after the rank span {x : C x = 0}. Its cost grows with the factor's
// nonzeros (near-linearly for the chains, ropes and lattices frames are made of), where
// the dense SVD of null_space.hpp grows with the cube of the columns: a rope of 2,000
// pinned struts took 142 s and 1.6 GB by SVD.

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace fetic::scenes {

// Up to `limit` orthonormal basis vectors (columns) of {x : C x = 0}; all of them when
// limit < 0. Rank decided like null_space(): a pivot column below 1e-9 max(1, largest row
// norm) counts as dependent.
Eigen::MatrixXd sparse_null_space(const Eigen::SparseMatrix<double>& C, int limit = -1);

// How many columns are worth the sparse factorization instead of the dense SVD.
inline constexpr int kSparseNullSpaceColumns = 240;

}  // namespace fetic::scenes
