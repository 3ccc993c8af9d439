#pragma once
// FETI-DP as a decomposition (docs/METHODS.md, "FETI-DP"): the boxes of decompose() are
// joined by their corners - a few interface DOFs made primal, shared instead of glued by
// multipliers - into clusters, and every cluster becomes one subdomain of the FETI system.
// Its stiffness is assembled over its boxes with the corner DOFs shared, its kernel is
// the cluster's rigid-body motions (and, in the frame model, mechanisms of pinned joints),
// and the dual operator, the projector, MPRGP and PCPG run on it unchanged.
//
// Corners: in the plane model the corner nodes of every box that are interface nodes
// (the cross points and the end nodes of every interface edge); in the frame model every
// interface node (all three components) and the shared components of every joint; in the
// bar model every interface node. With one cluster per connected set of boxes this is
// plain FETI-DP; `cluster_size` > 0 first groups the boxes into clusters of about that
// many (consecutive boxes of a strut) and joins corners only inside a cluster, so the
// clusters are glued by multipliers as in FETI-1 (hybrid FETI-DP, as ESPRESO's hybrid
// TFETI): the coarse problem has the modes of the clusters.

#include "solver/decomposition.hpp"
#include "solver/model.hpp"
#include "solver/stiffness.hpp"

namespace fetic::solver {

// cluster_size: 0 joins every corner (plain FETI-DP), N > 0 clusters of about N boxes.
// edge_averages: the plane model's edge averages inside a cluster primal too
// (edge_averages.hpp).
Decomposition join_corners(const Model& model, const Decomposition& boxes, int cluster_size = 0,
                           bool edge_averages = false);

// Per strut, the nodes join_corners() makes primal (for drawing them), in increasing order.
std::vector<std::vector<int>> corner_nodes(const Model& model, const Decomposition& boxes);

// K of a subdomain (assembled over its parts) and its kernel, dof_count x mode_count.
SparseMatrix subdomain_stiffness(const Model& model, const Subdomain& sub);
Eigen::MatrixXd subdomain_modes(const Model& model, const Subdomain& sub);

}  // namespace fetic::solver
