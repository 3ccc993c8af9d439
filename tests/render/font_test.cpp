// Text through ImGui's font atlas (CPU only): DejaVu Sans when installed, ImGui's built-in
// font with a message naming the missing file otherwise; alignment and vertical labels.

#include <catch2/catch.hpp>

#include <algorithm>

#include "render/font.hpp"

using namespace fetic::render;

namespace {

Rect bounds(const std::vector<TexturedVertex>& vertices) {
  Rect box{1e9f, 1e9f, -1e9f, -1e9f};
  for (const TexturedVertex& v : vertices) {
    box.x0 = std::min(box.x0, v.x);
    box.y0 = std::min(box.y0, v.y);
    box.x1 = std::max(box.x1, v.x);
    box.y1 = std::max(box.y1, v.y);
  }
  return box;
}

TextItem item(const std::string& text, HAlign h, VAlign v, bool vertical = false) {
  TextItem t;
  t.text = text;
  t.anchor = {200, 100};
  t.size = 14;
  t.color = {0, 0, 0, 255};
  t.h_align = h;
  t.v_align = v;
  t.vertical = vertical;
  return t;
}

}  // namespace

TEST_CASE("a missing TTF falls back to ImGui's built-in font and says which file") {
  const FontAtlas font(22.0f, "/nonexistent/DejaVuSans.ttf", "/nonexistent/DejaVuSans-Bold.ttf");
  CHECK_THAT(font.note(), Catch::Contains("/nonexistent/DejaVuSans.ttf"));
  CHECK_THAT(font.note(), Catch::Contains("built-in"));
  std::vector<TexturedVertex> glyphs;
  font.layout(item("abc", HAlign::Left, VAlign::Top), glyphs);
  CHECK(glyphs.size() == 3 * 6);  // two triangles per glyph
}

TEST_CASE("text is aligned at its anchor, vertical labels read bottom to top") {
  const FontAtlas font;
  CHECK(font.note().empty());  // fonts-dejavu-core is a dependency
  std::vector<TexturedVertex> left, right, centred, vertical;
  font.layout(item("iteration", HAlign::Left, VAlign::Top), left);
  font.layout(item("iteration", HAlign::Right, VAlign::Top), right);
  font.layout(item("iteration", HAlign::Center, VAlign::Middle), centred);
  font.layout(item("iteration", HAlign::Center, VAlign::Top, true), vertical);
  CHECK(bounds(left).x0 >= 199.0f);
  CHECK(bounds(right).x1 <= 201.0f);
  const Rect middle = bounds(centred);
  CHECK(0.5f * (middle.x0 + middle.x1) == Approx(200.0f).margin(2.0));
  CHECK(0.5f * (middle.y0 + middle.y1) == Approx(100.0f).margin(3.0));
  const Rect turned = bounds(vertical);
  CHECK(turned.height() > 2.0f * turned.width());  // runs along y
  CHECK(turned.x0 >= 199.0f);                      // VAlign::Top: the glyph tops face the anchor
  CHECK(0.5f * (turned.y0 + turned.y1) == Approx(100.0f).margin(2.0));
  const Point measured = font.measure("iteration", 14, false);
  CHECK(measured.x == Approx(bounds(left).width()).margin(2.0));
  CHECK(estimated_text_width("iteration", 14) >= measured.x);  // layout estimates are safe
}
