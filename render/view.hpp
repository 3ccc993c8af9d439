#pragma once
// How a solver state is shown: image size, magnification, what to colour by and which
// layers to draw. Plain settings; the command line and the tests fill them in.

#include <string>

namespace fetic::render {

// Subdomain: each FETI piece its own colour; Strut: one colour per strut (subdomains hidden);
// Stress: axial stress; Moment: the bending moment of frame beams, along each element
// (struts without one - bars, plane struts - are drawn in palette::no_value grey).
enum class ColorBy { Subdomain, Stress, Strut, Moment };

// Colourings that map a signed value to the diverging colour map.
inline bool colors_by_value(ColorBy color) {
  return color == ColorBy::Stress || color == ColorBy::Moment;
}

struct View {
  int width = 1280;
  int height = 720;
  // Displacements (and gaps, see magnify_gaps) are drawn this many times larger;
  // 0 chooses a round factor from the largest displacement and gap of the run.
  double magnification = 0.0;
  // Draw gaps magnified like displacements, so that a closed contact is drawn closed and
  // an open one open. Otherwise the tips of a closing contact would overlap on screen.
  bool magnify_gaps = true;
  ColorBy color_by = ColorBy::Subdomain;
  bool show_supports = true;
  bool show_loads = true;
  bool show_gaps = true;
  bool show_contacts = true;  // red circles at active contact pairs
  bool show_forces = true;    // contact force glyphs scaled by lambda
  bool show_overlay = true;   // title, method, iteration, residual, plots
  bool show_labels = false;   // strut names beside the struts (where there is room)
  bool show_corners = false;  // FETI-DP's primal corners (render/corner_marks.hpp)
  bool show_legend = true;    // what the glyphs mean
  bool show_scale = true;     // a length scale bar
  bool show_chart = false;    // the per-contact chart beside the picture (contact_chart.hpp)
  // The base text size is at least this (0: from the image size alone): the window keeps
  // its smallest text - plot ticks, at 0.68 of it - at 11 pixels or more (times its scale).
  float min_text_size = 0.0f;
  float bar_width = 0.0f;  // on-screen width of bars in pixels; 0: from the image size
  // A window's pan and zoom (a saved view, app/view_file.hpp): the fit is scaled by
  // `zoom`, and when `centered` the world point (center_x, center_y) is drawn at the
  // centre of the scene region.
  double zoom = 1.0;
  bool centered = false;
  double center_x = 0.0, center_y = 0.0;
  // Where the colour map's and the force glyphs' scales come from when they are fixed
  // beyond the state shown ("over loads 0-2", "over all 14 frames"):
  // the legends then say "scale X: largest in/over <basis>; now Y". Empty: the scales are
  // the largest values of the state shown, and the legends say "largest X".
  std::string scale_basis;
};

// Text height in pixels that suits an image of this size: a 48th of its height (of its
// width's 16:9 share when it is wider), at least 10. Everything else - lines, glyphs,
// panels - is sized from it, so a 5000x3000 frame reads like a 1280x720 one.
inline float base_text_size(int width, int height) {
  const int smaller = width * 9 < height * 16 ? width * 9 / 16 : height;
  const float size = static_cast<float>(smaller) / 48.0f;
  return size < 10.0f ? 10.0f : static_cast<float>(static_cast<int>(size));
}

// The base text size of a view: base_text_size of its size, at least its min_text_size.
inline float text_size(const View& view) {
  const float size = base_text_size(view.width, view.height);
  return size < view.min_text_size ? view.min_text_size : size;
}

}  // namespace fetic::render
