#include "render/frame_sequence.hpp"

#include <algorithm>
#include <cmath>

#include "solver/element_results.hpp"
#include "solver/load_sweep.hpp"
#include "solver/stiffness.hpp"

namespace fetic::render {

int run_frames(solver::Method& method, const FramePlan& plan,
               const std::function<bool(const Frame&)>& visit) {
  // The sweep of `fetic solve` (solver::sweep): the same warm starts, so the same
  // iterations; a frame per iterate (iteration 0 of each solve included) or per step.
  int index = 0;
  int step = 0;
  bool stop = false;
  solver::SweepHooks hooks;
  hooks.keep_going = [&] { return !stop; };
  hooks.record_stop = false;  // no solve after the last frame wanted
  if (plan.every_iteration)
    hooks.on_iteration = [&](double, const solver::Method& running) {
      if (stop) return;
      const solver::Snapshot snapshot = running.snapshot();
      stop = !visit(Frame{index++, step, snapshot, running.history()});
    };
  hooks.on_step = [&](const solver::SweepStep& done) {
    if (!plan.every_iteration && !stop)
      stop = !visit(Frame{index++, step, done.state, done.history});
    ++step;
  };
  solver::sweep(method, plan.load_factors, hooks);
  return index;
}

double largest_displacement(const solver::Snapshot& snapshot) {
  double largest = 0.0;
  for (const solver::Piece& piece : snapshot.pieces)
    for (const solver::Vec2& u : piece.displacement)
      if (std::isfinite(u.norm())) largest = std::max(largest, u.norm());
  return largest;
}

std::vector<std::vector<double>> piece_stresses(const solver::Model& model,
                                                const solver::Snapshot& snapshot) {
  std::vector<std::vector<double>> stresses;
  stresses.reserve(snapshot.pieces.size());
  for (const solver::Piece& piece : snapshot.pieces) {
    const solver::StrutMesh& mesh = model.struts[static_cast<std::size_t>(piece.strut)];
    const Eigen::VectorXd box_dofs = solver::piece_dofs(mesh, piece);
    const Eigen::VectorXd sigma = solver::axial_stress(mesh, piece.box, box_dofs);
    stresses.emplace_back(sigma.data(), sigma.data() + sigma.size());
  }
  return stresses;
}

namespace {

// |u_i - u_j| / |x_i - x_j| over the neighbouring nodes of a piece (along and across).
double piece_stretch(const solver::StrutMesh& mesh, const solver::Piece& piece) {
  double largest = 0.0;
  const solver::NodeBox& box = piece.box;
  const auto check = [&](int i0, int k0, int i1, int k1) {
    const solver::Vec2& u0 = piece.displacement[static_cast<std::size_t>(box.local(i0, k0))];
    const solver::Vec2& u1 = piece.displacement[static_cast<std::size_t>(box.local(i1, k1))];
    const double apart = (mesh.nodes[static_cast<std::size_t>(mesh.node(i1, k1))] -
                          mesh.nodes[static_cast<std::size_t>(mesh.node(i0, k0))])
                             .norm();
    const double stretch = (u1 - u0).norm() / apart;
    if (apart > 0.0 && std::isfinite(stretch)) largest = std::max(largest, stretch);
  };
  for (int i = box.i0; i <= box.i1; ++i)
    for (int k = box.k0; k <= box.k1; ++k) {
      if (i < box.i1) check(i, k, i + 1, k);
      if (k < box.k1) check(i, k, i, k + 1);
    }
  return largest;
}

}  // namespace

void RunExtent::include(const solver::Model& model, const Frame& frame) {
  frame_count = std::max(frame_count, frame.index + 1);
  largest_displacement =
      std::max(largest_displacement, render::largest_displacement(frame.snapshot));
  strut_lateral.resize(model.struts.size(), 0.0);
  for (const solver::Piece& piece : frame.snapshot.pieces) {
    const solver::StrutMesh& mesh = model.struts[static_cast<std::size_t>(piece.strut)];
    largest_stretch = std::max(largest_stretch, piece_stretch(mesh, piece));
    double& lateral = strut_lateral[static_cast<std::size_t>(piece.strut)];
    for (const solver::Vec2& u : piece.displacement)
      if (u.allFinite()) lateral = std::max(lateral, std::abs(u.dot(mesh.e2)));
  }
  for (double f : frame.snapshot.force)
    if (std::isfinite(f)) largest_force = std::max(largest_force, std::abs(f));
  for (const auto& piece : piece_stresses(model, frame.snapshot))
    for (double s : piece)
      if (std::isfinite(s)) largest_stress = std::max(largest_stress, std::abs(s));
  if (model.frame())
    for (const solver::BeamMoments& piece : solver::piece_moments(model, frame.snapshot))
      for (const auto& ends : piece.ends)
        for (double m : ends)
          if (std::isfinite(m)) largest_moment = std::max(largest_moment, std::abs(m));
  largest_iteration = std::max(largest_iteration, frame.snapshot.iteration);
  largest_active_set = std::max(largest_active_set, frame.snapshot.active_set_size());
  // Every point the plots will show: the whole history up to this frame.
  for (const solver::HistoryEntry& entry : frame.history) {
    largest_iteration = std::max(largest_iteration, entry.iteration);
    largest_active_set = std::max(largest_active_set, entry.active_set);
    if (entry.residual == 0.0) zero_residual = true;
    if (std::isfinite(entry.residual) && entry.residual > 0.0) {
      smallest_residual =
          smallest_residual > 0.0 ? std::min(smallest_residual, entry.residual) : entry.residual;
      largest_residual = std::max(largest_residual, entry.residual);
    }
  }
  if (frame.load_step >= static_cast<int>(steps.size()))
    steps.resize(static_cast<std::size_t>(frame.load_step) + 1);
  StepSummary& step = steps[static_cast<std::size_t>(frame.load_step)];
  step = summarize(frame.snapshot);
  final_status = frame.snapshot.status;
  final_message = frame.snapshot.message;
}

StepSummary summarize(const solver::Snapshot& snapshot) {
  StepSummary step;
  step.load_factor = snapshot.load_factor;
  step.iterations = snapshot.iteration;
  step.active_set = snapshot.active_set_size();
  for (double f : snapshot.force)
    if (std::isfinite(f)) step.total_force += f;
  step.largest_displacement = largest_displacement(snapshot);
  return step;
}

RunExtent survey(const solver::Model& model, solver::Method& method, const FramePlan& plan,
                 const std::function<bool()>& keep_going) {
  RunExtent extent;
  run_frames(method, plan, [&](const Frame& frame) {
    extent.include(model, frame);
    return !keep_going || keep_going();
  });
  return extent;
}

}  // namespace fetic::render
