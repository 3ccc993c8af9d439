#pragma once
// What a scene frame shows besides the struts (which are a SceneMesh, drawn by the GPU):
// supports as walls, loads as arrows, open gaps, active contacts and their forces, strut
// labels, and what the frame shows - a caption, the stress or moment colour legend, a
// legend of the glyphs, a length scale bar.
//
// Glyphs are sized from the zoom and the local spacing of the struts (level of detail):
// nothing is drawn over a strut beyond a small share of its pixels. Where struts lie too
// close for a glyph, it is aggregated (one glyph per contact face, one row of arrows per
// strut side for a distributed load) or left out, and the legend says how many were left
// out at this zoom.

#include <string>
#include <vector>

#include "render/draw_list.hpp"
#include "render/scene_framing.hpp"
#include "render/scene_mesh.hpp"
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

// What the caption names: the method and, when the plan has several, the load step.
struct SceneCaption {
  std::string method;     // e.g. "feti-c (dirichlet)"
  std::string load_step;  // e.g. "step 3 of 10"
};

// Glyphs and annotations of one state, in pixels (over the struts).
DrawList draw_glyphs(const solver::Model& model, const solver::Snapshot& snapshot, const View& view,
                     const SceneFraming& framing, const SceneCaption& caption);

// The whole scene on the CPU: the struts (expand_mesh) and the glyphs, for figures and
// tests without GL.
DrawList draw_scene(const solver::Model& model, const solver::Snapshot& snapshot, const View& view,
                    const SceneFraming& framing, const SceneCaption& caption = {});

}  // namespace fetic::render
