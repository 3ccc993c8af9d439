// Valid scenes load as SCENES.md defines them: defaults, optional keys, numbers given as
// integers, geometry of contacts.

#include <catch2/catch.hpp>

#include <filesystem>

#include "scenes/load_scene.hpp"
#include "scenes/scene_geometry.hpp"
#include "tests/support/scene_toml.hpp"

using namespace fetic::scenes;
using fetic::testing::SceneToml;

TEST_CASE("defaults apply where a strut omits a key, and a strut's own value wins") {
  const char* text = R"(
title = "t"
model = "bar"
[defaults]
E = 2.1e11
area = 1
elements = 3
subdomains = 3
fixed = ["from"]
[[strut]]
name = "A"
from = [0, 0]
to = [2, 0]
[[strut]]
name = "B_2-x"
from = [0.0, 1.0]
to = [2.0, 1.0]
E = 7e10
fixed = ["to"]
subdomains = 1
)";
  const Scene scene = parse_scene(text, "d.toml");
  REQUIRE(scene.struts.size() == 2);
  CHECK(scene.title == "t");
  CHECK(scene.struts[0].E == 2.1e11);
  CHECK(scene.struts[0].area == 1.0);  // integer accepted as a number
  CHECK(scene.struts[0].to[0] == 2.0);
  CHECK(scene.struts[0].subdomains == 3);
  CHECK(scene.struts[0].fixed_from);
  CHECK_FALSE(scene.struts[0].fixed_to);
  CHECK(scene.struts[1].E == 7e10);
  CHECK_FALSE(scene.struts[1].fixed_from);
  CHECK(scene.struts[1].fixed_to);
  CHECK(scene.struts[1].subdomains == 1);
  CHECK(scene.struts[0].line == 10);  // the [[strut]] header
}

TEST_CASE("loads and contacts may come before the struts they name") {
  const std::string text =
      SceneToml("bar")
          .per_length("B", {-3.0, 0.0})
          .contact("A.to", "B.from")
          .strut("A", {0.0, 0.0}, {1.0, 0.0},
                 "E = 1e9, area = 1e-4, elements = 1, fixed = ['from']")
          .strut("B", {1.0, 0.0}, {2.0, 0.0}, "E = 1e9, area = 1e-4, elements = 1, fixed = ['to']");
  const Scene scene = parse_scene(text, "order.toml");
  REQUIRE(scene.loads.size() == 1);
  CHECK(scene.loads[0].strut == 1);
  CHECK(scene.loads[0].per_length);
  REQUIRE(scene.contacts.size() == 1);
  const ContactGeometry g = contact_geometry(scene, scene.contacts[0]);
  CHECK(g.gap == 0.0);  // a zero gap is allowed
  CHECK(g.normal[0] == 1.0);
}

TEST_CASE("contact normal and gap follow a's axis for any direction and orientation") {
  // A runs from (1,1) toward (0,0); B lies beyond A.from, reversed.
  const std::string text = SceneToml("bar", "[defaults]", "E = 1e9, area = 1e-4, elements = 2")
                               .strut("A", {0.0, 0.0}, {1.0, 1.0}, "fixed = ['to']")
                               .strut("B", {-2.0, -2.0}, {-0.5, -0.5}, "fixed = ['from']")
                               .contact("A.from", "B.to");
  const Scene scene = parse_scene(text, "diag.toml");
  const ContactGeometry g = contact_geometry(scene, scene.contacts[0]);
  CHECK(g.normal[0] == Approx(-std::sqrt(0.5)));
  CHECK(g.normal[1] == Approx(-std::sqrt(0.5)));
  CHECK(g.gap == Approx(std::sqrt(0.5)));
}

TEST_CASE("every bundled scene loads") {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(FETIC_BUNDLED_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    INFO(entry.path());
    CHECK_NOTHROW(load_scene_file(entry.path().string()));
    ++count;
  }
  CHECK(count >= 4);
}

TEST_CASE("a gap at the resolution of the coordinates is kept and reported as a warning") {
  const std::string text = SceneToml("bar", "[defaults]", "E = 1e9, area = 1e-4, elements = 1")
                               .strut("A", {0.0, 0.0}, {1.0, 0.0}, "fixed = ['from']")
                               .strut("B", {1.000000000000001, 0.0}, {2.0, 0.0}, "fixed = ['to']")
                               .contact("A.to", "B.from");
  const Scene scene = parse_scene(text, "tiny.toml");
  REQUIRE(scene.warnings.size() == 1);
  CHECK(scene.warnings[0].line == 16);  // the [[contact]] table
  CHECK_THAT(scene.warnings[0].message, Catch::Contains("at the resolution of the coordinates"));
  CHECK(contact_geometry(scene, scene.contacts[0]).gap > 0.0);
}

