// The plane model's reference: assembled here from SCENES.md with its own element code
// (bilinear rectangle in its local frame, 3x3 Gauss, then rotated - not the solver's
// isoparametric 2x2 routine), condensed onto the DOFs of the contact faces (dense
// Cholesky of the interior), and the condensed QP solved exactly by CGAL.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "tests/support/reference_qp.hpp"
#include "tests/support/reference_qp_parts.hpp"

namespace fetic::testing {
namespace {

struct PlaneStrut {
  Eigen::Vector2d from, e1, e2;
  double length, height;
  int nx, ny;
  int first_dof = 0;
  int node(int i, int k) const { return i * (ny + 1) + k; }
  int nodes() const { return (nx + 1) * (ny + 1); }
  Eigen::Vector2d position(int i, int k) const {
    return from + (length * i / nx) * e1 + (-0.5 * height + height * k / ny) * e2;
  }
};

PlaneStrut describe(const scenes::Strut& s) {
  PlaneStrut p;
  p.from = {s.from[0], s.from[1]};
  const Eigen::Vector2d to(s.to[0], s.to[1]);
  p.length = (to - p.from).norm();
  p.e1 = (to - p.from) / p.length;
  p.e2 = {-p.e1.y(), p.e1.x()};
  p.height = s.height;
  p.nx = s.elements;
  p.ny = s.elements_across;
  return p;
}

// Stiffness of an a x b rectangle in plane stress, local axes, corners counterclockwise
// from (0,0); 3x3 Gauss-Legendre.
Eigen::Matrix<double, 8, 8> rectangle_stiffness(double a, double b, double E, double nu, double t) {
  Eigen::Matrix3d D;
  D << 1, nu, 0, nu, 1, 0, 0, 0, (1 - nu) / 2;
  D *= E / (1 - nu * nu);
  const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
  Eigen::Matrix<double, 8, 8> K = Eigen::Matrix<double, 8, 8>::Zero();
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) {
      Eigen::Matrix<double, 3, 8> B = Eigen::Matrix<double, 3, 8>::Zero();
      for (int n = 0; n < 4; ++n) {
        const double dx = sx[n] * (1 + sy[n] * g[q]) / 4 * (2 / a);
        const double dy = sy[n] * (1 + sx[n] * g[p]) / 4 * (2 / b);
        B(0, 2 * n) = dx;
        B(1, 2 * n + 1) = dy;
        B(2, 2 * n) = dy;
        B(2, 2 * n + 1) = dx;
      }
      K += B.transpose() * D * B * (w[p] * w[q] * a * b / 4 * t);
    }
  return K;
}

}  // namespace

