// fetic-bench-scale: FETI-C and MPRGP on generated plane scenes up to a million unknowns,
// every figure a ratio measured in the same run:
//   1. against the direct floor (one CHOLMOD solve with FETI-C's final working set
//      imposed as equalities), the primal active-set method and Ipopt;
//   2. numerical scalability: iterations and applications of F as the number of
//      subdomains grows 16 (full: 64) times at fixed H/h, and as h shrinks at fixed H,
//      for each method and preconditioner, with MPRGP's steps by kind and the
//      applications of F spent before the working set settled; 2c the same scenes
//      pressed flat (the whole end faces close), which isolates the face solve;
//   3. memory: FETI-C's factors (the bytes kept, and CHOLMOD's peaks summed over all
//      factorizations) against the CHOLMOD factor of the whole problem;
//   4. the frame model (generated pairs of portal frames): iterations as in 2, and a
//      comparison row as in 1.
// Tables are printed and written as CSV. `--preset quick` runs in about a minute.

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/exit_codes.hpp"
#include "app/heap_policy.hpp"
#include "app/output_file.hpp"
#include "bench/floor_pair.hpp"
#include "bench/ipopt_qp.hpp"
#include "bench/local_bytes.hpp"
#include "scenes/generate_scene.hpp"
#include "solver/direct_floor.hpp"
#include "solver/feti_method.hpp"
#include "solver/method.hpp"
#include "solver/mprgp.hpp"
#include "solver/primal_problem.hpp"
#include "solver/stopwatch.hpp"

namespace fetic::bench {
namespace {

using Clock = std::chrono::steady_clock;

using solver::seconds_since;

std::string fixed(double value, int digits = 2) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
  return buffer;
}

std::string scientific(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1e", value);
  return buffer;
}

std::string megabytes(std::size_t bytes) {
  return fixed(bytes / 1048576.0, 1);
}

// A printed table that is also written as CSV.
struct Table {
  std::string name;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  void print() const {
    std::vector<size_t> width(header.size());
    for (size_t c = 0; c < header.size(); ++c)
      width[c] = header[c].size();
    for (const auto& row : rows)
      for (size_t c = 0; c < row.size(); ++c)
        width[c] = std::max(width[c], row[c].size());
    std::cout << "\n" << name << "\n";
    auto line = [&](const std::vector<std::string>& cells) {
      std::cout << "|";
      for (size_t c = 0; c < cells.size(); ++c)
        std::cout << " " << cells[c] << std::string(width[c] - cells[c].size(), ' ') << " |";
      std::cout << "\n";
    };
    line(header);
    std::cout << "|";
    for (size_t w : width)
      std::cout << std::string(w + 2, '-') << "|";
    std::cout << "\n";
    for (const auto& row : rows)
      line(row);
    std::cout.flush();
  }
  // RFC 4180: cells such as "2 pairs, 16x8" are quoted. Written atomically.
  void write_csv(const std::string& directory, const std::string& file) const {
    if (directory.empty()) return;
    std::filesystem::create_directories(directory);
    app::write_output(directory + "/" + file, [&](std::ostream& out) {
      auto write = [&](const std::vector<std::string>& cells) {
        for (size_t c = 0; c < cells.size(); ++c)
          out << (c ? "," : "") << csv_cell(cells[c]);
        out << "\n";
      };
      write(header);
      for (const auto& row : rows)
        write(row);
    });
  }

  static std::string csv_cell(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text)
      quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
  }
};

struct FetiRun {
  int iterations = 0;
  long long f_applications = 0;  // in the solve
  int setup_f_applications = 0;  // MPRGP's Lanczos estimate of ||F||
  // Applications of F up to the iteration that last changed the working set's size: the
  // cost of finding the contact zone, the rest is the conjugate gradients on its face.
  long long f_to_settle = 0;
  solver::Mprgp::Counts steps;  // MPRGP: its steps by kind
  bool converged = false;
  double setup = 0.0, solve = 0.0;
  std::size_t memory = 0;  // CHOLMOD's peaks, summed over every factorization
  std::size_t kept = 0;    // bytes the factors hold after the set-up
  solver::Snapshot state;
  double total() const { return setup + solve; }
};