TEST_CASE("plane elements of extreme aspect ratio are reported as a warning") {
  const std::string text = SceneToml("plane").strut(
      "thin", {0.0, 0.0}, {1.0, 0.0},
      "E = 2.1e11, nu = 0.3, height = 1e-6, thickness = 0.01, elements = 10, "
      "elements_across = 1, fixed = ['from']");
  const Scene scene = parse_scene(text, "thin.toml");
  REQUIRE(scene.warnings.size() == 1);
  CHECK(scene.warnings[0].line == 2);
  CHECK_THAT(scene.warnings[0].message, Catch::Contains("aspect ratio 100000"));
}

TEST_CASE("a scene may declare its units, SI when it does not") {
  const std::string base = SceneToml("bar").strut(
      "A", {0.0, 0.0}, {500.0, 0.0}, "E = 210000, area = 100, elements = 2, fixed = ['from']");
  const Scene si = parse_scene(base, "si.toml");
  CHECK(si.units.length == "m");
  CHECK(si.units.force == "N");
  const Scene mm = parse_scene(base + "[units]\nlength = \"mm\"\nforce = \"kN\"\n", "mm.toml");
  CHECK(mm.units.length == "mm");
  CHECK(mm.units.force == "kN");
  // Only what is given changes.
  const Scene inches = parse_scene(std::string("units = { length = \"in\" }\n") + base, "in.toml");
  CHECK(inches.units.length == "in");
  CHECK(inches.units.force == "N");
}

TEST_CASE("units: derived names and the prefix a legend uses") {
  CHECK(stress_unit({"m", "N"}) == "Pa");
  CHECK(stress_unit({"mm", "N"}) == "MPa");
  CHECK(stress_unit({"mm", "kN"}) == "GPa");
  CHECK(stress_unit({"m", "kN"}) == "kPa");
  CHECK(stress_unit({"cm", "N"}) == "N/cm²");  // 10 kPa has no prefix of its own
  CHECK(stress_unit({"in", "lbf"}) == "psi");
  CHECK(stress_unit({"in", "kip"}) == "ksi");
  CHECK(force_per_length_unit({"mm", "N"}) == "N/mm");
  // The unit a legend shows for its largest value, and that value in it. 420 N/mm² is
  // 420 MPa; 420e6 N/m² too; 0.42 kN/mm² is 420 MPa as well. Moments: the scene's length,
  // the force prefixed: 3.2e6 N mm reads 3.2 MN mm.
  struct Shown {
    Quantity quantity;
    Units units;
    double largest;
    std::string name;
    double number;
  };
  for (const Shown& c : {Shown{Quantity::Stress, {"mm", "N"}, 420.0, "MPa", 420.0},
                         Shown{Quantity::Stress, {"m", "N"}, 420e6, "MPa", 420.0},
                         Shown{Quantity::Stress, {"mm", "kN"}, 0.42, "MPa", 420.0},
                         Shown{Quantity::Force, {"mm", "N"}, 84000.0, "kN", 84.0},
                         Shown{Quantity::Moment, {"mm", "N"}, 3.2e6, "MN mm", 3.2},
                         Shown{Quantity::Moment, {"mm", "N"}, 420.0, "N mm", 420.0},
                         Shown{Quantity::Moment, {"m", "N"}, 6800.0, "kN m", 6.8}}) {
    INFO(c.largest << " " << c.units.force << ", " << c.units.length);
    const DisplayUnit unit = display_unit(c.quantity, c.units, c.largest);
    CHECK(unit.name == c.name);
    CHECK(c.largest / unit.divisor == Approx(c.number));
  }
  CHECK(display_unit(Quantity::Moment, {"in", "kip"}, 30.0).name == "kip in");
  // Lengths stay in the scene's unit; imperial quantities are not converted.
  CHECK(display_unit(Quantity::Length, {"mm", "N"}, 0.001).name == "mm");
  CHECK(display_unit(Quantity::Stress, {"in", "lbf"}, 3000.0).name == "psi");
  CHECK(display_unit(Quantity::Stress, {"in", "lbf"}, 3000.0).divisor == 1.0);
  CHECK(metres_per("in") == Approx(0.0254));
  CHECK(!newtons_per("kgf").has_value());
}
