// fetic solve SCENE: solve one scene with one method, print a summary, write the result file.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "app/atomic_file.hpp"
#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/result_json.hpp"
#include "app/scene_input.hpp"
#include "solver/method.hpp"

namespace fetic::app {
namespace {

struct SolveArgs {
  std::string scene;
  std::string method = "active-set";
  std::string preconditioner = "dirichlet";
  double tolerance = 1e-10;
  int max_iterations = 0;
  double load_factor = 1.0;
  std::string json;
  bool quiet = false;
};

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          if (std::isfinite(std::stod(text))) return {};
        } catch (const std::exception&) {
        }
        return "must be a finite number, got " + text;
      },
      "FINITE");
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

void print_summary(const solver::Model& model, const solver::Snapshot& state, const RunInfo& info) {
  const auto displacements = solver::strut_displacements(model, state);
  double largest = 0.0;
  int largest_strut = -1, largest_node = -1;
  for (size_t s = 0; s < displacements.size(); ++s)
    for (size_t n = 0; n < displacements[s].size(); ++n)
      if (displacements[s][n].norm() > largest || largest_strut < 0) {
        largest = displacements[s][n].norm();
        largest_strut = static_cast<int>(s);
        largest_node = static_cast<int>(n);
      }
  const int active = state.active_set_size();
  std::cout << "scene        " << info.scene_path << " (" << scenes::to_string(model.kind) << ", "
            << model.struts.size() << " struts, " << model.contact_labels.size() << " contacts, "
            << model.dof_count() << " unknowns)\n";
  std::cout << "method       " << solver::to_string(info.method);
  if (info.method == solver::MethodKind::Feti || info.method == solver::MethodKind::FetiC)
    std::cout << " (preconditioner " << solver::to_string(info.preconditioner) << ")";
  std::cout << ", load factor " << state.load_factor << ", tolerance " << info.tolerance << "\n";
  std::cout << "converged    " << (state.status == solver::Status::Converged ? "yes" : "NO")
            << " after " << state.iteration << " iterations, relative residual "
            << format("%.3e", state.residual) << "\n";
  if (!state.message.empty()) std::cout << "             " << state.message << "\n";
  std::cout << "contacts     " << active << " of " << model.pairs.size() << " node pairs active\n";
  if (largest_strut >= 0)
    std::cout << "largest displacement " << format("%.6e", largest) << " (strut '"
              << model.strut_names[largest_strut] << "', node " << largest_node << ")\n";
  std::cout << "time         set-up " << format("%.3f", info.setup_seconds * 1e3) << " ms, solve "
            << format("%.3f", info.solve_seconds * 1e3) << " ms\n";
}

int run_solve(const SolveArgs& args) {
  const auto scene = load_scene_or_report(args.scene);
  if (!scene) return kExitInvalidScene;
  const solver::Model model = solver::build_model(*scene);

  solver::SolveOptions options;
  options.tolerance = args.tolerance;
  options.max_iterations = args.max_iterations;
  options.preconditioner = *solver::parse_preconditioner(args.preconditioner);
  RunInfo info;
  info.scene_path = args.scene;
  info.method = *solver::parse_method(args.method);
  info.preconditioner = options.preconditioner;
  info.tolerance = args.tolerance;

  const auto setup_start = std::chrono::steady_clock::now();
  std::unique_ptr<solver::Method> method;
  try {
    method = solver::make_method(info.method, model, options);
  } catch (const solver::SolverError& error) {
    std::cerr << args.scene << ": " << error.what() << '\n';
    return kExitSolverSetup;
  }
  info.setup_seconds = seconds_since(setup_start);

  const auto solve_start = std::chrono::steady_clock::now();
  method->start(args.load_factor);
  solver::run_to_end(*method);
  info.solve_seconds = seconds_since(solve_start);
  const solver::Snapshot state = method->snapshot();

  if (!args.quiet) print_summary(model, state, info);
  if (!args.json.empty()) {
    try {
      const nlohmann::json result = result_json(model, state, method->history(), info);
      write_file_atomically(args.json, [&](std::ostream& out) { out << result.dump(1) << '\n'; });
    } catch (const OutputError& error) {
      std::cerr << error.what() << '\n';
      return kExitOutput;
    }
  }
  if (state.status != solver::Status::Converged) {
    std::cerr << args.scene << ": " << solver::to_string(info.method)
              << " did not converge: " << state.message << '\n';
    return kExitNotConverged;
  }
  return kExitOk;
}

}  // namespace

void register_solve(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SolveArgs>();
  CLI::App* command = app.add_subcommand("solve", "Solve a scene and report the result");
  command->add_option("scene", args->scene, "Scene file (TOML, see README)")->required();
  command->add_option("--method", args->method, "Method")
      ->check(CLI::IsMember({"sd", "cg", "active-set", "feti", "feti-c"}))
      ->capture_default_str();
  command->add_option("--preconditioner", args->preconditioner, "FETI preconditioner")
      ->check(CLI::IsMember({"none", "lumped", "dirichlet"}))
      ->capture_default_str();
  command->add_option("--tol", args->tolerance, "Relative tolerance")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      ->add_option("--max-iterations", args->max_iterations,
                   "Iteration cap (0: the method's default)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--load-factor", args->load_factor, "Global load factor t")
      ->check(finite_number())
      ->capture_default_str();
  command->add_option("--json", args->json, "Write the result file (JSON) here");
  command->add_flag("--quiet", args->quiet, "Print no summary");
  command->callback([args, &exit_code] { exit_code = run_solve(*args); });
}

}  // namespace fetic::app
