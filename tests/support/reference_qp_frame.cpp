// The frame model's reference, assembled here from SCENES.md "Frame model" without any
// solver code and by other means than the solver:
// * element stiffness by 2-point Gauss integration of E*inertia*N''N'' over the cubic
//   Hermite shape functions and E*area*N'N' over linear ones, in the element's own axes,
//   then mapped to x, y by the axis vectors (the solver writes down the closed-form 6x6
//   matrix and rotates it);
// * consistent nodal loads by integrating the same shape functions against q;
// * joints by merging DOFs (union-find over (strut, node, component); the solver's FETI
//   glues copies with rows of B, its primal problem numbers owners);
// * the kernel of the stiffness (free motions of floating or pinned parts) from a dense
//   eigen-decomposition of the Jacobi-scaled stiffness (the solver uses rigid-body
//   kinematics), written u = Z y + w with w = 0 on DOFs that pin Z, so that the energy
//   is 1/2 w'K w exactly and the QP's quadratic form is positive semidefinite in exact
//   arithmetic;
// * w condensed onto the DOFs the contacts touch (dense Cholesky of the rest), and the
//   QP in (y, w_c) solved exactly by CGAL.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>

#include "tests/support/reference_qp.hpp"
#include "tests/support/reference_qp_parts.hpp"

