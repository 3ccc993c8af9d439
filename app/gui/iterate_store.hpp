#pragma once
// The iterates of a solve the window keeps for scrubbing back through it. On a small scene
// every iterate is kept; on a huge one each takes tens of MB (ten million unknowns: about
// 85 MB), so only a bounded number are: iteration 0, the newest, and every s-th between
// them, s the smallest power of two that keeps the count within the budget. The vector
// still has one entry per iteration; an entry thinned out points to the kept iterate
// before it, so scrubbing there shows the nearest earlier kept iterate (and says which
// iteration it is).

#include <cstddef>
#include <memory>
#include <vector>

#include "solver/method.hpp"

namespace fetic::app::gui {

using Iterates = std::vector<std::shared_ptr<const solver::Snapshot>>;

// Bytes of the values a snapshot holds (displacements, rotations, multipliers, forces).
std::size_t snapshot_bytes(const solver::Snapshot& snapshot);

// Distinct iterates kept within `budget_bytes` of ones like `snapshot`: at least 3 (the
// first, one between, the newest).
std::size_t iterates_within(const solver::Snapshot& snapshot, std::size_t budget_bytes);

// Appends the newest iterate and thins the ones between the first and it so that at most
// `keep` (3 or more) distinct iterates remain.
void append_iterate(Iterates& iterates, std::shared_ptr<const solver::Snapshot> newest,
                    std::size_t keep);

// What the window keeps of one solve's iterates: 256 MiB.
inline constexpr std::size_t kIterateBudget = std::size_t{256} << 20;

}  // namespace fetic::app::gui
