// fetic solve SCENE: solve a scene with one method (at one load factor or over load
// steps), print a summary, write the result file.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "app/load_factor_check.hpp"
#include "app/method_options.hpp"
#include "app/out_of_memory.hpp"
#include "app/output_file.hpp"
#include "app/processes.hpp"
#include "app/progress.hpp"
#include "app/result_json.hpp"
#include "app/scene_input.hpp"
#include "app/solve_monitor.hpp"
#include "app/solve_outputs.hpp"
#include "app/solve_profile.hpp"
#include "scenes/scene_error.hpp"
#include "solver/feti_method.hpp"
#include "solver/interruption.hpp"
#include "solver/load_sweep.hpp"
#include "solver/method.hpp"

namespace fetic::app {
namespace {

struct SolveArgs {
  std::string scene;
  MethodArgs method;
  SolveOutputArgs outputs;  // --json, --csv, --csv-steps, --vtu, ...
  std::string profile;
  std::string monitor;  // --monitor: one JSON line per iteration (app/solve_monitor.hpp)
  int monitor_full = 0;
  bool reference = false;
  bool quiet = false;
  bool progress = false;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

// "1 iteration", "2 iterations".
std::string count_of(long long n, const char* singular, const char* plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
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
      << count_of(static_cast<long long>(model.struts.size()), "strut", "struts") << ", "
      << count_of(static_cast<long long>(model.contact_labels.size()), "contact", "contacts")
      << ", " << count_of(model.dof_count(), "unknown", "unknowns") << ")\n";
  out << "method       " << solver::to_string(info.method);
  if (solver::is_dual(info.method))
    out << " (preconditioner " << solver::to_string(info.preconditioner) << ")";
  out << ", load factor " << state.load_factor << ", tolerance " << info.tolerance << "\n";
  out << "converged    " << (state.status == solver::Status::Converged ? "yes" : "NO") << " after "
      << count_of(state.iteration, "iteration", "iterations") << ", relative residual "
      << format("%.3e", state.residual) << "\n";
  if (!state.message.empty()) out << "             " << state.message << "\n";
  out << "contacts     " << state.active_set_size() << " of "
      << count_of(static_cast<long long>(model.pairs.size()), "node pair", "node pairs")
      << " active";
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

int report_result(const SolveArgs& args, const solver::Model& model,
                  const std::vector<solver::SweepStep>& steps, const RunInfo& info,
                  size_t load_factor_count, bool was_interrupted, int signal,
                  const std::optional<OutputError>& output_error, SolveOutputs& outputs,
                  std::ostream& report);

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
  // Under mpirun every process runs this function in step: each reads the scene, builds
  // the model (replicated metadata) and its own subdomains; every decision that ends the
  // run is taken alike by all of them, and rank 0 alone prints and writes files.
  const solver::Communicator& processes = app::processes();
  if (processes.distributed() && !solver::distributable(args.method.kind())) {
    std::cerr << "fetic solve: --method " << solver::to_string(args.method.kind())
              << " runs in one process; under mpirun use --method feti, feti-c or mprgp\n";
    return kExitUsage;
  }
  if (args.monitor_full > 0 && args.monitor.empty()) {
    std::cerr << "fetic solve: --monitor-full needs --monitor FILE\n";
    return kExitUsage;
  }
  if (is_stdout(args.monitor) && (is_stdout(args.outputs.json) || is_stdout(args.outputs.csv) ||
                                  is_stdout(args.outputs.csv_steps))) {
    std::cerr << "fetic solve: --monitor - and another output on - cannot both go to standard "
                 "output\n";
    return kExitUsage;
  }
  if (processes.distributed() && args.outputs.vtu_every_iteration) {
    std::cerr << "fetic solve: --vtu-every-iteration runs in one process (an iterate lives in "
                 "pieces on every process); under mpirun --vtu writes one frame per load step\n";
    return kExitUsage;
  }
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
  MemoryUse use{{args.method.kind()}, !args.outputs.json.empty(), 0};
  if (args.reference) use.methods.push_back(solver::MethodKind::ActiveSet);
  if (!memory_suffices(*scene, args.scene, use, status)) return status;
  Activity assembling("assembling the model");
  const solver::Model model = solver::build_model(*scene);

  RunInfo info;
  info.scene_path = args.scene;
  info.method = args.method.kind();
  info.preconditioner = args.method.options().preconditioner;
  info.tolerance = args.method.tolerance;
  info.ranks = processes.size();

  Activity setting_up("setting up the method (factorizing the subdomains)");
  const auto setup_start = std::chrono::steady_clock::now();
  std::unique_ptr<solver::Method> method;
  std::map<double, std::vector<std::vector<solver::Vec2>>> references;
  try {
    method = solver::make_method(info.method, model, args.method.options(), processes);
    info.setup_seconds = seconds_since(setup_start);
    if (auto* dual = dynamic_cast<const solver::FetiMethod*>(method.get()))
      info.subdomains_per_rank = dual->system().partition().subdomains_per_part();
    if (args.reference) references = reference_solutions(model, args.method, args.scene);
  } catch (const solver::SolverError& error) {
    std::cerr << scenes::printable(args.scene) << ": " << error.what() << '\n';
    return kExitSolverSetup;
  }

  auto* dual = dynamic_cast<const solver::FetiMethod*>(method.get());
  ProfileRun profile;
  if (dual) profile.before_solve = dual->profile();
  const std::vector<double> load_factors = args.method.load_factors();
  const bool sweeping = !args.method.load_steps.empty();
  // Rank 0 alone writes: the other processes keep the checks (--csv-node) but no paths.
  SolveOutputArgs output_args = args.outputs;
  if (!processes.root()) {
    output_args = SolveOutputArgs{};
    output_args.csv_nodes = args.outputs.csv_nodes;
  }
  std::unique_ptr<SolveOutputs> outputs;
  int output_status = kExitOk;
  try {
    outputs = std::make_unique<SolveOutputs>(output_args, model, load_factors);
    outputs->show_progress(progress_mode(args.progress, args.quiet));
  } catch (const CLI::ValidationError& error) {
    std::cerr << scenes::printable(args.scene) << ": " << error.what() << '\n';
    output_status = kExitUsage;
  } catch (const OutputError& error) {
    output_status = report_output_error(error);
  }
  // Agreed, so that no process goes on alone (rank 0 made the directories).
  // The monitor: every process observes (a full line gathers the state, a collective),
  // rank 0 alone opens and writes.
  SolveMonitor monitor(model, args.monitor_full, processes.root());
  if (output_status == kExitOk && !args.monitor.empty()) try {
      monitor.open(args.monitor);
    } catch (const OutputError& error) {
      output_status = report_output_error(error);
    }
  output_status = static_cast<int>(processes.max(static_cast<double>(output_status)));
  if (output_status != kExitOk) return output_status;
  // With an output on stdout (-), the report goes to stderr.
  std::ostream& report = outputs->uses_stdout() || is_stdout(args.monitor) ? std::cerr : std::cout;
  if (sweeping && !args.quiet)
    report << "load steps   " << load_factors.size() << " from " << load_factors.front() << " to "
           << load_factors.back() << ", each warm-started\n";
  Activity solving("solving");
  ProgressLine progress(progress_mode(args.progress, args.quiet));
  int step_number = 0;
  const auto solve_start = std::chrono::steady_clock::now();
  solver::SweepHooks hooks;
  hooks.before_start = [&](double t) {
    ++step_number;
    monitor.begin_load(t);
    if (!args.reference) return;
    const auto it = references.find(t);
    method->set_reference(it != references.end() ? it->second
                                                 : std::vector<std::vector<solver::Vec2>>{});
  };
  hooks.on_iteration = [&](double t, const solver::Method& running) {
    outputs->iteration(running);
    if (!progress.due()) return;
    char line[160];
    const auto& history = running.history();
    std::snprintf(line, sizeof line, "solve  t = %g%s  iteration %d  residual %.3e  active %d", t,
                  sweeping ? (" (step " + std::to_string(step_number) + " of " +
                              std::to_string(load_factors.size()) + ")")
                                 .c_str()
                           : "",
                  running.iteration(), history.empty() ? 0.0 : history.back().residual,
                  history.empty() ? 0 : history.back().active_set);
    progress.update(line);
  };
  hooks.on_step = [&](const solver::SweepStep& step) {
    outputs->step(step);
    if (!sweeping || args.quiet) return;
    progress.clear();
    char line[160];
    std::snprintf(
        line, sizeof line, "  t = %-12.6g %-9s %4d iterations  %5d active  residual %.3e\n",
        step.load_factor,
        step.state.status == solver::Status::Running ? "stopped"
                                                     : solver::to_string(step.state.status),
        step.state.iteration, step.state.active_set_size(), step.state.residual);
    report << line << std::flush;
  };
  // Every process asks between iterations, so all stop at the same one: for a signal
  // (any process may have received it) or for an output rank 0 could not write.
  std::optional<OutputError> output_error;
  bool stop = false;
  hooks.keep_going = [&] {
    stop = stop || processes.any(interrupted() || output_error.has_value());
    return !stop;
  };
  // Distributed, each step's whole state (the pieces of every process) is gathered for
  // rank 0's outputs; the sweep itself keeps the local states for its warm starts. An
  // output rank 0 cannot write must not leave the sweep early there (the others would
  // wait in the next exchange): it is kept and agreed at the next keep_going.
  std::vector<solver::Snapshot> whole_states;
  const auto on_root_keeping_failure = [&](const auto& write) {
    if (!processes.root() || output_error) return;
    try {
      write();
    } catch (const OutputError& error) {
      output_error = error;
    }
  };
  if (processes.distributed()) {
    hooks.on_step = [&, on_step = hooks.on_step](const solver::SweepStep& step) {
      whole_states.push_back(method->gathered_snapshot());
      on_root_keeping_failure([&] {
        on_step({step.load_factor, whole_states.back(), step.history});
      });
    };
    hooks.on_iteration = [&, on_iteration = hooks.on_iteration](double t,
                                                                const solver::Method& running) {
      on_root_keeping_failure([&] { on_iteration(t, running); });
    };
  }
  // The monitor hook runs on every process, outside the rank-0 wrapping above: a full
  // line gathers the state (a collective every process calls at the same iterations,
  // the history being replicated). Its writes never throw (a failure is kept in the
  // stream and reported at close), so rank 0 never leaves the sweep early for it.
  if (!args.monitor.empty())
    hooks.on_iteration = [&, on_iteration = hooks.on_iteration](double t,
                                                                const solver::Method& running) {
      on_iteration(t, running);
      monitor.observe(running);
    };
  std::vector<solver::SweepStep> steps;
  try {
    steps = solver::sweep(*method, load_factors, hooks);
  } catch (const OutputError& error) {
    progress.clear();
    return report_output_error(error);  // one process: nobody waits for it
  }
  progress.clear();
  info.solve_seconds = seconds_since(solve_start) - outputs->writing_seconds();
  for (size_t i = 0; i < whole_states.size() && i < steps.size(); ++i)
    steps[i].state = whole_states[i];
  const bool was_interrupted = processes.any(interrupted());
  // The signal some process received (rank 0 may have received none).
  const int signal = static_cast<int>(processes.max(static_cast<double>(interrupt_signal())));

  if (!args.profile.empty() && dual) {
    profile.after_solve = dual->profile();
    profile.setup_seconds = info.setup_seconds;
    profile.solve_seconds = info.solve_seconds;
    profile.iterations = steps.empty() ? 0 : steps.back().state.iteration;
    if (const auto* mprgp = dynamic_cast<const solver::Mprgp*>(dual))
      profile.mprgp_steps = mprgp->counts();
    try {
      write_solve_profile(args.profile, processes, profile);
    } catch (const OutputError& error) {
      if (processes.root()) status = report_output_error(error);
    }
  }
  // A monitor line that did not arrive: reported, and the status says so unless a signal
  // ended the run.
  int monitor_status = kExitOk;
  if (!args.monitor.empty())
    if (const std::string problem = monitor.close(); !problem.empty()) {
      std::cerr << problem << '\n';
      monitor_status = kExitOutput;
    }
  if (processes.root() && status == kExitOk)
    status = report_result(args, model, steps, info, load_factors.size(), was_interrupted, signal,
                           output_error, *outputs, report);
  if (monitor_status != kExitOk && status != kExitInterrupted) status = monitor_status;
  return static_cast<int>(processes.max(static_cast<double>(status)));
}

// Rank 0 (or the only process): the outputs, the interrupt message or the summary.
int report_result(const SolveArgs& args, const solver::Model& model,
                  const std::vector<solver::SweepStep>& steps, const RunInfo& info,
                  size_t load_factor_count, bool was_interrupted, int signal,
                  const std::optional<OutputError>& output_error, SolveOutputs& outputs,
                  std::ostream& report) {
  if (output_error) return report_output_error(*output_error);
  const bool sweeping = !args.method.load_steps.empty();
  const bool announce_first =
      was_interrupted && processes().distributed() && outputs.writes_anything();
  try {
    // An interrupted solve still writes its outputs, with the current iterate marked
    // "interrupted": true, "converged": false.
    Activity writing("writing the outputs");
    // Under mpirun a signal to mpirun ends the job (SIGKILL) soon after it reaches the
    // processes, often before the outputs are written and the last message is forwarded:
    // say so first. A file appears whole or not at all.
    if (announce_first)
      std::cerr << scenes::printable(args.scene) << ": interrupted by " << signal_name(signal)
                << " at iteration " << (steps.empty() ? 0 : steps.back().state.iteration)
                << "; writing the outputs marked interrupted (a signal to mpirun may end the "
                   "job first: then none is written)"
                << std::endl;
    outputs.finish(steps, info, sweeping);
  } catch (const OutputError& error) {
    return report_output_error(error);
  }
  if (was_interrupted && announce_first) {
    std::cerr << scenes::printable(args.scene) << ": written, the current iterate marked "
              << "interrupted: " << outputs.written_list() << '\n';
    return kExitInterrupted;
  }
  if (was_interrupted) {
    const bool cut = steps.empty() || steps.size() < load_factor_count ||
                     steps.back().state.status == solver::Status::Running;
    std::cerr << scenes::printable(args.scene) << ": interrupted by " << signal_name(signal);
    if (!cut)
      std::cerr << " after the solve had finished; the outputs are complete";
    else
      std::cerr << " at iteration " << (steps.empty() ? 0 : steps.back().state.iteration);
    if (cut && outputs.writes_anything())
      std::cerr << (steps.empty() ? "; no outputs were written"
                                  : "; the current iterate, marked interrupted, is in " +
                                        outputs.written_list());
    std::cerr << '\n';
    return kExitInterrupted;
  }
  const solver::SweepStep& last = steps.back();
  if (!args.quiet) print_summary(report, model, last.state, info);
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
  add_solve_output_options(command, args->outputs);
  command->add_flag("--reference", args->reference,
                    "Record each iteration's displacement error against an active-set solve "
                    "made in the same run");
  command->add_flag("--quiet", args->quiet, "Print no summary and no progress");
  add_monitor_options(command, args->monitor, args->monitor_full,
                      "Write one JSON line per iteration here as the solve runs (- for stdout; "
                      "a FIFO or pipe can follow it live; docs/COMMANDS.md)");
  command->add_flag("--progress", args->progress,
                    "Show the progress line on stderr even when it is not a terminal");
  command->add_option("--profile", args->profile,
                      "feti, feti-c, mprgp: write what each process did in the solve (time split, "
                      "messages, bytes, coarse problem, memory) as JSON here");
  command->callback([args, &exit_code] {
    try {
      exit_code = run_solve(*args);
    } catch (const solver::SetupInterrupted& stop) {
      // Ctrl-C during the set-up: no output has been opened yet.
      const std::string message = scenes::printable(args->scene) + ": interrupted by " +
                                  interrupt_name() + " while " + stop.during() +
                                  "; no outputs were written";
      if (!processes().distributed()) {
        std::cerr << message << '\n';
        exit_code = kExitInterrupted;
        return;
      }
      // The other processes may wait in an exchange this one left: end them all.
      report_from_any_rank(message);
      solver::mpi_abort(kExitInterrupted);
    } catch (const std::bad_alloc&) {
      // Distributed, a failure that only this process met would leave the others
      // waiting in the next exchange: end them all (mpirun reports the status).
      if (!processes().distributed()) throw;
      report_from_any_rank("fetic solve: process " + std::to_string(processes().rank()) +
                           ": out of memory while " + current_activity());
      solver::mpi_abort(kExitOutOfMemory);
    } catch (const std::exception& error) {
      if (!processes().distributed()) throw;
      report_from_any_rank("fetic solve: process " + std::to_string(processes().rank()) +
                           " failed: " + error.what());
      solver::mpi_abort(kExitSolverSetup);
    }
  });
}

}  // namespace fetic::app