FetiRun run_dual(solver::MethodKind kind, const solver::Model& model,
                 solver::Preconditioner preconditioner) {
  FetiRun run;
  solver::SolveOptions options;
  options.preconditioner = preconditioner;
  auto start = Clock::now();
  auto method = solver::make_method(kind, model, options);
  run.setup = seconds_since(start);
  start = Clock::now();
  method->start(1.0);
  solver::run_to_end(*method);
  run.solve = seconds_since(start);
  run.iterations = method->iteration();
  run.f_applications = method->history().back().f_applications;
  if (const auto* mprgp = dynamic_cast<const solver::Mprgp*>(method.get())) {
    run.setup_f_applications = mprgp->setup_f_applications();
    run.steps = mprgp->counts();
  }
  const auto& history = method->history();
  for (std::size_t k = 1; k < history.size(); ++k)
    if (history[k].active_set != history[k - 1].active_set)
      run.f_to_settle = history[k].f_applications;
  run.converged = method->status() == solver::Status::Converged;
  run.state = method->snapshot();
  const auto& feti = dynamic_cast<const solver::FetiMethod&>(*method);
  run.memory = feti.factor_memory();
  const solver::ProcessProfile profile = feti.profile();
  // The coarse factor stays CHOLMOD's, so its peak is what it keeps (with a workspace).
  run.kept =
      static_cast<std::size_t>(profile.memory.factor + profile.memory.preconditioner_factor) +
      profile.coarse_memory;
  return run;
}

FetiRun run_feti_c(const solver::Model& model, solver::Preconditioner preconditioner) {
  return run_dual(solver::MethodKind::FetiC, model, preconditioner);
}

// "iterations / F applications", "!" when the solve did not converge.
std::string counts(const FetiRun& run) {
  return std::to_string(run.iterations) + " / " + std::to_string(run.f_applications) +
         (run.converged ? "" : "!");
}

double error_against(const solver::Model& model, const std::vector<solver::Piece>& pieces,
                     const std::vector<solver::Piece>& reference) {
  solver::Snapshot a, b;
  a.pieces = pieces;
  b.pieces = reference;
  return solver::relative_error(solver::strut_displacements(model, a),
                                solver::strut_displacements(model, b));
}

scenes::GenerateOptions plane(int pairs, int ex, int ey, int sx, int sy) {
  scenes::GenerateOptions o;
  o.model = scenes::ModelKind::Plane;
  o.pairs = pairs;
  o.elements = ex;
  o.elements_across = ey;
  o.subdomains = sx;
  o.subdomains_across = sy;
  return o;
}

scenes::GenerateOptions frame(int pairs, int elements, int subdomains) {
  scenes::GenerateOptions o;
  o.model = scenes::ModelKind::Frame;
  o.pairs = pairs;
  o.elements = elements;
  o.subdomains = subdomains;
  return o;
}

std::string describe(const scenes::GenerateOptions& o) {
  if (o.model == scenes::ModelKind::Frame)
    return std::to_string(o.pairs) + "x2 portals(" + std::to_string(o.elements) + " el, " +
           std::to_string(o.subdomains) + " sub per strut)";
  return std::to_string(o.pairs) + "x(" + std::to_string(o.elements) + "x" +
         std::to_string(o.elements_across) + " el, " + std::to_string(o.subdomains) + "x" +
         std::to_string(o.subdomains_across) + " sub)";
}

// The generator bends the left plane struts by a load along their length: without it the
// struts stay straight and their end faces close completely.
void remove_bending_loads(scenes::Scene& scene) {
  std::erase_if(scene.loads, [](const scenes::Load& load) { return load.per_length; });
}

struct Args {
  std::string preset = "quick";
  std::string csv_dir;
  bool skip_active_set_above_limit = true;
  std::vector<std::string> only;  // parts to run; empty: all
  std::string method = "mprgp";   // --only method
  std::string working_set;        // --only method writes it, --only floor reads it
  bool runs(const std::string& part) const { return only.empty() || asked(part); }
  // method and floor run only when asked for, each alone (floor_pair.hpp).
  bool asked(const std::string& part) const {
    return std::find(only.begin(), only.end(), part) != only.end();
  }
};

