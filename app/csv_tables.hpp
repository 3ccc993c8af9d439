#pragma once
// CSV tables of a solve (docs/SCENES.md "CSV tables"): the iteration history of every load
// step, and one row per load step with the load factor, the displacements of chosen
// nodes, and the total force and active pairs of every contact - a load curve.

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "solver/load_sweep.hpp"
#include "solver/model.hpp"

namespace fetic::app {

// A node picked on the command line: "NAME.from", "NAME.to" or "NAME@i" (i = 0..elements
// along the strut). In the plane model the node of that station nearest the axis.
struct TrackedNode {
  std::string label;
  int strut = 0;
  int node = 0;
};

// The node, or nullopt with `problem` saying why.
std::optional<TrackedNode> find_node(const solver::Model& model, const std::string& label,
                                     std::string& problem);

// Both ends of every contact, each once, in scene order.
std::vector<TrackedNode> contact_end_nodes(const solver::Model& model);

// load_step,load_factor,iteration,residual,active_set[,error]: one row per history entry.
void write_history_csv(std::ostream& out, const std::vector<solver::SweepStep>& steps);

// load_step,load_factor,status,iterations,residual,active_pairs, then ux:NODE [L],uy:NODE [L]
// per node and force:A/B [F],active_pairs:A/B per contact (L, F: the scene's units).
void write_steps_csv(std::ostream& out, const solver::Model& model,
                     const std::vector<solver::SweepStep>& steps,
                     const std::vector<TrackedNode>& nodes);

}  // namespace fetic::app
