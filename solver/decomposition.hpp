#pragma once
// Tearing the model into FETI subdomains (docs/METHODS.md 1-2).
//
// Each strut is split into `subdomains` boxes along its axis and `subdomains_across`
// across it (plane model); neighbouring boxes share their interface nodes. We use
// *total* FETI: clamped DOFs stay in K_j and become Dirichlet rows of B, so every
// subdomain floats and its kernel is known exactly (its rigid-body modes). K_j^+ then
// always comes from fixing the DOFs that pin those modes, with no numerical rank
// decision, and a breakdown of the factorization can only mean a singularity the
// rigid-body modes do not explain - which is reported.
//
// Rows of B, in this order: gluing rows u_a - u_b = 0 (one per DOF of every interface
// node and every pair of subdomains sharing it: fully redundant at cross points, which
// keeps the scaled Dirichlet preconditioner effective there), Dirichlet rows u = 0
// (every copy of every clamped DOF; a clamped node gets no gluing row), then one contact
// row (u_a - u_b) . n <= gap per contact pair. A pair whose two nodes are
// both clamped can never move and gets no row (its force is zero).

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "solver/model.hpp"
#include "solver/stiffness.hpp"

namespace fetic::solver {

// One box of one strut inside a subdomain. FETI-DP's subdomains (clusters, corners.hpp)
// hold several boxes joined by their corners, which they share; FETI-1's hold one.
struct SubdomainPart {
  int strut = 0;
  NodeBox box;
  int piece = 0;          // index of the box in decompose()'s order (one Piece each)
  std::vector<int> dofs;  // box-local DOF -> subdomain DOF (empty: the same)
};

struct Subdomain {
  int strut = 0;        // of the first part (for messages)
  NodeBox box;          // the first part's box
  int dof_count = 0;    // box nodes x DOFs per node
  int dof_offset = 0;   // first DOF in the concatenation of all subdomain vectors
  int mode_offset = 0;  // first rigid-body mode in the coarse space
  int mode_count = 0;
  Eigen::VectorXd load;  // this subdomain's share of the strut's nodal loads (t = 1)
  // Clusters (corners.hpp): their boxes, and their kernel as amplitudes of the boxes'
  // rigid-body modes (rows: the parts' modes in order, columns: mode_count). Empty for a
  // subdomain of one box.
  std::vector<SubdomainPart> parts;
  Eigen::MatrixXd part_modes;
  // Clusters of several boxes: clamped DOFs made primal (corners.hpp) - held at zero in
  // K (row and column cleared, diagonal kept), with no row of B and no load.
  std::vector<int> fixed;
  // Clusters with edge averages primal (edge_averages.hpp): DOFs eliminated by the
  // constraint that two boxes' averages over their interface edge agree. Such a DOF is
  // held like a fixed one in K (its couplings moved onto its terms), has no row of B, no
  // load and no modes; its value is the sum of value x DOF over its terms.
  struct TiedDof {
    int dof = 0;
    std::vector<std::pair<int, double>> terms;  // (subdomain DOF, coefficient)
  };
  std::vector<TiedDof> ties;
  // A DOF of no box (edge_averages.hpp: the sum shared by the two boxes of an edge): its
  // value in a rigid-body motion is the sum of coefficient x DOF over `of`.
  struct SumDof {
    int dof = 0;
    std::vector<std::pair<int, double>> of;
  };
  std::vector<SumDof> sums;
};

// The boxes of a subdomain: its parts, or the subdomain's own box as the only one.
std::vector<SubdomainPart> parts_of(const Subdomain& sub, int index);

enum class RowKind { Gluing, Dirichlet, Contact };

struct RowEntry {
  int subdomain = 0;
  int dof = 0;  // subdomain-local DOF
  double value = 0.0;
};

struct Row {
  RowKind kind = RowKind::Gluing;
  int pair = -1;     // contact pair (Contact rows)
  double rhs = 0.0;  // c: 0 for gluing and Dirichlet rows, the gap for contact rows
  std::vector<RowEntry> entries;
  std::vector<RowEntry> copies;  // gluing rows: every copy of the node's DOF (for scaling)
};

// The gluing rows of one DOF of a node with three or more copies: one row per pair of
// copies (i, j), u_i - u_j = 0, so they are linearly dependent.
struct RedundantGroup {
  int copies = 0;
  std::vector<int> rows;
  std::vector<std::pair<int, int>> ends;  // (i, j) of each row, indices into the copies
};

struct Decomposition {
  std::vector<Subdomain> subdomains;
  std::vector<Row> rows;  // equality rows first, then contact rows
  int equality_rows = 0;
  std::vector<int> pair_row;  // per contact pair: its row, or -1 (both nodes clamped)
  int total_dofs = 0;
  int total_modes = 0;
  int total_pieces = 0;  // boxes (decompose()'s subdomains)
  std::vector<RedundantGroup> redundant_groups;

  int row_count() const { return static_cast<int>(rows.size()); }
  int contact_rows() const { return row_count() - equality_rows; }
};

// Element ranges [first node, last node] of `parts` nearly equal parts of `elements`.
std::vector<std::pair<int, int>> split_nodes(int elements, int parts);

Decomposition decompose(const Model& model);

}  // namespace fetic::solver