Table comparison_table(const std::vector<scenes::GenerateOptions>& sizes, long long ipopt_limit,
                       long long active_set_limit) {
  Table table{
      "1. FETI-C and MPRGP (Dirichlet) against the direct floor, the active-set method and "
      "Ipopt (times in seconds, set-up + solve; it / F: iterations / applications of F, "
      "MPRGP's set-up estimate of ||F|| included; ratios = other / FETI-C; error = relative "
      "displacement error against the floor)",
      {"scene", "unknowns", "subdomains", "contact pairs", "FETI-C it / F", "FETI-C s",
       "MPRGP it / F", "MPRGP s", "floor s", "FETI-C/floor", "MPRGP/floor", "active-set s",
       "AS/FETI-C", "Ipopt s", "Ipopt/FETI-C", "FETI-C err", "MPRGP err", "Ipopt err"},
      {}};
  for (const auto& options : sizes) {
    const scenes::Scene scene = scenes::generate_scene(options);
    const solver::Model model = solver::build_model(scene);
    const FetiRun feti = run_feti_c(model, solver::Preconditioner::Dirichlet);
    const FetiRun mprgp =
        run_dual(solver::MethodKind::Mprgp, model, solver::Preconditioner::Dirichlet);
    const solver::FloorSolution floor =
        solver::solve_with_working_set(model, 1.0, feti.state.in_working_set);
    FetiRun mprgp_total = mprgp;
    mprgp_total.f_applications += mprgp.setup_f_applications;
    std::vector<std::string> row{describe(options),
                                 std::to_string(model.dof_count()),
                                 std::to_string(feti.state.pieces.size()),
                                 std::to_string(model.pairs.size()),
                                 counts(feti),
                                 fixed(feti.total()),
                                 counts(mprgp_total),
                                 fixed(mprgp.total()),
                                 fixed(floor.total_seconds()),
                                 fixed(feti.total() / floor.total_seconds()),
                                 fixed(mprgp.total() / floor.total_seconds())};
    if (model.dof_count() <= active_set_limit) {
      const auto start = Clock::now();
      auto method = solver::make_method(solver::MethodKind::ActiveSet, model, {});
      method->start(1.0);
      solver::run_to_end(*method);
      const double seconds = seconds_since(start);
      row.push_back(fixed(seconds) + " (" + std::to_string(method->iteration()) + " it)");
      row.push_back(fixed(seconds / feti.total(), 1));
    } else {
      row.insert(row.end(), {"-", "-"});
    }
    std::string ipopt_error = "-";
    if (model.dof_count() <= ipopt_limit) {
      const IpoptResult ipopt = solve_with_ipopt(model, 1.0, 1e-10);
      const solver::PrimalProblem problem(model, false);
      if (ipopt.u.size() == problem.size())
        ipopt_error = scientific(error_against(model, problem.pieces(ipopt.u), floor.pieces));
      row.push_back(fixed(ipopt.seconds) + " (" + std::to_string(ipopt.iterations) + " it" +
                    (ipopt.solved ? "" : ", " + ipopt.status) + ")");
      row.push_back(fixed(ipopt.seconds / feti.total(), 1));
    } else {
      row.insert(row.end(), {"-", "-"});
    }
    row.push_back(scientific(error_against(model, feti.state.pieces, floor.pieces)));
    row.push_back(scientific(error_against(model, mprgp.state.pieces, floor.pieces)));
    row.push_back(ipopt_error);
    table.rows.push_back(row);
    // Progress on stderr (the big rows take minutes); the table is printed once, complete.
    std::cerr << "  done: " << row[0] << ", " << row[1] << " unknowns\n";
  }
  table.print();
  return table;
}

