#include "solver/rigid_modes.hpp"

namespace fetic::solver {

Vec2 box_centre(const StrutMesh& mesh, const NodeBox& box) {
  Vec2 centre(0, 0);
  for (int i = box.i0; i <= box.i1; ++i)
    for (int k = box.k0; k <= box.k1; ++k)
      centre += mesh.nodes[mesh.node(i, k)];
  return centre / box.node_count();
}

Eigen::MatrixXd rigid_body_modes(const StrutMesh& mesh, const NodeBox& box) {
  const int nodes = box.node_count();
  const int dofs = mesh.dofs_per_node;
  if (dofs == 1) return Eigen::MatrixXd::Ones(nodes, 1);
  const Vec2 centre = box_centre(mesh, box);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(dofs * nodes, 3);
  for (int i = box.i0; i <= box.i1; ++i) {
    for (int k = box.k0; k <= box.k1; ++k) {
      const Vec2 p = mesh.nodes[mesh.node(i, k)] - centre;
      const int n = box.local(i, k);
      R(dofs * n, 0) = -p.y();
      R(dofs * n + 1, 0) = p.x();
      R(dofs * n, 1) = 1.0;
      R(dofs * n + 1, 2) = 1.0;
      if (dofs == 3) R(dofs * n + 2, 0) = 1.0;
    }
  }
  return R;
}

}  // namespace fetic::solver
