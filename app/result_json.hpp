#pragma once
// The result file of SCENES.md: scene, method, load factor, convergence, per-strut nodes
// and displacements, per-contact pairs with gap, force and activity, and the history;
// extended by stresses, axial forces, reactions and pair geometry (app/state_json.hpp).

#include <string>

#include <nlohmann/json.hpp>

#include "app/json_stream.hpp"
#include "solver/method.hpp"

namespace fetic::app {

struct RunInfo {
  std::string scene_path;
  solver::MethodKind method = solver::MethodKind::ActiveSet;
  solver::Preconditioner preconditioner = solver::Preconditioner::Dirichlet;
  double tolerance = 0.0;
  double setup_seconds = 0.0;
  double solve_seconds = 0.0;
  int ranks = 1;                         // processes the solve ran on (mpirun -np)
  std::vector<int> subdomains_per_rank;  // dual methods: subdomains each process held
};

// Keys in insertion order; app/json_layout.hpp puts the plain values first when written.
// With `streamed`, the struts are placeholders for write_streamed() (app/state_json.hpp).
nlohmann::ordered_json result_json(const solver::Model& model, const solver::Snapshot& final_state,
                                   const std::vector<solver::HistoryEntry>& history,
                                   const RunInfo& info, StreamedParts* streamed = nullptr);

}  // namespace fetic::app