// Iterations / applications of F per method and preconditioner; MPRGP's estimate of ||F||
// (set-up, once per model) in its own column. `dirichlet_only`: the largest scenes, where
// the slower preconditioners would take too long to be useful.
// `adjust` changes each generated scene before it is solved (the pressed-flat variant).
Table scalability_table(const std::string& title, const std::vector<scenes::GenerateOptions>& sizes,
                        int dirichlet_only_above = 0,
                        const std::function<void(scenes::Scene&)>& adjust = {}) {
  Table table{
      title,
      {"scene", "unknowns", "subdomains", "H/h", "FETI-C dirichlet", "FETI-C lumped", "FETI-C none",
       "MPRGP dirichlet", "MPRGP lumped", "MPRGP none", "MPRGP power F", "FETI-C d s", "MPRGP d s",
       "MPRGP d cg / exp / prop", "F to settle: FETI-C d / MPRGP d"},
      {}};
  for (const auto& options : sizes) {
    scenes::Scene scene = scenes::generate_scene(options);
    if (adjust) adjust(scene);
    const solver::Model model = solver::build_model(scene);
    const int subdomains = options.pairs * 2 * options.subdomains * options.subdomains_across;
    std::vector<std::string> row{describe(options), std::to_string(model.dof_count()),
                                 std::to_string(subdomains),
                                 std::to_string(options.elements / options.subdomains)};
    double seconds[2] = {0.0, 0.0};
    long long settle[2] = {0, 0};
    solver::Mprgp::Counts steps;
    int power = 0;
    for (solver::MethodKind kind : {solver::MethodKind::FetiC, solver::MethodKind::Mprgp})
      for (solver::Preconditioner p :
           {solver::Preconditioner::Dirichlet, solver::Preconditioner::Lumped,
            solver::Preconditioner::None}) {
        if (dirichlet_only_above > 0 && subdomains > dirichlet_only_above &&
            p != solver::Preconditioner::Dirichlet) {
          row.push_back("-");
          continue;
        }
        const FetiRun run = run_dual(kind, model, p);
        row.push_back(counts(run));
        if (p == solver::Preconditioner::Dirichlet) {
          const int column = kind == solver::MethodKind::Mprgp ? 1 : 0;
          seconds[column] = run.total();
          settle[column] = run.f_to_settle;
          if (column == 1) steps = run.steps;
        }
        if (kind == solver::MethodKind::Mprgp) power = run.setup_f_applications;
      }
    row.push_back(std::to_string(power));
    row.push_back(fixed(seconds[0]));
    row.push_back(fixed(seconds[1]));
    row.push_back(std::to_string(steps.cg) + " / " + std::to_string(steps.expansion) + " / " +
                  std::to_string(steps.proportioning));
    row.push_back(std::to_string(settle[0]) + " / " + std::to_string(settle[1]));
    table.rows.push_back(row);
    std::cerr << "  done: " << row[0] << ", " << row[1] << " unknowns\n";
  }
  table.print();
  return table;
}

// FETI-C's factors against the floor's. Each subdomain's two factors pass through
// CHOLMOD (a double factor and its workspace) one subdomain at a time per thread and are
// kept as lean copies, so the sum of CHOLMOD's peaks over all factorizations is never
// held at once: the bytes kept are what the factors cost a solve (docs/BENCHMARKS.md).
Table memory_table(const std::vector<scenes::GenerateOptions>& sizes) {
  Table table{
      "3. Memory: FETI-C's factors (subdomains, Dirichlet interiors, coarse) against "
      "the factor of the whole problem (MB): the bytes kept after the set-up, and "
      "CHOLMOD's peaks summed over all factorizations (never held at once)",
      {"scene", "unknowns", "FETI-C kept MB", "floor factor MB", "kept / floor",
       "FETI-C CHOLMOD peaks summed MB", "peaks / floor", "floor factor nnz"},
      {}};
  for (const auto& options : sizes) {
    const scenes::Scene scene = scenes::generate_scene(options);
    const solver::Model model = solver::build_model(scene);
    const FetiRun feti = run_feti_c(model, solver::Preconditioner::Dirichlet);
    const solver::FloorSolution floor =
        solver::solve_with_working_set(model, 1.0, feti.state.in_working_set);
    table.rows.push_back({describe(options), std::to_string(model.dof_count()),
                          megabytes(feti.kept), megabytes(floor.factor_memory),
                          fixed(static_cast<double>(feti.kept) / floor.factor_memory),
                          megabytes(feti.memory),
                          fixed(static_cast<double>(feti.memory) / floor.factor_memory),
                          std::to_string(floor.factor_nonzeros)});
  }
  table.print();
  return table;
}

std::string machine() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " threads";
}

int finish() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::cout << "\npeak resident memory of this run: " << usage.ru_maxrss / 1024 << " MB\n";
  return 0;
}

