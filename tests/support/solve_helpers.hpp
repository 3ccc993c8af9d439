#pragma once
// Small helpers shared by the solver tests: load a scene from text, run a method to the
// end, compare displacements and forces with a reference.

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "scenes/load_scene.hpp"
#include "solver/cholmod_factor.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"
#include "solver/primal_problem.hpp"
#include "tests/support/reference_qp.hpp"
#include "tests/support/scene_toml.hpp"

namespace fetic::testing {

struct Solved {
  solver::Model model;
  std::unique_ptr<solver::Method> method;
  solver::Snapshot state;
};

inline std::unique_ptr<Solved> solve(const scenes::Scene& scene, solver::MethodKind kind,
                                     double load_factor = 1.0, solver::SolveOptions options = {}) {
  auto result = std::make_unique<Solved>();
  result->model = solver::build_model(scene);
  result->method = solver::make_method(kind, result->model, options);
  result->method->start(load_factor);
  solver::run_to_end(*result->method);
  result->state = result->method->snapshot();
  return result;
}

inline std::unique_ptr<Solved> solve_text(const std::string& text, solver::MethodKind kind,
                                          double load_factor = 1.0,
                                          solver::SolveOptions options = {}) {
  return solve(scenes::parse_scene(text, "test.toml"), kind, load_factor, options);
}

inline scenes::Scene bundled_scene(const std::string& name) {
  return scenes::load_scene_file(std::string(FETIC_BUNDLED_SCENES_DIR) + "/" + name);
}

// One method solving at `load`, then at `next` warm-started from that solution, then at
// `next` cold: the three final states.
struct WarmAndCold {
  solver::Snapshot first, warm, cold;
};

inline WarmAndCold warm_and_cold(solver::Method& method, double load, double next) {
  WarmAndCold states;
  method.start(load);
  solver::run_to_end(method);
  states.first = method.snapshot();
  method.start(next, &states.first);
  solver::run_to_end(method);
  states.warm = method.snapshot();
  method.start(next);
  solver::run_to_end(method);
  states.cold = method.snapshot();
  return states;
}

// A warm start after a 5% load change (1 to 1.05) needs fewer iterations than a cold one
// and ends at the same displacements (to 1e-8).
inline void check_warm_start(solver::Method& method, const solver::Model& model) {
  const WarmAndCold states = warm_and_cold(method, 1.0, 1.05);
  REQUIRE(states.first.status == solver::Status::Converged);
  REQUIRE(states.warm.status == solver::Status::Converged);
  REQUIRE(states.cold.status == solver::Status::Converged);
  CHECK(states.warm.iteration < states.cold.iteration);
  CHECK(solver::relative_error(solver::strut_displacements(model, states.warm),
                               solver::strut_displacements(model, states.cold)) <= 1e-8);
}

// ||u - u_ref|| / ||u_ref|| over every node of every strut.
inline double displacement_error(const Solved& solved, const ReferenceSolution& reference) {
  const auto u = solver::strut_displacements(solved.model, solved.state);
  double difference = 0.0, size = 0.0;
  for (size_t s = 0; s < u.size(); ++s)
    for (size_t n = 0; n < u[s].size(); ++n) {
      const auto& r = reference.displacement.at(s).at(n);
      difference += std::pow(u[s][n].x() - r[0], 2) + std::pow(u[s][n].y() - r[1], 2);
      size += r[0] * r[0] + r[1] * r[1];
    }
  return size > 0.0 ? std::sqrt(difference / size) : std::sqrt(difference);
}

// ||force - force_ref|| / max(||force_ref||, force_scale) over every contact pair.
inline double force_error(const Solved& solved, const ReferenceSolution& reference,
                          double force_scale) {
  double difference = 0.0, size = 0.0;
  for (size_t k = 0; k < reference.force.size(); ++k) {
    difference += std::pow(solved.state.force.at(k) - reference.force[k], 2);
    size += reference.force[k] * reference.force[k];
  }
  return std::sqrt(difference) / std::max(std::sqrt(size), force_scale);
}

// Sum of the magnitudes of all nodal loads at load factor 1: the scale of contact forces.
inline double load_scale(const solver::Model& model) {
  double total = 0.0;
  for (const auto& load : model.loads)
    total += load.lpNorm<1>();
  return std::max(total, 1e-300);
}

// The frame cantilever of the closed-form tests: 8 elements, 3 subdomains, clamped at its
// 'from' end.
inline constexpr const char* kCantileverKeys =
    "E = 2.1e11, area = 2.0e-3, inertia = 3.0e-6, elements = 8, subdomains = 3, "
    "fixed = ['from']";

// The displacements and contact forces of `solved` agree with the reference to 1e-8
// (forces relative to the larger of their size and 1e-12 of the loads).
inline void check_against_reference(const Solved& solved, const ReferenceSolution& reference) {
  CHECK(displacement_error(solved, reference) <= 1e-8);
  CHECK(force_error(solved, reference, 1e-12 * load_scale(solved.model)) <= 1e-8);
}

// A bar chain: a clamped base, a floating middle strut pushed onto it (its left end 1 mm
// away), and a floating tip touching the middle one, pulled by `tip_force` along x: away
// (> 0) the scene is unbounded, pushed back (< 0) it rests on the chain.
inline std::string floating_chain(double tip_force) {
  return SceneToml("bar", "[defaults]", "E = 2e11, area = 1e-4, elements = 3, subdomains = 2")
      .strut("base", {0.0, 0.0}, {1.0, 0.0}, "fixed = ['from']")
      .strut("middle", {1.001, 0.0}, {2.0, 0.0})
      .strut("tip", {2.0, 0.0}, {3.0, 0.0})
      .contact("base.to", "middle.from")
      .contact("middle.to", "tip.from")
      .load("middle", "from", {-800.0, 0.0})
      .load("tip", "to", {tip_force, 0.0});
}

// The displacements of a direct solve (no contacts): CHOLMOD on the assembled stiffness.
inline std::vector<std::vector<solver::Vec2>> direct_displacements(const solver::Model& model) {
  solver::PrimalProblem problem(model);
  solver::CholmodFactor factor;
  if (factor.factorize(problem.stiffness()) != solver::CholmodFactor::Result::Ok)
    throw std::runtime_error("the stiffness is singular");
  Eigen::VectorXd f = problem.load(), u(problem.size());
  factor.solve(f.data(), u.data());
  solver::Snapshot direct;
  direct.pieces = problem.pieces(u);
  return solver::strut_displacements(model, direct);
}

}  // namespace fetic::testing
