// Example 1: FETI-C on the thesis' test problem, one line per iteration.
//
// The thesis' scene is two sets of opposing bars whose facing tips may touch
// (docs/METHODS.md 5). This program does what `fetic solve scenes/thesis.toml --method
// feti-c` does, in the open: read the scene, build the model (meshes, subdomains,
// contact pairs), set the method up (the subdomain factorizations and the coarse
// problem happen here, once), then step it. Every method is a stepper: start() makes the
// initial iterate, step() one iteration, and history() holds one entry per iterate - the
// relative residual and how many contact pairs the working set holds. The window, the
// renderer and the tests read the same entries.

#include <cstdio>
#include <string>

#include "scenes/load_scene.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"

using namespace fetic;

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : FETIC_EXAMPLE_SCENES "/thesis.toml";

  // 1. Read the scene (TOML, docs/SCENES.md) and build the model.
  const scenes::Scene scene = scenes::load_scene_file(path);
  const solver::Model model = solver::build_model(scene);
  std::printf("%s: %lld unknowns, %zu contact pairs\n", path.c_str(),
              static_cast<long long>(model.dof_count()), model.pairs.size());

  // 2. Set up FETI-C with the Dirichlet preconditioner.
  solver::SolveOptions options;
  options.tolerance = 1e-10;
  options.preconditioner = solver::Preconditioner::Dirichlet;
  auto method = solver::make_method(solver::MethodKind::FetiC, model, options);

  // 3. Solve at load factor 1, printing each iterate as it comes.
  method->start(1.0);
  for (;;) {
    const solver::HistoryEntry& now = method->history().back();
    std::printf("iteration %2d  residual %.3e  active pairs %d\n", now.iteration, now.residual,
                now.active_set);
    if (method->status() != solver::Status::Running) break;
    method->step();
  }

  // 4. The result: converged, and the contact forces of the final state.
  const solver::Snapshot state = method->snapshot();
  double total = 0.0;
  for (double force : state.force)
    total += force;
  std::printf("%s after %d iterations, total contact force %.6e %s\n",
              solver::to_string(state.status), state.iteration, total, model.units.force.c_str());
  return state.status == solver::Status::Converged ? 0 : 1;
}
