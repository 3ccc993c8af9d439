#pragma once
// The null space of a small dense matrix, by SVD: used by the frame kinematics (free
// motions of groups of struts) and by the solver's free-motion space. One translation
// unit holds the SVD, the heaviest template of Eigen to compile.

#include <Eigen/Core>

namespace fetic::scenes {

// An orthonormal basis (columns) of {x in R^columns : C x = 0}: the right singular
// vectors whose singular values are below 1e-9 max(1, sigma_max) - rounding, for the
// unit-scaled constraint rows the callers build. All of R^columns when C has no rows.
Eigen::MatrixXd null_space(const Eigen::MatrixXd& C, int columns);

}  // namespace fetic::scenes
