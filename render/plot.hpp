#pragma once
// Line plots as draw lists: axes with ticks (linear or log), grid, labels, title, series
// and a legend. Used by the overlay's small plots and by the thesis figures, which also
// draw their own content (contours, paths) into the plot area through PlotArea.

#include <limits>
#include <string>
#include <vector>

#include "render/draw_list.hpp"

namespace fetic::render {

struct Axis {
  std::string label;
  double min = std::numeric_limits<double>::quiet_NaN();  // NaN: from the data
  double max = std::numeric_limits<double>::quiet_NaN();
  bool log = false;
  bool integer = false;  // ticks at whole numbers only (iterations, counts)
};

struct Series {
  std::string name;  // empty: not in the legend
  std::vector<double> x, y;
  Color color;
  float width = 2.0f;
  bool markers = false;
  bool steps = false;  // piecewise constant (counts per iteration)
};

enum class Corner { TopLeft, TopRight, BottomLeft, BottomRight };

struct PlotSpec {
  Rect frame;  // everything, labels included
  std::string title;
  Axis x, y;
  std::vector<Series> series;
  float text_size = 14.0f;
  bool grid = true;
  bool equal_aspect = false;  // one unit is as long on x as on y (the ranges widen)
  Corner legend = Corner::TopRight;
};

struct Tick {
  double value = 0.0;
  std::string label;
  bool major = true;
};

// Tick positions and labels for a range: 1-2-5 steps (linear), powers of ten (log).
std::vector<Tick> linear_ticks(double min, double max, int target_count, bool integer);
std::vector<Tick> log_ticks(double min, double max, int target_count);
// Range rounded out to the tick grid (linear) or to whole decades (log).
void nice_range(const Axis& axis, double& min, double& max, const std::vector<double>& data);

// The data-to-pixel map of a laid-out plot.
class PlotArea {
 public:
  PlotArea() = default;
  PlotArea(Rect inner, double x0, double x1, double y0, double y1, bool log_x, bool log_y);
  const Rect& inner() const { return inner_; }
  double x_min() const { return x0_; }
  double x_max() const { return x1_; }
  double y_min() const { return y0_; }
  double y_max() const { return y1_; }
  bool log_y() const { return log_y_; }
  Point to_pixel(double x, double y) const;

 private:
  Rect inner_;
  double x0_ = 0, x1_ = 1, y0_ = 0, y1_ = 1;
  bool log_x_ = false, log_y_ = false;
};

// Axes, grid, ticks, labels and title; returns the area the data goes into.
PlotArea draw_axes(DrawList& list, const PlotSpec& spec);
// One series, clipped to the area (points outside a log axis' domain break the line).
void draw_series(DrawList& list, const PlotArea& area, const Series& series);
void draw_legend(DrawList& list, const PlotArea& area, const std::vector<Series>& series,
                 Corner corner, float text_size);
// All of it.
DrawList draw_plot(const PlotSpec& spec);

}  // namespace fetic::render
