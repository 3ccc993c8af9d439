#pragma once
// Which solver states become frames, and the range of values over all of them. A movie
// is rendered in two passes over the same deterministic run: the first (survey) finds the
// largest displacement, force and stress so that magnification, colour scales and plot
// axes stay fixed from frame to frame; the second renders.

#include <functional>
#include <string>
#include <vector>

#include "solver/method.hpp"
#include "solver/model.hpp"

namespace fetic::render {

struct FramePlan {
  std::vector<double> load_factors{1.0};  // one solve per factor, each warm from the last
                                          // (e.g. solver::load_steps(a, b, n))
  bool every_iteration = true;            // else only the final state of each solve
};

struct Frame {
  int index = 0;      // 0, 1, ... over the whole plan
  int load_step = 0;  // index into FramePlan::load_factors
  const solver::Snapshot& snapshot;
  const std::vector<solver::HistoryEntry>& history;  // of the current solve, so far
};

// Drives `method` through the plan and calls `visit` for each frame in order (frame 0 of
// a solve is its initial state, right after start()). Stops early when `visit` returns
// false. Returns the number of frames visited.
int run_frames(solver::Method& method, const FramePlan& plan,
               const std::function<bool(const Frame&)>& visit);

// The final state of one load step, for plots against the load factor.
struct StepSummary {
  double load_factor = 0.0;
  int iterations = 0;
  int active_set = 0;
  double total_force = 0.0;  // sum of the contact forces
  double largest_displacement = 0.0;
};

// Largest values over a run, for fixed scales.
struct RunExtent {
  int frame_count = 0;
  double largest_displacement = 0.0;  // |u| over all nodes and frames
  double largest_force = 0.0;         // contact pressure
  double largest_stress = 0.0;        // |axial stress|
  double largest_moment = 0.0;        // |bending moment| of frame beams (0: none)
  int largest_iteration = 0;          // iterations of the longest solve
  int largest_active_set = 0;
  double smallest_residual = 0.0;  // positive residuals only; 0 when there were none
  double largest_residual = 0.0;
  bool zero_residual = false;  // some iterate's residual was exactly 0
  // Largest |u_i - u_j| / |x_i - x_j| over neighbouring nodes (an element's stretch), and
  // per strut its largest displacement across its axis: they bound the magnification.
  double largest_stretch = 0.0;
  std::vector<double> strut_lateral;
  std::vector<StepSummary> steps;  // per load step, its last state
  solver::Status final_status = solver::Status::Running;
  std::string final_message;

  void include(const solver::Model& model, const Frame& frame);
};

// The survey pass: runs the plan once and returns its extent; stops early when
// keep_going (if given) returns false.
RunExtent survey(const solver::Model& model, solver::Method& method, const FramePlan& plan,
                 const std::function<bool()>& keep_going = {});

// The summary of a solve's state (its load factor, iterations, active set, forces).
StepSummary summarize(const solver::Snapshot& snapshot);

// Largest |displacement| of a snapshot, and its axial stresses per piece and element.
double largest_displacement(const solver::Snapshot& snapshot);
std::vector<std::vector<double>> piece_stresses(const solver::Model& model,
                                                const solver::Snapshot& snapshot);

}  // namespace fetic::render
