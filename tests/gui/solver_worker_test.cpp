// The solver thread of `fetic gui` without a window: it answers the newest request with a
// finished, warm-started solve whose working set is `fetic solve`'s, publishes immutable
// states, and a newer request supersedes an older one. The slider's automatic maximum.

#include <catch2/catch.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>

#include "app/gui/solver_worker.hpp"
#include "scenes/load_scene.hpp"
#include "solver/method.hpp"

using fetic::app::gui::automatic_max_load;
using fetic::app::gui::SolverTarget;
using fetic::app::gui::SolverWorker;
namespace solver = fetic::solver;

namespace {

std::shared_ptr<const solver::Model> model_of(const std::string& path) {
  return std::make_shared<const solver::Model>(
      solver::build_model(fetic::scenes::load_scene_file(path)));
}

std::vector<char> working_set_at(const solver::Model& model, double load) {
  auto method = solver::make_method(solver::MethodKind::FetiC, model, {});
  method->start(load);
  solver::run_to_end(*method);
  REQUIRE(method->status() == solver::Status::Converged);
  return method->snapshot().in_working_set;
}

}  // namespace

TEST_CASE("the worker answers the newest load request with a converged warm solve", "[worker]") {
  const auto model = model_of(std::string(FETIC_BUNDLED_SCENES_DIR) + "/thesis.toml");
  SolverWorker worker({});
  SolverTarget target;
  target.model = model;
  target.model_generation = 1;
  target.max_load = 2.0;
  target.load_factor = 0.0;
  target.request = 1;
  worker.request(target);
  // Two quick requests: the first may be abandoned, the second must be answered.
  target.load_factor = 0.5;
  target.request = 2;
  worker.request(target);
  target.load_factor = 1.5;
  target.request = 3;
  worker.request(target);
  const auto state = worker.wait_for(3, std::chrono::seconds(60));
  REQUIRE(state);
  REQUIRE(state->request == 3);
  REQUIRE(state->finished);
  CHECK(state->status == solver::Status::Converged);
  CHECK(state->load_factor == 1.5);
  CHECK(state->max_load == 2.0);
  REQUIRE(state->extent);
  CHECK(state->extent->largest_force > 0.0);
  // One iterate per iteration, from iteration 0; the last is the converged solution.
  CHECK(state->iterates.size() == state->history.size());
  CHECK(state->iterates.back()->in_working_set == working_set_at(*model, 1.5));
  CHECK(!worker.busy());

  // A small change re-solves warm: fewer iterations than the cold solve needs.
  target.load_factor = 1.55;
  target.request = 4;
  worker.request(target);
  const auto warm = worker.wait_for(4, std::chrono::seconds(60));
  REQUIRE(warm->request == 4);
  auto cold = solver::make_method(solver::MethodKind::FetiC, *model, {});
  cold->start(1.55);
  solver::run_to_end(*cold);
  CHECK(warm->iterates.size() - 1 < static_cast<std::size_t>(cold->iteration()));
}

TEST_CASE("a method that cannot solve the scene is a finished state with the reason", "[worker]") {
  const auto model = model_of(std::string(FETIC_BUNDLED_SCENES_DIR) + "/two_bars.toml");
  SolverWorker worker({});
  SolverTarget target;
  target.model = model;
  target.model_generation = 1;
  target.method = solver::MethodKind::ConjugateGradient;
  target.request = 1;
  worker.request(target);
  const auto state = worker.wait_for(1, std::chrono::seconds(30));
  REQUIRE(state);
  CHECK(state->finished);
  CHECK(state->iterates.empty());
  CHECK(state->error.find("contact") != std::string::npos);
}

TEST_CASE("the slider reaches contact: its automatic maximum", "[worker]") {
  // Thesis: contacts close at the scene's loads, so twice those.
  const auto thesis = model_of(std::string(FETIC_BUNDLED_SCENES_DIR) + "/thesis.toml");
  auto method = solver::make_method(solver::MethodKind::FetiC, *thesis, {});
  method->start(1.0);
  solver::run_to_end(*method);
  CHECK(automatic_max_load(*thesis, method->snapshot()) == 2.0);

  // Two bars 10 mm apart whose tip moves 3 mm at load 1: the gap closes at 10/3, so the
  // slider goes to 2 x 3.33 rounded up to 10.
  const auto path = std::filesystem::temp_directory_path() / "fetic_wide_two_bars.toml";
  std::ofstream(path) << R"(model = "bar"
[defaults]
E = 2.1e11
area = 1.0e-4
elements = 4
subdomains = 2
[[strut]]
name = "left"
from = [0.0, 0.0]
to = [1.0, 0.0]
fixed = ["from"]
[[strut]]
name = "right"
from = [1.01, 0.0]
to = [2.01, 0.0]
fixed = ["to"]
[[load]]
strut = "right"
at = "from"
force = [-63000.0, 0.0]
[[contact]]
a = "left.to"
b = "right.from"
)";
  const auto wide = model_of(path.string());
  auto open = solver::make_method(solver::MethodKind::FetiC, *wide, {});
  open->start(1.0);
  solver::run_to_end(*open);
  REQUIRE(open->snapshot().active_set_size() == 0);
  CHECK(automatic_max_load(*wide, open->snapshot()) == 10.0);
  CHECK(working_set_at(*wide, 10.0) == std::vector<char>{1});
  CHECK(working_set_at(*wide, 3.0) == std::vector<char>{0});
}