int run(const Args& args) {
  const bool full = args.preset == "full";
  std::cout << "fetic-bench-scale, preset " << args.preset << ", machine: " << machine() << "\n";
  // 1. comparison: ~10k, ~100k and (full) ~1M unknowns; square elements, ~square subdomains.
  std::vector<scenes::GenerateOptions> sizes{plane(4, 40, 10, 4, 1), plane(5, 100, 24, 5, 1)};
  // ~100k is where the issue sets the Ipopt target; above ~200k the active-set method
  // (one contact per iteration, each a pass over the whole problem) and Ipopt take too
  // long to be useful.
  if (full) sizes.push_back(plane(10, 100, 24, 5, 1));
  if (full) sizes.push_back(plane(25, 200, 48, 10, 2));
  // The paired floor ratio: the largest comparison scene, one part per process.
  if (args.asked("method")) return run_method_part(sizes.back(), args.method, args.working_set);
  if (args.asked("floor")) return run_floor_part(sizes.back(), args.working_set);
  if (args.runs("comparison"))
    comparison_table(sizes, 120'000, 200'000).write_csv(args.csv_dir, "comparison.csv");

  // 1b. bytes: memory per unknown by kind, the set-up by part, F against the bandwidth,
  // on scenes of ~20x24-element subdomains (the H/h of the 1e7 scene).
  if (args.runs("bytes")) {
    std::vector<scenes::GenerateOptions> scenes{plane(5, 100, 24, 5, 1)};
    if (full) scenes.push_back(plane(25, 200, 48, 10, 2));
    if (full) scenes.push_back(plane(25, 320, 100, 16, 4));
    std::vector<std::string> names;
    for (const auto& options : scenes)
      names.push_back(describe(options));
    const BytesTables bytes = local_bytes(scenes, names);
    Table memory{"1b. Bytes per unknown by kind after MPRGP's set-up (Dirichlet preconditioner)",
                 bytes.memory_header, bytes.memory};
    memory.print();
    memory.write_csv(args.csv_dir, "bytes.csv");
    Table setup{"1c. Set-up seconds by part", bytes.setup_header, bytes.setup};
    setup.print();
    setup.write_csv(args.csv_dir, "setup.csv");
    Table apply{
        "1d. One application of F and of M^-1 (the fastest of 15 each): the bytes of the factors "
        "and blocks they read against a triad",
        bytes.apply_header, bytes.apply};
    apply.print();
    apply.write_csv(args.csv_dir, "apply_F.csv");
  }

  // 2. numerical scalability.
  const int step = full ? 16 : 8;  // elements per subdomain side (H/h)
  // 2x1 subdomains per strut have no cross points and no inner subdomain, an easy start;
  // 16x is read both from 2x1 to 8x4 and from 4x2 to 16x8.
  std::vector<scenes::GenerateOptions> more_subdomains{
      plane(2, 2 * step, step, 2, 1), plane(2, 4 * step, 2 * step, 4, 2),
      plane(2, 8 * step, 4 * step, 8, 4), plane(2, 16 * step, 8 * step, 16, 8)};
  // Full: one step further, 32x16 subdomains per strut (about a million unknowns), with
  // the Dirichlet preconditioner only.
  if (full) more_subdomains.push_back(plane(2, 32 * step, 16 * step, 32, 16));
  if (args.runs("subdomains"))
    scalability_table("2a. Iterations / applications of F as the subdomains grow at fixed H/h",
                      more_subdomains, 1024)
        .write_csv(args.csv_dir, "subdomains.csv");
  // 2c. The same scenes pressed flat: without the bending loads the end faces close over
  // their whole height, so the contact zone is known after the first proportioning and
  // what remains is the conjugate gradients on the face. Set beside 2a, it separates the
  // cost of finding the zone's edge (which grows with the nodes along the face) from the
  // cost of the face solve.
  if (args.runs("pressed"))
    scalability_table(
        "2c. The scenes of 2a pressed flat (no bending loads: the whole end faces close)",
        more_subdomains, 1, remove_bending_loads)
        .write_csv(args.csv_dir, "subdomains_pressed.csv");
  std::vector<scenes::GenerateOptions> finer{plane(2, 8, 4, 4, 2), plane(2, 16, 8, 4, 2),
                                             plane(2, 32, 16, 4, 2)};
  if (full) finer.push_back(plane(2, 64, 32, 4, 2));
  if (args.runs("refinement"))
    scalability_table(
        "2b. Iterations / applications of F as h shrinks at fixed H (4x2 subdomains per strut)",
        finer)
        .write_csv(args.csv_dir, "refinement.csv");

  // 3. memory.
  std::vector<scenes::GenerateOptions> memory{plane(5, 100, 24, 5, 1)};
  if (full) memory.push_back(plane(25, 200, 48, 10, 2));
  if (args.runs("memory")) memory_table(memory).write_csv(args.csv_dir, "memory.csv");
  if (!args.runs("frames")) return finish();

  // 4. frames: the same questions on generated portal frames (6 struts per pair).
  const int frame_step = full ? 16 : 8;
  std::vector<scenes::GenerateOptions> frame_subdomains{
      frame(4, 2 * frame_step, 2), frame(4, 4 * frame_step, 4), frame(4, 8 * frame_step, 8),
      frame(4, 16 * frame_step, 16)};
  scalability_table("4a. Frames: iterations as the subdomains grow 8 times at fixed H/h",
                    frame_subdomains)
      .write_csv(args.csv_dir, "frame_subdomains.csv");
  std::vector<scenes::GenerateOptions> frame_finer{frame(4, 8, 4), frame(4, 16, 4), frame(4, 32, 4),
                                                   frame(4, 64, 4)};
  if (full) frame_finer.push_back(frame(4, 128, 4));
  scalability_table("4b. Frames: iterations as h shrinks at fixed H (4 subdomains per strut)",
                    frame_finer)
      .write_csv(args.csv_dir, "frame_refinement.csv");
  std::vector<scenes::GenerateOptions> frame_sizes{frame(20, 40, 4)};
  if (full) frame_sizes.push_back(frame(50, 100, 5));
  comparison_table(frame_sizes, 120'000, 200'000).write_csv(args.csv_dir, "frame_comparison.csv");
  return finish();
}

}  // namespace
}  // namespace fetic::bench

