// Example 2: MPRGP stepped by hand, watching the working set.
//
// MPRGP (docs/METHODS.md 4.6) solves the same dual problem as FETI-C with bounds on the
// contact multipliers, lambda >= 0: a contact pair whose multiplier is off the bound
// carries force, and those pairs are the working set that the result file and the window
// show. The active-set method changes that set by one pair an iteration; MPRGP's
// expansion and proportioning steps may move many pairs at once. This program steps the
// method itself and prints, after every iteration, which contacts entered the working
// set and which left it.

#include <cstdio>
#include <string>
#include <vector>

#include "scenes/load_scene.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"

using namespace fetic;

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : FETIC_EXAMPLE_SCENES "/thesis.toml";
  const solver::Model model = solver::build_model(scenes::load_scene_file(path));
  auto method = solver::make_method(solver::MethodKind::Mprgp, model, solver::SolveOptions{});

  method->start(1.0);
  std::vector<char> before(model.pairs.size(), 0);
  int changes = 0;
  while (true) {
    const std::vector<char> now = method->working_set();
    std::string entered, left;
    for (size_t k = 0; k < now.size(); ++k) {
      if (now[k] && !before[k]) entered += " " + model.contact_labels[model.pairs[k].contact];
      if (!now[k] && before[k]) left += " " + model.contact_labels[model.pairs[k].contact];
    }
    changes += !entered.empty() || !left.empty();
    std::printf("iteration %2d  residual %.3e  working set %3d  entered:%s  left:%s\n",
                method->iteration(), method->history().back().residual,
                method->history().back().active_set, entered.empty() ? " -" : entered.c_str(),
                left.empty() ? " -" : left.c_str());
    before = now;
    if (method->status() != solver::Status::Running) break;
    method->step();
  }
  std::printf("%s; the working set changed at %d iterates\n", solver::to_string(method->status()),
              changes);
  return method->status() == solver::Status::Converged ? 0 : 1;
}
