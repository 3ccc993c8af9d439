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
#include <thread>

#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "app/load_factor_check.hpp"
#include "app/method_options.hpp"
#include "app/out_of_memory.hpp"
#include "app/output_file.hpp"
#include "app/output_options.hpp"
#include "app/processes.hpp"
#include "app/progress.hpp"
#include "app/result_json.hpp"
#include "app/scene_input.hpp"
#include "app/solve_monitor.hpp"
#include "app/solve_outputs.hpp"
#include "app/solve_profile.hpp"
#include "scenes/scene_error.hpp"
#include "solver/element_results.hpp"
#include "solver/feti_method.hpp"
#include "solver/interruption.hpp"
#include "solver/load_sweep.hpp"
#include "solver/method.hpp"
#include "solver/stopwatch.hpp"
#include "solver/threads.hpp"

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

using solver::seconds_since;

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

// "1 iteration", "2 iterations".
std::string count_of(long long n, const char* singular, const char* plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

// The largest displacement (the first node that has it): strut by strut on the process'
// threads, one strut's nodes at a time (the whole model's were 155 MB at 1e7).
struct Largest {
  double size = 0.0;
  int strut = -1, node = -1;
};
Largest largest_displacement(const solver::Model& model, const solver::Snapshot& state) {
  const solver::StrutResults results(model, state);
  std::vector<Largest> per_strut(model.struts.size());
  const int threads = solver::threads_for(model.dof_count());
#pragma omp parallel for num_threads(threads) schedule(dynamic)
  for (size_t s = 0; s < per_strut.size(); ++s) {
    const std::vector<solver::Vec2> u = results.displacements(static_cast<int>(s));
    for (size_t n = 0; n < u.size(); ++n)
      if (per_strut[s].node < 0 || u[n].norm() > per_strut[s].size)
        per_strut[s] = {u[n].norm(), static_cast<int>(s), static_cast<int>(n)};
  }
  Largest largest;
  for (const Largest& strut : per_strut)
    if (strut.node >= 0 && (largest.strut < 0 || strut.size > largest.size)) largest = strut;
  return largest;
}

void print_summary(std::ostream& out, const solver::Model& model, const solver::Snapshot& state,
                   const RunInfo& info) {
  const Largest found = largest_displacement(model, state);
  const double largest = found.size;
  const int largest_strut = found.strut, largest_node = found.node;
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

// Under mpirun every process runs the phases of run_solve in step: each reads the scene,
// builds the model (replicated metadata) and its own subdomains; every decision that ends
// the run is taken alike by all of them, and rank 0 alone prints and writes files. That
// policy lives here.
class RankPolicy {
 public:
  explicit RankPolicy(const solver::Communicator& processes) : processes_(processes) {}
  const solver::Communicator& processes() const { return processes_; }
  bool distributed() const { return processes_.distributed(); }
  // Rank 0 (or the only process): prints and writes.
  bool writes() const { return processes_.root(); }
  // The worst status of any process, so that every process ends alike.
  int agree(int status) const {
    return static_cast<int>(processes_.max(static_cast<double>(status)));
  }
  bool any(bool flag) const { return processes_.any(flag); }
  // The signal some process received (rank 0 may have received none).
  int signal() const { return agree(interrupt_signal()); }
  // Runs `write` on rank 0. Distributed, an output rank 0 cannot write must not leave the
  // sweep early there (the others would wait in the next exchange): the failure is kept
  // and agreed between iterations (stop_requested); one process rethrows it.
  template <class Write>
  void on_root(const Write& write) {
    if (!writes() || output_error_) return;
    try {
      write();
    } catch (const OutputError& error) {
      if (!distributed()) throw;
      output_error_ = error;
    }
  }
  // Every process asks between iterations, so all stop at the same one: for a signal (any
  // process may have received it) or for an output rank 0 could not write.
  bool stop_requested() {
    stop_ = stop_ || any(interrupted() || output_error_.has_value());
    return stop_;
  }
  const std::optional<OutputError>& output_error() const { return output_error_; }

 private:
  const solver::Communicator& processes_;
  std::optional<OutputError> output_error_;
  bool stop_ = false;
};

// ---- phase 0: the arguments and the output targets, before any work ----

int refused_combination(const SolveArgs& args, const RankPolicy& ranks) {
  const solver::MethodKind kind = args.method.kind();
  const char* problem = nullptr;
  if (ranks.distributed() && !solver::distributable(kind))
    problem = "runs in one process; under mpirun use --method feti, feti-c, mprgp or feti-dp";
  else if (args.monitor_full > 0 && args.monitor.empty())
    problem = "--monitor-full needs --monitor FILE";
  else if (is_stdout(args.monitor) &&
           (is_stdout(args.outputs.json) || is_stdout(args.outputs.csv) ||
            is_stdout(args.outputs.csv_steps)))
    problem = "--monitor - and another output on - cannot both go to standard output";
  else if (ranks.distributed() && args.outputs.vtu_every_iteration)
    problem =
        "--vtu-every-iteration runs in one process (an iterate lives in pieces on every "
        "process); under mpirun --vtu writes one frame per load step";
  else if (!args.profile.empty() && !solver::is_dual(kind))
    problem = "keeps no profile: --profile is for feti, feti-c, mprgp and feti-dp";
  if (!problem) return kExitOk;
  std::cerr << "fetic solve: ";
  if (problem[0] != '-') std::cerr << "--method " << solver::to_string(kind) << " ";
  std::cerr << problem << '\n';
  return kExitUsage;
}

// Every output target is checked before the work starts (a missing folder must not
// surface after an hour's solve, nor after another output has been replaced).
int refused_target(const SolveArgs& args, const RankPolicy& ranks) {
  int status = kExitOk;
  if (ranks.writes()) try {
      for (const std::string* file : {&args.outputs.json, &args.outputs.csv,
                                      &args.outputs.csv_steps, &args.monitor, &args.profile})
        if (!file->empty()) check_output_file(*file);
      if (!args.outputs.vtu.empty()) check_output_folder(args.outputs.vtu);
    } catch (const OutputError& error) {
      status = report_output_error(error);
    }
  return ranks.agree(status);
}

// ---- phase 1: read the scene ----

// What the memory check counts for this solve (app/memory_estimate.hpp).
MemoryUse memory_use(const SolveArgs& args) {
  MemoryUse use{{args.method.kind()},
                !args.outputs.json.empty(),
                0,
                !args.outputs.vtu.empty(),
                args.method.single_factors,
                args.method.preconditioner == "dirichlet"};
  if (args.reference) use.methods.push_back(solver::MethodKind::ActiveSet);
  return use;
}

std::optional<scenes::Scene> read_scene(const SolveArgs& args, int& status) {
  auto scene = load_scene_or_report(args.scene, status);
  if (!scene) return std::nullopt;
  if (const std::string problem =
          load_factor_problem(*scene, args.method.load_factors(),
                              args.method.load_steps.empty() ? "--load-factor" : "--load-steps");
      !problem.empty()) {
    std::cerr << scenes::printable(args.scene) << ": " << problem << '\n';
    status = kExitUsage;
    return std::nullopt;
  }
  if (!memory_suffices(*scene, args.scene, memory_use(args), status)) return std::nullopt;
  return scene;
}

// ---- phase 2: set up the method ----

struct SetUp {
  std::unique_ptr<solver::Method> method;
  const solver::FetiMethod* dual = nullptr;  // the method, when it is a dual one
  std::map<double, std::vector<std::vector<solver::Vec2>>> references;  // --reference
  RunInfo info;
  ProfileRun profile;
  bool profiled = false;  // profile holds the solve's figures
  std::thread releasing;  // frees the method while the outputs are written

  SetUp() = default;
  SetUp(const SetUp&) = delete;
  SetUp& operator=(const SetUp&) = delete;
  ~SetUp() {
    if (releasing.joinable()) releasing.join();
  }
};

// After the sweep the method is needed only for its profile, taken here. In one process it
// is then freed on another thread while the outputs are written: the subdomain factors
// are most of the process (6.5 GB of the 1e7 scene), and freeing them took about a second
// after the summary (docs/BENCHMARKS.md, "Outputs at 1e7"); the outputs are then also
// written beside less memory.
void take_profile(const std::vector<solver::SweepStep>& steps, SetUp& setup, bool distributed,
                  SolveOutputs& outputs) {
  if (setup.dual) {
    ProfileRun& profile = setup.profile;
    profile.after_solve = setup.dual->profile();
    profile.setup_seconds = setup.info.setup_seconds;
    profile.solve_seconds = setup.info.solve_seconds;
    profile.iterations = steps.empty() ? 0 : steps.back().state.iteration;
    if (const auto* mprgp = dynamic_cast<const solver::Mprgp*>(setup.dual)) {
      profile.mprgp_steps = mprgp->counts();
      profile.setup_f_applications = mprgp->setup_f_applications();
      profile.setup_norm_estimate_seconds = mprgp->norm_estimate_seconds();
      profile.contact_coarse_columns = mprgp->contact_columns();
    }
    profile.condition = setup.dual->condition_estimate();
    setup.profiled = true;
  }
  setup.dual = nullptr;
  // Under mpirun every process frees its method here, on the main thread (its destruction
  // sends nothing): rank 0 would otherwise write the outputs beside its factors, which set
  // its peak (docs/DISTRIBUTED.md, rank 0's peak).
  if (distributed)
    setup.method.reset();
  else
    setup.releasing = std::thread([method = std::move(setup.method)]() mutable { method.reset(); });
  outputs.method_released();
}

int set_up(const SolveArgs& args, const solver::Model& model, const RankPolicy& ranks,
           SetUp& setup) {
  RunInfo& info = setup.info;
  info.scene_path = args.scene;
  info.method = args.method.kind();
  info.preconditioner = args.method.options().preconditioner;
  info.tolerance = args.method.tolerance;
  info.ranks = ranks.processes().size();
  Activity setting_up("setting up the method (factorizing the subdomains)");
  const auto start = std::chrono::steady_clock::now();
  try {
    setup.method =
        solver::make_method(info.method, model, args.method.options(), ranks.processes());
    info.setup_seconds = seconds_since(start);
    setup.dual = dynamic_cast<const solver::FetiMethod*>(setup.method.get());
    if (setup.dual) {
      info.subdomains_per_rank = setup.dual->system().partition().subdomains_per_part();
      setup.profile.before_solve = setup.dual->profile();
    }
    if (args.reference) setup.references = reference_solutions(model, args.method, args.scene);
  } catch (const solver::SolverError& error) {
    std::cerr << scenes::printable(args.scene) << ": " << error.what() << '\n';
    return kExitSolverSetup;
  }
  return kExitOk;
}

// ---- phase 3: open the outputs ----

// Rank 0 alone writes: the other processes keep the checks (--csv-node) but no paths.
// The monitor: every process observes (a full line gathers the state, a collective), rank
// 0 alone opens and writes.
int open_outputs(const SolveArgs& args, const solver::Model& model, const RankPolicy& ranks,
                 SolveOutputArgs& output_args, std::unique_ptr<SolveOutputs>& outputs,
                 SolveMonitor& monitor) {
  output_args = args.outputs;  // kept by the caller: SolveOutputs refers to it
  if (!ranks.writes()) {
    output_args = SolveOutputArgs{};
    output_args.csv_nodes = args.outputs.csv_nodes;
  }
  int status = kExitOk;
  try {
    outputs = std::make_unique<SolveOutputs>(output_args, model, args.method.load_factors());
    outputs->show_progress(progress_mode(args.progress, args.quiet));
    if (!args.monitor.empty()) monitor.open(args.monitor);
  } catch (const CLI::ValidationError& error) {
    std::cerr << scenes::printable(args.scene) << ": " << error.what() << '\n';
    status = kExitUsage;
  } catch (const OutputError& error) {
    status = report_output_error(error);
  }
  return ranks.agree(status);  // so that no process goes on alone
}

// ---- phase 4: sweep the load factors ----

struct Sweep {
  const SolveArgs& args;
  const solver::Model& model;
  SetUp& setup;
  RankPolicy& ranks;
  SolveOutputs& outputs;
  SolveMonitor& monitor;
  std::ostream& report;
  std::vector<double> load_factors = args.method.load_factors();
  bool sweeping = !args.method.load_steps.empty();
  int step_number = 0;
  ProgressLine progress{progress_mode(args.progress, args.quiet)};

  void before_start(double t) {
    ++step_number;
    monitor.begin_load(t);
    if (!args.reference) return;
    const auto it = setup.references.find(t);
    setup.method->set_reference(
        it != setup.references.end() ? it->second : std::vector<std::vector<solver::Vec2>>{});
  }
  // Every process: the monitor observes (a full line gathers the state, a collective
  // every process calls at the same iterations); its writes never throw (a failure is
  // kept in the stream and reported at close).
  void on_iteration(double t, const solver::Method& running) {
    ranks.on_root([&] { outputs.iteration(running); });
    if (!args.monitor.empty()) monitor.observe(running);
    if (!ranks.writes() || !progress.due()) return;
    char line[160];
    const auto& history = running.history();
    const std::string step = sweeping ? " (step " + std::to_string(step_number) + " of " +
                                            std::to_string(load_factors.size()) + ")"
                                      : "";
    std::snprintf(line, sizeof line, "solve  t = %g%s  iteration %d  residual %.3e  active %d", t,
                  step.c_str(), running.iteration(),
                  history.empty() ? 0.0 : history.back().residual,
                  history.empty() ? 0 : history.back().active_set);
    progress.update(line);
  }
  // Distributed, each step's own state is replaced by the whole one (the pieces of every
  // process), gathered on rank 0 for its outputs (collective). It is moved, never copied:
  // rank 0 held it twice beside the factors (docs/DISTRIBUTED.md, rank 0's peak).
  void on_step(solver::SweepStep& step) {
    if (ranks.distributed()) step.state = setup.method->gathered(std::move(step.state));
    report_step(step);
  }
  void report_step(const solver::SweepStep& finished) {
    const solver::SweepStep* step = &finished;
    ranks.on_root([&] { outputs.step(finished); });
    if (!sweeping || args.quiet || !ranks.writes()) return;
    progress.clear();
    char line[160];
    std::snprintf(
        line, sizeof line, "  t = %-12.6g %-9s %4d iterations  %5d active  residual %.3e\n",
        step->load_factor,
        step->state.status == solver::Status::Running ? "stopped"
                                                      : solver::to_string(step->state.status),
        step->state.iteration, step->state.active_set_size(), step->state.residual);
    report << line << std::flush;
  }

  // Throws OutputError (one process) when an output cannot be written.
  std::vector<solver::SweepStep> run() {
    if (sweeping && !args.quiet && ranks.writes())
      report << "load steps   " << load_factors.size() << " from " << load_factors.front() << " to "
             << load_factors.back() << ", each warm-started\n";
    Activity solving("solving");
    solver::SweepHooks hooks;
    hooks.before_start = [&](double t) { before_start(t); };
    hooks.on_iteration = [&](double t, const solver::Method& m) { on_iteration(t, m); };
    hooks.on_step = [&](solver::SweepStep& step) { on_step(step); };
    hooks.keep_going = [&] { return !ranks.stop_requested(); };
    const auto start = std::chrono::steady_clock::now();
    std::vector<solver::SweepStep> steps;
    try {
      steps = solver::sweep(*setup.method, load_factors, hooks);
    } catch (...) {
      progress.clear();
      throw;
    }
    progress.clear();
    setup.info.solve_seconds = seconds_since(start) - outputs.writing_seconds();
    return steps;
  }
};

// ---- phase 5: write the outputs, all or none ----

// Collective (the profile gathers every process' figures). The files wait in their
// temporaries (PendingOutputs) and are committed only when every output could be
// written; otherwise none replaces what was there.
int write_outputs(const SolveArgs& args, const std::vector<solver::SweepStep>& steps, SetUp& setup,
                  RankPolicy& ranks, SolveOutputs& outputs, SolveMonitor& monitor,
                  PendingOutputs& pending, bool was_interrupted) {
  int status = kExitOk;
  take_profile(steps, setup, ranks.distributed(), outputs);
  // Interrupted under mpirun with outputs to write: rank 0 says so before it writes.
  const int signal = was_interrupted ? ranks.signal() : 0;  // collective
  const bool announce = was_interrupted && ranks.distributed() && outputs.writes_anything();
  const auto keep_first = [&](const OutputError& error) {
    if (status == kExitOk) status = report_output_error(error);
  };
  if (ranks.writes()) try {
      if (ranks.output_error()) throw *ranks.output_error();
      Activity writing("writing the outputs");
      // Under mpirun a signal to mpirun ends the job (SIGKILL) soon after it reaches the
      // processes, often before the outputs are written and the last message is
      // forwarded: say so first. A file appears whole or not at all.
      if (announce)
        std::cerr << scenes::printable(args.scene) << ": interrupted by " << signal_name(signal)
                  << " at iteration " << (steps.empty() ? 0 : steps.back().state.iteration)
                  << "; writing the outputs marked interrupted (a signal to mpirun may end the "
                     "job first: then none is written)"
                  << std::endl;
      // An interrupted solve still writes its outputs, with the current iterate marked
      // "interrupted": true, "converged": false.
      outputs.finish(steps, setup.info, !args.method.load_steps.empty());
    } catch (const OutputError& error) {
      keep_first(error);
    }
  if (!args.profile.empty() && setup.profiled) {
    try {
      write_solve_profile(args.profile, ranks.processes(), setup.profile);
    } catch (const OutputError& error) {
      if (ranks.writes()) keep_first(error);
    }
  }
  // A monitor line that did not arrive: the run's outputs are incomplete.
  if (!args.monitor.empty())
    if (const std::string problem = monitor.close(); !problem.empty() && status == kExitOk) {
      std::cerr << problem << '\n';
      status = interrupted() ? kExitInterrupted : kExitOutput;
    }
  if (status == kExitOk && ranks.writes()) try {
      pending.commit();
    } catch (const OutputError& error) {
      keep_first(error);
    }
  return ranks.agree(status);
}

// ---- phase 6: report ----

// Rank 0 (or the only process): the interrupt message or the summary.
int report_result(const SolveArgs& args, const solver::Model& model,
                  const std::vector<solver::SweepStep>& steps, const RunInfo& info,
                  const RankPolicy& ranks, bool was_interrupted, const SolveOutputs& outputs,
                  std::ostream& report) {
  if (was_interrupted) {
    const int signal = ranks.signal();
    if (!ranks.writes()) return kExitInterrupted;
    if (ranks.distributed() && outputs.writes_anything()) {  // announced before writing
      std::cerr << scenes::printable(args.scene) << ": written, the current iterate marked "
                << "interrupted: " << outputs.written_list() << '\n';
      return kExitInterrupted;
    }
    const bool cut = steps.empty() || steps.size() < args.method.load_factors().size() ||
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
  if (!ranks.writes()) return kExitOk;
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

// The phases: check, read, set up, open the outputs, sweep, write, report.
int run_solve(const SolveArgs& args) {
  RankPolicy ranks(app::processes());
  if (const int status = refused_combination(args, ranks)) return status;
  if (const int status = refused_target(args, ranks)) return status;
  int status = kExitOk;
  const auto scene = read_scene(args, status);
  if (!scene) return status;
  const solver::Model model = [&] {
    Activity assembling("assembling the model");
    return solver::build_model(*scene);
  }();
  SetUp setup;
  // Beside the measured peak in --profile: how well the memory check estimated it.
  setup.profile.estimated_peak_bytes = estimate_memory(*scene, memory_use(args)).bytes;
  if (const int failed = set_up(args, model, ranks, setup)) return failed;
  PendingOutputs pending;  // every file waits for the commit in write_outputs
  SolveOutputArgs output_args;
  std::unique_ptr<SolveOutputs> outputs;
  SolveMonitor monitor(model, args.monitor_full, ranks.writes());
  if (const int failed = open_outputs(args, model, ranks, output_args, outputs, monitor))
    return failed;
  // With an output on stdout (-), the report goes to stderr.
  std::ostream& report = outputs->uses_stdout() || is_stdout(args.monitor) ? std::cerr : std::cout;
  Sweep sweep{args, model, setup, ranks, *outputs, monitor, report};
  std::vector<solver::SweepStep> steps;
  try {
    steps = sweep.run();
  } catch (const OutputError& error) {
    return report_output_error(error);  // one process: nobody waits for it
  }
  const bool was_interrupted = ranks.any(interrupted());
  if (const int failed =
          write_outputs(args, steps, setup, ranks, *outputs, monitor, pending, was_interrupted))
    return failed;
  return ranks.agree(
      report_result(args, model, steps, setup.info, ranks, was_interrupted, *outputs, report));
}

}  // namespace

void register_solve(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SolveArgs>();
  CLI::App* command = app.add_subcommand("solve", "Solve a scene and report the result");
  look_up_bundled_scenes(command->add_option("scene", args->scene, kSceneArgumentHelp))->required();
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
  command
      ->add_option(
          "--profile", args->profile,
          "feti, feti-c, mprgp, feti-dp: write what each process did in the solve (time split, "
          "messages, bytes, coarse problem, memory) as JSON here")
      ->check(output_name());
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
