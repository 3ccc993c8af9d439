#include "bench/floor_pair.hpp"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <vector>

#include "app/exit_codes.hpp"
#include "app/output_file.hpp"
#include "solver/direct_floor.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"
#include "solver/stopwatch.hpp"

namespace fetic::bench {
namespace {

using Clock = std::chrono::steady_clock;

using solver::seconds_since;

// The model both parts start from, and the seconds it took (the same in both processes).
solver::Model timed_model(const scenes::GenerateOptions& options) {
  const auto start = Clock::now();
  solver::Model model = solver::build_model(scenes::generate_scene(options));
  std::printf("scene        %lld unknowns, %zu contact pairs\nmodel s      %.3f\n",
              static_cast<long long>(model.dof_count()), model.pairs.size(), seconds_since(start));
  return model;
}

}  // namespace

int run_method_part(const scenes::GenerateOptions& scene, const std::string& method,
                    const std::string& working_set_file) {
  const solver::Model model = timed_model(scene);
  const auto kind = solver::parse_method(method);
  if (!kind || !solver::is_dual(*kind)) {
    std::cerr << "--method must be a dual method (mprgp, feti-c), got " << method << '\n';
    return app::kExitUsage;
  }
  auto start = Clock::now();
  auto solver_method = solver::make_method(*kind, model, {});
  const double setup = seconds_since(start);
  start = Clock::now();
  solver_method->start(1.0);
  solver::run_to_end(*solver_method);
  const double solve = seconds_since(start);
  const bool converged = solver_method->status() == solver::Status::Converged;
  std::printf(
      "method       %s: %d iterations, %lld F%s\nmethod s     %.3f (set-up %.3f + solve %.3f)\n",
      method.c_str(), solver_method->iteration(), solver_method->history().back().f_applications,
      converged ? "" : ", NOT converged", setup + solve, setup, solve);
  if (!working_set_file.empty()) {
    const std::vector<char> working_set = solver_method->working_set();
    app::write_output(working_set_file, [&](std::ostream& out) {
      for (char in : working_set)
        out << (in ? '1' : '0');
      out << '\n';
    });
  }
  return converged ? 0 : app::kExitNotConverged;
}

int run_floor_part(const scenes::GenerateOptions& scene, const std::string& working_set_file) {
  std::ifstream in(working_set_file);
  std::string text;
  if (!in || !std::getline(in, text)) {
    std::cerr << working_set_file
              << ": cannot read the working set (write it first with --only method "
                 "--working-set FILE)\n";
    return app::kExitInvalidScene;
  }
  const solver::Model model = timed_model(scene);
  std::vector<char> working_set;
  for (char c : text) {
    if (c != '0' && c != '1') {
      std::cerr << working_set_file << ":1: the working set holds only 0 and 1, found '" << c
                << "'\n";
      return app::kExitInvalidScene;
    }
    working_set.push_back(c == '1' ? 1 : 0);
  }
  if (working_set.size() != model.pairs.size()) {
    std::cerr << working_set_file << ":1: " << working_set.size() << " pairs, the scene has "
              << model.pairs.size() << " (written for another --preset?)\n";
    return app::kExitInvalidScene;
  }
  const auto start = Clock::now();
  const solver::FloorSolution floor = solver::solve_with_working_set(model, 1.0, working_set);
  std::printf("floor s      %.3f (assemble %.3f, factorize %.3f, solve %.3f; %zu unknowns)\n",
              seconds_since(start), floor.assemble_seconds, floor.factorize_seconds,
              floor.solve_seconds, floor.unknowns);
  return 0;
}

}  // namespace fetic::bench
