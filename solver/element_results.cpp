#include "solver/element_results.hpp"

#include <cmath>
#include <limits>

#include "solver/decomposition.hpp"
#include "solver/method.hpp"
#include "solver/stiffness.hpp"
#include "solver/threads.hpp"

namespace fetic::solver {
namespace {

void put_node_dofs(const StrutMesh& mesh, const Vec2& u, double* node_dofs);

}  // namespace

Eigen::VectorXd piece_dofs(const StrutMesh& mesh, const Piece& piece) {
  const int d = mesh.dofs_per_node;
  Eigen::VectorXd dofs = Eigen::VectorXd::Zero(piece.box.node_count() * d);
  for (int local = 0; local < piece.box.node_count(); ++local) {
    put_node_dofs(mesh, piece.displacement[static_cast<size_t>(local)], dofs.data() + local * d);
    if (d == 3 && static_cast<size_t>(local) < piece.rotation.size())  // frame: the rotation
      dofs(local * d + 2) = piece.rotation[static_cast<size_t>(local)];
  }
  return dofs;
}

namespace {

bool is_plane(const StrutMesh& mesh) {
  return mesh.ny > 0;
}

// Per strut node: 1 when all its DOFs are clamped.
std::vector<char> clamped_flags(const Model& model, int strut) {
  std::vector<char> flags(static_cast<size_t>(model.struts[strut].node_count()), 0);
  for (int node : model.clamped_nodes[strut])
    flags[static_cast<size_t>(node)] = 1;
  return flags;
}

// The DOFs of one node from its displacement vector (the inverse of node_displacement).
void put_node_dofs(const StrutMesh& mesh, const Vec2& u, double* node_dofs) {
  if (mesh.dofs_per_node == 1) {
    node_dofs[0] = u.dot(mesh.e1);
  } else {
    node_dofs[0] = u.x();
    node_dofs[1] = u.y();
  }
}

// piece_dofs with the clamped nodes exactly zero.
Eigen::VectorXd clamped_piece_dofs(const StrutMesh& mesh, const Piece& piece,
                                   const std::vector<char>& clamped) {
  const int d = mesh.dofs_per_node;
  Eigen::VectorXd dofs = piece_dofs(mesh, piece);
  for (int i = piece.box.i0; i <= piece.box.i1; ++i)
    for (int k = piece.box.k0; k <= piece.box.k1; ++k)
      if (clamped[static_cast<size_t>(mesh.node(i, k))])
        dofs.segment(piece.box.local(i, k) * d, d).setZero();
  return dofs;
}

// Element index within its strut: i along (bar), i * ny + k (plane).
int element_index(const StrutMesh& mesh, int i, int k) {
  return is_plane(mesh) ? i * mesh.ny + k : i;
}

// Connectivity and subdomains only: the value fields stay empty.
StrutElements shape(const StrutMesh& mesh, int first_subdomain) {
  StrutElements elements;
  const bool plane = is_plane(mesh);
  elements.nodes_per_element = plane ? 4 : 2;
  const int count = plane ? mesh.nx * mesh.ny : mesh.nx;
  elements.connectivity.reserve(static_cast<size_t>(count * elements.nodes_per_element));
  for (int i = 0; i < mesh.nx; ++i) {
    if (!plane) {
      elements.connectivity.insert(elements.connectivity.end(), {i, i + 1});
      continue;
    }
    for (int k = 0; k < mesh.ny; ++k)
      elements.connectivity.insert(
          elements.connectivity.end(),
          {mesh.node(i, k), mesh.node(i + 1, k), mesh.node(i + 1, k + 1), mesh.node(i, k + 1)});
  }
  // Subdomains as decompose() numbers them: boxes along, then across within each.
  elements.subdomain.assign(static_cast<size_t>(count), 0);
  const auto along = split_nodes(mesh.nx, mesh.subdomains_along);
  const auto across = plane ? split_nodes(mesh.ny, mesh.subdomains_across)
                            : std::vector<std::pair<int, int>>{{0, 1}};
  int index = first_subdomain;
  for (const auto& [i0, i1] : along)
    for (const auto& [k0, k1] : across) {
      for (int i = i0; i < i1; ++i)
        for (int k = k0; k < k1; ++k)
          elements.subdomain[static_cast<size_t>(element_index(mesh, i, k))] = index;
      ++index;
    }
  return elements;
}

StrutElements topology(const StrutMesh& mesh, int first_subdomain) {
  StrutElements elements = shape(mesh, first_subdomain);
  const bool plane = is_plane(mesh);
  const int count = elements.element_count();
  const std::vector<std::string> stress_names =
      plane ? std::vector<std::string>{"axial", "sxx", "syy", "sxy", "von_mises"}
            : std::vector<std::string>{"axial"};
  for (const std::string& name : stress_names)
    elements.stress.push_back({name, std::vector<double>(static_cast<size_t>(count), 0.0)});
  elements.resultants.push_back(
      {"axial_force", std::vector<double>(static_cast<size_t>(count), 0.0)});
  if (mesh.dofs_per_node == 3)  // frame: the bending moment at the element's middle
    elements.resultants.push_back(
        {"bending_moment", std::vector<double>(static_cast<size_t>(count), 0.0)});
  return elements;
}

int subdomains_of(const StrutMesh& mesh) {
  return mesh.subdomains_along * (is_plane(mesh) ? mesh.subdomains_across : 1);
}

// Per strut, the number of its first subdomain (the subdomains numbered strut by strut).
std::vector<int> first_subdomains(const Model& model) {
  std::vector<int> first;
  int next = 0;
  for (const StrutMesh& mesh : model.struts) {
    first.push_back(next);
    next += subdomains_of(mesh);
  }
  return first;
}

// Bar: axial stress E (u_{i+1} - u_i) / h and axial force stress * area.
void recover_bar(const StrutMesh& mesh, const NodeBox& box, const Eigen::VectorXd& dofs,
                 StrutElements& out) {
  const double h = mesh.length / mesh.nx;
  for (int i = box.i0; i < box.i1; ++i) {
    const double stress = mesh.E * (dofs(box.local(i + 1, 0)) - dofs(box.local(i, 0))) / h;
    out.stress[0].values[static_cast<size_t>(i)] = stress;
    out.resultants[0].values[static_cast<size_t>(i)] = stress * mesh.area;
  }
}

// Plane: stresses at the element centre; the axial force is the axial stress times the
// element's share of the cross-section (thickness * height / elements_across), so the
// elements of one station add up to the strut's axial force there.
void recover_plane(const StrutMesh& mesh, const NodeBox& box, const Eigen::VectorXd& dofs,
                   StrutElements& out) {
  const Vec2& e = mesh.e1;
  const double share = mesh.thickness * mesh.height / mesh.ny;
  for (int i = box.i0; i < box.i1; ++i)
    for (int k = box.k0; k < box.k1; ++k) {
      Eigen::Matrix<double, 8, 1> corners;
      const int nodes[4] = {box.local(i, k), box.local(i + 1, k), box.local(i + 1, k + 1),
                            box.local(i, k + 1)};
      for (int a = 0; a < 4; ++a) {
        corners(2 * a) = dofs(2 * nodes[a]);
        corners(2 * a + 1) = dofs(2 * nodes[a] + 1);
      }
      const Eigen::Vector3d s = quad_centre_stress(mesh, i, k, corners);
      const double axial = s(0) * e.x() * e.x() + s(1) * e.y() * e.y() + 2.0 * s(2) * e.x() * e.y();
      const double von_mises = std::sqrt(s(0) * s(0) - s(0) * s(1) + s(1) * s(1) + 3 * s(2) * s(2));
      const auto at = static_cast<size_t>(element_index(mesh, i, k));
      out.stress[0].values[at] = axial;
      out.stress[1].values[at] = s(0);
      out.stress[2].values[at] = s(1);
      out.stress[3].values[at] = s(2);
      out.stress[4].values[at] = von_mises;
      out.resultants[0].values[at] = axial * share;
    }
}

// Frame: axial stress and force as a bar's, and the bending moment (sagging positive) at
// the element's middle (the mean of its two end moments; exact for end loads).
void recover_frame(const StrutMesh& mesh, const NodeBox& box, const Eigen::VectorXd& dofs,
                   StrutElements& out) {
  const BeamForces forces = beam_forces(mesh, box, dofs);
  for (int i = box.i0; i < box.i1; ++i) {
    const auto at = static_cast<size_t>(i);
    out.resultants[0].values[at] = forces.axial(i - box.i0);
    out.stress[0].values[at] = forces.axial(i - box.i0) / mesh.area;
    out.resultants[1].values[at] =
        0.5 * (forces.moment(i - box.i0, 0) + forces.moment(i - box.i0, 1));
  }
}

}  // namespace

StrutResults::StrutResults(const Model& model, const Snapshot& snapshot)
    : model_(model),
      snapshot_(snapshot),
      pieces_(pieces_by_strut(model, snapshot)),
      first_subdomain_(first_subdomains(model)) {}

std::vector<Vec2> StrutResults::displacements(int strut) const {
  return strut_displacements(model_, snapshot_, strut, pieces_[static_cast<size_t>(strut)]);
}

std::vector<double> StrutResults::rotations(int strut) const {
  return strut_rotations(model_, snapshot_, strut, pieces_[static_cast<size_t>(strut)]);
}

StrutElements StrutResults::topology(int strut) const {
  const auto at = static_cast<size_t>(strut);
  return fetic::solver::topology(model_.struts[at], first_subdomain_[at]);
}

StrutElements StrutResults::shape(int strut) const {
  const auto at = static_cast<size_t>(strut);
  return fetic::solver::shape(model_.struts[at], first_subdomain_[at]);
}

StrutElements StrutResults::elements(int strut) const {
  StrutElements out = topology(strut);
  const StrutMesh& mesh = model_.struts[static_cast<size_t>(strut)];
  const std::vector<char> clamped = clamped_flags(model_, strut);
  const std::vector<int>& pieces = pieces_[static_cast<size_t>(strut)];
  if (mesh.dofs_per_node != 1 && !is_plane(mesh) && mesh.dofs_per_node != 3) {
    // A model without a recovery here yet: its values are unknown, not zero.
    for (auto* fields : {&out.stress, &out.resultants})
      for (NamedValues& field : *fields)
        field.values.assign(field.values.size(), std::numeric_limits<double>::quiet_NaN());
    return out;
  }
  // Each piece writes the elements of its own box: the pieces run on the process' threads
  // (a plane strut of a 1e7-unknown scene has 192 pieces and 190,000 elements, and every
  // output asks for them).
  const int threads = threads_for(static_cast<long long>(out.element_count()));
#pragma omp parallel for num_threads(threads) schedule(dynamic)
  for (size_t at = 0; at < pieces.size(); ++at) {
    const Piece& piece = snapshot_.pieces[static_cast<size_t>(pieces[at])];
    const Eigen::VectorXd dofs = clamped_piece_dofs(mesh, piece, clamped);
    if (mesh.dofs_per_node == 1) {
      recover_bar(mesh, piece.box, dofs, out);
    } else if (is_plane(mesh)) {
      recover_plane(mesh, piece.box, dofs, out);
    } else {
      recover_frame(mesh, piece.box, dofs, out);
    }
  }
  return out;
}

std::vector<StrutElements> element_topology(const Model& model) {
  const std::vector<int> first = first_subdomains(model);
  std::vector<StrutElements> result;
  for (size_t s = 0; s < model.struts.size(); ++s)
    result.push_back(topology(model.struts[s], first[s]));
  return result;
}

std::vector<StrutElements> element_results(const Model& model, const Snapshot& snapshot) {
  const StrutResults results(model, snapshot);
  std::vector<StrutElements> all;
  all.reserve(model.struts.size());
  for (size_t s = 0; s < model.struts.size(); ++s)
    all.push_back(results.elements(static_cast<int>(s)));
  return all;
}

namespace {

BeamMoments beam_moments(const StrutMesh& mesh, int strut, const NodeBox& box,
                         const Eigen::VectorXd& dofs) {
  BeamMoments moments;
  moments.strut = strut;
  moments.first_element = box.i0;
  if (mesh.dofs_per_node != 3) return moments;
  const BeamForces forces = beam_forces(mesh, box, dofs);
  for (Eigen::Index e = 0; e < forces.moment.rows(); ++e)
    moments.ends.push_back({forces.moment(e, 0), forces.moment(e, 1)});
  return moments;
}

}  // namespace

std::vector<BeamMoments> piece_moments(const Model& model, const Snapshot& snapshot) {
  std::vector<BeamMoments> result;
  result.reserve(snapshot.pieces.size());
  for (const Piece& piece : snapshot.pieces) {
    const StrutMesh& mesh = model.struts[static_cast<size_t>(piece.strut)];
    if (mesh.dofs_per_node != 3) {
      result.push_back({piece.strut, piece.box.i0, {}});
      continue;
    }
    const Eigen::VectorXd dofs = clamped_piece_dofs(mesh, piece, clamped_flags(model, piece.strut));
    result.push_back(beam_moments(mesh, piece.strut, piece.box, dofs));
  }
  return result;
}

std::vector<BeamMoments> strut_moments(const Model& model, const Snapshot& snapshot) {
  std::vector<BeamMoments> result;
  const std::vector<Eigen::VectorXd> dofs = strut_dofs(model, snapshot);
  for (size_t s = 0; s < model.struts.size(); ++s)
    result.push_back(
        beam_moments(model.struts[s], static_cast<int>(s), whole_strut(model.struts[s]), dofs[s]));
  return result;
}

std::vector<Eigen::VectorXd> strut_dofs(const Model& model, const Snapshot& snapshot) {
  const std::vector<std::vector<Vec2>> u = strut_displacements(model, snapshot);
  const std::vector<std::vector<double>> rotations =
      model.frame() ? strut_rotations(model, snapshot) : std::vector<std::vector<double>>{};
  std::vector<Eigen::VectorXd> dofs;
  for (size_t s = 0; s < model.struts.size(); ++s) {
    const StrutMesh& mesh = model.struts[s];
    Eigen::VectorXd v = Eigen::VectorXd::Zero(mesh.dof_count());
    for (int n = 0; n < mesh.node_count(); ++n) {
      put_node_dofs(mesh, u[s][static_cast<size_t>(n)], v.data() + n * mesh.dofs_per_node);
      if (mesh.dofs_per_node == 3) v(n * 3 + 2) = rotations[s][static_cast<size_t>(n)];
    }
    for (int node : model.clamped_nodes[s])
      v.segment(node * mesh.dofs_per_node, mesh.dofs_per_node).setZero();
    dofs.push_back(std::move(v));
  }
  return dofs;
}

std::vector<Eigen::VectorXd> contact_nodal_forces(const Model& model, const Snapshot& snapshot) {
  std::vector<Eigen::VectorXd> forces;
  for (const StrutMesh& mesh : model.struts)
    forces.push_back(Eigen::VectorXd::Zero(mesh.dof_count()));
  for (size_t p = 0; p < model.pairs.size() && p < snapshot.force.size(); ++p) {
    const ContactPair& pair = model.pairs[p];
    const double lambda = snapshot.force[p];
    if (lambda == 0.0) continue;
    // The force lambda pushes the two sides apart: minus lambda times the row on each.
    for (const ContactSide& side : contact_sides(model, pair)) {
      const StrutMesh& mesh = model.struts[static_cast<size_t>(side.strut)];
      forces[static_cast<size_t>(side.strut)].segment(
          side.node * mesh.dofs_per_node, mesh.dofs_per_node) -= lambda * side.coefficients;
    }
  }
  return forces;
}

std::vector<SupportReaction> support_reactions(const Model& model, const Snapshot& snapshot) {
  std::vector<SupportReaction> reactions;
  const std::vector<Eigen::VectorXd> u = strut_dofs(model, snapshot);
  const std::vector<Eigen::VectorXd> contact = contact_nodal_forces(model, snapshot);
  for (size_t s = 0; s < model.struts.size(); ++s) {
    const StrutMesh& mesh = model.struts[s];
    const int d = mesh.dofs_per_node;
    for (const scenes::StrutEnd end : {scenes::StrutEnd::From, scenes::StrutEnd::To}) {
      const int station = end == scenes::StrutEnd::From ? 0 : mesh.nx;
      SupportReaction reaction;
      reaction.strut = static_cast<int>(s);
      reaction.end = end;
      for (int node : model.clamped_nodes[s])
        if (node / mesh.nodes_across() == station) reaction.nodes.push_back(node);
      if (reaction.nodes.empty()) continue;
      // K u at the end's nodes needs only the layer of elements touching them.
      const int i0 = end == scenes::StrutEnd::From ? 0 : mesh.nx - 1;
      const NodeBox box{i0, i0 + 1, 0, mesh.ny};
      Eigen::VectorXd u_box(box.node_count() * d);
      for (int i = box.i0; i <= box.i1; ++i)
        for (int k = box.k0; k <= box.k1; ++k)
          u_box.segment(box.local(i, k) * d, d) = u[s].segment(mesh.node(i, k) * d, d);
      const Eigen::VectorXd ku = assemble_stiffness(mesh, box) * u_box;
      for (int node : reaction.nodes) {
        const int local = box.local(station, node % mesh.nodes_across());
        const Eigen::VectorXd r = ku.segment(local * d, d) -
                                  snapshot.load_factor * model.loads[s].segment(node * d, d) -
                                  contact[s].segment(node * d, d);
        const Vec2 force = node_displacement(mesh, r.data());
        reaction.node_forces.push_back(force);
        reaction.force += force;
      }
      reactions.push_back(std::move(reaction));
    }
  }
  return reactions;
}

}  // namespace fetic::solver
