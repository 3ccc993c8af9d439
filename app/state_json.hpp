#pragma once
// The part of the result file that describes one solver state (docs/SCENES.md): load
// factor, convergence, per strut nodes, displacements, elements, stresses and axial
// forces, per contact its pairs with nodes, points, normal, gap, force and activity, and
// the support reactions. The top level of the result file and every entry of `steps[]`
// (--load-steps) carry it in the same shape.

#include <vector>

#include <nlohmann/json.hpp>

#include "app/json_stream.hpp"
#include "solver/method.hpp"

namespace fetic::app {

using OrderedJson = nlohmann::ordered_json;

// Adds the state's keys to `out` (an object). A state still Running was interrupted:
// it is written with "interrupted": true, "converged": false, "status": "interrupted".
// With `streamed`, every strut is a placeholder whose writer (added to the list) writes it
// as text when write_streamed() comes to it (app/json_stream.hpp); the struts'
// displacements and element results are held as numbers until then, never as JSON.
void add_state(OrderedJson& out, const solver::Model& model, const solver::Snapshot& state,
               StreamedParts* streamed = nullptr);

OrderedJson history_json(const std::vector<solver::HistoryEntry>& history);

// "NAME.from" / "NAME.to" for a strut end.
std::string end_label(const solver::Model& model, int strut, scenes::StrutEnd end);

}  // namespace fetic::app
