#include "app/gui/iterate_store.hpp"

#include <algorithm>

namespace fetic::app::gui {

std::size_t snapshot_bytes(const solver::Snapshot& snapshot) {
  std::size_t bytes =
      sizeof(solver::Snapshot) + snapshot.in_working_set.size() +
      sizeof(double) * (snapshot.force.size() + static_cast<std::size_t>(snapshot.primal.size()) +
                        static_cast<std::size_t>(snapshot.dual.size()));
  for (const solver::Piece& piece : snapshot.pieces)
    bytes += sizeof(solver::Piece) + sizeof(solver::Vec2) * piece.displacement.size() +
             sizeof(double) * piece.rotation.size();
  return bytes;
}

std::size_t iterates_within(const solver::Snapshot& snapshot, std::size_t budget_bytes) {
  return std::max<std::size_t>(3,
                               budget_bytes / std::max<std::size_t>(1, snapshot_bytes(snapshot)));
}

void append_iterate(Iterates& iterates, std::shared_ptr<const solver::Snapshot> newest,
                    std::size_t keep) {
  iterates.push_back(std::move(newest));
  const std::size_t n = iterates.size();
  keep = std::max<std::size_t>(keep, 3);
  if (n <= keep) return;
  // Kept: 0, the multiples of the stride below the newest, the newest. A larger stride
  // keeps a subset of a smaller one's, so what is thinned out is never needed again.
  std::size_t stride = 1;
  while (1 + (n - 2) / stride + 1 > keep)
    stride *= 2;
  for (std::size_t i = 1; i + 1 < n; ++i)
    if (i % stride != 0) iterates[i] = iterates[i - i % stride];
}

}  // namespace fetic::app::gui
