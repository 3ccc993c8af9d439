#pragma once
// Everything `fetic solve` writes besides its summary: the result file (--json), the CSV
// tables (--csv, --csv-steps) and the ParaView series (--vtu). The VTU frames are written
// while the solve runs (one per load step, or per iteration), except the last load
// step's, which finish() writes on a thread of its own beside the result file; the rest
// when it ends. An interrupted solve writes all of them with the current iterate, marked
// interrupted.

#include <memory>
#include <optional>
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
  // step, the last load step's kept for finish(). Throw OutputError.
  void iteration(const solver::Method& method);
  void step(const solver::SweepStep& step);
  // The last load step's VTU frame (of steps.back()), the result file and the CSV tables.
  // The frame and the result file are written at the same time, each on a thread: each
  // alone left a core idle for much of its time (docs/BENCHMARKS.md, "Outside set-up and
  // solve"). Throws OutputError (the result file's first, when both fail).
  void finish(const std::vector<solver::SweepStep>& steps, const RunInfo& info, bool sweeping);

  // A progress line for a result file or ParaView frame that takes over a second.
  void show_progress(ProgressMode mode) {
    progress_ = mode;
    if (vtu_) vtu_->show_progress(mode);
  }
  // The solve's method has been freed: the frame finish() writes may use more memory
  // for less work (VtuSeries::hold_fields).
  void method_released() {
    if (vtu_) vtu_->hold_fields(true);
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
  void write_result_file(const std::vector<solver::SweepStep>& steps, const RunInfo& info,
                         bool sweeping, SharedProgress& progress);

  std::unique_ptr<VtuSeries> vtu_;
  size_t load_steps_ = 0;                  // planned
  size_t steps_seen_ = 0;                  // by step()
  std::optional<double> last_frame_time_;  // the last load step's frame, kept for finish()
  bool time_is_load_factor_ = false;
  double writing_seconds_ = 0.0;
  ProgressMode progress_ = ProgressMode::Never;
};

}  // namespace fetic::app
