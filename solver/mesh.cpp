#include "solver/mesh.hpp"

#include "scenes/scene_geometry.hpp"

namespace fetic::solver {

std::vector<int> StrutMesh::end_face(scenes::StrutEnd end) const {
  const int i = end == scenes::StrutEnd::From ? 0 : nx;
  std::vector<int> face;
  for (int k = 0; k <= ny; ++k)
    face.push_back(node(i, k));
  return face;
}

StrutMesh build_strut_mesh(const scenes::Scene& scene, int strut_index) {
  const scenes::Strut& strut = scene.struts.at(strut_index);
  StrutMesh mesh;
  mesh.strut = strut_index;
  const bool plane = scene.model == scenes::ModelKind::Plane;
  mesh.dofs_per_node = plane ? 2 : (scene.model == scenes::ModelKind::Frame ? 3 : 1);
  mesh.nx = strut.elements;
  mesh.ny = plane ? strut.elements_across : 0;
  mesh.origin = Vec2(strut.from[0], strut.from[1]);
  const scenes::Point e = scenes::axis(strut);
  mesh.e1 = Vec2(e[0], e[1]);
  mesh.e2 = Vec2(-e[1], e[0]);
  mesh.length = scenes::length(strut);
  mesh.height = plane ? strut.height : 0.0;
  mesh.E = strut.E;
  mesh.area = strut.area;
  mesh.inertia = strut.inertia;
  mesh.thickness = strut.thickness;
  mesh.nu = strut.nu;
  mesh.subdomains_along = strut.subdomains;
  mesh.subdomains_across = plane ? strut.subdomains_across : 1;
  mesh.nodes.reserve(static_cast<size_t>(mesh.nx + 1) * (mesh.ny + 1));
  const Vec2 to(strut.to[0], strut.to[1]);
  for (int i = 0; i <= mesh.nx; ++i) {
    // Interpolate between the two end points so that the 'to' end is exact.
    const double s = static_cast<double>(i) / mesh.nx;
    const Vec2 on_axis = (1.0 - s) * mesh.origin + s * to;
    for (int k = 0; k <= mesh.ny; ++k) {
      const double across = plane ? -0.5 * mesh.height + mesh.height * k / mesh.ny : 0.0;
      mesh.nodes.push_back(on_axis + across * mesh.e2);
    }
  }
  return mesh;
}

Eigen::Vector3d component_coefficients3(const StrutMesh& mesh, const Vec2& direction) {
  if (mesh.dofs_per_node == 1) return {mesh.e1.dot(direction), 0.0, 0.0};
  return {direction.x(), direction.y(), 0.0};
}

Eigen::VectorXd component_coefficients(const StrutMesh& mesh, const Vec2& direction) {
  return component_coefficients3(mesh, direction).head(mesh.dofs_per_node);
}

Vec2 node_displacement(const StrutMesh& mesh, const double* node_dofs) {
  if (mesh.dofs_per_node == 1) return node_dofs[0] * mesh.e1;
  return Vec2(node_dofs[0], node_dofs[1]);
}

double node_rotation(const StrutMesh& mesh, const double* node_dofs) {
  return mesh.dofs_per_node == 3 ? node_dofs[2] : 0.0;
}

}  // namespace fetic::solver
