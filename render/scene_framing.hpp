#pragma once
// Where a scene lands on screen: the magnification (automatic or fixed), how gaps are
// drawn magnified, and the world-to-pixel fit. Fixed for a whole run, so that frames of a
// movie line up.
//
// Drawn position of a node: X + (m - 1) q(X) + m u, with u its displacement and q the gap
// widening: a field along each strut's axis, zero at clamped ends, that opens every
// contact's gap from g to m g (and so keeps a closed contact drawn closed). The struts
// between make room for it by being drawn a little shorter or longer, never their
// supports: clamped ends stay on their walls.

#include <memory>
#include <string>
#include <vector>

#include "render/draw_list.hpp"
#include "render/frame_sequence.hpp"
#include "render/view.hpp"
#include "solver/model.hpp"

namespace fetic::render {

// The gap widening per strut and node, shared by the copies of a framing: a zoomed or
// panned framing is copied for every picture, and on ten million unknowns the field is
// 77 MB.
class Widening {
 public:
  using Field = std::vector<std::vector<solver::Vec2>>;
  Widening() = default;
  Widening(Field field) : field_(std::make_shared<const Field>(std::move(field))) {}  // NOLINT
  operator const Field&() const { return field_ ? *field_ : empty_field(); }          // NOLINT
  bool empty() const { return !field_ || field_->empty(); }
  std::size_t size() const { return field_ ? field_->size() : 0; }
  const std::vector<solver::Vec2>& operator[](std::size_t s) const { return (*field_)[s]; }

 private:
  static const Field& empty_field() {
    static const Field none;
    return none;
  }
  std::shared_ptr<const Field> field_;
};

struct SceneFraming {
  double magnification = 1.0;
  bool gaps_magnified = false;
  // Why the automatic magnification is not larger: "" (the 8% rule), or what a larger one
  // would break ("gaps", "elements", "crossing").
  std::string limited_by;
  Widening widening;              // per strut and node, per unit of m - 1
  std::vector<double> clearance;  // per strut: free distance to the nearest strut beside it
  Rect region;                    // pixels the scene may use
  double pixels_per_unit = 1.0;   // world length unit to pixels
  solver::Vec2 world_center{0, 0};
  Point pixel_center;
  float bar_width = 6.0f;   // pixels
  float widest_bar = 9.0f;  // bars are at most this wide (from the region), ...
  bool fixed_bar = false;   // ... or exactly bar_width when the view fixes it
  float lane = 1e9f;        // pixels between the axes of side-by-side parallel struts
  float text_size = 14.0f;  // pixels
  // No text is set smaller than this when the view asks for legible text (the window's
  // View::min_text_size; 0: a legend or caption may shrink to fit).
  float smallest_text = 0.0f;
  float line_width = 1.0f;    // pixels of a thin line; grows with the text
  double force_scale = 0.0;   // largest contact force of the run (glyph size 1)
  double stress_scale = 0.0;  // largest |axial stress| of the run (colour map end)
  double moment_scale = 0.0;  // largest |bending moment| of the run (colour map end)
  double load_scale = 0.0;    // largest nodal load at load factor 1 (arrow length 1)

  Point to_pixel(const solver::Vec2& world) const;
  // Screen direction of a world direction (y flipped), unit length.
  Point direction(const solver::Vec2& world) const;
  // Drawn world position of a node of a strut displaced by u.
  solver::Vec2 drawn(const solver::Model& model, int strut, int node, const solver::Vec2& u) const;
  // The same in pixels.
  Point node(const solver::Model& model, int strut, int node, const solver::Vec2& u) const;
};

// The largest of 1, 2, 5 x 10^k that is at most `raw` (raw > 0).
double round_magnification(double raw);

// The gap widening q per strut node, per unit of m - 1: along each strut's axis, linear
// from one end to the other; zero at clamped ends; for every contact pair
// (q_b - q_a) . n = gap. Where the struts of a chain cannot all keep their length, the
// change of length is spread over them evenly (least squares).
std::vector<std::vector<solver::Vec2>> gap_widening(const solver::Model& model);

// Per strut, the free distance (between the faces, heights taken off) to the nearest
// parallel strut that lies beside it; infinity when there is none.
std::vector<double> side_clearances(const solver::Model& model);

struct MagnificationChoice {
  double magnification = 1.0;
  std::string limited_by;  // see SceneFraming::limited_by
};
// The largest displacement or gap of the run drawn as 8% of the scene's larger side,
// rounded down to 1, 2 or 5 x 10^k - unless that would draw struts crossing each other
// (lateral displacements beyond 40% of the clearance), elements turned inside out (a
// quarter of their length), or gaps that eat more than a quarter of a strut's length.
MagnificationChoice automatic_magnification(const solver::Model& model, const RunExtent& extent,
                                            bool magnify_gaps,
                                            const std::vector<std::vector<solver::Vec2>>& widening,
                                            const std::vector<double>& clearance);

// The top band of a scene region (the caption) and the bottom band (glyph legend, stress
// colours, length scale): the struts are fitted between them.
float caption_band(float text_size);
float legend_band(float text_size);
Rect geometry_region(const Rect& scene_region, float text_size);

// The framing zoomed by `zoom` about nothing in particular, its centre drawn at `center`
// (the window's pan and zoom): scale, lane and bar width follow.
SceneFraming zoomed(const SceneFraming& framing, float zoom, Point center);

// A saved view's zoom and centre (View::zoom, View::centered): the framing zoomed, with
// the view's world centre drawn at the middle of the scene region.
SceneFraming placed(const SceneFraming& framing, const View& view);

// Fits the scene into `region` (between its bands), for the whole run.
SceneFraming frame_scene(const solver::Model& model, const View& view, const RunExtent& extent,
                         const Rect& region);

// Applies the view's zoom and centre to a fitted framing (frame_scene does; the window,
// which pans and zooms by itself, places a loaded view's centre with it).
void place_view(SceneFraming& framing, const View& view);

}  // namespace fetic::render
