#pragma once
// What an engineer reads off a solver state besides displacements: per element the
// connectivity, the FETI subdomain, the stresses and the stress resultants (stress
// recovery), and per clamped end the support reaction. Generic over the models: each
// model supplies its element topology and recovery in element_results.cpp (bar: axial
// stress; plane: sxx, syy, sxy, von Mises and the axial stress e1' sigma e1); a new model
// adds a case there and everything that writes results (JSON, VTU, CSV) follows.

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "solver/method.hpp"
#include "solver/model.hpp"

namespace fetic::solver {

struct NamedValues {
  std::string name;
  std::vector<double> values;  // one per element
};

struct StrutElements {
  int nodes_per_element = 2;            // 2: line (bar, beam), 4: quadrilateral (counterclockwise)
  std::vector<int> connectivity;        // nodes_per_element strut node indices per element
  std::vector<int> subdomain;           // FETI subdomain per element (numbered as decompose() does)
  std::vector<NamedValues> stress;      // "axial" for every model; plane adds "sxx", "syy",
                                        // "sxy" (global axes), "von_mises"
  std::vector<NamedValues> resultants;  // "axial_force" for every model

  int element_count() const { return static_cast<int>(connectivity.size()) / nodes_per_element; }
};

// A piece's DOF vector in box-local numbering, as the piece holds it (a torn iterate's
// clamped copies included): per node u . e1 (bar), ux, uy (plane), ux, uy, rotation (frame).
Eigen::VectorXd piece_dofs(const StrutMesh& mesh, const Piece& piece);

// Elements of every strut with the stresses and resultants of `snapshot`. Each element's
// values come from the displacements of the piece (subdomain) that holds it, so a torn
// FETI iterate shows each subdomain's own stresses.
std::vector<StrutElements> element_results(const Model& model, const Snapshot& snapshot);

// The element topology alone (connectivity and subdomains, no values).
std::vector<StrutElements> element_topology(const Model& model);

// One strut's results at a time, the same values as the whole-model functions: what
// writes the results of a large scene (app/vtu_export.cpp, app/state_json.cpp) then holds
// one strut's nodes and elements, not every one's.
class StrutResults {
 public:
  StrutResults(const Model& model, const Snapshot& snapshot);
  std::vector<Vec2> displacements(int strut) const;  // strut_displacements(...)[strut]
  std::vector<double> rotations(int strut) const;    // strut_rotations(...)[strut]
  StrutElements topology(int strut) const;           // element_topology(...)[strut]
  // topology(strut) without its value fields (empty): connectivity and subdomains only,
  // for the writers' arrays that need no values (a plane strut's six fields are 48 of
  // its 68 bytes per element).
  StrutElements shape(int strut) const;
  StrutElements elements(int strut) const;  // element_results(...)[strut]

 private:
  const Model& model_;
  const Snapshot& snapshot_;
  std::vector<std::vector<int>> pieces_;  // per strut: its pieces in snapshot_
  std::vector<int> first_subdomain_;      // per strut: the number of its first subdomain
};

// The bending moment M = E I w'' along the beam elements of a frame strut. An
// Euler-Bernoulli element's w is cubic, so M is linear along it: its two end values come
// from the element's end rotations and transverse end displacements in local axes (the
// Hermite second derivatives; exact for loads at the nodes). Sign: sagging positive - M
// is positive where it bends the strut towards +e2 (its axis e1 turned +90 degrees), i.e.
// concave towards +e2; for a strut drawn left to right, sagging (concave up).
struct BeamMoments {
  int strut = 0;
  int first_element = 0;                    // strut element index of ends[0]
  std::vector<std::array<double, 2>> ends;  // per element: M at xi = 0 (its node i) and 1 (i + 1)

  // M at xi in [0, 1] along element `element` (strut numbering) of this range.
  double at(int element, double xi) const {
    const auto& m = ends[static_cast<size_t>(element - first_element)];
    return (1.0 - xi) * m[0] + xi * m[1];
  }
  bool empty() const { return ends.empty(); }
};

// One per piece of `snapshot`, in its order: the moments of the elements of the piece's
// box, from the piece's own displacements (a torn FETI iterate shows each subdomain's
// own moments). Empty for struts without bending stiffness (bars, plane struts).
std::vector<BeamMoments> piece_moments(const Model& model, const Snapshot& snapshot);

// One per strut: the moments of all its elements from its DOF vector (strut_dofs). Empty
// for struts that are not beams.
std::vector<BeamMoments> strut_moments(const Model& model, const Snapshot& snapshot);

// The force a clamped end exerts on its strut: r = K u - t f - (contact forces) at the
// end's nodes. Summed over all supports, the reactions balance the applied loads.
struct SupportReaction {
  int strut = 0;
  scenes::StrutEnd end = scenes::StrutEnd::From;
  std::vector<int> nodes;         // the clamped nodes of that end
  std::vector<Vec2> node_forces;  // per node [N]
  Vec2 force{0, 0};               // their sum [N]
};

std::vector<SupportReaction> support_reactions(const Model& model, const Snapshot& snapshot);

// Nodal forces the contact pairs exert on each strut (DOF-indexed like Model::loads):
// a pair with pressure lambda pushes node a by -lambda n and node b by +lambda n.
std::vector<Eigen::VectorXd> contact_nodal_forces(const Model& model, const Snapshot& snapshot);

// The strut DOF vectors of a snapshot (the average of the pieces holding a node, as
// strut_displacements), with every clamped DOF exactly zero.
std::vector<Eigen::VectorXd> strut_dofs(const Model& model, const Snapshot& snapshot);

}  // namespace fetic::solver
