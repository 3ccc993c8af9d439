#pragma once
// Everything `fetic solve` writes besides its summary: the result file (--json), the CSV
// tables (--csv, --csv-steps) and the ParaView series (--vtu). The VTU frames are written
// while the solve runs (one per load step, or per iteration); the rest when it ends. An
// interrupted solve writes all of them with the current iterate, marked interrupted.

#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/csv_tables.hpp"
#include "app/progress.hpp"
#include "app/result_json.hpp"
#include "app/vtu_export.hpp"
#include "solver/load_sweep.hpp"

namespace fetic::app {

struct SolveOutputArgs {
  std::string json;
  std::string csv;
  std::string csv_steps;
  std::vector<std::string> csv_nodes;
  std::string vtu;
  std::string vtu_format = "zlib";
  bool vtu_every_iteration = false;
};

void add_solve_output_options(CLI::App* command, SolveOutputArgs& args);

class SolveOutputs {
 public:
  // Throws CLI::ValidationError for a --csv-node the scene does not have.
  SolveOutputs(const SolveOutputArgs& args, const solver::Model& model,
               const std::vector<double>& load_factors);
  // Hooks of the sweep: a VTU frame per iteration (--vtu-every-iteration) or per load
  // step. Throw OutputError.
  void iteration(const solver::Method& method);
  void step(const solver::SweepStep& step);
  // The result file and the CSV tables. Throws OutputError.
  void finish(const std::vector<solver::SweepStep>& steps, const RunInfo& info, bool sweeping);

  // A progress line for a result file or ParaView frame that takes over a second.
  void show_progress(ProgressMode mode) {
    progress_ = mode;
    if (vtu_) vtu_->show_progress(mode);
  }
  bool writes_anything() const;
  // An output goes to standard output ("-"): the command reports on stderr then.
  bool uses_stdout() const;
  // Time spent in the hooks writing files, so that the solve time can leave it out.
  double writing_seconds() const { return writing_seconds_; }
  // "result file, CSV tables, ParaView series" - what finish() and the hooks write.
  std::string written_list() const;

 private:
  const SolveOutputArgs& args_;
  const solver::Model& model_;
  std::vector<TrackedNode> nodes_;
  std::unique_ptr<VtuSeries> vtu_;
  bool time_is_load_factor_ = false;
  double writing_seconds_ = 0.0;
  ProgressMode progress_ = ProgressMode::Never;
};

}  // namespace fetic::app
