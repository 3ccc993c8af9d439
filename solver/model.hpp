#pragma once
// The discrete model of a scene: the mesh of every strut, nodal loads at load factor 1,
// clamped nodes and the contact node pairs with their normals and gaps. Everything the
// methods need, nothing of TOML: the solver layer starts here.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "scenes/scene.hpp"
#include "solver/mesh.hpp"

namespace fetic::solver {

// One node-to-node non-penetration row: (u_a - u_b) . normal <= gap.
struct ContactPair {
  int contact = 0;  // index of the [[contact]] in the scene
  int pair = 0;     // index of the pair within it (increasing coordinate along t)
  int strut_a = 0, node_a = 0;
  int strut_b = 0, node_b = 0;
  Vec2 normal{1, 0};
  double gap = 0.0;
};

struct Model {
  scenes::ModelKind kind = scenes::ModelKind::Bar;
  std::string path;
  std::string title;
  scenes::Units units;  // what the scene's numbers are in (for legends and reports)
  std::vector<std::string> strut_names;
  std::vector<StrutMesh> struts;
  // Nodal forces per strut at load factor 1, DOF-indexed like the strut (node * dofs + c).
  std::vector<Eigen::VectorXd> loads;
  // The scene's [[load]]s as written (point or per length), for drawing them as glyphs.
  std::vector<scenes::Load> scene_loads;
  // Per strut: nodes whose DOFs are all clamped, in increasing order.
  std::vector<std::vector<int>> clamped_nodes;
  std::vector<ContactPair> pairs;
  std::vector<std::string> contact_labels;  // "a - b" per scene contact, e.g. "L01.to - R01.from"
  std::vector<std::pair<std::string, std::string>> contact_ends;  // ("L01.to", "R01.from")
  std::vector<int> contact_first_pair;  // per contact, its first pair; back() = pairs.size()

  int dofs_per_node() const { return kind == scenes::ModelKind::Bar ? 1 : 2; }
  long long dof_count() const;
  bool floating(int strut) const { return clamped_nodes[strut].empty(); }
};

Model build_model(const scenes::Scene& scene);

// Consistent nodal forces of one strut at load factor 1 (SCENES.md).
Eigen::VectorXd strut_load(const scenes::Scene& scene, const StrutMesh& mesh);

}  // namespace fetic::solver
