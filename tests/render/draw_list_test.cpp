// Draw lists are plain data: primitives become the triangles they should, text keeps its
// place among them.

#include <catch2/catch.hpp>

#include <cmath>

#include "render/colormap.hpp"
#include "render/draw_list.hpp"
#include "render/text_format.hpp"

using namespace fetic::render;

namespace {

double area(const DrawList& list) {
  double total = 0.0;
  const auto& v = list.vertices();
  for (std::size_t i = 0; i + 2 < v.size(); i += 3) {
    const Point a = v[i].position, b = v[i + 1].position, c = v[i + 2].position;
    total += 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
  }
  return total;
}

}  // namespace

TEST_CASE("primitives cover the area they should") {
  DrawList rect;
  rect.rect({10, 20, 40, 30}, palette::ink);
  CHECK(rect.triangle_count() == 2);
  CHECK(area(rect) == Approx(300.0));

  DrawList line;
  line.line({0, 0}, {30, 40}, 2.0f, palette::ink);  // 50 long, 2 wide
  CHECK(area(line) == Approx(100.0));

  DrawList disc;
  disc.disc({0, 0}, 10.0f, palette::ink);
  CHECK(area(disc) == Approx(M_PI * 100.0).epsilon(0.015));

  DrawList ring;
  ring.ring({0, 0}, 10.0f, 2.0f, palette::ink);  // between radii 9 and 11
  CHECK(area(ring) == Approx(M_PI * (121.0 - 81.0)).epsilon(0.015));

  DrawList nothing;
  nothing.line({5, 5}, {5, 5}, 3.0f, palette::ink);  // zero length: no triangles, no NaN
  CHECK(nothing.empty());
}

TEST_CASE("an arrow ends exactly at its tip") {
  DrawList arrow;
  arrow.arrow({0, 0}, {100, 0}, 2.0f, 10.0f, palette::load);
  float right_most = -1e9f;
  for (const Vertex& v : arrow.vertices())
    right_most = std::max(right_most, v.position.x);
  CHECK(right_most == Approx(100.0f));
}

TEST_CASE("text items are drawn after the triangles added before them, also when appended") {
  DrawList first;
  first.rect({0, 0, 1, 1}, palette::ink);
  first.text("a", {0, 0}, 12, palette::ink);
  DrawList second;
  second.rect({0, 0, 1, 1}, palette::ink);
  second.text("b", {0, 0}, 12, palette::ink);
  first.append(second);
  REQUIRE(first.texts().size() == 2);
  CHECK(first.texts()[0].after_vertex == 6);
  CHECK(first.texts()[1].after_vertex == 12);
  CHECK(first.texts()[1].text == "b");
}

TEST_CASE("text helpers: powers of ten, magnification, SI units, wrapping") {
  CHECK(power_of_ten(-3) == "10⁻³");
  CHECK(power_of_ten(12) == "10¹²");
  CHECK(times(50.0) == "×50");
  CHECK(times(0.5) == "×0.5");
  std::string unit;
  CHECK(si_scale(2.5e8, "Pa", unit) == 1e6);
  CHECK(unit == "MPa");
  CHECK(estimated_text_width("10⁻³", 10.0f) == Approx(4 * 6.2f));  // code points, not bytes
  const auto lines = wrap("Thesis benchmark: 50 pairs of opposing bars", 150.0f, 14.0f, false);
  REQUIRE(lines.size() >= 2);
  for (const std::string& line : lines)
    CHECK(estimated_text_width(line, 14.0f) <= 150.0f);
}

TEST_CASE("colour maps: compression blue, tension red, zero neutral, subdomains differ") {
  CHECK(diverging(-1.0).b > diverging(-1.0).r);
  CHECK(diverging(1.0).r > diverging(1.0).b);
  const Color zero = diverging(0.0);
  CHECK(zero.r == zero.g);
  CHECK(diverging(5.0) == diverging(1.0));  // clamped
  CHECK(diverging(std::nan("")) == zero);
  for (int strut = 0; strut < 6; ++strut) {
    CHECK_FALSE(subdomain_color(strut, 0) == subdomain_color(strut, 1));
    CHECK_FALSE(subdomain_color(strut, 1) == subdomain_color(strut, 2));
  }
}
