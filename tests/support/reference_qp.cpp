#include "tests/support/reference_qp.hpp"

#include <cmath>
#include <map>

#include "tests/support/reference_qp_parts.hpp"

namespace fetic::testing {
namespace {

using Vec = std::array<double, 2>;

double dot(Vec a, Vec b) {
  return a[0] * b[0] + a[1] * b[1];
}

// Bar model straight from the contract: nodes at equal spacing from 'from' to 'to', one
// axial DOF each, elements of stiffness E*area/h.
struct BarStrut {
  Vec from, axis;
  double length, h, k;
  int nodes;
  int first_dof = 0;  // within its group
};

BarStrut describe(const scenes::Strut& s) {
  BarStrut b;
  b.from = {s.from[0], s.from[1]};
  const double dx = s.to[0] - s.from[0], dy = s.to[1] - s.from[1];
  b.length = std::sqrt(dx * dx + dy * dy);
  b.axis = {dx / b.length, dy / b.length};
  b.h = b.length / s.elements;
  b.k = s.E * s.area / b.h;
  b.nodes = s.elements + 1;
  return b;
}

}  // namespace

ReferenceSolution solve_plane_reference_qp(const scenes::Scene& scene, double load_factor);
ReferenceSolution solve_frame_reference_qp(const scenes::Scene& scene, double load_factor);

ReferenceSolution solve_reference_qp(const scenes::Scene& scene, double load_factor) {
  if (scene.model == scenes::ModelKind::Plane) return solve_plane_reference_qp(scene, load_factor);
  if (scene.model == scenes::ModelKind::Frame) return solve_frame_reference_qp(scene, load_factor);
  const int strut_count = static_cast<int>(scene.struts.size());
  std::vector<BarStrut> bars;
  for (const scenes::Strut& s : scene.struts)
    bars.push_back(describe(s));

  // Groups of struts connected by contacts are independent problems.
  scenes::UnionFind sets(strut_count);
  for (const scenes::Contact& c : scene.contacts)
    sets.join(c.a.strut, c.b.strut);

  ReferenceSolution solution;
  solution.optimal = true;
  solution.displacement.resize(strut_count);
  solution.force.assign(scene.contacts.size(), 0.0);

  for (const std::vector<int>& members : groups_of(sets, strut_count)) {
    const int group = sets.root(members[0]);
    int dofs = 0;
    for (int s : members) {
      bars[s].first_dof = dofs;
      dofs += bars[s].nodes;
    }
    CGAL::Quadratic_program<double> qp(CGAL::SMALLER, false, 0, false, 0);
    std::map<std::pair<int, int>, double> D;  // lower triangle of K
    std::vector<double> f(dofs, 0.0);
    for (int s : members) {
      const scenes::Strut& strut = scene.struts[s];
      const BarStrut& b = bars[s];
      for (int e = 0; e + 1 < b.nodes; ++e) {
        const int i = b.first_dof + e, j = i + 1;
        D[{i, i}] += b.k;
        D[{j, j}] += b.k;
        D[{j, i}] -= b.k;
      }
      if (strut.fixed_from) {
        qp.set_l(b.first_dof, true, 0.0);
        qp.set_u(b.first_dof, true, 0.0);
      }
      if (strut.fixed_to) {
        qp.set_l(b.first_dof + b.nodes - 1, true, 0.0);
        qp.set_u(b.first_dof + b.nodes - 1, true, 0.0);
      }
      for (const scenes::Load& load : scene.loads) {
        if (load.strut != s) continue;
        const double axial = dot({load.force[0], load.force[1]}, b.axis);
        if (load.per_length) {
          for (int e = 0; e + 1 < b.nodes; ++e) {
            f[b.first_dof + e] += 0.5 * b.h * axial;
            f[b.first_dof + e + 1] += 0.5 * b.h * axial;
          }
        } else {
          f[b.first_dof + (load.at == scenes::StrutEnd::From ? 0 : b.nodes - 1)] += axial;
        }
      }
    }
    // 1/2 u'K u as CGAL's x'D x: set_d takes 2 D_ij = K_ij.
    for (const auto& [ij, value] : D)
      qp.set_d(ij.first, ij.second, value);
    for (int i = 0; i < dofs; ++i)
      qp.set_c(i, -load_factor * f[i]);

    std::vector<int> rows;  // contact index of each constraint
    for (size_t c = 0; c < scene.contacts.size(); ++c) {
      const scenes::Contact& contact = scene.contacts[c];
      if (sets.root(contact.a.strut) != group) continue;
      const BarStrut& a = bars[contact.a.strut];
      const BarStrut& b = bars[contact.b.strut];
      const bool a_to = contact.a.end == scenes::StrutEnd::To;
      const bool b_to = contact.b.end == scenes::StrutEnd::To;
      const Vec n = a_to ? a.axis : Vec{-a.axis[0], -a.axis[1]};
      const Vec pa =
          a_to ? Vec{a.from[0] + a.length * a.axis[0], a.from[1] + a.length * a.axis[1]} : a.from;
      const Vec pb =
          b_to ? Vec{b.from[0] + b.length * b.axis[0], b.from[1] + b.length * b.axis[1]} : b.from;
      double gap = dot({pb[0] - pa[0], pb[1] - pa[1]}, n);
      if (gap < 0.0 && gap > -1e-9 * std::max(a.length, b.length)) gap = 0.0;
      const int row = static_cast<int>(rows.size());
      const int dof_a = a.first_dof + (a_to ? a.nodes - 1 : 0);
      const int dof_b = b.first_dof + (b_to ? b.nodes - 1 : 0);
      qp.set_a(dof_a, row, dot(a.axis, n));
      qp.set_a(dof_b, row, -dot(b.axis, n));
      qp.set_b(row, gap);
      rows.push_back(static_cast<int>(c));
    }

    const ExactSolution exact = solve_exact(qp, dofs, static_cast<int>(rows.size()));
    if (!exact.optimal) {
      solution.optimal = false;
      continue;
    }
    for (int s : members) {
      const BarStrut& b = bars[s];
      for (int i = 0; i < b.nodes; ++i) {
        const double value = exact.x(b.first_dof + i);
        solution.displacement[s].push_back({value * b.axis[0], value * b.axis[1]});
      }
    }
    for (size_t row = 0; row < rows.size(); ++row)
      solution.force[rows[row]] = exact.multipliers[row];
  }
  return solution;
}

}  // namespace fetic::testing
