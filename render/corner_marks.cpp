#include "render/corner_marks.hpp"

#include <algorithm>

#include "render/colormap.hpp"
#include "solver/corners.hpp"
#include "solver/decomposition.hpp"

namespace fetic::render {
namespace {

// The displacement of a strut node as the first piece of the snapshot holding it has it.
solver::Vec2 first_piece_displacement(const solver::Snapshot& snapshot, int strut, int i, int k) {
  for (const solver::Piece& piece : snapshot.pieces) {
    if (piece.strut != strut || !piece.box.contains(i, k)) continue;
    const solver::Vec2& u = piece.displacement[static_cast<std::size_t>(piece.box.local(i, k))];
    return u.allFinite() ? u : solver::Vec2::Zero();
  }
  return solver::Vec2::Zero();
}

}  // namespace

std::vector<Point> corner_points(const solver::Model& model, const solver::Snapshot& snapshot,
                                 const SceneFraming& framing) {
  const std::vector<std::vector<int>> corners =
      solver::corner_nodes(model, solver::decompose(model));
  std::vector<Point> points;
  for (std::size_t s = 0; s < corners.size(); ++s) {
    const solver::StrutMesh& mesh = model.struts[s];
    for (int node : corners[s]) {
      const int i = node / mesh.nodes_across(), k = node % mesh.nodes_across();
      const int strut = static_cast<int>(s);
      points.push_back(
          framing.node(model, strut, node, first_piece_displacement(snapshot, strut, i, k)));
    }
  }
  return points;
}

float corner_mark_radius(const SceneFraming& framing) {
  return std::max(2.0f, 0.2f * framing.text_size);
}

void draw_corner_marks(DrawList& list, const solver::Model& model, const solver::Snapshot& snapshot,
                       const SceneFraming& framing) {
  const float radius = corner_mark_radius(framing);
  for (const Point& p : corner_points(model, snapshot, framing)) {
    list.disc(p, radius, kCornerMark);
    list.ring(p, radius, std::max(1.0f, 0.25f * radius), palette::ink);
  }
}

}  // namespace fetic::render