namespace fetic::testing {
namespace {

using Vec = Eigen::Vector2d;

struct Beam {
  Vec from, to, e, m;  // ends, unit axis, axis turned +90 degrees
  double length = 0.0, h = 0.0;
  int nodes = 0;
  Vec node(int i) const {
    if (i == 0) return from;
    if (i == nodes - 1) return to;
    const double s = static_cast<double>(i) / (nodes - 1);
    return (1.0 - s) * from + s * to;
  }
};

Beam describe(const scenes::Strut& s) {
  Beam b;
  b.from = {s.from[0], s.from[1]};
  b.to = {s.to[0], s.to[1]};
  b.length = (b.to - b.from).norm();
  b.e = (b.to - b.from) / b.length;
  b.m = {-b.e.y(), b.e.x()};
  b.nodes = s.elements + 1;
  b.h = b.length / s.elements;
  return b;
}

// Hermite shape functions on xi in [0, 1] for (v1, theta1, v2, theta2) and their second
// derivatives with respect to x.
Eigen::Vector4d hermite(double xi, double h) {
  return {1 - 3 * xi * xi + 2 * xi * xi * xi, h * (xi - 2 * xi * xi + xi * xi * xi),
          3 * xi * xi - 2 * xi * xi * xi, h * (-xi * xi + xi * xi * xi)};
}
Eigen::Vector4d hermite_second(double xi, double h) {
  return Eigen::Vector4d(-6 + 12 * xi, h * (-4 + 6 * xi), 6 - 12 * xi, h * (-2 + 6 * xi)) / (h * h);
}

// Element stiffness and the map from its 6 global DOFs (ux, uy, theta at both nodes).
Eigen::Matrix<double, 6, 6> element_stiffness(const scenes::Strut& strut, const Beam& b) {
  // Local DOFs (u1, u2) axial and (v1, t1, v2, t2) bending, each as a row over globals.
  Eigen::Matrix<double, 2, 6> axial = Eigen::Matrix<double, 2, 6>::Zero();
  Eigen::Matrix<double, 4, 6> bending = Eigen::Matrix<double, 4, 6>::Zero();
  for (int n = 0; n < 2; ++n) {
    axial(n, 3 * n) = b.e.x();
    axial(n, 3 * n + 1) = b.e.y();
    bending(2 * n, 3 * n) = b.m.x();
    bending(2 * n, 3 * n + 1) = b.m.y();
    bending(2 * n + 1, 3 * n + 2) = 1.0;
  }
  Eigen::Matrix2d ka;
  ka << 1, -1, -1, 1;
  ka *= strut.E * strut.area / b.h;
  Eigen::Matrix4d kb = Eigen::Matrix4d::Zero();
  const double g = 0.5 / std::sqrt(3.0);
  for (double xi : {0.5 - g, 0.5 + g}) {
    const Eigen::Vector4d B = hermite_second(xi, b.h);
    kb += strut.E * strut.inertia * B * B.transpose() * (0.5 * b.h);
  }
  return axial.transpose() * ka * axial + bending.transpose() * kb * bending;
}

using scenes::UnionFind;

int node_of(const scenes::Scene& scene, const scenes::EndRef& ref) {
  if (ref.node >= 0) return ref.node;
  return ref.end == scenes::StrutEnd::From ? 0 : scene.struts[ref.strut].elements;
}

}  // namespace

ReferenceSolution solve_frame_reference_qp(const scenes::Scene& scene, double load_factor) {
  const int strut_count = static_cast<int>(scene.struts.size());
  std::vector<Beam> beams;
  std::vector<int> first;  // first raw DOF of each strut
  int raw = 0;
  for (const scenes::Strut& s : scene.struts) {
    beams.push_back(describe(s));
    first.push_back(raw);
    raw += 3 * beams.back().nodes;
  }
  auto dof = [&](int strut, int node, int c) { return first[strut] + 3 * node + c; };

  // Joints merge DOFs; supports fix them (a merged DOF is fixed when any member is).
  UnionFind same(raw);
  for (const scenes::Joint& joint : scene.joints) {
    const int shared = joint.kind == scenes::JointKind::Rigid ? 3 : 2;
    for (const scenes::EndRef& end : joint.ends)
      for (int c = 0; c < shared; ++c)
        same.join(dof(joint.ends[0].strut, node_of(scene, joint.ends[0]), c),
                  dof(end.strut, node_of(scene, end), c));
  }
  std::vector<char> fixed_root(raw, 0);
  for (int s = 0; s < strut_count; ++s) {
    const scenes::Strut& strut = scene.struts[s];
    for (int end = 0; end < 2; ++end) {
      const int node = end == 0 ? 0 : beams[s].nodes - 1;
      const bool clamped = end == 0 ? strut.fixed_from : strut.fixed_to;
      const bool pinned = end == 0 ? strut.pinned_from : strut.pinned_to;
      for (int c = 0; c < 3; ++c)
        if (clamped || (pinned && c < 2)) fixed_root[same.root(dof(s, node, c))] = 1;
    }
  }

  // Independent groups: struts joined by joints or contacts.
  UnionFind group_of(strut_count);
  for (const scenes::Joint& joint : scene.joints)
    for (const scenes::EndRef& end : joint.ends)
      group_of.join(joint.ends[0].strut, end.strut);
  for (const scenes::Contact& contact : scene.contacts)
    group_of.join(contact.a.strut, contact.b.strut);

  ReferenceSolution solution;
  solution.optimal = true;
  solution.displacement.resize(strut_count);
  solution.rotation.resize(strut_count);
  solution.force.assign(scene.contacts.size(), 0.0);

  for (const std::vector<int>& members : groups_of(group_of, strut_count)) {
    const int group = group_of.root(members[0]);
    // Unknowns: one per free merged DOF of the group.
    std::map<int, int> unknown_of_root;
    for (int s : members)
      for (int d = first[s]; d < first[s] + 3 * beams[s].nodes; ++d) {
        const int r = same.root(d);
        if (!fixed_root[r] && !unknown_of_root.count(r))
          unknown_of_root.emplace(r, static_cast<int>(unknown_of_root.size()));
      }
    auto unknown = [&](int d) {
      const auto it = unknown_of_root.find(same.root(d));
      return it == unknown_of_root.end() ? -1 : it->second;
    };
    const int n = static_cast<int>(unknown_of_root.size());
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
    for (int s : members) {
      const scenes::Strut& strut = scene.struts[s];
      const Beam& b = beams[s];
      const Eigen::Matrix<double, 6, 6> Ke = element_stiffness(strut, b);
      for (int e = 0; e + 1 < b.nodes; ++e) {
        int map[6];
        for (int i = 0; i < 6; ++i)
          map[i] = unknown(dof(s, e + i / 3, i % 3));
        for (int i = 0; i < 6; ++i)
          for (int j = 0; j < 6; ++j)
            if (map[i] >= 0 && map[j] >= 0) K(map[i], map[j]) += Ke(i, j);
      }
      for (const scenes::Load& load : scene.loads) {
        if (load.strut != s) continue;
        const Vec q(load.force[0], load.force[1]);
        if (!load.per_length) {
          const int node =
              load.node >= 0 ? load.node : (load.at == scenes::StrutEnd::From ? 0 : b.nodes - 1);
          const double values[3] = {q.x(), q.y(), load.moment};
          for (int c = 0; c < 3; ++c)
            if (unknown(dof(s, node, c)) >= 0) f(unknown(dof(s, node, c))) += values[c];
          continue;
        }
        // Consistent loads: integral of the shape functions against q (2-point Gauss is
        // exact for these cubics).
        const double qt = q.dot(b.e), qm = q.dot(b.m);
        for (int e = 0; e + 1 < b.nodes; ++e) {
          Eigen::Matrix<double, 6, 1> fe = Eigen::Matrix<double, 6, 1>::Zero();
          const double g = 0.5 / std::sqrt(3.0);
          for (double xi : {0.5 - g, 0.5 + g}) {
            const Eigen::Vector4d N = hermite(xi, b.h);
            const double w = 0.5 * b.h;
            const double linear[2] = {1 - xi, xi};
            for (int k = 0; k < 2; ++k) {
              fe.segment<2>(3 * k) += w * (qt * linear[k] * b.e + qm * N(2 * k) * b.m);
              fe(3 * k + 2) += w * qm * N(2 * k + 1);
            }
          }
          for (int i = 0; i < 6; ++i)
            if (unknown(dof(s, e + i / 3, i % 3)) >= 0)
              f(unknown(dof(s, e + i / 3, i % 3))) += fe(i);
        }
      }
    }
    f *= load_factor;
    K = 0.5 * (K + K.transpose()).eval();

    // Contact rows over the unknowns.
    std::vector<ContactRow> rows;
    for (size_t c = 0; c < scene.contacts.size(); ++c) {
      const scenes::Contact& contact = scene.contacts[c];
      if (group_of.root(contact.a.strut) != group) continue;
      const int na = node_of(scene, contact.a), nb = node_of(scene, contact.b);
      const Vec xa = beams[contact.a.strut].node(na), xb = beams[contact.b.strut].node(nb);
      Vec normal;
      if (contact.has_normal)
        normal = Vec(contact.normal[0], contact.normal[1]).normalized();
      else
        normal = (xb - xa).normalized();
      double gap = normal.dot(xb - xa);
      const double scale = std::max(beams[contact.a.strut].length, beams[contact.b.strut].length);
      if (std::abs(gap) < 1e-9 * scale) gap = 0.0;
      ContactRow row{static_cast<int>(c), {}, gap};
      for (int k = 0; k < 2; ++k) {
        const int ua = unknown(dof(contact.a.strut, na, k));
        const int ub = unknown(dof(contact.b.strut, nb, k));
        if (ua >= 0) row.entries.emplace_back(ua, normal(k));
        if (ub >= 0) row.entries.emplace_back(ub, -normal(k));
      }
      rows.push_back(row);
    }

    // Kernel of K (Jacobi-scaled eigen-decomposition) and the DOFs that pin it.
    Eigen::VectorXd scale(n);
    for (int i = 0; i < n; ++i)
      scale(i) = 1.0 / std::sqrt(K(i, i));
    const Eigen::MatrixXd Ks = scale.asDiagonal() * K * scale.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(Ks);
    const double largest = eigen.eigenvalues().cwiseAbs().maxCoeff();
    int kernel_size = 0;
    while (kernel_size < n && eigen.eigenvalues()(kernel_size) < 1e-11 * largest)
      ++kernel_size;
    Eigen::MatrixXd Z = scale.asDiagonal() * eigen.eigenvectors().leftCols(kernel_size);
    std::vector<char> pinned(n, 0);
    if (kernel_size > 0) {
      Eigen::MatrixXd Zn = Z;
      for (int j = 0; j < kernel_size; ++j)
        Zn.col(j).normalize();
      const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Zn.transpose());
      for (int j = 0; j < kernel_size; ++j)
        pinned[qr.colsPermutation().indices()(j)] = 1;
    }
    // w: unknowns outside the pinned ones; those the contacts touch are kept, the rest
    // condensed out.
    std::vector<char> touched(n, 0);
    for (const ContactRow& row : rows)
      for (const auto& [u, value] : row.entries)
        touched[u] = 1;
    std::vector<int> kept, interior, kept_pos(n, -1);
    for (int i = 0; i < n; ++i) {
      if (pinned[i]) continue;
      if (touched[i]) {
        kept_pos[i] = static_cast<int>(kept.size());
        kept.push_back(i);
      } else {
        interior.push_back(i);
      }
    }
    const Condensation condensed(K, f, kept, interior);
    const Eigen::MatrixXd& S = condensed.S();
    const Eigen::VectorXd& g = condensed.g();
    const Eigen::VectorXd Zf = Z.transpose() * f;

    // Variables: y (kernel amplitudes) first, then w_c. Objective 1/2 w_c'S w_c - g'w_c
    // - (Z'f)'y; rows a'(Z y + w) <= gap.
    const int ny = kernel_size, nc = static_cast<int>(kept.size());
    CGAL::Quadratic_program<double> qp(CGAL::SMALLER, false, 0, false, 0);
    for (int x = 0; x < nc; ++x)
      for (int y = 0; y <= x; ++y)
        if (S(x, y) != 0.0) qp.set_d(ny + x, ny + y, S(x, y));
    for (int x = 0; x < ny; ++x)
      qp.set_c(x, -Zf(x));
    for (int x = 0; x < nc; ++x)
      qp.set_c(ny + x, -g(x));
    for (size_t r = 0; r < rows.size(); ++r) {
      std::vector<double> coefficient(ny + nc, 0.0);
      for (const auto& [u, value] : rows[r].entries) {
        for (int j = 0; j < ny; ++j)
          coefficient[j] += value * Z(u, j);
        if (kept_pos[u] >= 0) coefficient[ny + kept_pos[u]] += value;
      }
      for (int j = 0; j < ny + nc; ++j)
        if (coefficient[j] != 0.0) qp.set_a(j, static_cast<int>(r), coefficient[j]);
      qp.set_b(static_cast<int>(r), rows[r].gap);
    }
    Eigen::VectorXd variables = Eigen::VectorXd::Zero(ny + nc);
    if (ny + nc > 0) {
      const ExactSolution exact = solve_exact(qp, ny + nc, static_cast<int>(rows.size()));
      if (!exact.optimal) {
        solution.optimal = false;
        continue;
      }
      variables = exact.x;
      for (size_t r = 0; r < rows.size(); ++r)
        solution.force[rows[r].index] = exact.multipliers[r];
    }
    const Eigen::VectorXd wc = variables.tail(nc);
    const Eigen::VectorXd wi = condensed.interior(wc);
    Eigen::VectorXd u = Z * variables.head(ny);
    for (int x = 0; x < nc; ++x)
      u(kept[x]) += wc(x);
    for (size_t x = 0; x < interior.size(); ++x)
      u(interior[x]) += wi(static_cast<int>(x));
    for (int s : members)
      for (int node = 0; node < beams[s].nodes; ++node) {
        const int ux = unknown(dof(s, node, 0)), uy = unknown(dof(s, node, 1)),
                  rz = unknown(dof(s, node, 2));
        solution.displacement[s].push_back({ux >= 0 ? u(ux) : 0.0, uy >= 0 ? u(uy) : 0.0});
        solution.rotation[s].push_back(rz >= 0 ? u(rz) : 0.0);
      }
  }
  return solution;
}

}  // namespace fetic::testing
