// fetic solve SCENE: solve a scene with one method (at one load factor or over load
// steps), print a summary, write the result file.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "app/load_factor_check.hpp"
#include "app/method_options.hpp"
#include "app/out_of_memory.hpp"
#include "app/output_file.hpp"
#include "app/result_json.hpp"
#include "app/scene_input.hpp"
#include "scenes/scene_error.hpp"
#include "solver/load_sweep.hpp"
#include "solver/method.hpp"

namespace fetic::app {
namespace {

struct SolveArgs {
  std::string scene;
  MethodArgs method;
  std::string json;
  bool reference = false;
  bool quiet = false;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

void print_summary(std::ostream& out, const solver::Model& model, const solver::Snapshot& state,
                   const RunInfo& info) {
  const auto displacements = solver::strut_displacements(model, state);
  double largest = 0.0;
  int largest_strut = -1, largest_node = -1;
  for (size_t s = 0; s < displacements.size(); ++s)
    for (size_t n = 0; n < displacements[s].size(); ++n)
      if (largest_strut < 0 || displacements[s][n].norm() > largest) {
        largest = displacements[s][n].norm();
        largest_strut = static_cast<int>(s);
        largest_node = static_cast<int>(n);
      }
  out << "scene        " << info.scene_path << " (" << scenes::to_string(model.kind) << ", "
      << model.struts.size() << " struts, " << model.contact_labels.size() << " contacts, "
      << model.dof_count() << " unknowns)\n";
  out << "method       " << solver::to_string(info.method);
  if (solver::is_dual(info.method))
    out << " (preconditioner " << solver::to_string(info.preconditioner) << ")";
  out << ", load factor " << state.load_factor << ", tolerance " << info.tolerance << "\n";
  out << "converged    " << (state.status == solver::Status::Converged ? "yes" : "NO") << " after "
      << state.iteration << " iterations, relative residual " << format("%.3e", state.residual)
      << "\n";
  if (!state.message.empty()) out << "             " << state.message << "\n";
  out << "contacts     " << state.active_set_size() << " of " << model.pairs.size()
      << " node pairs active";
  double total_force = 0.0;
  for (double force : state.force)
    if (std::isfinite(force)) total_force += force;
  if (!model.pairs.empty())
    out << ", total contact force " << format("%.6e", total_force) << " " << model.units.force;
  out << "\n";
  out << "units        lengths in " << model.units.length << ", forces in " << model.units.force
      << ", stresses in " << scenes::stress_unit(model.units) << "\n";
  if (largest_strut >= 0)
    out << "largest displacement " << format("%.6e", largest) << " " << model.units.length
        << " (strut '" << model.strut_names[largest_strut] << "', node " << largest_node << ")\n";
  out << "time         set-up " << format("%.3f", info.setup_seconds * 1e3) << " ms, solve "
      << format("%.3f", info.solve_seconds * 1e3) << " ms\n";
}

// Displacements of a direct (active-set) solve at every load factor, for error histories.
// A load factor the reference cannot solve (an unbounded scene) gets no error history; the
// solve itself then reports the problem with its own status.
std::map<double, std::vector<std::vector<solver::Vec2>>> reference_solutions(
    const solver::Model& model, const MethodArgs& args, const std::string& scene) {
  solver::SolveOptions options = args.options();
  options.max_iterations = 0;
  auto reference = solver::make_method(solver::MethodKind::ActiveSet, model, options);
  std::map<double, std::vector<std::vector<solver::Vec2>>> result;
  for (double t : args.load_factors()) {
    reference->start(t);
    solver::run_to_end(*reference);
    if (reference->status() != solver::Status::Converged) {
      std::cerr << scenes::printable(scene) << ": note: no error history at load factor " << t
                << ": the reference solve (active set) did not converge: " << reference->message()
                << '\n';
      continue;
    }
    result[t] = solver::strut_displacements(model, reference->snapshot());
  }
  return result;
}

int run_solve(const SolveArgs& args) {
  int status = kExitOk;
  const auto scene = load_scene_or_report(args.scene, status);
  if (!scene) return status;
  if (const std::string problem =
          load_factor_problem(*scene, args.method.load_factors(),
                              args.method.load_steps.empty() ? "--load-factor" : "--load-steps");
      !problem.empty()) {
    std::cerr << scenes::printable(args.scene) << ": " << problem << '\n';
    return kExitUsage;
  }
  MemoryUse use{{args.method.kind()}, !args.json.empty(), 0};
  if (args.reference) use.methods.push_back(solver::MethodKind::ActiveSet);
  if (!memory_suffices(*scene, args.scene, use, status)) return status;
  Activity assembling("assembling the model");
  const solver::Model model = solver::build_model(*scene);
  Activity setting_up("setting up the method (factorizing the subdomains)");

  RunInfo info;
  info.scene_path = args.scene;
  info.method = args.method.kind();
  info.preconditioner = args.method.options().preconditioner;
  info.tolerance = args.method.tolerance;

  const auto setup_start = std::chrono::steady_clock::now();
  std::unique_ptr<solver::Method> method;
  std::map<double, std::vector<std::vector<solver::Vec2>>> references;
  try {
    method = solver::make_method(info.method, model, args.method.options());
    info.setup_seconds = seconds_since(setup_start);
    if (args.reference) references = reference_solutions(model, args.method, args.scene);
  } catch (const solver::SolverError& error) {
    std::cerr << scenes::printable(args.scene) << ": " << error.what() << '\n';
    return kExitSolverSetup;
  }

  const std::vector<double> load_factors = args.method.load_factors();
  const bool sweeping = !args.method.load_steps.empty();
  // With --json - the result goes to stdout: the report goes to stderr then.
  std::ostream& report = is_stdout(args.json) ? std::cerr : std::cout;
  if (sweeping && !args.quiet)
    report << "load steps   " << load_factors.size() << " from " << load_factors.front() << " to "
           << load_factors.back() << ", each warm-started\n";
  Activity solving("solving");
  const auto solve_start = std::chrono::steady_clock::now();
  solver::SweepHooks hooks;
  hooks.before_start = [&](double t) {
    if (!args.reference) return;
    const auto it = references.find(t);
    method->set_reference(it != references.end() ? it->second
                                                 : std::vector<std::vector<solver::Vec2>>{});
  };
  hooks.on_step = [&](const solver::SweepStep& step) {
    if (!sweeping || args.quiet) return;
    char line[160];
    std::snprintf(line, sizeof line,
                  "  t = %-12.6g %-9s %4d iterations  %5d active  residual %.3e\n",
                  step.load_factor, solver::to_string(step.state.status), step.state.iteration,
                  step.state.active_set_size(), step.state.residual);
    report << line << std::flush;
  };
  hooks.keep_going = [] { return !interrupted(); };
  const std::vector<solver::SweepStep> steps = solver::sweep(*method, load_factors, hooks);
  if (interrupted()) {
    std::cerr << scenes::printable(args.scene) << ": interrupted by " << interrupt_name()
              << " at iteration " << method->iteration() << "; no result file written\n";
    return kExitInterrupted;
  }
  info.solve_seconds = seconds_since(solve_start);
  const solver::SweepStep& last = steps.back();

  if (!args.quiet) print_summary(report, model, last.state, info);
  if (!args.json.empty()) {
    try {
      Activity writing("writing the result file");
      nlohmann::json result = result_json(model, last.state, last.history, info);
      if (sweeping) {
        nlohmann::json list = nlohmann::json::array();
        for (const solver::SweepStep& step : steps)
          list.push_back({{"load_factor", step.load_factor},
                          {"converged", step.state.status == solver::Status::Converged},
                          {"iterations", step.state.iteration},
                          {"active_set", step.state.active_set_size()},
                          {"residual", step.state.residual}});
        result["steps"] = list;
      }
      write_output(args.json, [&](std::ostream& out) { out << result.dump(1) << '\n'; });
    } catch (const OutputError& error) {
      return report_output_error(error);
    }
  }
  for (const solver::SweepStep& step : steps)
    if (step.state.status != solver::Status::Converged) {
      std::cerr << scenes::printable(args.scene) << ": " << solver::to_string(info.method)
                << " did not converge at load factor " << step.load_factor << ": "
                << step.state.message << '\n';
      return kExitNotConverged;
    }
  return kExitOk;
}

}  // namespace

void register_solve(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SolveArgs>();
  CLI::App* command = app.add_subcommand("solve", "Solve a scene and report the result");
  command->add_option("scene", args->scene, "Scene file (TOML, see docs/SCENES.md)")->required();
  add_method_options(command, args->method);
  command->add_option("--json", args->json, "Write the result file (JSON) here (- for stdout)");
  command->add_flag("--reference", args->reference,
                    "Record each iteration's displacement error against an active-set solve "
                    "made in the same run");
  command->add_flag("--quiet", args->quiet, "Print no summary");
  command->callback([args, &exit_code] { exit_code = run_solve(*args); });
}

}  // namespace fetic::app
