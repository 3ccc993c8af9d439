#include "app/gui/pick_index.hpp"

#include <algorithm>
#include <cmath>

namespace fetic::app::gui {

void PickIndex::build(std::vector<Pickable> items, float width, float height, float cell) {
  cell_ = cell;
  columns_ = std::max(1, static_cast<int>(std::ceil(width / cell)));
  rows_ = std::max(1, static_cast<int>(std::ceil(height / cell)));
  // Off-screen items cannot be hovered: drop them.
  const auto cell_of = [&](const render::Point& p) {
    return static_cast<int>(p.y / cell) * columns_ + static_cast<int>(p.x / cell);
  };
  std::erase_if(items, [&](const Pickable& item) {
    return !(item.at.x >= 0.0f && item.at.y >= 0.0f && item.at.x < width && item.at.y < height);
  });
  // Counting sort by cell.
  cell_start_.assign(static_cast<std::size_t>(columns_) * rows_ + 1, 0);
  for (const Pickable& item : items)
    ++cell_start_[static_cast<std::size_t>(cell_of(item.at)) + 1];
  for (std::size_t c = 1; c < cell_start_.size(); ++c)
    cell_start_[c] += cell_start_[c - 1];
  items_.resize(items.size());
  std::vector<std::uint32_t> next(cell_start_.begin(), cell_start_.end() - 1);
  for (const Pickable& item : items)
    items_[next[static_cast<std::size_t>(cell_of(item.at))]++] = item;
}

std::optional<Pickable> PickIndex::nearest(render::Point at, float radius) const {
  if (items_.empty()) return std::nullopt;
  const int x0 = std::max(0, static_cast<int>(std::floor((at.x - radius) / cell_)));
  const int x1 = std::min(columns_ - 1, static_cast<int>(std::floor((at.x + radius) / cell_)));
  const int y0 = std::max(0, static_cast<int>(std::floor((at.y - radius) / cell_)));
  const int y1 = std::min(rows_ - 1, static_cast<int>(std::floor((at.y + radius) / cell_)));
  std::optional<Pickable> best;
  float best_score = 0.0f;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * columns_ + x;
      for (std::uint32_t i = cell_start_[c]; i < cell_start_[c + 1]; ++i) {
        const Pickable& item = items_[i];
        const float dx = item.at.x - at.x, dy = item.at.y - at.y;
        const float d = dx * dx + dy * dy;
        if (d > radius * radius) continue;
        // A pair sits between (or on) two nodes: within 3 pixels it wins.
        const float score = d - (item.kind == Pickable::Kind::Pair ? 9.0f : 0.0f);
        if (!best || score < best_score) {
          best = item;
          best_score = score;
        }
      }
    }
  return best;
}

std::optional<render::Point> PickIndex::position(const Pickable& item) const {
  for (const Pickable& candidate : items_)
    if (candidate == item) return candidate.at;
  return std::nullopt;
}

}  // namespace fetic::app::gui
