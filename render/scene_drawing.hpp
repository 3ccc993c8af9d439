#pragma once
// One solver state as a draw list: struts deformed by the magnification (bars as bands of
// a fixed on-screen width, plane struts as their deformed mesh), every piece (FETI
// subdomain) drawn on its own so that pieces that do not yet agree are seen torn apart;
// supports as hatched walls, loads as arrows, gaps, active contacts in red circles,
// contact forces as glyphs scaled by lambda, and the stress colour legend.

#include <vector>

#include "render/draw_list.hpp"
#include "render/scene_framing.hpp"
#include "render/view.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"

namespace fetic::render {

// Where a contact pair is drawn and in what state.
struct ContactMark {
  int pair = 0;
  Point a, b;    // drawn positions of its two nodes
  Point center;  // midway
  Point normal;  // screen direction from a toward b
  bool active = false;
  double force = 0.0;
};

std::vector<ContactMark> contact_marks(const solver::Model& model, const solver::Snapshot& snapshot,
                                       const SceneFraming& framing);

// Drawn node positions of each piece, in box-local order.
std::vector<std::vector<Point>> piece_outline_nodes(const solver::Model& model,
                                                    const solver::Snapshot& snapshot,
                                                    const SceneFraming& framing);

DrawList draw_scene(const solver::Model& model, const solver::Snapshot& snapshot, const View& view,
                    const SceneFraming& framing);

}  // namespace fetic::render
