// Figure 2.1: the shapes of f(x) = 1/2 x'K x for 2x2 matrices K of the four kinds, drawn as
// shaded surfaces over [-1, 1]^2 (painter's algorithm, far quads first).

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Core>

#include "render/colormap.hpp"
#include "render/figures.hpp"
#include "render/text_format.hpp"
#include "render/view.hpp"

namespace fetic::render {
namespace {

struct Panel {
  const char* title;
  const char* matrix;
  Eigen::Matrix2d K;
};

void draw_surface(DrawList& list, const Panel& panel, const Rect& box) {
  constexpr int kGrid = 24;
  constexpr double kAzimuth = 0.62, kElevation = 0.8;  // radians
  const double ca = std::cos(kAzimuth), sa = std::sin(kAzimuth);
  const double ce = std::cos(kElevation), se = std::sin(kElevation);
  const auto value = [&](double x, double y) {
    const Eigen::Vector2d v(x, y);
    return 0.5 * v.dot(panel.K * v);
  };
  double largest = 0.0;
  for (int i = 0; i <= kGrid; ++i)
    for (int j = 0; j <= kGrid; ++j)
      largest = std::max(largest, std::abs(value(-1.0 + 2.0 * i / kGrid, -1.0 + 2.0 * j / kGrid)));
  const double z_scale = largest > 0.0 ? 0.9 / largest : 1.0;

  // View coordinates: right, up (on screen) and depth (away from the viewer).
  struct Projected {
    double right, up, depth;
  };
  const auto project = [&](double x, double y, double z) {
    const double xr = x * ca - y * sa, yr = x * sa + y * ca;
    return Projected{xr, yr * se + z * ce, yr * ce - z * se};
  };
  // Fit the surface's projection into the panel.
  double left = 1e9, right = -1e9, bottom = 1e9, top = -1e9;
  for (int i = 0; i <= kGrid; ++i)
    for (int j = 0; j <= kGrid; ++j) {
      const double x = -1.0 + 2.0 * i / kGrid, y = -1.0 + 2.0 * j / kGrid;
      const Projected p = project(x, y, z_scale * value(x, y));
      left = std::min(left, p.right);
      right = std::max(right, p.right);
      bottom = std::min(bottom, p.up);
      top = std::max(top, p.up);
    }
  const float scale =
      static_cast<float>(std::min(box.width() / (right - left), box.height() / (top - bottom)));
  const Point center{0.5f * (box.x0 + box.x1), 0.5f * (box.y0 + box.y1)};
  const double middle_right = 0.5 * (left + right), middle_up = 0.5 * (bottom + top);
  const auto to_screen = [&](const Projected& p) {
    return Point{center.x + scale * static_cast<float>(p.right - middle_right),
                 center.y - scale * static_cast<float>(p.up - middle_up)};
  };

  struct Quad {
    double depth;
    std::array<Point, 4> corners;
    Color color;
  };
  std::vector<Quad> quads;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      Quad quad{};
      double depth = 0.0, height = 0.0;
      const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
      for (int c = 0; c < 4; ++c) {
        const double x = -1.0 + 2.0 * (i + di[c]) / kGrid, y = -1.0 + 2.0 * (j + dj[c]) / kGrid;
        const double z = z_scale * value(x, y);
        const Projected p = project(x, y, z);
        quad.corners[static_cast<std::size_t>(c)] = to_screen(p);
        depth += p.depth;
        height += z;
      }
      quad.depth = depth / 4;
      quad.color = sequential(0.5 + height / 4 / 1.5);
      quads.push_back(quad);
    }
  std::stable_sort(quads.begin(), quads.end(),
                   [](const Quad& a, const Quad& b) { return a.depth > b.depth; });
  const Color edge{20, 20, 30, 90};
  for (const Quad& q : quads) {
    list.quad(q.corners[0], q.corners[1], q.corners[2], q.corners[3], q.color);
    list.polyline({q.corners[0], q.corners[1], q.corners[2], q.corners[3]}, 0.8f, edge, true);
  }
}

}  // namespace

DrawList figure_quadratic_forms(int width, int height) {
  const std::array<Panel, 4> panels{{
      {"a) positive definite", "K = [3 1; 1 2]", (Eigen::Matrix2d() << 3, 1, 1, 2).finished()},
      {"b) negative definite", "K = [−3 −1; −1 −2]",
       (Eigen::Matrix2d() << -3, -1, -1, -2).finished()},
      {"c) positive semidefinite (singular)", "K = [1 1; 1 1]",
       (Eigen::Matrix2d() << 1, 1, 1, 1).finished()},
      {"d) indefinite", "K = [2 1; 1 −2]", (Eigen::Matrix2d() << 2, 1, 1, -2).finished()},
  }};
  DrawList list;
  const float text = base_text_size(width, height);
  const auto w = static_cast<float>(width), h = static_cast<float>(height);
  list.text("Figure 2.1  Shapes of the quadratic form f(x) = ½ x'K x for 2×2 matrices K",
            {0.5f * w, 0.5f * text}, text, palette::ink, HAlign::Center, VAlign::Top, true);
  const float top = 2.0f * text;
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const float x0 = (p % 2) * 0.5f * w, y0 = top + (p / 2) * 0.5f * (h - top);
    const Rect cell{x0, y0, x0 + 0.5f * w, y0 + 0.5f * (h - top)};
    list.text(panels[p].title, {0.5f * (cell.x0 + cell.x1), cell.y0 + 0.3f * text}, text,
              palette::ink, HAlign::Center, VAlign::Top);
    list.text(panels[p].matrix, {0.5f * (cell.x0 + cell.x1), cell.y0 + 1.5f * text}, 0.85f * text,
              palette::muted, HAlign::Center, VAlign::Top);
    draw_surface(list, panels[p],
                 {cell.x0 + 0.5f * text, cell.y0 + 2.7f * text, cell.x1 - 0.5f * text,
                  cell.y1 - 0.3f * text});
  }
  return list;
}

}  // namespace fetic::render
