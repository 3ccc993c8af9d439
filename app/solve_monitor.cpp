#include "app/solve_monitor.hpp"

#include <cmath>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/method_options.hpp"
#include "app/output_options.hpp"
#include "app/version.hpp"
#include "scenes/units.hpp"

namespace fetic::app {

void add_monitor_options(CLI::App* command, std::string& path, int& full_every,
                         const std::string& path_help) {
  command->add_option("--monitor", path, path_help)->check(output_name());
  command
      ->add_option("--monitor-full", full_every,
                   "With --monitor: add the state (displacements, contact multipliers) every "
                   "N-th iteration (N = 1 when not given)")
      ->expected(0, 1)
      ->default_str("1")
      ->check(integer_in(1, 1'000'000'000));
}

SolveMonitor::SolveMonitor(const solver::Model& model, int full_every, bool writes)
    : model_(&model), full_every_(full_every), writes_(writes) {}

void SolveMonitor::open(const std::string& path) {
  if (writes_) out_.open(path);
  start_ = std::chrono::steady_clock::now();
}

void SolveMonitor::begin_load(double load_factor) {
  load_factor_ = load_factor;
  written_ = 0;
}

void SolveMonitor::begin_load(double load_factor, const solver::Model& model) {
  model_ = &model;
  begin_load(load_factor);
}

void SolveMonitor::observe(const solver::Method& method) {
  const std::vector<solver::HistoryEntry>& history = method.history();
  if (written_ >= history.size()) return;
  const bool full = full_every_ > 0 && method.iteration() % full_every_ == 0;
  // The whole state (collective under MPI: every process gathers, rank 0 writes). The
  // working set is the same on every process.
  solver::Snapshot state;
  if (full) state = method.gathered_snapshot();
  std::vector<char> working_set;
  if (full)
    working_set = state.in_working_set;
  else if (!model_->pairs.empty())
    working_set = method.working_set();
  if (!writes_) {
    written_ = history.size();
    return;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  working_set.resize(model_->pairs.size(), 0);
  if (working_set_.size() != working_set.size()) working_set_.assign(working_set.size(), 0);

  std::string lines;
  for (; written_ < history.size(); ++written_) {
    const solver::HistoryEntry& entry = history[written_];
    nlohmann::ordered_json line;
    line["load_factor"] = load_factor_;
    line["iteration"] = entry.iteration;
    line["residual"] = entry.residual;
    line["active_set"] = entry.active_set;
    if (!std::isnan(entry.error)) line["error"] = entry.error;
    // Only the newest entry has the state at hand; the working set changes are its.
    const bool newest = written_ + 1 == history.size();
    nlohmann::ordered_json entered = nlohmann::ordered_json::array(),
                           left = nlohmann::ordered_json::array();
    if (newest)
      for (size_t k = 0; k < working_set.size(); ++k) {
        if (working_set[k] && !working_set_[k]) entered.push_back(k);
        if (!working_set[k] && working_set_[k]) left.push_back(k);
      }
    line["entered"] = entered;
    line["left"] = left;
    line["time"] = seconds;
    if (newest && full) {
      const auto displacements = solver::strut_displacements(*model_, state);
      nlohmann::ordered_json struts = nlohmann::ordered_json::array();
      for (const auto& strut : displacements) {
        nlohmann::ordered_json nodes = nlohmann::ordered_json::array();
        for (const solver::Vec2& u : strut)
          nodes.push_back({u.x(), u.y()});
        struts.push_back(nodes);
      }
      line["displacements"] = struts;
      line["multipliers"] = state.force;
    }
    lines += line.dump() + '\n';
  }
  working_set_ = working_set;
  if (!header_written_) {
    // Written with the first iteration's line, not at open: a FIFO's reader sees both.
    const nlohmann::ordered_json header = {{"fetic_version", fetic_version()},
                                           {"units",
                                            {{"length", model_->units.length},
                                             {"force", model_->units.force},
                                             {"stress", scenes::stress_unit(model_->units)}}}};
    lines = header.dump() + '\n' + lines;
    header_written_ = true;
  }
  out_.write(lines);
}

std::string SolveMonitor::close() {
  return writes_ ? out_.close() : std::string();
}

}  // namespace fetic::app
