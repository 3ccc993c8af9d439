#pragma once
// Element stiffness and its assembly over a box of a strut's mesh (a whole strut for the
// primal methods, one subdomain for FETI). Bar: 2-node elements E*area/h. Plane: 4-node
// bilinear quadrilaterals in plane stress, 2x2 Gauss integration.

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "solver/mesh.hpp"

namespace fetic::solver {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// A rectangle of nodes i0..i1 along and k0..k1 across (inclusive); its elements are
// those whose four (bar: two) nodes lie inside. Box nodes are numbered
// (i - i0) * (k1 - k0 + 1) + (k - k0).
struct NodeBox {
  int i0 = 0, i1 = 0, k0 = 0, k1 = 0;
  int across() const { return k1 - k0 + 1; }
  int node_count() const { return (i1 - i0 + 1) * across(); }
  int local(int i, int k) const { return (i - i0) * across() + (k - k0); }
  bool contains(int i, int k) const { return i >= i0 && i <= i1 && k >= k0 && k <= k1; }
};

NodeBox whole_strut(const StrutMesh& mesh);

// 8x8 stiffness of a plane-stress quadrilateral with corners x[0..3] counterclockwise.
Eigen::Matrix<double, 8, 8> quad_stiffness(const Eigen::Matrix<double, 4, 2>& corners, double E,
                                           double nu, double thickness);

// Stiffness over the box in box-local DOF numbering (node * dofs_per_node + component).
SparseMatrix assemble_stiffness(const StrutMesh& mesh, const NodeBox& box);

// Axial stress per element of the box given the box's DOF values (bar: E * strain;
// plane: e1' sigma e1 at the element centre). Elements ordered (i - i0) * (k1 - k0) + k - k0.
Eigen::VectorXd axial_stress(const StrutMesh& mesh, const NodeBox& box,
                             const Eigen::VectorXd& box_dofs);

// Plane stress (sxx, syy, sxy) in global axes at the centre of element (i, k) of a plane
// strut, from its corner DOFs (corners (i,k), (i+1,k), (i+1,k+1), (i,k+1); x then y each).
Eigen::Vector3d quad_centre_stress(const StrutMesh& mesh, int i, int k,
                                   const Eigen::Matrix<double, 8, 1>& corner_dofs);

}  // namespace fetic::solver
