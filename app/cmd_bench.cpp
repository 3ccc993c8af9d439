// fetic bench [SCENES...]: every method that applies, on each scene: iterations,
// applications of F (dual methods), set-up and solve time (median of repeated runs), and the ratio
// of each to the primal active-set method measured in the same run. Also warm against cold starts
// after a 5% load change. Ratios, not absolute times, are what carries over between machines.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/data_paths.hpp"
#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "app/out_of_memory.hpp"
#include "app/output_file.hpp"
#include "app/output_options.hpp"
#include "app/scene_input.hpp"
#include "scenes/scene_error.hpp"
#include "solver/feti_method.hpp"
#include "solver/load_sweep.hpp"
#include "solver/method.hpp"

namespace fetic::app {
namespace {

struct BenchArgs {
  std::vector<std::string> scenes;
  int repeat = 5;
  std::string csv;
};

struct Variant {
  solver::MethodKind method;
  solver::Preconditioner preconditioner = solver::Preconditioner::Dirichlet;
  bool scaling = true;
  std::string label() const {
    std::string text = solver::to_string(method);
    if (solver::is_dual(method)) {
      text += std::string("/") + solver::to_string(preconditioner);
      if (!scaling && preconditioner != solver::Preconditioner::None) text += "-unscaled";
    }
    return text;
  }
};

struct Measurement {
  std::string scene, variant;
  long long unknowns = 0;
  int iterations = 0;
  long long f_applications = -1;  // in the solve; the dual methods' measure of cost
  bool converged = false;
  double setup_ms = 0.0, solve_ms = 0.0;
  int warm_iterations = -1, cold_iterations = -1;  // after a 5% load change
  double kappa = 0.0;  // the dual methods' Lanczos estimate (solver/condition_estimate.hpp)
};

double milliseconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

std::vector<Variant> variants_for(const solver::Model& model) {
  using solver::MethodKind;
  using solver::Preconditioner;
  std::vector<Variant> variants{{MethodKind::ActiveSet}};
  const bool contact_free = model.pairs.empty();
  if (contact_free) {
    variants.push_back({MethodKind::SteepestDescent});
    variants.push_back({MethodKind::ConjugateGradient});
  }
  for (Preconditioner p :
       {Preconditioner::Dirichlet, Preconditioner::Lumped, Preconditioner::None}) {
    if (contact_free) variants.push_back({MethodKind::Feti, p});
    variants.push_back({MethodKind::FetiC, p});
  }
  for (Preconditioner p : {Preconditioner::Dirichlet, Preconditioner::Lumped, Preconditioner::None})
    variants.push_back({MethodKind::Mprgp, p});
  for (Preconditioner p : {Preconditioner::Dirichlet, Preconditioner::Lumped, Preconditioner::None})
    variants.push_back({MethodKind::FetiDp, p});
  variants.push_back({MethodKind::FetiC, Preconditioner::Dirichlet, false});
  return variants;
}

Measurement measure(const solver::Model& model, const std::string& scene, const Variant& variant,
                    int repeat) {
  Measurement m;
  m.scene = scene;
  m.variant = variant.label();
  m.unknowns = model.dof_count();
  solver::SolveOptions options;
  options.preconditioner = variant.preconditioner;
  options.scaling = variant.scaling;
  const auto setup_start = std::chrono::steady_clock::now();
  auto method = solver::make_method(variant.method, model, options);
  m.setup_ms = milliseconds(std::chrono::steady_clock::now() - setup_start);
  std::vector<double> times;
  std::optional<solver::SweepDriver> driver;
  for (int r = 0; r < repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    driver.emplace(*method);  // cold
    driver->solve(1.0);
    times.push_back(milliseconds(std::chrono::steady_clock::now() - start));
  }
  m.solve_ms = median(times);
  m.iterations = method->iteration();
  if (!method->history().empty()) m.f_applications = method->history().back().f_applications;
  m.converged = method->status() == solver::Status::Converged;
  if (const auto* dual = dynamic_cast<const solver::FetiMethod*>(method.get()))
    m.kappa = dual->condition_estimate().kappa();
  if (m.converged && solver::handles_contact(variant.method)) {
    // A load step as fetic solve --load-steps takes it, and the same solve cold.
    m.warm_iterations = driver->solve(1.05).state.iteration;
    m.cold_iterations = solver::SweepDriver(*method).solve(1.05).state.iteration;
  }
  return m;
}

std::string table(const std::vector<Measurement>& rows) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line, "%-22s %-28s %9s %6s %6s %10s %10s %9s %9s %11s\n", "scene",
                "method", "unknowns", "iter", "F", "setup ms", "solve ms", "solve/AS", "total/AS",
                "warm/cold");
  out << line;
  for (size_t i = 0; i < rows.size(); ++i) {
    const Measurement& m = rows[i];
    // The active-set row of the same scene is the reference.
    const Measurement* reference = nullptr;
    for (const Measurement& r : rows)
      if (r.scene == m.scene && r.variant == "active-set") reference = &r;
    const double solve_ratio = reference ? m.solve_ms / reference->solve_ms : 0.0;
    const double total_ratio =
        reference ? (m.setup_ms + m.solve_ms) / (reference->setup_ms + reference->solve_ms) : 0.0;
    std::string warm = "-";
    if (m.warm_iterations >= 0)
      warm = std::to_string(m.warm_iterations) + "/" + std::to_string(m.cold_iterations);
    const std::string applied = m.f_applications >= 0 ? std::to_string(m.f_applications) : "-";
    std::snprintf(line, sizeof line, "%-22s %-28s %9lld %5d%s %6s %10.3f %10.3f %9.3f %9.3f %11s\n",
                  std::filesystem::path(m.scene).filename().string().c_str(), m.variant.c_str(),
                  m.unknowns, m.iterations, m.converged ? " " : "!", applied.c_str(), m.setup_ms,
                  m.solve_ms, solve_ratio, total_ratio, warm.c_str());
    out << line;
  }
  return out.str();
}

