#pragma once
// Writes a result document exactly as scalars_first(document).dump(1) would, without the
// whole document in memory: an array element that is a placeholder (deferred()) is made
// by its maker when it is written and dropped right after. The result file of a 1e7-
// unknown solve thus holds one strut's JSON at a time instead of every node's
// (docs/BENCHMARKS.md, "Writing the outputs"). A placeholder made by written() is
// written by its writer straight as text (app/json_text.hpp), without JSON values.

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/json_text.hpp"

namespace fetic::app {

using ElementMaker = std::function<nlohmann::ordered_json(int index)>;
// Writes element `index` at `depth` as write_streamed would write what a maker made.
using ElementWriter = std::function<void(JsonText& text, int index, int depth)>;

// The placeholder for element `index` of maker `maker` (an index into write_streamed's list).
nlohmann::ordered_json deferred(int maker, int index);
// The placeholder for element `index` of writer `writer` (an index into write_streamed's list).
nlohmann::ordered_json written(int writer, int index);

// What write_streamed makes or writes as it goes; the placeholders index into these.
struct StreamedParts {
  std::vector<ElementMaker> makers;
  std::vector<ElementWriter> writers;
};

void write_streamed(std::ostream& out, const nlohmann::ordered_json& document,
                    const StreamedParts& parts);
void write_streamed(std::ostream& out, const nlohmann::ordered_json& document,
                    const std::vector<ElementMaker>& makers);

}  // namespace fetic::app
