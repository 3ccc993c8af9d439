#pragma once
// FETI-DP's edge averages (docs/METHODS.md "FETI-DP", issue 24): besides the corners, the
// average of each displacement component over the interior nodes of an interface edge
// between two boxes of one cluster is made primal.
//
// The change of basis of Klawonn-Widlund and Li-Widlund (the edge average a DOF shared
// by the two boxes like a corner, the rest glued by multipliers), written in the boxes'
// own DOFs: per such edge and component the sum s = sum_i u_p,i of the first box's m
// interior copies becomes a DOF of the cluster (Subdomain::SumDof), and the copy of the
// edge's last node in each box is tied to it, u_p,m = s - sum_{i != m} u_p,i and
// u_q,m = s - sum_{i != m} u_q,i (Subdomain::TiedDof), so the two sums agree; the gluing
// row u_p,m - u_q,m = 0 is dropped (it follows from the others). The remaining rows are
// u_p,i - u_q,i, i != m, as in the new basis, so F is the same. A tied DOF is held like a
// clamped one in K, its couplings moved onto its terms (T'KT), its load likewise (T'f),
// and its value recovered after the solve. Each tie makes one box's edge DOFs a dense
// block of K (a 2m x 2m block per box and edge, both components); tying one copy to both
// boxes' copies instead (no shared DOF) made one 2(2m-1) square block per edge and a
// factor half as large again (docs/BENCHMARKS.md "Edge averages").

#include "solver/decomposition.hpp"
#include "solver/model.hpp"

namespace fetic::solver {

// Plane model only (the frame and bar models' interface nodes are all corners): ties the
// edges inside d's clusters (not between clusters: the hybrid's gluing stays dual) and
// drops their rows. An edge any of whose DOFs a Dirichlet or contact row touches is left
// as it is.
void tie_edge_averages(const Model& model, Decomposition& d);

}  // namespace fetic::solver
