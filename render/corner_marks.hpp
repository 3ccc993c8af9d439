#pragma once
// FETI-DP's primal corners on the picture (`fetic render --corners`, the window's
// "corners" toggle): a small amber disc with a dark rim at every node that
// solver::corner_nodes() makes primal, where the first piece holding the node draws it.
// Drawn for any method: the corners are those FETI-DP would choose for the scene's boxes.

#include <vector>

#include "render/draw_list.hpp"
#include "render/scene_framing.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"

namespace fetic::render {

inline constexpr Color kCornerMark{255, 190, 0, 255};

// Per corner node (strut by strut, in increasing node order) its drawn pixel position.
std::vector<Point> corner_points(const solver::Model& model, const solver::Snapshot& snapshot,
                                 const SceneFraming& framing);
// Disc radius in pixels: a fifth of the text size, at least 2.
float corner_mark_radius(const SceneFraming& framing);
void draw_corner_marks(DrawList& list, const solver::Model& model, const solver::Snapshot& snapshot,
                       const SceneFraming& framing);

}  // namespace fetic::render
