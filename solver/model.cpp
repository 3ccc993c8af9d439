#include "solver/model.hpp"

#include <algorithm>

#include "scenes/scene_geometry.hpp"

namespace fetic::solver {
namespace {

void add_force(const StrutMesh& mesh, Eigen::VectorXd& load, int node, const Vec2& force) {
  const Eigen::VectorXd c = component_coefficients(mesh, force);
  // component_coefficients(mesh, f) is the load itself: e1.f for a bar, (fx, fy) for plane.
  load.segment(node * mesh.dofs_per_node, mesh.dofs_per_node) += c;
}

std::vector<int> sorted_along(const StrutMesh& mesh, std::vector<int> face, const Vec2& t) {
  std::stable_sort(face.begin(), face.end(),
                   [&](int p, int q) { return mesh.nodes[p].dot(t) < mesh.nodes[q].dot(t); });
  return face;
}

}  // namespace

long long Model::dof_count() const {
  long long total = 0;
  for (const StrutMesh& mesh : struts)
    total += mesh.dof_count();
  return total;
}

Eigen::VectorXd strut_load(const scenes::Scene& scene, const StrutMesh& mesh) {
  Eigen::VectorXd load = Eigen::VectorXd::Zero(mesh.dof_count());
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

Model build_model(const scenes::Scene& scene) {
  Model model;
  model.kind = scene.model;
  model.path = scene.path;
  model.title = scene.title;
  model.units = scene.units;
  model.scene_loads = scene.loads;
  const int strut_count = static_cast<int>(scene.struts.size());
  for (int s = 0; s < strut_count; ++s) {
    const scenes::Strut& strut = scene.struts[s];
    model.strut_names.push_back(strut.name);
    model.struts.push_back(build_strut_mesh(scene, s));
    const StrutMesh& mesh = model.struts.back();
    model.loads.push_back(strut_load(scene, mesh));
    std::vector<int> clamped;
    for (scenes::StrutEnd end : {scenes::StrutEnd::From, scenes::StrutEnd::To})
      if (strut.fixed(end))
        for (int node : mesh.end_face(end))
          clamped.push_back(node);
    std::sort(clamped.begin(), clamped.end());
    clamped.erase(std::unique(clamped.begin(), clamped.end()), clamped.end());
    model.clamped_nodes.push_back(std::move(clamped));
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