int run_bench(const BenchArgs& args) {
  std::vector<std::string> scenes = args.scenes;
  if (scenes.empty()) {
    for (const char* name :
         {"thesis.toml", "two_bars.toml", "chain.toml", "cantilevers.toml", "plane_pair.toml",
          "frame_post_on_beam.toml", "frame_apex_stop.toml", "frame_portal_sway.toml",
          "frame_beam_on_contacts.toml", "frame_truss_bridge.toml", "frame_scaffold.toml"})
      scenes.push_back(bundled_scene(name));
    if (!std::filesystem::exists(scenes.front())) {
      std::cerr << "fetic bench: the bundled scenes are not installed (looked for "
                << scenes.front() << "; set FETIC_DATA_DIR or name the scene files)\n";
      return kExitUsage;
    }
  }
  std::vector<Measurement> rows;
  bool warmed_up = false;
  for (const std::string& path : scenes) {
    int status = kExitOk;
    const auto scene = load_scene_or_report(path, status);
    if (!scene) return status;
    if (!memory_suffices(*scene, path, {solver::all_methods(), false, 0}, status)) return status;
    Activity measuring("measuring the methods");
    const solver::Model model = solver::build_model(*scene);
    if (!warmed_up) {
      // The first parallel region starts OpenMP's threads: keep that out of the table.
      measure(model, path, {solver::MethodKind::FetiC}, 1);
      warmed_up = true;
    }
    for (const Variant& variant : variants_for(model)) {
      if (interrupted()) {
        std::cerr << scenes::printable(path) << ": fetic bench interrupted by " << interrupt_name()
                  << " after " << rows.size() << " measurement(s); no table or CSV written\n";
        return kExitInterrupted;
      }
      try {
        rows.push_back(measure(model, path, variant, std::max(1, args.repeat)));
      } catch (const solver::SolverError& error) {
        std::cerr << scenes::printable(path) << ": " << variant.label() << ": " << error.what()
                  << '\n';
      }
    }
  }
  // With --csv - the CSV goes to stdout: the table goes to stderr then.
  std::ostream& report = is_stdout(args.csv) ? std::cerr : std::cout;
  report << "Median of " << args.repeat
         << " solves per row. solve/AS, total/AS: time relative to the active-set method on "
            "the same scene, measured in this run (total = set-up + solve). warm/cold: "
            "iterations of a re-solve after a 5% load change, warm-started against cold. F: "
            "applications of the FETI operator F in the solve (MPRGP's Lanczos estimate of "
            "||F|| runs once, in the set-up). "
            "'!' marks a solve that did not converge.\n\n"
         << table(rows);
  if (args.csv.empty()) return kExitOk;
  return exit_status_of_writing([&] {
    write_output(args.csv, [&](std::ostream& out) {
      out << "scene,method,unknowns,iterations,converged,setup_ms,solve_ms,warm_iterations,"
             "cold_iterations,f_applications,kappa\n";
      for (const Measurement& m : rows)
        out << m.scene << ',' << m.variant << ',' << m.unknowns << ',' << m.iterations << ','
            << m.converged << ',' << m.setup_ms << ',' << m.solve_ms << ',' << m.warm_iterations
            << ',' << m.cold_iterations << ',' << m.f_applications << ',' << m.kappa << '\n';
    });
  });
}

}  // namespace

void register_bench(CLI::App& app, int& exit_code) {
  const auto [command, args] =
      add_command(app, "bench", "Benchmark every method on scenes (default: the bundled ones)",
                  exit_code, run_bench);
  look_up_bundled_scenes(command->add_option(
      "scenes", args->scenes, "Scene files (paths, or names of bundled scenes: fetic scenes)"));
  command->add_option("--repeat", args->repeat, "Solves per measurement (median)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  command->add_option("--csv", args->csv, "Also write the table as CSV (- for stdout)")
      ->check(output_name());
}

}  // namespace fetic::app
