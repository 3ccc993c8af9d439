#include "app/solve_outputs.hpp"

#include "app/json_layout.hpp"
#include "app/output_file.hpp"
#include "app/output_options.hpp"
#include "app/state_json.hpp"
#include "solver/stopwatch.hpp"

#include <exception>
#include <thread>

namespace fetic::app {

void add_solve_output_options(CLI::App* command, SolveOutputArgs& args) {
  command
      ->add_option("--json", args.json,
                   "Write the result file (JSON, docs/SCENES.md) here (- for stdout)")
      ->check(output_name());
  command
      ->add_option("--csv", args.csv,
                   "Write the iteration history of every load step as CSV here (- for stdout)")
      ->check(output_name());
  command
      ->add_option("--csv-steps", args.csv_steps,
                   "Write one CSV row per load step here: load factor, displacements of the "
                   "--csv-node nodes, total force and active pairs of every contact (in "
                   "scene units, named in the header)")
      ->check(output_name());
  command->add_option("--csv-node", args.csv_nodes,
                      "A node for --csv-steps: STRUT.from, STRUT.to or STRUT@i (repeatable; "
                      "default: both ends of every contact)");
  command
      ->add_option("--vtu", args.vtu,
                   "Write ParaView files here: struts.pvd and contacts.pvd with one .vtu "
                   "pair per load step")
      ->check(output_name(OutputKind::Folder));
  command->add_option("--vtu-format", args.vtu_format, "Data encoding of the .vtu files")
      ->check(CLI::IsMember({"ascii", "binary", "zlib"}))
      ->capture_default_str();
  command->add_flag("--vtu-every-iteration", args.vtu_every_iteration,
                    "One .vtu pair per iteration instead of per load step");
}

SolveOutputs::SolveOutputs(const SolveOutputArgs& args, const solver::Model& model,
                           const std::vector<double>& load_factors)
    : args_(args), model_(model), load_steps_(load_factors.size()) {
  if (args.csv_nodes.empty()) {
    nodes_ = contact_end_nodes(model);
  } else {
    for (const std::string& label : args.csv_nodes) {
      std::string problem;
      const auto node = find_node(model, label, problem);
      if (!node) throw CLI::ValidationError("--csv-node", problem);
      nodes_.push_back(*node);
    }
  }
  // ParaView's time is the load factor for a rising sweep with a frame per step.
  time_is_load_factor_ = !args.vtu_every_iteration;
  for (size_t k = 1; k < load_factors.size(); ++k)
    time_is_load_factor_ = time_is_load_factor_ && load_factors[k] > load_factors[k - 1];
  if (!args.vtu.empty())
    vtu_ = std::make_unique<VtuSeries>(args.vtu, model, *parse_vtk_encoding(args.vtu_format));
}

bool SolveOutputs::uses_stdout() const {
  return is_stdout(args_.json) || is_stdout(args_.csv) || is_stdout(args_.csv_steps);
}

bool SolveOutputs::writes_anything() const {
  return !args_.json.empty() || !args_.csv.empty() || !args_.csv_steps.empty() || vtu_;
}

std::string SolveOutputs::written_list() const {
  std::string list;
  const auto add = [&](const std::string& item) { list += (list.empty() ? "" : ", ") + item; };
  if (!args_.json.empty()) add(args_.json);
  if (!args_.csv.empty()) add(args_.csv);
  if (!args_.csv_steps.empty()) add(args_.csv_steps);
  if (vtu_) add(args_.vtu + "/struts.pvd, contacts.pvd");
  return list;
}

void SolveOutputs::iteration(const solver::Method& method) {
  if (!vtu_ || !args_.vtu_every_iteration) return;
  const solver::Stopwatch watch(writing_seconds_);
  vtu_->write(method.snapshot(), vtu_->frames());
}

void SolveOutputs::step(const solver::SweepStep& step) {
  if (!vtu_ || args_.vtu_every_iteration) return;
  const double time = time_is_load_factor_ ? step.load_factor : vtu_->frames();
  if (++steps_seen_ == load_steps_) {
    last_frame_time_ = time;  // written by finish(), from steps.back()
    return;
  }
  const solver::Stopwatch watch(writing_seconds_);
  vtu_->write(step.state, time);
}

void SolveOutputs::finish(const std::vector<solver::SweepStep>& steps, const RunInfo& info,
                          bool sweeping) {
  if (steps.empty()) return;
  SharedProgress progress(progress_, 2);
  std::exception_ptr frame_error;
  std::thread frame;
  if (last_frame_time_)
    frame = std::thread([&, time = *last_frame_time_] {
      try {
        vtu_->write(steps.back().state, time,
                    [&](const std::string& text) { progress.update(1, text); });
      } catch (...) {
        frame_error = std::current_exception();
      }
      progress.done(1);
    });
  last_frame_time_.reset();
  try {
    write_result_file(steps, info, sweeping, progress);
  } catch (...) {
    if (frame.joinable()) frame.join();
    throw;
  }
  if (frame.joinable()) frame.join();
  if (frame_error) std::rethrow_exception(frame_error);
  if (!args_.csv.empty())
    write_output(args_.csv, [&](std::ostream& out) { write_history_csv(out, steps); });
  if (!args_.csv_steps.empty())
    write_output(args_.csv_steps,
                 [&](std::ostream& out) { write_steps_csv(out, model_, steps, nodes_); });
}

void SolveOutputs::write_result_file(const std::vector<solver::SweepStep>& steps,
                                     const RunInfo& info, bool sweeping, SharedProgress& progress) {
  if (args_.json.empty()) return;
  const solver::SweepStep& last = steps.back();
  // Streamed (app/json_stream.hpp): the final state's struts and every step are made
  // as they are written.
  StreamedParts parts;
  nlohmann::ordered_json result = result_json(model_, last.state, last.history, info, &parts);
  if (sweeping) {
    const int maker = static_cast<int>(parts.makers.size());
    parts.makers.push_back([&](int k) {
      const solver::SweepStep& step = steps[static_cast<size_t>(k)];
      nlohmann::ordered_json entry;
      add_state(entry, model_, step.state);
      entry["history"] = history_json(step.history);
      return entry;
    });
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (size_t k = 0; k < steps.size(); ++k)
      list.push_back(deferred(maker, static_cast<int>(k)));
    result["steps"] = std::move(list);
  }
  int made = 0;
  const int total = static_cast<int>(model_.struts.size() + (sweeping ? steps.size() : 0));
  const auto count_part = [&] {
    progress.update(0, "writing " + args_.json + ": " + std::to_string(made) + " of " +
                           std::to_string(total) + " parts");
    ++made;
  };
  for (ElementMaker& maker : parts.makers)
    maker = [&, make = std::move(maker)](int k) {
      count_part();
      return make(k);
    };
  for (ElementWriter& writer : parts.writers)
    writer = [&, write = std::move(writer)](JsonText& text, int k, int depth) {
      count_part();
      write(text, k, depth);
    };
  write_output(args_.json, [&](std::ostream& out) {
    write_streamed(out, result, parts);
    out << '\n';
  });
  progress.done(0);
}

}  // namespace fetic::app
