#pragma once
// FETI-DP's edge averages (docs/METHODS.md "FETI-DP", issue 24): besides the corners, the
// average of each displacement component over the interior nodes of an interface edge
// between two boxes of one cluster is made primal.
//
// By elimination in the boxes' own DOFs: per such edge and component, the copy u_q,m of
// the edge's last node in the second box q is tied to the others by the condition that
// the two averages agree, u_q,m = sum_i u_p,i - sum_{i != m} u_q,i, and its gluing row
// u_p,m - u_q,m = 0 is dropped (it follows from the others once the averages agree).
// This is the change of basis of Klawonn-Widlund and Li-Widlund (the edge average a DOF
// shared like a corner, the rest glued by multipliers) written without the new basis:
// the same primal space and the same gluing rows u_p,i - u_q,i, i != m, so the same F.
// The tied DOF is held like a clamped one in K (Subdomain::ties), with its couplings moved
// onto its terms (T'KT), its load moved likewise (T'f), and its value recovered after the
// solve.

#include "solver/decomposition.hpp"
#include "solver/model.hpp"

namespace fetic::solver {

// Plane model only (the frame and bar models' interface nodes are all corners): ties the
// edges inside d's clusters (not between clusters: the hybrid's gluing stays dual) and
// drops their rows. An edge any of whose DOFs a Dirichlet or contact row touches is left
// as it is.
void tie_edge_averages(const Model& model, Decomposition& d);

}  // namespace fetic::solver
