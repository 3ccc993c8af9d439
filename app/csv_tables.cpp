#include "app/csv_tables.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "scenes/message_text.hpp"
#include "solver/element_results.hpp"

namespace fetic::app {
namespace {

// Shortest text that reads back as the same double.
std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  double back = 0.0;
  for (int digits = 1; digits <= 17; ++digits) {
    char shorter[32];
    std::snprintf(shorter, sizeof shorter, "%.*g", digits, value);
    if (std::sscanf(shorter, "%lf", &back) == 1 && back == value) return shorter;
  }
  return buffer;
}

const char* status_text(const solver::Snapshot& state) {
  return state.status == solver::Status::Running ? "interrupted" : solver::to_string(state.status);
}

}  // namespace

std::optional<TrackedNode> find_node(const solver::Model& model, const std::string& label,
                                     std::string& problem) {
  const size_t at = label.find('@');
  const size_t dot = label.rfind('.');
  std::string name, index;
  int station = -1;
  if (at != std::string::npos) {
    name = label.substr(0, at);
    index = label.substr(at + 1);
    if (index.empty() || index.find_first_not_of("0123456789") != std::string::npos) {
      problem = scenes::quoted(label) + ": the node index after '@' must be a whole number";
      return std::nullopt;
    }
    // More digits than an int holds: out of range like any index past the last node.
    station = index.size() > 9 ? std::numeric_limits<int>::max() : std::stoi(index);
  } else if (dot != std::string::npos &&
             (label.substr(dot) == ".from" || label.substr(dot) == ".to")) {
    name = label.substr(0, dot);
  } else {
    problem = scenes::quoted(label) + ": name a node as STRUT.from, STRUT.to or STRUT@i";
    return std::nullopt;
  }
  for (size_t s = 0; s < model.strut_names.size(); ++s) {
    if (model.strut_names[s] != name) continue;
    const solver::StrutMesh& mesh = model.struts[s];
    if (station < 0) station = label.substr(dot) == ".from" ? 0 : mesh.nx;
    if (station > mesh.nx) {
      problem = scenes::quoted(label) + ": node index " + scenes::shortened(index) +
                " is out of range: strut " + scenes::quoted(name) + " has nodes 0.." +
                std::to_string(mesh.nx);
      return std::nullopt;
    }
    return TrackedNode{label, static_cast<int>(s), mesh.node(station, mesh.ny / 2)};
  }
  problem = scenes::quoted(label) + ": the scene has no strut " + scenes::quoted(name);
  return std::nullopt;
}

std::vector<TrackedNode> contact_end_nodes(const solver::Model& model) {
  std::vector<TrackedNode> nodes;
  std::string problem;
  for (const auto& [a, b] : model.contact_ends)
    for (const std::string& label : {a, b}) {
      bool seen = false;
      for (const TrackedNode& node : nodes)
        seen = seen || node.label == label;
      if (seen) continue;
      if (auto node = find_node(model, label, problem)) nodes.push_back(*node);
    }
  return nodes;
}

void write_history_csv(std::ostream& out, const std::vector<solver::SweepStep>& steps) {
  bool errors = false;
  for (const solver::SweepStep& step : steps)
    for (const solver::HistoryEntry& entry : step.history)
      errors = errors || !std::isnan(entry.error);
  out << "load_step,load_factor,iteration,residual,active_set" << (errors ? ",error" : "") << '\n';
  for (size_t k = 0; k < steps.size(); ++k)
    for (const solver::HistoryEntry& entry : steps[k].history) {
      out << k << ',' << number(steps[k].load_factor) << ',' << entry.iteration << ','
          << number(entry.residual) << ',' << entry.active_set;
      if (errors) out << ',' << (std::isnan(entry.error) ? "" : number(entry.error));
      out << '\n';
    }
}

namespace {

// The tracked nodes' displacements, reading one strut's nodes at a time.
std::vector<solver::Vec2> node_displacements(const solver::Model& model,
                                             const solver::Snapshot& state,
                                             const std::vector<TrackedNode>& nodes) {
  std::vector<solver::Vec2> result(nodes.size(), solver::Vec2::Zero());
  std::vector<std::vector<size_t>> of_strut(model.struts.size());
  for (size_t k = 0; k < nodes.size(); ++k)
    of_strut[static_cast<size_t>(nodes[k].strut)].push_back(k);
  const solver::StrutResults results(model, state);
  for (size_t s = 0; s < of_strut.size(); ++s) {
    if (of_strut[s].empty()) continue;
    const std::vector<solver::Vec2> u = results.displacements(static_cast<int>(s));
    for (size_t k : of_strut[s])
      result[k] = u[static_cast<size_t>(nodes[k].node)];
  }
  return result;
}

}  // namespace

void write_steps_csv(std::ostream& out, const solver::Model& model,
                     const std::vector<solver::SweepStep>& steps,
                     const std::vector<TrackedNode>& nodes) {
  // Quantities with a unit name it, in the scene's units: "ux:left.to [m]".
  const std::string length = " [" + model.units.length + "]",
                    force_unit = " [" + model.units.force + "]";
  out << "load_step,load_factor,status,iterations,residual,active_pairs";
  for (const TrackedNode& node : nodes)
    out << ",ux:" << node.label << length << ",uy:" << node.label << length;
  for (const auto& [a, b] : model.contact_ends)
    out << ",force:" << a << '/' << b << force_unit << ",active_pairs:" << a << '/' << b;
  out << '\n';
  for (size_t k = 0; k < steps.size(); ++k) {
    const solver::Snapshot& state = steps[k].state;
    out << k << ',' << number(steps[k].load_factor) << ',' << status_text(state) << ','
        << state.iteration << ',' << number(state.residual) << ',' << state.active_set_size();
    for (const solver::Vec2& d : node_displacements(model, state, nodes))
      out << ',' << number(d.x()) << ',' << number(d.y());
    for (size_t c = 0; c + 1 < model.contact_first_pair.size(); ++c) {
      double force = 0.0;
      int active = 0;
      for (int p = model.contact_first_pair[c]; p < model.contact_first_pair[c + 1]; ++p) {
        const auto at = static_cast<size_t>(p);
        if (at < state.force.size()) force += state.force[at];
        if (at < state.in_working_set.size() && state.in_working_set[at]) ++active;
      }
      out << ',' << number(force) << ',' << active;
    }
    out << '\n';
  }
}

}  // namespace fetic::app
