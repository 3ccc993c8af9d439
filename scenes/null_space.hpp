#pragma once
// The null space of a small dense matrix, by SVD: used by the frame kinematics (free
// motions of groups of struts), by the solver's free-motion space and by FETI-DP's
// clusters. One translation unit holds the SVD, the heaviest template of Eigen to compile
// (about 50 s of CPU at -O3 each copy; keep it the only one).

#include <Eigen/Core>

namespace fetic::scenes {

// An orthonormal basis (columns) of {x in R^columns : C x = 0}: the right singular
// vectors whose singular values are below 1e-9 max(1, sigma_max) - rounding, for the
// unit-scaled constraint rows the callers build. All of R^columns when C has no rows.
Eigen::MatrixXd null_space(const Eigen::MatrixXd& C, int columns);

// The same with the cut relative to the largest singular value alone: the right singular
// vectors whose singular values are at most `relative` sigma_max (at most `relative` when
// C is empty). For rows that carry a length scale, as rigid-mode rows do (solver/corners).
Eigen::MatrixXd null_space_relative(const Eigen::MatrixXd& C, double relative);

// C's right singular vectors split at `relative` sigma_max (C with rows and columns): those
// above it, a basis of C's row space, and the rest, null_space_relative's basis. For the
// active-set method's held and free rigid modes (solver/active_set.cpp).
struct RightSingularSplit {
  Eigen::MatrixXd row_space;
  Eigen::MatrixXd null_space;
};
RightSingularSplit split_right_singular_vectors(const Eigen::MatrixXd& C, double relative);

}  // namespace fetic::scenes
