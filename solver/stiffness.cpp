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

// The beam element in its local axes: (u1, v1, rotation1, u2, v2, rotation2).
Eigen::Matrix<double, 6, 6> local_beam_stiffness(double E, double area, double inertia, double h) {
  const double a = E * area / h;
  const double b = E * inertia / (h * h * h);
  Eigen::Matrix<double, 6, 6> k;
  k << a, 0, 0, -a, 0, 0,                                         //
      0, 12 * b, 6 * b * h, 0, -12 * b, 6 * b * h,                //
      0, 6 * b * h, 4 * b * h * h, 0, -6 * b * h, 2 * b * h * h,  //
      -a, 0, 0, a, 0, 0,                                          //
      0, -12 * b, -6 * b * h, 0, 12 * b, -6 * b * h,              //
      0, 6 * b * h, 2 * b * h * h, 0, -6 * b * h, 4 * b * h * h;
  return k;
}

// Global DOFs to local ones.
Eigen::Matrix<double, 6, 6> beam_rotation(const Vec2& e) {
  Eigen::Matrix<double, 6, 6> T = Eigen::Matrix<double, 6, 6>::Zero();
  for (int n = 0; n < 2; ++n) {
    T.block<3, 3>(3 * n, 3 * n) << e.x(), e.y(), 0.0, -e.y(), e.x(), 0.0, 0.0, 0.0, 1.0;
  }
  return T;
}

}  // namespace

Eigen::Matrix<double, 6, 6> beam_stiffness(double E, double area, double inertia, double h,
                                           const Vec2& e) {
  const Eigen::Matrix<double, 6, 6> T = beam_rotation(e);
  const Eigen::Matrix<double, 6, 6> K =
      T.transpose() * local_beam_stiffness(E, area, inertia, h) * T;
  return 0.5 * (K + K.transpose());  // exactly symmetric
}

BeamForces beam_forces(const StrutMesh& mesh, const NodeBox& box, const Eigen::VectorXd& box_dofs) {
  const double h = mesh.length / mesh.nx;
  const Eigen::Matrix<double, 6, 6> k = local_beam_stiffness(mesh.E, mesh.area, mesh.inertia, h);
  const Eigen::Matrix<double, 6, 6> T = beam_rotation(mesh.e1);
  BeamForces forces;
  const int elements = box.i1 - box.i0;
  forces.axial.resize(elements);
  forces.moment.resize(elements, 2);
  for (int i = box.i0; i < box.i1; ++i) {
    Eigen::Matrix<double, 6, 1> u;
    u.head<3>() = box_dofs.segment<3>(3 * box.local(i, 0));
    u.tail<3>() = box_dofs.segment<3>(3 * box.local(i + 1, 0));
    // End forces the element's neighbours exert on it, in local axes.
    const Eigen::Matrix<double, 6, 1> f = k * (T * u);
    forces.axial(i - box.i0) = f(3);
    // Internal moment (sagging positive): -f_rotation1 at the first node, f_rotation2 at
    // the second.
    forces.moment(i - box.i0, 0) = -f(2);
    forces.moment(i - box.i0, 1) = f(5);
  }
  return forces;
}

