#pragma once
// The discrete model of a scene: the mesh of every strut, nodal loads at load factor 1,
// supported DOFs, joints (frame model) and the contact node pairs with their normals and
// gaps. Everything the methods need, nothing of TOML: the solver layer starts here.

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "scenes/frame_kinematics.hpp"
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

// A node with DOFs held at zero: bit c of `components` holds component c.
struct HeldNode {
  int node = 0;
  unsigned components = 0;
};

// Frame model: strut ends joined at one point. The ends share their first `shared`
// components: 3 (ux, uy, rotation) for a rigid joint, 2 (ux, uy) for a pinned one.
struct JointLink {
  std::vector<std::pair<int, int>> ends;  // (strut, node), as the scene lists them
  int shared = 3;
};

// How a strut end is supported (frame model pinned ends; clamped in every model).
enum class Support { None, Clamped, Pinned };

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
  // Per strut: nodes with held DOFs (supports; in the frame model also a joint component
  // that another end of the joint holds), in increasing order. Bar and plane model: the
  // clamped nodes, every component held.
  std::vector<std::vector<HeldNode>> held_nodes;
  std::vector<std::array<Support, 2>> end_supports;  // per strut: 'from', 'to'
  std::vector<JointLink> joints;                     // frame model
  // Frame model: the motions supports and joints leave free (scenes/frame_kinematics).
  scenes::FrameKinematics kinematics;
  std::vector<ContactPair> pairs;
  std::vector<std::string> contact_labels;  // "a - b" per scene contact, e.g. "L01.to - R01.from"
  std::vector<std::pair<std::string, std::string>> contact_ends;  // ("L01.to", "R01.from")
  std::vector<int> contact_first_pair;  // per contact, its first pair; back() = pairs.size()

  int dofs_per_node() const {
    return kind == scenes::ModelKind::Bar ? 1 : (kind == scenes::ModelKind::Plane ? 2 : 3);
  }
  bool frame() const { return kind == scenes::ModelKind::Frame; }
  long long dof_count() const;
  bool floating(int strut) const { return clamped_nodes[strut].empty(); }
  // Held components of a node (bit c: component c), 0 when free.
  unsigned held(int strut, int node) const;
  // Whether a node cannot move at all (both displacement components, or the axial one of
  // a bar, held).
  bool translation_held(int strut, int node) const;
};

Model build_model(const scenes::Scene& scene);

// One side of a contact pair's row: its strut and node, and the row's coefficients on the
// node's DOFs - the normal on side a, its negative on side b, so that the row reads
// (u_a - u_b) . normal. The assembled problem, the FETI rows and the contact forces
// all take the pair apart this one way.
struct ContactSide {
  int strut = 0, node = 0;
  Eigen::VectorXd coefficients;
};
std::array<ContactSide, 2> contact_sides(const Model& model, const ContactPair& pair);

// Consistent nodal forces of one strut at load factor 1 (SCENES.md).
Eigen::VectorXd strut_load(const scenes::Scene& scene, const StrutMesh& mesh);

}  // namespace fetic::solver
