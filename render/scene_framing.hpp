#pragma once
// Where a scene lands on screen: the magnification (automatic or fixed), the shift of each
// strut that draws gaps magnified, and the world-to-pixel fit. Fixed for a whole run, so
// that frames of a movie line up.

#include <vector>

#include "render/draw_list.hpp"
#include "render/frame_sequence.hpp"
#include "render/view.hpp"
#include "solver/model.hpp"

namespace fetic::render {

struct SceneFraming {
  double magnification = 1.0;
  bool gaps_magnified = false;
  std::vector<solver::Vec2> strut_offset;  // world shift of each strut (gaps drawn magnified)
  Rect region;                             // pixels the scene may use
  double pixels_per_unit = 1.0;            // world length unit (m) to pixels
  solver::Vec2 world_center{0, 0};
  Point pixel_center;
  float bar_width = 6.0f;     // pixels
  float lane = 1e9f;          // pixels between the axes of side-by-side parallel struts
  float text_size = 14.0f;    // pixels
  double force_scale = 0.0;   // largest contact force of the run (glyph size 1)
  double stress_scale = 0.0;  // largest |axial stress| of the run (colour map end)
  double load_scale = 0.0;    // largest nodal load at load factor 1 (arrow length 1)

  Point to_pixel(const solver::Vec2& world) const;
  // Screen direction of a world direction (y flipped), unit length.
  Point direction(const solver::Vec2& world) const;
  // Drawn position of a node of a strut displaced by u.
  Point node(const solver::Model& model, int strut, int node, const solver::Vec2& u) const;
};

// The largest of 1, 2, 5 x 10^k that is at most `raw` (raw > 0).
double round_magnification(double raw);

// Per strut shifts that widen every contact's gap from g to m g: strut b of a contact
// moves by (m - 1) g n relative to strut a. Applied along the contact graph from a clamped
// strut of each connected group; a contact that closes a loop inconsistently keeps the
// shift found first.
std::vector<solver::Vec2> gap_offsets(const solver::Model& model, double magnification);

// Magnification that draws the largest displacement or gap of the run as 8% of the
// scene's larger side, rounded down to 1, 2 or 5 x 10^k.
double automatic_magnification(const solver::Model& model, const RunExtent& extent,
                               bool magnify_gaps);

SceneFraming frame_scene(const solver::Model& model, const View& view, const RunExtent& extent,
                         const Rect& region);

// Applies the view's zoom and centre to a fitted framing (frame_scene does; the window,
// which pans and zooms by itself, places a loaded view's centre with it).
void place_view(SceneFraming& framing, const View& view);

}  // namespace fetic::render
