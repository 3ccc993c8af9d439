#pragma once
// The finite-element mesh of every strut, exactly as SCENES.md defines it: bar model
// nodes along the axis (1 axial DOF each); plane model a grid of bilinear quadrilaterals
// (2 DOFs each); frame model nodes along the axis with ux, uy and the rotation (3 DOFs
// each). Nodes are numbered i * (ny + 1) + k: i along the axis (0 at 'from'), k across it
// (0 at the -height/2 side of e2 = e1 rotated by +90 degrees).

#include <array>
#include <vector>

#include <Eigen/Core>

#include "scenes/scene.hpp"

namespace fetic::solver {

using Vec2 = Eigen::Vector2d;

struct StrutMesh {
  int strut = 0;          // index into scene.struts
  int dofs_per_node = 1;  // 1 bar, 2 plane, 3 frame
  int nx = 1;             // elements along the axis
  int ny = 0;             // elements across (0 in the bar model)
  Vec2 origin{0, 0};      // the 'from' end point (on the axis)
  Vec2 e1{1, 0};          // unit axis from 'from' to 'to'
  Vec2 e2{0, 1};          // unit, e1 rotated by +90 degrees
  double length = 0.0;
  double height = 0.0;  // plane model
  double E = 0.0;
  double area = 0.0;       // bar and frame model
  double inertia = 0.0;    // frame model
  double thickness = 0.0;  // plane model
  double nu = 0.0;         // plane model
  int subdomains_along = 1;
  int subdomains_across = 1;  // plane model
  std::vector<Vec2> nodes;    // reference positions

  int nodes_across() const { return ny + 1; }
  int node(int i, int k) const { return i * (ny + 1) + k; }
  int node_count() const { return static_cast<int>(nodes.size()); }
  int dof_count() const { return node_count() * dofs_per_node; }
  // Nodes of an end face in increasing k.
  std::vector<int> end_face(scenes::StrutEnd end) const;
};

StrutMesh build_strut_mesh(const scenes::Scene& scene, int strut);

// Coefficients that turn a node's DOFs into its displacement component along `direction`.
// Bar: one coefficient (e1 . direction); plane: (direction.x, direction.y); frame:
// (direction.x, direction.y, 0).
Eigen::VectorXd component_coefficients(const StrutMesh& mesh, const Vec2& direction);
// The same in the first dofs_per_node entries of a fixed-size vector, which allocates
// nothing (a node force in the load: one per element corner when a model is built).
Eigen::Vector3d component_coefficients3(const StrutMesh& mesh, const Vec2& direction);

// Displacement vector (ux, uy) of node `node` from the strut's DOF values `dofs`
// (indexed node * dofs_per_node + component).
Vec2 node_displacement(const StrutMesh& mesh, const double* node_dofs);
// Rotation of a node (frame model; 0 in the others).
double node_rotation(const StrutMesh& mesh, const double* node_dofs);

}  // namespace fetic::solver
