#pragma once
// Writes a result document exactly as scalars_first(document).dump(1) would, without the
// whole document in memory: an array element that is a placeholder (deferred()) is made
// by its maker when it is written and dropped right after. The result file of a 1e7-
// unknown solve thus holds one strut's JSON at a time instead of every node's
// (docs/BENCHMARKS.md, "Writing the outputs").

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fetic::app {

using ElementMaker = std::function<nlohmann::ordered_json(int index)>;

// The placeholder for element `index` of maker `maker` (an index into write_streamed's list).
nlohmann::ordered_json deferred(int maker, int index);

void write_streamed(std::ostream& out, const nlohmann::ordered_json& document,
                    const std::vector<ElementMaker>& makers);

}  // namespace fetic::app
