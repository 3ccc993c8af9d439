#pragma once
// What one frame shows, as plain CPU data: coloured triangles in pixel coordinates
// (origin top left, y down) and text items anchored at a point. No GL here, so scenes,
// overlays and figures can be built and tested without a context. Items are drawn in the
// order they were added; a text item is drawn after the triangles added before it.

#include <cstdint>
#include <string>
#include <vector>

namespace fetic::render {

struct Color {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  bool operator==(const Color&) const = default;
};

// Linear blend: t = 0 gives a, t = 1 gives b.
Color mix(Color a, Color b, double t);
Color with_alpha(Color color, std::uint8_t alpha);

struct Point {
  float x = 0.0f, y = 0.0f;
  bool operator==(const Point&) const = default;
};

inline Point operator+(Point a, Point b) {
  return {a.x + b.x, a.y + b.y};
}
inline Point operator-(Point a, Point b) {
  return {a.x - b.x, a.y - b.y};
}
inline Point operator*(float s, Point a) {
  return {s * a.x, s * a.y};
}
float length(Point a);
// a / |a|, or (0, 0) for a zero vector.
Point normalized(Point a);
// a turned by +90 degrees on screen (clockwise, since y points down).
inline Point perpendicular(Point a) {
  return {-a.y, a.x};
}

struct Rect {
  float x0 = 0.0f, y0 = 0.0f, x1 = 0.0f, y1 = 0.0f;
  float width() const { return x1 - x0; }
  float height() const { return y1 - y0; }
  bool contains(Point p) const { return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1; }
};

struct Vertex {
  Point position;
  Color color;
};

enum class HAlign { Left, Center, Right };
enum class VAlign { Top, Middle, Bottom };

struct TextItem {
  std::string text;    // UTF-8
  Point anchor;        // the point the alignment refers to
  float size = 14.0f;  // pixel height of the font
  Color color;
  HAlign h_align = HAlign::Left;
  VAlign v_align = VAlign::Top;
  bool bold = false;
  bool vertical = false;         // turned by -90 degrees (reads bottom to top), for y-axis labels
  std::size_t after_vertex = 0;  // drawn after this many triangle vertices
};

// Width of `text` in DejaVu Sans at `size` pixels, slightly overestimated (0.62 em per
// character, the width of a digit is 0.636 em, of most letters less): for layout.
float estimated_text_width(const std::string& text, float size, bool bold = false);

class DrawList {
 public:
  const std::vector<Vertex>& vertices() const { return vertices_; }  // 3 per triangle
  const std::vector<TextItem>& texts() const { return texts_; }
  std::size_t triangle_count() const { return vertices_.size() / 3; }
  bool empty() const { return vertices_.empty() && texts_.empty(); }

  void triangle(Point a, Point b, Point c, Color color);
  // Per-vertex colours (interpolated), for colour maps.
  void triangle(Vertex a, Vertex b, Vertex c);
  // Convex quadrilateral a b c d (in order around it).
  void quad(Point a, Point b, Point c, Point d, Color color);
  void rect(const Rect& rect, Color color);
  void rect_outline(const Rect& rect, float width, Color color);
  // A straight segment `width` pixels wide (butt ends).
  void line(Point a, Point b, float width, Color color);
  // Joined segments; round joints when wider than 2 pixels.
  void polyline(const std::vector<Point>& points, float width, Color color, bool closed = false);
  void dashed_line(Point a, Point b, float width, float dash, float space, Color color);
  void disc(Point center, float radius, Color color);
  void ring(Point center, float radius, float width, Color color);
  // Shaft from `tail` to `tip` with a filled head of length `head` at the tip.
  void arrow(Point tail, Point tip, float width, float head, Color color);
  void text(TextItem item);
  void text(const std::string& text, Point anchor, float size, Color color,
            HAlign h_align = HAlign::Left, VAlign v_align = VAlign::Top, bool bold = false);
  // Appends another list (its text items keep their place relative to its triangles).
  void append(const DrawList& other);

 private:
  std::vector<Vertex> vertices_;
  std::vector<TextItem> texts_;
};

}  // namespace fetic::render
