#pragma once
// Result files are read by people too: in every object the plain values (numbers,
// strings, booleans) come first, the arrays and objects after them, each group in the
// order the keys were added. A reader sees "converged" and "iterations" at the top, not
// between two megabytes of displacements.

#include <nlohmann/json.hpp>

namespace fetic::app {

// The same document with every object's keys reordered as above (recursively).
nlohmann::ordered_json scalars_first(nlohmann::ordered_json document);

}  // namespace fetic::app
