// How many random scenes a cross-check against the independent QP solver runs.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <string>

namespace fetic::testing {

// `full`, or the share of it that FETIC_RANDOM_SCENE_SHARE names (at least 20 scenes).
// scripts/sanitize.sh sets a quarter: under the sanitizers each scene costs about ten
// times as much, and what they look for - memory and undefined-behaviour errors - lies on
// code paths the first scenes already take; the full counts run in the main test stage.
inline int random_trials(int full) {
  const char* share = std::getenv("FETIC_RANDOM_SCENE_SHARE");
  if (!share || !*share) return full;
  const double fraction = std::clamp(std::strtod(share, nullptr), 0.0, 1.0);
  return std::min(full, std::max(20, static_cast<int>(full * fraction)));
}

}  // namespace fetic::testing
