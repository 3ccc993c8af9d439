#include "solver/rigid_modes.hpp"

namespace fetic::solver {

Eigen::MatrixXd rigid_body_modes(const StrutMesh& mesh, const NodeBox& box) {
  const int nodes = box.node_count();
  if (mesh.dofs_per_node == 1) return Eigen::MatrixXd::Ones(nodes, 1);
  Vec2 centre(0, 0);
  for (int i = box.i0; i <= box.i1; ++i)
    for (int k = box.k0; k <= box.k1; ++k)
      centre += mesh.nodes[mesh.node(i, k)];
  centre /= nodes;
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(2 * nodes, 3);
  for (int i = box.i0; i <= box.i1; ++i) {
    for (int k = box.k0; k <= box.k1; ++k) {
      const Vec2 p = mesh.nodes[mesh.node(i, k)] - centre;
      const int n = box.local(i, k);
      R(2 * n, 0) = -p.y();
      R(2 * n + 1, 0) = p.x();
      R(2 * n, 1) = 1.0;
      R(2 * n + 1, 2) = 1.0;
    }
  }
  return R;
}

}  // namespace fetic::solver
