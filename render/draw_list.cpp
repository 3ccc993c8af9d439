#include "render/draw_list.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace fetic::render {
namespace {

std::uint8_t blend_channel(std::uint8_t a, std::uint8_t b, double t) {
  return static_cast<std::uint8_t>(std::lround(a + (b - a) * std::clamp(t, 0.0, 1.0)));
}

// Segments of a circle of radius r so that the chord error stays below 0.1 pixel.
int circle_segments(float radius) {
  const double step = 2.0 * std::acos(std::max(0.0, 1.0 - 0.1 / std::max(radius, 0.5f)));
  return std::clamp(static_cast<int>(std::ceil(2.0 * std::numbers::pi / step)), 8, 128);
}

}  // namespace

Color mix(Color a, Color b, double t) {
  return {blend_channel(a.r, b.r, t), blend_channel(a.g, b.g, t), blend_channel(a.b, b.b, t),
          blend_channel(a.a, b.a, t)};
}

Color with_alpha(Color color, std::uint8_t alpha) {
  color.a = alpha;
  return color;
}

float length(Point a) {
  return std::sqrt(a.x * a.x + a.y * a.y);
}

Point normalized(Point a) {
  const float l = length(a);
  return l > 0.0f ? Point{a.x / l, a.y / l} : Point{0.0f, 0.0f};
}

float estimated_text_width(const std::string& text, float size, bool bold) {
  // Count code points, not bytes: UTF-8 continuation bytes start with 10xxxxxx.
  const auto characters =
      std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; });
  return static_cast<float>(characters) * size * (bold ? 0.70f : 0.62f);
}

void DrawList::triangle(Point a, Point b, Point c, Color color) {
  vertices_.push_back({a, color});
  vertices_.push_back({b, color});
  vertices_.push_back({c, color});
}

void DrawList::triangle(Vertex a, Vertex b, Vertex c) {
  vertices_.push_back(a);
  vertices_.push_back(b);
  vertices_.push_back(c);
}

void DrawList::quad(Point a, Point b, Point c, Point d, Color color) {
  triangle(a, b, c, color);
  triangle(a, c, d, color);
}

void DrawList::rect(const Rect& r, Color color) {
  quad({r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}, color);
}

void DrawList::rect_outline(const Rect& r, float width, Color color) {
  const float h = width / 2;
  rect({r.x0 - h, r.y0 - h, r.x1 + h, r.y0 + h}, color);
  rect({r.x0 - h, r.y1 - h, r.x1 + h, r.y1 + h}, color);
  rect({r.x0 - h, r.y0 + h, r.x0 + h, r.y1 - h}, color);
  rect({r.x1 - h, r.y0 + h, r.x1 + h, r.y1 - h}, color);
}

void DrawList::line(Point a, Point b, float width, Color color) {
  const Point side = (width / 2) * perpendicular(normalized(b - a));
  if (side == Point{}) return;
  quad(a + side, b + side, b - side, a - side, color);
}

void DrawList::polyline(const std::vector<Point>& points, float width, Color color, bool closed) {
  const std::size_t n = points.size();
  if (n < 2) return;
  for (std::size_t i = 0; i + 1 < n; ++i)
    line(points[i], points[i + 1], width, color);
  if (closed) line(points[n - 1], points[0], width, color);
  if (width > 2.0f)
    for (std::size_t i = closed ? 0 : 1; i < (closed ? n : n - 1); ++i)
      disc(points[i], width / 2, color);
}

void DrawList::dashed_line(Point a, Point b, float width, float dash, float space, Color color) {
  const float total = length(b - a);
  const Point direction = normalized(b - a);
  for (float s = 0.0f; s < total; s += dash + space)
    line(a + s * direction, a + std::min(s + dash, total) * direction, width, color);
}

void DrawList::disc(Point center, float radius, Color color) {
  const int segments = circle_segments(radius);
  Point previous{center.x + radius, center.y};
  for (int i = 1; i <= segments; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / segments;
    const Point next{center.x + radius * static_cast<float>(std::cos(angle)),
                     center.y + radius * static_cast<float>(std::sin(angle))};
    triangle(center, previous, next, color);
    previous = next;
  }
}

void DrawList::ring(Point center, float radius, float width, Color color) {
  const int segments = circle_segments(radius + width / 2);
  const float inner = std::max(0.0f, radius - width / 2), outer = radius + width / 2;
  for (int i = 0; i < segments; ++i) {
    const double a0 = 2.0 * std::numbers::pi * i / segments;
    const double a1 = 2.0 * std::numbers::pi * (i + 1) / segments;
    const Point d0{static_cast<float>(std::cos(a0)), static_cast<float>(std::sin(a0))};
    const Point d1{static_cast<float>(std::cos(a1)), static_cast<float>(std::sin(a1))};
    quad(center + inner * d0, center + outer * d0, center + outer * d1, center + inner * d1, color);
  }
}

void DrawList::arrow(Point tail, Point tip, float width, float head, Color color) {
  const float total = length(tip - tail);
  if (total <= 0.0f) return;
  const Point direction = normalized(tip - tail);
  head = std::min(head, total);
  const Point base = tip - head * direction;
  line(tail, base + 0.5f * direction, width, color);  // overlap the head by half a pixel
  const Point side = (0.5f * head) * perpendicular(direction);
  triangle(tip, base + side, base - side, color);
}

void DrawList::text(TextItem item) {
  item.after_vertex = vertices_.size();
  texts_.push_back(std::move(item));
}

void DrawList::text(const std::string& text, Point anchor, float size, Color color, HAlign h_align,
                    VAlign v_align, bool bold) {
  this->text(TextItem{.text = text,
                      .anchor = anchor,
                      .size = size,
                      .color = color,
                      .h_align = h_align,
                      .v_align = v_align,
                      .bold = bold});
}

void DrawList::append(const DrawList& other) {
  const std::size_t offset = vertices_.size();
  vertices_.insert(vertices_.end(), other.vertices_.begin(), other.vertices_.end());
  for (TextItem item : other.texts_) {
    item.after_vertex += offset;
    texts_.push_back(std::move(item));
  }
}

}  // namespace fetic::render
