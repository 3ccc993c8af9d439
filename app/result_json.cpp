#include "app/result_json.hpp"

#include "app/state_json.hpp"
#include "app/version.hpp"

namespace fetic::app {

nlohmann::ordered_json result_json(const solver::Model& model, const solver::Snapshot& final_state,
                                   const std::vector<solver::HistoryEntry>& history,
                                   const RunInfo& info, StreamedParts* streamed) {
  nlohmann::ordered_json result;
  result["fetic_version"] = fetic_version();
  result["scene"] = info.scene_path;
  result["title"] = model.title;
  result["model"] = scenes::to_string(model.kind);
  result["units"] = {{"length", model.units.length},
                     {"force", model.units.force},
                     {"stress", scenes::stress_unit(model.units)}};
  result["method"] = solver::to_string(info.method);
  if (solver::is_dual(info.method))
    result["preconditioner"] = solver::to_string(info.preconditioner);
  result["tolerance"] = info.tolerance;
  result["time_seconds"] = {{"setup", info.setup_seconds}, {"solve", info.solve_seconds}};
  result["ranks"] = info.ranks;
  if (!info.subdomains_per_rank.empty()) result["subdomains_per_rank"] = info.subdomains_per_rank;
  // load_factor, converged, iterations, struts, contacts, reactions, ...
  add_state(result, model, final_state, streamed);
  result["history"] = history_json(history);
  return result;
}

}  // namespace fetic::app
