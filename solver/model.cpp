#include "solver/model.hpp"

#include <algorithm>
#include <map>

#include "scenes/scene_geometry.hpp"
#include "solver/threads.hpp"

namespace fetic::solver {
namespace {

// component_coefficients(mesh, f) is the load itself: e1.f for a bar, (fx, fy) for plane.
// Its fixed-size form: one vector allocated per element corner was most of assembling a
// 1e7-unknown model.
void add_force(const StrutMesh& mesh, Eigen::VectorXd& load, int node, const Vec2& force) {
  const int n = mesh.dofs_per_node;
  load.segment(node * n, n) += component_coefficients3(mesh, force).head(n);
}

// Frame model: point forces and moments at nodes; a per-length load q as consistent
// nodal forces q h/2 and moments +-(q.e2) h^2/12 per element (SCENES.md).
void add_frame_loads(const scenes::Scene& scene, const StrutMesh& mesh, Eigen::VectorXd& load) {
  for (const scenes::Load& item : scene.loads) {
    if (item.strut != mesh.strut) continue;
    const Vec2 force(item.force[0], item.force[1]);
    if (item.per_length) {
      const double h = mesh.length / mesh.nx;
      const double moment = force.dot(mesh.e2) * h * h / 12.0;
      for (int i = 0; i < mesh.nx; ++i) {
        load.segment<2>(3 * i) += force * (0.5 * h);
        load.segment<2>(3 * (i + 1)) += force * (0.5 * h);
        load(3 * i + 2) += moment;
        load(3 * (i + 1) + 2) -= moment;
      }
    } else {
      const int node =
          item.node >= 0 ? item.node : (item.at == scenes::StrutEnd::From ? 0 : mesh.nx);
      load.segment<2>(3 * node) += force;
      load(3 * node + 2) += item.moment;
    }
  }
}

std::vector<int> sorted_along(const StrutMesh& mesh, std::vector<int> face, const Vec2& t) {
  std::stable_sort(face.begin(), face.end(),
                   [&](int p, int q) { return mesh.nodes[p].dot(t) < mesh.nodes[q].dot(t); });
  return face;
}

// Frame model: held DOFs (clamped: all three, pinned: ux and uy; a joint component that
// one of its ends holds is held at every end, since the joint makes them equal), the
// joints, one node pair per contact, and the free motions.
void add_frame_supports_and_joints(const scenes::Scene& scene, Model& model) {
  const int strut_count = static_cast<int>(scene.struts.size());
  std::vector<std::map<int, unsigned>> held(strut_count);
  for (int s = 0; s < strut_count; ++s) {
    const int last = model.struts[s].nx;
    for (int e = 0; e < 2; ++e) {
      const int node = e == 0 ? 0 : last;
      if (model.end_supports[s][e] == Support::Clamped) held[s][node] |= 7u;
      if (model.end_supports[s][e] == Support::Pinned) held[s][node] |= 3u;
    }
  }
  for (const scenes::Joint& joint : scene.joints) {
    JointLink link;
    link.shared = joint.kind == scenes::JointKind::Rigid ? 3 : 2;
    const unsigned shared = (1u << link.shared) - 1u;
    unsigned any = 0;
    for (const scenes::EndRef& end : joint.ends) {
      link.ends.emplace_back(end.strut, scenes::node_index(scene, end));
      const auto it = held[end.strut].find(link.ends.back().second);
      if (it != held[end.strut].end()) any |= it->second & shared;
    }
    if (any)
      for (const auto& [strut, node] : link.ends)
        held[strut][node] |= any;
    model.joints.push_back(std::move(link));
  }
  for (int s = 0; s < strut_count; ++s) {
    std::vector<HeldNode> nodes;
    std::vector<int> clamped;
    for (const auto& [node, components] : held[s]) {
      nodes.push_back({node, components});
      if (components == 7u) clamped.push_back(node);
    }
    model.held_nodes.push_back(std::move(nodes));
    model.clamped_nodes[s] = std::move(clamped);
  }
  for (size_t c = 0; c < scene.contacts.size(); ++c) {
    const scenes::Contact& contact = scene.contacts[c];
    const scenes::FrameContactGeometry geometry = scenes::frame_contact_geometry(scene, contact);
    model.contact_first_pair.push_back(static_cast<int>(model.pairs.size()));
    model.contact_ends.emplace_back(scenes::end_label(scene, contact.a),
                                    scenes::end_label(scene, contact.b));
    model.contact_labels.push_back(model.contact_ends.back().first + " - " +
                                   model.contact_ends.back().second);
    ContactPair pair;
    pair.contact = static_cast<int>(c);
    pair.strut_a = contact.a.strut;
    pair.node_a = scenes::node_index(scene, contact.a);
    pair.strut_b = contact.b.strut;
    pair.node_b = scenes::node_index(scene, contact.b);
    pair.normal = Vec2(geometry.normal[0], geometry.normal[1]);
    pair.gap = std::max(0.0, geometry.gap);
    model.pairs.push_back(pair);
  }
  model.contact_first_pair.push_back(static_cast<int>(model.pairs.size()));
  model.kinematics = scenes::frame_kinematics(scene);
}

}  // namespace

long long Model::dof_count() const {
  long long total = 0;
  for (const StrutMesh& mesh : struts)
    total += mesh.dof_count();
  return total;
}

unsigned Model::held(int strut, int node) const {
  const auto& nodes = held_nodes[strut];
  const auto it = std::lower_bound(nodes.begin(), nodes.end(), node,
                                   [](const HeldNode& h, int n) { return h.node < n; });
  return it != nodes.end() && it->node == node ? it->components : 0u;
}

bool Model::translation_held(int strut, int node) const {
  const unsigned translation = dofs_per_node() == 1 ? 1u : 3u;
  return (held(strut, node) & translation) == translation;
}

std::array<ContactSide, 2> contact_sides(const Model& model, const ContactPair& pair) {
  const StrutMesh& a = model.struts[static_cast<size_t>(pair.strut_a)];
  const StrutMesh& b = model.struts[static_cast<size_t>(pair.strut_b)];
  return {ContactSide{pair.strut_a, pair.node_a, component_coefficients(a, pair.normal)},
          ContactSide{pair.strut_b, pair.node_b, component_coefficients(b, Vec2(-pair.normal))}};
}

Eigen::VectorXd strut_load(const scenes::Scene& scene, const StrutMesh& mesh) {
  Eigen::VectorXd load = Eigen::VectorXd::Zero(mesh.dof_count());
  if (mesh.dofs_per_node == 3) {
    add_frame_loads(scene, mesh, load);
    return load;
  }
  for (const scenes::Load& item : scene.loads) {
    if (item.strut != mesh.strut) continue;
    const Vec2 force(item.force[0], item.force[1]);
    if (!item.per_length) {
      // Uniform traction on the end face: each face segment gives half its share to each
      // of its two nodes (a bar's end face is its single end node).
      const std::vector<int> face = mesh.end_face(item.at);
      if (mesh.ny == 0) {
        add_force(mesh, load, face[0], force);
      } else {
        for (int k = 0; k < mesh.ny; ++k) {
          add_force(mesh, load, face[k], force * (0.5 / mesh.ny));
          add_force(mesh, load, face[k + 1], force * (0.5 / mesh.ny));
        }
      }
    } else if (mesh.ny == 0) {
      // Bar: consistent nodal forces, h/2 to each node of an element.
      const double h = mesh.length / mesh.nx;
      for (int i = 0; i < mesh.nx; ++i) {
        add_force(mesh, load, i, force * (0.5 * h));
        add_force(mesh, load, i + 1, force * (0.5 * h));
      }
    } else {
      // Plane: uniform body force, a quarter of each element's share to each corner.
      const Vec2 share = force * (mesh.length / (static_cast<double>(mesh.nx) * mesh.ny));
      for (int i = 0; i < mesh.nx; ++i)
        for (int k = 0; k < mesh.ny; ++k)
          for (int node :
               {mesh.node(i, k), mesh.node(i + 1, k), mesh.node(i + 1, k + 1), mesh.node(i, k + 1)})
            add_force(mesh, load, node, share * 0.25);
    }
  }
  return load;
}

namespace {

// Each strut's mesh, load and clamped nodes, on the process' threads (each strut alone,
// so the values do not depend on the threads): this serial pass was about 1.3 s of a
// 1e7-unknown run (docs/BENCHMARKS.md, "Outside set-up and solve").
void build_struts(const scenes::Scene& scene, Model& model) {
  const int strut_count = static_cast<int>(scene.struts.size());
  model.struts.resize(static_cast<size_t>(strut_count));
  model.loads.resize(static_cast<size_t>(strut_count));
  model.clamped_nodes.resize(static_cast<size_t>(strut_count));
  long long nodes = 0;
  for (const scenes::Strut& strut : scene.struts)
    nodes += (strut.elements + 1LL) * (std::max(strut.elements_across, 0) + 1LL);
  const int threads = threads_for(nodes);
#pragma omp parallel for num_threads(threads) schedule(dynamic)
  for (int s = 0; s < strut_count; ++s) {
    const scenes::Strut& strut = scene.struts[s];
    StrutMesh& mesh = model.struts[static_cast<size_t>(s)];
    mesh = build_strut_mesh(scene, s);
    model.loads[static_cast<size_t>(s)] = strut_load(scene, mesh);
    std::vector<int>& clamped = model.clamped_nodes[static_cast<size_t>(s)];
    for (scenes::StrutEnd end : {scenes::StrutEnd::From, scenes::StrutEnd::To})
      if (strut.fixed(end))
        for (int node : mesh.end_face(end))
          clamped.push_back(node);
    std::sort(clamped.begin(), clamped.end());
    clamped.erase(std::unique(clamped.begin(), clamped.end()), clamped.end());
  }
}

}  // namespace

Model build_model(const scenes::Scene& scene) {
  Model model;
  model.kind = scene.model;
  model.path = scene.path;
  model.title = scene.title;
  model.units = scene.units;
  model.scene_loads = scene.loads;
  build_struts(scene, model);
  for (const scenes::Strut& strut : scene.struts) {
    model.strut_names.push_back(strut.name);
    model.end_supports.push_back({strut.fixed(scenes::StrutEnd::From)    ? Support::Clamped
                                  : strut.pinned(scenes::StrutEnd::From) ? Support::Pinned
                                                                         : Support::None,
                                  strut.fixed(scenes::StrutEnd::To)    ? Support::Clamped
                                  : strut.pinned(scenes::StrutEnd::To) ? Support::Pinned
                                                                       : Support::None});
  }
  if (model.frame()) {
    add_frame_supports_and_joints(scene, model);
    return model;
  }
  const unsigned all = (1u << model.dofs_per_node()) - 1u;
  for (const auto& clamped : model.clamped_nodes) {
    std::vector<HeldNode> held;
    for (int node : clamped)
      held.push_back({node, all});
    model.held_nodes.push_back(std::move(held));
  }
  for (size_t c = 0; c < scene.contacts.size(); ++c) {
    const scenes::Contact& contact = scene.contacts[c];
    const scenes::ContactGeometry geometry = scenes::contact_geometry(scene, contact);
    const Vec2 n(geometry.normal[0], geometry.normal[1]);
    const Vec2 t(-n.y(), n.x());
    const StrutMesh& a = model.struts[contact.a.strut];
    const StrutMesh& b = model.struts[contact.b.strut];
    const std::vector<int> face_a = sorted_along(a, a.end_face(contact.a.end), t);
    const std::vector<int> face_b = sorted_along(b, b.end_face(contact.b.end), t);
    model.contact_first_pair.push_back(static_cast<int>(model.pairs.size()));
    model.contact_ends.emplace_back(scenes::end_label(scene, contact.a),
                                    scenes::end_label(scene, contact.b));
    model.contact_labels.push_back(model.contact_ends.back().first + " - " +
                                   model.contact_ends.back().second);
    for (size_t p = 0; p < face_a.size(); ++p) {
      ContactPair pair;
      pair.contact = static_cast<int>(c);
      pair.pair = static_cast<int>(p);
      pair.strut_a = contact.a.strut;
      pair.node_a = face_a[p];
      pair.strut_b = contact.b.strut;
      pair.node_b = face_b[p];
      pair.normal = n;
      // Gap of the node pair along n in the reference configuration; for collinear
      // facing end faces it equals the gap of the end points (rounding taken as zero).
      const double gap = (b.nodes[pair.node_b] - a.nodes[pair.node_a]).dot(n);
      pair.gap = std::max(0.0, std::abs(gap - geometry.gap) <= 1e-9 * std::max(a.length, b.length)
                                   ? geometry.gap
                                   : gap);
      model.pairs.push_back(pair);
    }
  }
  model.contact_first_pair.push_back(static_cast<int>(model.pairs.size()));
  return model;
}

}  // namespace fetic::solver