namespace {

// Polls the worker's newest state until `done` holds for it (at most `seconds`).
template <class Predicate>
std::shared_ptr<const fetic::app::gui::SolveState> poll(const SolverWorker& worker, Predicate done,
                                                        double seconds = 60.0) {
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(static_cast<int>(seconds * 1e3));
  while (std::chrono::steady_clock::now() < deadline) {
    const auto state = worker.latest();
    if (state && done(*state)) return state;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return worker.latest();
}

}  // namespace

TEST_CASE("stepping live, the solver makes only the iterations it is allowed", "[worker]") {
  const auto model = model_of(std::string(FETIC_BUNDLED_SCENES_DIR) + "/thesis.toml");
  SolverWorker worker({});
  SolverTarget target;
  target.model = model;
  target.model_generation = 1;
  target.max_load = 2.0;
  target.load_factor = 1.0;
  target.request = 1;
  target.live = true;
  worker.request(target);
  // It stops at iteration 0 and stays there.
  auto state = poll(worker, [](const auto& s) { return s.request == 1; });
  REQUIRE(state->request == 1);
  for (int i = 0; i < 100 && !worker.paused(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  CHECK(worker.paused());
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  state = worker.latest();
  CHECK(state->iterates.size() == 1);
  CHECK(!state->finished);
  // Two steps: iterations 1 and 2, the same as an uninterrupted cold solve's.
  worker.allow(2);
  state = poll(worker, [](const auto& s) { return s.iterates.size() == 3; });
  REQUIRE(state->iterates.size() == 3);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  CHECK(worker.latest()->iterates.size() == 3);
  auto cold = solver::make_method(solver::MethodKind::FetiC, *model, {});
  cold->start(1.0);
  cold->step();
  cold->step();
  CHECK(state->history.back().residual == Approx(cold->history().back().residual).epsilon(1e-9));
  // Off: to the end, converged with `fetic solve`'s working set.
  worker.allow(-1);
  state = worker.wait_for(1, std::chrono::seconds(60));
  REQUIRE(state->finished);
  CHECK(state->status == solver::Status::Converged);
  CHECK(!state->cancelled);
  CHECK(state->iterates.back()->in_working_set == working_set_at(*model, 1.0));
}

TEST_CASE("a cancelled solve stops, is published cancelled, and the next one goes on", "[worker]") {
  const auto model = model_of(std::string(FETIC_BUNDLED_SCENES_DIR) + "/thesis.toml");
  SolverWorker worker({});
  SolverTarget target;
  target.model = model;
  target.model_generation = 1;
  target.max_load = 2.0;
  target.load_factor = 1.0;
  target.request = 1;
  target.live = true;  // held at iteration 1, so that the cancel surely comes mid-solve
  worker.request(target);
  worker.allow(1);
  auto state = poll(worker, [](const auto& s) { return s.iterates.size() == 2; });
  REQUIRE(state->iterates.size() == 2);
  worker.cancel();
  state = worker.wait_for(1, std::chrono::seconds(30));
  REQUIRE(state->finished);
  CHECK(state->cancelled);
  CHECK(state->status == solver::Status::Running);
  CHECK(state->iterates.size() == 2);
  CHECK(state->message == "cancelled at iteration 1");
  CHECK(!worker.busy());
  // A new request solves to the end again.
  target.live = false;
  target.request = 2;
  target.load_factor = 1.2;
  worker.request(target);
  state = worker.wait_for(2, std::chrono::seconds(60));
  REQUIRE(state->request == 2);
  CHECK(state->status == solver::Status::Converged);
  CHECK(state->iterates.back()->in_working_set == working_set_at(*model, 1.2));
}