namespace {

void assemble_beams(const StrutMesh& mesh, const NodeBox& box,
                    std::vector<Eigen::Triplet<double>>& entries) {
  const double h = mesh.length / mesh.nx;
  const Eigen::Matrix<double, 6, 6> Ke =
      beam_stiffness(mesh.E, mesh.area, mesh.inertia, h, mesh.e1);
  entries.reserve(36 * static_cast<size_t>(box.i1 - box.i0));
  for (int i = box.i0; i < box.i1; ++i) {
    const int nodes[2] = {box.local(i, 0), box.local(i + 1, 0)};
    for (int a = 0; a < 2; ++a)
      for (int ca = 0; ca < 3; ++ca)
        for (int b = 0; b < 2; ++b)
          for (int cb = 0; cb < 3; ++cb)
            entries.emplace_back(3 * nodes[a] + ca, 3 * nodes[b] + cb, Ke(3 * a + ca, 3 * b + cb));
  }
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

namespace {

// Plane stress, straight into compressed columns: column 2p + c holds the two DOFs of
// every node q next to node p (the 3x3 nodes around it within the box, all of which share
// an element with it when the box has elements), in increasing order. Each element's
// 8x8 block is added in element order, the order in which setFromTriplets summed the
// same entries before, so K is bit for bit what the triplets gave - at a fraction of the
// cost (the triplets were a quarter of the FETI set-up's CPU: docs/BENCHMARKS.md).
SparseMatrix assemble_plane(const StrutMesh& mesh, const NodeBox& box) {
  const int rows_i = box.i1 - box.i0 + 1, across = box.across();
  const int nodes = rows_i * across;
  SparseMatrix K(2 * nodes, 2 * nodes);
  if (box.i1 <= box.i0 || box.k1 <= box.k0) return K;  // no element: no entry
  // slot[9 p + 3 (di + 1) + (dk + 1)]: where node (i + di, k + dk)'s rows start in the
  // columns of node p = (i, k).
  std::vector<int> slot(9 * static_cast<size_t>(nodes), -1);
  std::vector<int> start(2 * static_cast<size_t>(nodes) + 1, 0);
  for (int p = 0; p < nodes; ++p) {
    const int i = p / across, k = p % across;
    int count = 0;
    for (int di = -1; di <= 1; ++di)
      for (int dk = -1; dk <= 1; ++dk)
        if (i + di >= 0 && i + di < rows_i && k + dk >= 0 && k + dk < across)
          slot[9 * p + 3 * (di + 1) + dk + 1] = 2 * count++;
    start[2 * p + 1] = start[2 * p] + 2 * count;
    start[2 * p + 2] = start[2 * p + 1] + 2 * count;
  }
  K.resizeNonZeros(start.back());
  int* outer = K.outerIndexPtr();
  int* inner = K.innerIndexPtr();
  double* value = K.valuePtr();
  std::copy(start.begin(), start.end(), outer);
  std::fill(value, value + start.back(), 0.0);
  for (int p = 0; p < nodes; ++p)
    for (int neighbour = 0; neighbour < 9; ++neighbour) {
      const int at = slot[9 * p + neighbour];
      if (at < 0) continue;
      const int q = p + (neighbour / 3 - 1) * across + neighbour % 3 - 1;
      for (int c = 0; c < 2; ++c)
        for (int r = 0; r < 2; ++r)
          inner[start[2 * p + c] + at + r] = 2 * q + r;
    }
  // Every element of a uniform rectangular mesh has the same stiffness.
  const Eigen::Matrix<double, 8, 8> Ke =
      quad_stiffness(quad_corners(mesh, 0, 0), mesh.E, mesh.nu, mesh.thickness);
  static constexpr int corner_i[4] = {0, 1, 1, 0}, corner_k[4] = {0, 0, 1, 1};
  for (int i = box.i0; i < box.i1; ++i)
    for (int k = box.k0; k < box.k1; ++k) {
      const std::array<int, 4> corner = quad_box_nodes(box, i, k);
      for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a) {
          // Node a relative to node b, in the corners' order of quad_box_nodes.
          const int di = corner_i[a] - corner_i[b], dk = corner_k[a] - corner_k[b];
          const int at = slot[9 * corner[b] + 3 * (di + 1) + dk + 1];
          for (int cb = 0; cb < 2; ++cb)
            for (int ca = 0; ca < 2; ++ca)
              value[start[2 * corner[b] + cb] + at + ca] += Ke(2 * a + ca, 2 * b + cb);
        }
    }
  return K;
}

}  // namespace

SparseMatrix assemble_stiffness(const StrutMesh& mesh, const NodeBox& box) {
  const int n = box.node_count() * mesh.dofs_per_node;
  std::vector<Eigen::Triplet<double>> entries;
  if (mesh.dofs_per_node == 3) {
    assemble_beams(mesh, box, entries);
  } else if (mesh.dofs_per_node == 1) {
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
    return assemble_plane(mesh, box);
  }
  SparseMatrix K(n, n);
  K.setFromTriplets(entries.begin(), entries.end());
  return K;
}

Eigen::VectorXd axial_stress(const StrutMesh& mesh, const NodeBox& box,
                             const Eigen::VectorXd& box_dofs) {
  if (mesh.dofs_per_node == 3) {
    const double h = mesh.length / mesh.nx;
    Eigen::VectorXd stress(box.i1 - box.i0);
    for (int i = box.i0; i < box.i1; ++i) {
      const Vec2 du =
          box_dofs.segment<2>(3 * box.local(i + 1, 0)) - box_dofs.segment<2>(3 * box.local(i, 0));
      stress(i - box.i0) = mesh.E * du.dot(mesh.e1) / h;
    }
    return stress;
  }
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
