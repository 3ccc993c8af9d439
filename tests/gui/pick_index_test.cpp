// The window's pick index: the nearest drawn node or contact pair within a radius, equal
// to a brute-force search over every item.

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "app/gui/pick_index.hpp"

using fetic::app::gui::Pickable;
using fetic::app::gui::PickIndex;

TEST_CASE("the pick index finds what a brute-force search finds") {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> x(-20.0f, 520.0f), y(-20.0f, 420.0f);
  std::vector<Pickable> items;
  for (int i = 0; i < 5000; ++i)
    items.push_back({i % 3 == 0 ? Pickable::Kind::Pair : Pickable::Kind::Node,
                     i,
                     i % 7,
                     {x(random), y(random)}});
  PickIndex index;
  index.build(items, 500.0f, 400.0f);
  CHECK(index.size() < items.size());  // the ones off the picture are dropped
  const float radius = 8.0f;
  int found = 0;
  for (int q = 0; q < 2000; ++q) {
    const fetic::render::Point at{x(random), y(random)};
    std::optional<Pickable> expected;
    float best = 0.0f;
    for (const Pickable& item : items) {
      if (!(item.at.x >= 0 && item.at.y >= 0 && item.at.x < 500 && item.at.y < 400)) continue;
      const float d =
          (item.at.x - at.x) * (item.at.x - at.x) + (item.at.y - at.y) * (item.at.y - at.y);
      if (d > radius * radius) continue;
      const float score = d - (item.kind == Pickable::Kind::Pair ? 9.0f : 0.0f);
      if (!expected || score < best) {
        expected = item;
        best = score;
      }
    }
    const auto got = index.nearest(at, radius);
    REQUIRE(got.has_value() == expected.has_value());
    if (got) {
      CHECK(*got == *expected);
      ++found;
    }
  }
  CHECK(found > 100);
}

TEST_CASE("a contact pair wins over the node it sits on") {
  PickIndex index;
  index.build({{Pickable::Kind::Node, 3, 4, {100.0f, 100.0f}},
               {Pickable::Kind::Pair, 12, 0, {101.0f, 100.0f}}},
              200.0f, 200.0f);
  const auto got = index.nearest({100.0f, 100.0f}, 8.0f);
  REQUIRE(got);
  CHECK(got->kind == Pickable::Kind::Pair);
  CHECK(got->a == 12);
  CHECK_FALSE(index.nearest({150.0f, 150.0f}, 8.0f).has_value());
  const auto where = index.position({Pickable::Kind::Node, 3, 4, {}});
  REQUIRE(where);
  CHECK(where->x == 100.0f);
}