ReferenceSolution solve_plane_reference_qp(const scenes::Scene& scene, double load_factor) {
  const int strut_count = static_cast<int>(scene.struts.size());
  std::vector<PlaneStrut> struts;
  for (const scenes::Strut& s : scene.struts)
    struts.push_back(describe(s));

  scenes::UnionFind sets(strut_count);
  for (const scenes::Contact& c : scene.contacts)
    sets.join(c.a.strut, c.b.strut);

  ReferenceSolution solution;
  solution.optimal = true;
  solution.displacement.resize(strut_count);
  // Pairs are numbered in scene order: contact by contact, pair by pair.
  std::vector<int> first_pair;
  int pair_count = 0;
  for (const scenes::Contact& c : scene.contacts) {
    first_pair.push_back(pair_count);
    pair_count += scene.struts[c.a.strut].elements_across + 1;
  }
  solution.force.assign(pair_count, 0.0);

  for (const std::vector<int>& members : groups_of(sets, strut_count)) {
    const int group = sets.root(members[0]);
    int dofs = 0;
    for (int s : members) {
      struts[s].first_dof = dofs;
      dofs += 2 * struts[s].nodes();
    }
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(dofs, dofs);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs);
    std::vector<char> clamped(dofs, 0);
    for (int s : members) {
      const scenes::Strut& strut = scene.struts[s];
      const PlaneStrut& p = struts[s];
      const double a = p.length / p.nx, b = p.height / p.ny;
      Eigen::Matrix<double, 8, 8> T = Eigen::Matrix<double, 8, 8>::Zero();  // local -> global
      for (int n = 0; n < 4; ++n) {
        T.block<2, 2>(2 * n, 2 * n) << p.e1.x(), p.e1.y(), p.e2.x(), p.e2.y();
      }
      const Eigen::Matrix<double, 8, 8> Ke =
          T.transpose() * rectangle_stiffness(a, b, strut.E, strut.nu, strut.thickness) * T;
      for (int i = 0; i < p.nx; ++i)
        for (int k = 0; k < p.ny; ++k) {
          const int corner[4] = {p.node(i, k), p.node(i + 1, k), p.node(i + 1, k + 1),
                                 p.node(i, k + 1)};
          for (int m = 0; m < 4; ++m)
            for (int n = 0; n < 4; ++n)
              K.block<2, 2>(p.first_dof + 2 * corner[m], p.first_dof + 2 * corner[n]) +=
                  Ke.block<2, 2>(2 * m, 2 * n);
        }
      for (int k = 0; k <= p.ny; ++k) {
        if (strut.fixed_from)
          clamped[p.first_dof + 2 * p.node(0, k)] = clamped[p.first_dof + 2 * p.node(0, k) + 1] = 1;
        if (strut.fixed_to)
          clamped[p.first_dof + 2 * p.node(p.nx, k)] =
              clamped[p.first_dof + 2 * p.node(p.nx, k) + 1] = 1;
      }
      for (const scenes::Load& load : scene.loads) {
        if (load.strut != s) continue;
        const Eigen::Vector2d force(load.force[0], load.force[1]);
        if (load.per_length) {
          const Eigen::Vector2d quarter = force * p.length / (p.nx * p.ny) / 4;
          for (int i = 0; i < p.nx; ++i)
            for (int k = 0; k < p.ny; ++k)
              for (int node :
                   {p.node(i, k), p.node(i + 1, k), p.node(i + 1, k + 1), p.node(i, k + 1)})
                f.segment<2>(p.first_dof + 2 * node) += quarter;
        } else {
          const int i = load.at == scenes::StrutEnd::From ? 0 : p.nx;
          for (int k = 0; k < p.ny; ++k) {
            f.segment<2>(p.first_dof + 2 * p.node(i, k)) += force / p.ny / 2;
            f.segment<2>(p.first_dof + 2 * p.node(i, k + 1)) += force / p.ny / 2;
          }
        }
      }
    }
    f *= load_factor;

    // Contact rows over the group's DOFs.
    std::vector<ContactRow> rows;
    std::vector<char> on_contact(dofs, 0);
    for (size_t c = 0; c < scene.contacts.size(); ++c) {
      const scenes::Contact& contact = scene.contacts[c];
      if (sets.root(contact.a.strut) != group) continue;
      const PlaneStrut& A = struts[contact.a.strut];
      const PlaneStrut& B = struts[contact.b.strut];
      const bool a_to = contact.a.end == scenes::StrutEnd::To;
      const bool b_to = contact.b.end == scenes::StrutEnd::To;
      const Eigen::Vector2d n = a_to ? A.e1 : Eigen::Vector2d(-A.e1);
      const Eigen::Vector2d t(-n.y(), n.x());
      auto face = [&](const PlaneStrut& P, bool to) {
        std::vector<std::pair<double, int>> nodes;  // (coordinate along t, node)
        for (int k = 0; k <= P.ny; ++k) {
          const int i = to ? P.nx : 0;
          nodes.emplace_back(P.position(i, k).dot(t), P.node(i, k));
        }
        std::sort(nodes.begin(), nodes.end());
        return nodes;
      };
      const auto fa = face(A, a_to), fb = face(B, b_to);
      const Eigen::Vector2d end_a = a_to ? Eigen::Vector2d(A.from + A.length * A.e1) : A.from;
      const Eigen::Vector2d end_b = b_to ? Eigen::Vector2d(B.from + B.length * B.e1) : B.from;
      double gap = (end_b - end_a).dot(n);
      if (gap < 0.0 && gap > -1e-9 * std::max(A.length, B.length)) gap = 0.0;
      for (size_t q = 0; q < fa.size(); ++q) {
        ContactRow row{first_pair[c] + static_cast<int>(q), {}, gap};
        const int da = A.first_dof + 2 * fa[q].second, db = B.first_dof + 2 * fb[q].second;
        for (int comp = 0; comp < 2; ++comp) {
          if (!clamped[da + comp]) row.entries.emplace_back(da + comp, n(comp));
          if (!clamped[db + comp]) row.entries.emplace_back(db + comp, -n(comp));
          on_contact[da + comp] = on_contact[db + comp] = 1;
        }
        rows.push_back(row);
      }
    }

    // Condense onto the free DOFs of the contact faces.
    std::vector<int> c_dofs, i_dofs, c_pos(dofs, -1);
    for (int dof = 0; dof < dofs; ++dof) {
      if (clamped[dof]) continue;
      if (on_contact[dof]) {
        c_pos[dof] = static_cast<int>(c_dofs.size());
        c_dofs.push_back(dof);
      } else {
        i_dofs.push_back(dof);
      }
    }
    const Condensation condensed(K, f, c_dofs, i_dofs);
    const Eigen::MatrixXd& S = condensed.S();
    CGAL::Quadratic_program<double> qp(CGAL::SMALLER, false, 0, false, 0);
    for (int x = 0; x < S.rows(); ++x)
      for (int y = 0; y <= x; ++y)
        qp.set_d(x, y, S(x, y));
    for (int x = 0; x < condensed.g().size(); ++x)
      qp.set_c(x, -condensed.g()(x));
    for (size_t r = 0; r < rows.size(); ++r) {
      for (const auto& [dof, value] : rows[r].entries)
        qp.set_a(c_pos[dof], static_cast<int>(r), value);
      qp.set_b(static_cast<int>(r), rows[r].gap);
    }
    Eigen::VectorXd uc = Eigen::VectorXd::Zero(c_dofs.size());
    if (!c_dofs.empty()) {
      const int kept = static_cast<int>(c_dofs.size());
      const ExactSolution exact = solve_exact(qp, kept, static_cast<int>(rows.size()));
      if (!exact.optimal) {
        solution.optimal = false;
        continue;
      }
      uc = exact.x;
      for (size_t r = 0; r < rows.size(); ++r)
        solution.force[rows[r].index] = exact.multipliers[r];
    }
    const Eigen::VectorXd ui = condensed.interior(uc);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(dofs);
    for (size_t x = 0; x < c_dofs.size(); ++x)
      u(c_dofs[x]) = uc(x);
    for (size_t x = 0; x < i_dofs.size(); ++x)
      u(i_dofs[x]) = ui(x);
    for (int s : members)
      for (int node = 0; node < struts[s].nodes(); ++node)
        solution.displacement[s].push_back(
            {u(struts[s].first_dof + 2 * node), u(struts[s].first_dof + 2 * node + 1)});
  }
  return solution;
}

}  // namespace fetic::testing
