#pragma once
// Rigid-body modes (a basis of ker K) of a floating box of a strut's mesh (docs/METHODS.md
// section 2). Bar: a column of ones (axial translation). Plane: per node the rows
// [-y 1 0; x 0 1] (rotation, x-translation, y-translation), with (x, y) taken relative to
// the box centre so that the three columns are of comparable size. Frame: the same
// columns, with the node's rotation row [1 0 0].

#include <Eigen/Core>

#include "solver/stiffness.hpp"

namespace fetic::solver {

Eigen::MatrixXd rigid_body_modes(const StrutMesh& mesh, const NodeBox& box);

// The point the rotation mode turns about: the mean of the box's nodes.
Vec2 box_centre(const StrutMesh& mesh, const NodeBox& box);

}  // namespace fetic::solver