int main(int argc, char** argv) {
  fetic::app::keep_freed_heap_for_reuse();  // as fetic sets it (app/main.cpp)
  CLI::App app{
      "fetic-bench-scale: FETI-C and MPRGP at scale against the direct floor, the "
      "active-set method and Ipopt"};
  fetic::bench::Args args;
  app.add_option("--preset", args.preset, "quick (about a minute) or full (about 1M unknowns)")
      ->check(CLI::IsMember({"quick", "full"}))
      ->capture_default_str();
  app.add_option("--csv-dir", args.csv_dir, "Write every table as CSV into this directory")
      ->check(CLI::NonexistentPath | CLI::ExistingDirectory);
  app.add_option("--only", args.only,
                 "Run only these parts: comparison (against the direct floor), bytes (memory by "
                 "kind, set-up by part, F against the bandwidth), subdomains, pressed (2c: the "
                 "subdomain scenes pressed flat), refinement, memory, frames; or alone, one "
                 "process each for a paired ratio: method (--method on the largest comparison "
                 "scene), floor (the direct floor with --working-set)")
      ->check(CLI::IsMember({"comparison", "bytes", "subdomains", "pressed", "refinement", "memory",
                             "frames", "method", "floor"}));
  app.add_option("--method", args.method, "--only method: mprgp or feti-c (Dirichlet)")
      ->check(CLI::IsMember({"mprgp", "feti-c"}))
      ->capture_default_str();
  app.add_option("--working-set", args.working_set,
                 "--only method: write the final working set here; --only floor: read it");
  CLI11_PARSE(app, argc, argv);
  if (args.asked("floor") && args.working_set.empty()) {
    std::cerr << "--only floor needs --working-set FILE (written by --only method)\n";
    return fetic::app::kExitUsage;
  }
  if (args.asked("method") + args.asked("floor") > 0 && args.only.size() > 1) {
    std::cerr << "--only method and --only floor each run alone\n";
    return fetic::app::kExitUsage;
  }
  try {
    return fetic::bench::run(args);
  } catch (const fetic::app::OutputError& error) {
    std::cerr << error.what() << '\n';
  } catch (const std::filesystem::filesystem_error& error) {
    std::cerr << error.what() << '\n';
  }
  return fetic::app::kExitOutput;
}
