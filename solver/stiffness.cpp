#include "solver/stiffness.hpp"

#include <array>
#include <cmath>
#include <vector>

#include <Eigen/LU>

namespace fetic::solver {
namespace {

Eigen::Matrix3d plane_stress_elasticity(double E, double nu) {
  Eigen::Matrix3d D;
  D << 1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu);
  return D * (E / (1.0 - nu * nu));
}

// Strain-displacement matrix of the bilinear quadrilateral at (xi, eta); also returns
// det(J).
Eigen::Matrix<double, 3, 8> quad_strain(const Eigen::Matrix<double, 4, 2>& x, double xi, double eta,
                                        double& det_j) {
  static constexpr std::array<double, 4> xs = {-1.0, 1.0, 1.0, -1.0};
  static constexpr std::array<double, 4> es = {-1.0, -1.0, 1.0, 1.0};
  Eigen::Matrix<double, 2, 4> dN_ref;  // derivatives in (xi, eta)
  for (int a = 0; a < 4; ++a) {
    dN_ref(0, a) = 0.25 * xs[a] * (1.0 + es[a] * eta);
    dN_ref(1, a) = 0.25 * es[a] * (1.0 + xs[a] * xi);
  }
  const Eigen::Matrix2d J = dN_ref * x;  // rows: d/dxi, d/deta; cols: x, y
  det_j = J.determinant();
  const Eigen::Matrix<double, 2, 4> dN = J.inverse() * dN_ref;  // derivatives in (x, y)
  Eigen::Matrix<double, 3, 8> B = Eigen::Matrix<double, 3, 8>::Zero();
  for (int a = 0; a < 4; ++a) {
    B(0, 2 * a) = dN(0, a);
    B(1, 2 * a + 1) = dN(1, a);
    B(2, 2 * a) = dN(1, a);
    B(2, 2 * a + 1) = dN(0, a);
  }
  return B;
}

Eigen::Matrix<double, 4, 2> quad_corners(const StrutMesh& mesh, int i, int k) {
  Eigen::Matrix<double, 4, 2> x;
  const int nodes[4] = {mesh.node(i, k), mesh.node(i + 1, k), mesh.node(i + 1, k + 1),
                        mesh.node(i, k + 1)};
  for (int a = 0; a < 4; ++a)
    x.row(a) = mesh.nodes[nodes[a]].transpose();
  return x;
}

std::array<int, 4> quad_box_nodes(const NodeBox& box, int i, int k) {
  return {box.local(i, k), box.local(i + 1, k), box.local(i + 1, k + 1), box.local(i, k + 1)};
}

}  // namespace

NodeBox whole_strut(const StrutMesh& mesh) {
  return NodeBox{0, mesh.nx, 0, mesh.ny};
}

Eigen::Matrix<double, 8, 8> quad_stiffness(const Eigen::Matrix<double, 4, 2>& corners, double E,
                                           double nu, double thickness) {
  const Eigen::Matrix3d D = plane_stress_elasticity(E, nu);
  const double g = 1.0 / std::sqrt(3.0);
  Eigen::Matrix<double, 8, 8> K = Eigen::Matrix<double, 8, 8>::Zero();
  for (double xi : {-g, g}) {
    for (double eta : {-g, g}) {
      double det_j = 0.0;
      const Eigen::Matrix<double, 3, 8> B = quad_strain(corners, xi, eta, det_j);
      K.noalias() += B.transpose() * D * B * (det_j * thickness);
    }
  }
  return 0.5 * (K + K.transpose());  // exactly symmetric
}

SparseMatrix assemble_stiffness(const StrutMesh& mesh, const NodeBox& box) {
  const int n = box.node_count() * mesh.dofs_per_node;
  std::vector<Eigen::Triplet<double>> entries;
  if (mesh.dofs_per_node == 1) {
    const double k = mesh.E * mesh.area / (mesh.length / mesh.nx);
    entries.reserve(4 * static_cast<size_t>(box.i1 - box.i0));
    for (int i = box.i0; i < box.i1; ++i) {
      const int a = box.local(i, 0), b = box.local(i + 1, 0);
      entries.emplace_back(a, a, k);
      entries.emplace_back(b, b, k);
      entries.emplace_back(a, b, -k);
      entries.emplace_back(b, a, -k);
    }
  } else {
    entries.reserve(64 * static_cast<size_t>(box.i1 - box.i0) * (box.k1 - box.k0));
    // Every element of a uniform rectangular mesh has the same stiffness.
    const Eigen::Matrix<double, 8, 8> Ke =
        quad_stiffness(quad_corners(mesh, 0, 0), mesh.E, mesh.nu, mesh.thickness);
    for (int i = box.i0; i < box.i1; ++i) {
      for (int k = box.k0; k < box.k1; ++k) {
        const std::array<int, 4> nodes = quad_box_nodes(box, i, k);
        for (int a = 0; a < 4; ++a)
          for (int ca = 0; ca < 2; ++ca)
            for (int b = 0; b < 4; ++b)
              for (int cb = 0; cb < 2; ++cb)
                entries.emplace_back(2 * nodes[a] + ca, 2 * nodes[b] + cb,
                                     Ke(2 * a + ca, 2 * b + cb));
      }
    }
  }
  SparseMatrix K(n, n);
  K.setFromTriplets(entries.begin(), entries.end());
  return K;
}

Eigen::VectorXd axial_stress(const StrutMesh& mesh, const NodeBox& box,
                             const Eigen::VectorXd& box_dofs) {
  if (mesh.dofs_per_node == 1) {
    const double h = mesh.length / mesh.nx;
    Eigen::VectorXd stress(box.i1 - box.i0);
    for (int i = box.i0; i < box.i1; ++i)
      stress(i - box.i0) = mesh.E * (box_dofs(box.local(i + 1, 0)) - box_dofs(box.local(i, 0))) / h;
    return stress;
  }
  const Eigen::Matrix3d D = plane_stress_elasticity(mesh.E, mesh.nu);
  const int across = box.k1 - box.k0;
  Eigen::VectorXd stress((box.i1 - box.i0) * across);
  for (int i = box.i0; i < box.i1; ++i) {
    for (int k = box.k0; k < box.k1; ++k) {
      double det_j = 0.0;
      const Eigen::Matrix<double, 3, 8> B = quad_strain(quad_corners(mesh, i, k), 0.0, 0.0, det_j);
      Eigen::Matrix<double, 8, 1> ue;
      const std::array<int, 4> nodes = quad_box_nodes(box, i, k);
      for (int a = 0; a < 4; ++a) {
        ue(2 * a) = box_dofs(2 * nodes[a]);
        ue(2 * a + 1) = box_dofs(2 * nodes[a] + 1);
      }
      const Eigen::Vector3d s = D * (B * ue);  // (sxx, syy, sxy)
      const Vec2& e = mesh.e1;
      stress((i - box.i0) * across + (k - box.k0)) =
          s(0) * e.x() * e.x() + s(1) * e.y() * e.y() + 2.0 * s(2) * e.x() * e.y();
    }
  }
  return stress;
}

Eigen::Vector3d quad_centre_stress(const StrutMesh& mesh, int i, int k,
                                   const Eigen::Matrix<double, 8, 1>& corner_dofs) {
  double det_j = 0.0;
  const Eigen::Matrix<double, 3, 8> B = quad_strain(quad_corners(mesh, i, k), 0.0, 0.0, det_j);
  return plane_stress_elasticity(mesh.E, mesh.nu) * (B * corner_dofs);
}

}  // namespace fetic::solver
