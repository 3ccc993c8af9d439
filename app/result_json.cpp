#include "app/result_json.hpp"

#include <cmath>

namespace fetic::app {

using nlohmann::json;

nlohmann::json result_json(const solver::Model& model, const solver::Snapshot& final_state,
                           const std::vector<solver::HistoryEntry>& history, const RunInfo& info) {
  json result;
  result["scene"] = info.scene_path;
  result["title"] = model.title;
  result["model"] = scenes::to_string(model.kind);
  result["units"] = {{"length", model.units.length},
                     {"force", model.units.force},
                     {"stress", scenes::stress_unit(model.units)}};
  result["method"] = solver::to_string(info.method);
  if (solver::is_dual(info.method))
    result["preconditioner"] = solver::to_string(info.preconditioner);
  result["load_factor"] = final_state.load_factor;
  result["tolerance"] = info.tolerance;
  result["converged"] = final_state.status == solver::Status::Converged;
  result["status"] = solver::to_string(final_state.status);
  if (!final_state.message.empty()) result["message"] = final_state.message;
  result["iterations"] = final_state.iteration;
  result["time_seconds"] = {{"setup", info.setup_seconds}, {"solve", info.solve_seconds}};

  const auto displacements = solver::strut_displacements(model, final_state);
  json struts = json::array();
  for (size_t s = 0; s < model.struts.size(); ++s) {
    json nodes = json::array(), moved = json::array();
    for (size_t n = 0; n < model.struts[s].nodes.size(); ++n) {
      nodes.push_back({model.struts[s].nodes[n].x(), model.struts[s].nodes[n].y()});
      moved.push_back({displacements[s][n].x(), displacements[s][n].y()});
    }
    struts.push_back({{"name", model.strut_names[s]}, {"nodes", nodes}, {"displacements", moved}});
  }
  result["struts"] = struts;

  json contacts = json::array();
  for (size_t c = 0; c + 1 < model.contact_first_pair.size(); ++c) {
    json pairs = json::array();
    for (int k = model.contact_first_pair[c]; k < model.contact_first_pair[c + 1]; ++k) {
      const bool active =
          k < static_cast<int>(final_state.in_working_set.size()) && final_state.in_working_set[k];
      const double force =
          k < static_cast<int>(final_state.force.size()) ? final_state.force[k] : 0.0;
      pairs.push_back({{"gap", model.pairs[k].gap}, {"force", force}, {"active", active}});
    }
    contacts.push_back({{"a", model.contact_ends[c].first},
                        {"b", model.contact_ends[c].second},
                        {"pairs", pairs}});
  }
  result["contacts"] = contacts;

  json entries = json::array();
  for (const solver::HistoryEntry& entry : history) {
    json item = {{"iteration", entry.iteration},
                 {"residual", entry.residual},
                 {"active_set", entry.active_set}};
    if (!std::isnan(entry.error)) item["error"] = entry.error;
    if (entry.f_applications >= 0) item["f_applications"] = entry.f_applications;
    entries.push_back(item);
  }
  result["history"] = entries;
  return result;
}

}  // namespace fetic::app
