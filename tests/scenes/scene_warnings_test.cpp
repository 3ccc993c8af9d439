// Valid scenes with something the user should know: the loader accepts them and says so
// (file:line: warning: ...), as SCENES.md's "What fetic decides" documents.

#include <catch2/catch.hpp>

#include <string>

#include "scenes/load_scene.hpp"
#include "tests/support/scene_toml.hpp"

using namespace fetic::scenes;
using fetic::testing::SceneToml;

namespace {

SceneToml bar() {
  return SceneToml("bar", "[defaults]", "E = 2.1e11, area = 1e-4, elements = 4")
      .strut("L", {0.0, 0.0}, {1.0, 0.0}, "fixed = ['from']");
}

std::string all_warnings(const Scene& scene) {
  std::string text;
  for (const Problem& warning : scene.warnings)
    text += std::to_string(warning.line) + ": " + warning.message + "\n";
  return text;
}

}  // namespace

TEST_CASE("a sideways force on a bar strut is accepted with a warning naming what is dropped") {
  const Scene scene = parse_scene(bar()
                                      .load("L", "to", {300.0, 400.0})
                                      .per_length("L", {0.0, -50.0})
                                      .load("L", "to", {1000.0, 0.0})
                                      .str(),
                                  "sideways.toml");
  const std::string text = all_warnings(scene);
  INFO(text);
  REQUIRE(scene.warnings.size() == 2);  // the axial load gets none
  CHECK(scene.warnings[0].line == 11);
  CHECK_THAT(scene.warnings[0].message,
             Catch::Contains("load on strut 'L': the bar model carries only the axial "
                             "component of a force; the sideways component 400 N is dropped "
                             "(axial: 300 N)"));
  CHECK_THAT(scene.warnings[1].message, Catch::Contains("-50 N/m is dropped (axial: 0 N/m)"));
}

TEST_CASE("a sideways force on a tilted bar counts along its own axis") {
  const std::string text = SceneToml("bar")
                               .strut("D", {0.0, 0.0}, {3.0, 4.0},
                                      "E = 2.1e11, area = 1e-4, elements = 4, fixed = ['from']")
                               .load("D", "to", {30.0, 40.0});
  const Scene scene = parse_scene(text, "tilted.toml");
  CHECK(scene.warnings.empty());  // along the axis (0.6, 0.8): nothing dropped
}

TEST_CASE("plane contact faces of different heights are paired with a warning") {
  const std::string text =
      SceneToml("plane", "[defaults]",
                "E = 2.1e11, elements = 4, thickness = 0.01, nu = 0.3, elements_across = 2")
          .strut("P", {0.0, 0.0}, {1.0, 0.0}, "height = 0.1, fixed = ['from']")
          .strut("Q", {1.001, 0.0}, {2.0, 0.0}, "height = 0.3, fixed = ['to']")
          .contact("P.to", "Q.from");
  const Scene scene = parse_scene(text, "heights.toml");
  REQUIRE(scene.warnings.size() == 1);
  CHECK(scene.warnings[0].line == 20);
  CHECK_THAT(scene.warnings[0].message,
             Catch::Contains("contact P.to - Q.from: the end faces have different heights (0.1 "
                             "and 0.3)") &&
                 Catch::Contains("up to 0.1 apart across the axis"));
  std::string same = text;
  same.replace(same.find("height = 0.3"), 12, "height = 0.1");
  CHECK(parse_scene(same, "same.toml").warnings.empty());
}
