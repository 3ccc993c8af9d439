#pragma once
// What lies under the pointer in the window: a uniform grid over the drawn positions of
// the nodes and contact pairs of the last picture (pixels), so that hovering costs a few
// grid cells however dense the scene is. Rebuilt only when the picture is redrawn.

#include <cstdint>
#include <optional>
#include <vector>

#include "render/draw_list.hpp"

namespace fetic::app::gui {

struct Pickable {
  enum class Kind : std::uint8_t { Node, Pair };
  Kind kind = Kind::Node;
  int a = 0;  // Node: strut; Pair: pair index (result-file order)
  int b = 0;  // Node: node within the strut
  render::Point at;
  bool operator==(const Pickable& o) const { return kind == o.kind && a == o.a && b == o.b; }
};

class PickIndex {
 public:
  // `cell`: grid spacing in pixels (about the pick radius).
  void build(std::vector<Pickable> items, float width, float height, float cell = 12.0f);
  // The nearest item within `radius` pixels of `at`; contact pairs win over nodes at the
  // same distance (they sit on nodes).
  std::optional<Pickable> nearest(render::Point at, float radius) const;
  // Where an item is drawn (for the state file's "located" event).
  std::optional<render::Point> position(const Pickable& item) const;
  std::size_t size() const { return items_.size(); }

 private:
  std::vector<Pickable> items_;            // sorted by cell
  std::vector<std::uint32_t> cell_start_;  // per cell, first item; back(): items_.size()
  int columns_ = 0, rows_ = 0;
  float cell_ = 12.0f;
};

}  // namespace fetic::app::gui
