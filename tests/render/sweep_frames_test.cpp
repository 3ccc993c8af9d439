// One truth for a load sweep: `fetic render --every-iteration` writes exactly one frame per
// iteration that `fetic solve` reports for the same arguments, plus one frame per load
// step for its initial state (iteration 0) - for every bundled scene and every method.
// Both commands drive the sweep through solver::SweepDriver (docs/ARCHITECTURE.md).

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/process.hpp"
#include "tests/support/shell_run.hpp"

namespace fs = std::filesystem;
using fetic::test::read_text;
using fetic::test::run_shell;
using fetic::test::TempDir;

namespace {

struct SolveCount {
  int status = -1;
  int steps = 0;
  int iterations = 0;  // summed over the load steps
};

// The per-step table of `fetic solve --csv-steps`: load_step,load_factor,status,iterations,...
SolveCount solve_count(const std::string& arguments, const TempDir& dir) {
  const std::string csv = dir / "steps.csv";
  SolveCount count;
  count.status = run_shell(std::string(FETIC_EXECUTABLE) + " solve " + arguments +
                           " --quiet --csv-steps " + csv)
                     .status;
  std::istringstream lines(read_text(csv));
  std::string line;
  std::getline(lines, line);  // header
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string field;
    for (int column = 0; column <= 3 && std::getline(fields, field, ','); ++column)
      if (column == 3) count.iterations += std::stoi(field);
    ++count.steps;
  }
  return count;
}

struct RenderCount {
  int status = -1;
  int frames = 0;
  std::string output;
};

RenderCount render_count(const std::string& arguments, const TempDir& dir) {
  const fs::path out = dir.path() / "frames";
  RenderCount count;
  const auto run = run_shell(std::string(FETIC_EXECUTABLE) + " render " + arguments +
                             " --every-iteration --size 32x18 --samples 1 --threads 1 --quiet "
                             "--max-frames 100000 --out " +
                             out.string());
  count.status = run.status;
  count.output = run.output;
  if (fs::is_directory(out))
    for (const auto& entry : fs::directory_iterator(out))
      if (entry.path().extension() == ".png") ++count.frames;
  return count;
}

std::vector<std::string> bundled_scenes() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(FETIC_BUNDLED_SCENES_DIR))
    if (entry.path().extension() == ".toml") names.push_back(entry.path().string());
  std::sort(names.begin(), names.end());
  return names;
}

void check_sweep(const std::string& scene, const std::string& method,
                 const std::string& load_steps) {
  const std::string arguments = scene + " --method " + method + " --load-steps " + load_steps;
  INFO(arguments);
  TempDir dir;
  const SolveCount solved = solve_count(arguments, dir);
  const RenderCount rendered = render_count(arguments, dir);
  INFO(rendered.output);
  CHECK(rendered.status == solved.status);
  if (solved.steps == 0) {  // the method cannot solve this scene: both refuse it
    CHECK(solved.status != 0);
    CHECK(rendered.frames == 0);
    return;
  }
  CHECK(rendered.frames == solved.iterations + solved.steps);
}

}  // namespace

TEST_CASE("render's iteration movie of thesis 0.9:1.1:11 shows solve's 25 feti-c iterations",
          "[sweep]") {
  const std::string arguments = std::string(FETIC_BUNDLED_SCENES_DIR) +
                                "/thesis.toml --method feti-c --load-steps 0.9:1.1:11";
  TempDir dir;
  const SolveCount solved = solve_count(arguments, dir);
  REQUIRE(solved.status == 0);
  CHECK(solved.steps == 11);
  CHECK(solved.iterations == 25);  // 7, 5, 5, 0, 0, 0, 0, 3, 5, 0, 0 (issue 23)
  const RenderCount rendered = render_count(arguments, dir);
  INFO(rendered.output);
  CHECK(rendered.status == 0);
  CHECK(rendered.frames == 25 + 11);
}

// One test case per method, so that ctest runs them side by side (each a few seconds).
#define SWEEP_FRAMES_TEST(method)                                                        \
  TEST_CASE("every bundled scene, " method ": one frame per reported iteration and step", \
            "[sweep]") {                                                                 \
    for (const std::string& scene : bundled_scenes()) check_sweep(scene, method, "0.9:1.1:3"); \
  }
SWEEP_FRAMES_TEST("sd")
SWEEP_FRAMES_TEST("cg")
SWEEP_FRAMES_TEST("active-set")
SWEEP_FRAMES_TEST("feti")
SWEEP_FRAMES_TEST("feti-c")
SWEEP_FRAMES_TEST("mprgp")
