// The frame model's keys as the loader reads them (SCENES.md "Frame model"), the
// geometry of contacts in any direction, and the free motions behind the mechanism check.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "scenes/frame_kinematics.hpp"
#include "scenes/frame_mechanisms.hpp"
#include "scenes/generate_scene.hpp"
#include "scenes/load_scene.hpp"
#include "scenes/scene_error.hpp"
#include "scenes/scene_geometry.hpp"
#include "scenes/write_scene.hpp"
#include "tests/support/scene_toml.hpp"

using namespace fetic::scenes;

namespace {

using fetic::testing::SceneToml;

const std::string kFrameDefaults = "E = 2.0e11, area = 1.0e-3, inertia = 1.0e-6";

const std::string kFrame =
    SceneToml("frame", "[defaults]", kFrameDefaults)
        .strut("beam", {0.0, 0.0}, {2.0, 0.0}, "elements = 4, pinned = ['from'], fixed = ['to']")
        .strut("legL", {1.0, 2.0}, {1.5, 0.5}, "elements = 3, fixed = ['from']")
        .strut("legR", {2.0, 2.0}, {1.5, 0.5}, "elements = 3, pinned = ['from']")
        .joint("legL.to", "legR.to")
        .table("[[load]]", "strut = 'legL', at = 2, force = [1.0, -2.0], moment = 3.5")
        .table("[[load]]", "strut = 'beam', at = '3', moment = -1.0")
        .load("legR", "to", {0.0, -5.0})
        .contact("beam@3", "legL.to")
        .contact("beam.to", "legR@1", "normal = [0.70710678, 0.70710678]");

}  // namespace

TEST_CASE("frame: supports, joints, node loads with moments and contacts at any node") {
  const Scene scene = parse_scene(kFrame, "frame.toml");
  REQUIRE(scene.model == ModelKind::Frame);
  REQUIRE(scene.struts.size() == 3);
  CHECK(scene.struts[0].inertia == 1.0e-6);
  CHECK(scene.struts[0].pinned_from);
  CHECK_FALSE(scene.struts[0].fixed_from);
  CHECK(scene.struts[0].fixed_to);
  CHECK(scene.struts[2].pinned_from);

  REQUIRE(scene.joints.size() == 1);
  CHECK(scene.joints[0].kind == JointKind::Rigid);  // the default
  CHECK(end_label(scene, scene.joints[0].ends[1]) == "legR.to");

  REQUIRE(scene.loads.size() == 3);
  CHECK(scene.loads[0].node == 2);
  CHECK(scene.loads[0].moment == 3.5);
  CHECK(scene.loads[1].node == 3);  // a node index given as a string
  CHECK(scene.loads[1].force == Point{0.0, 0.0});
  CHECK(scene.loads[2].node == -1);
  CHECK(scene.loads[2].at == StrutEnd::To);

  REQUIRE(scene.contacts.size() == 2);
  CHECK(end_label(scene, scene.contacts[0].a) == "beam@3");
  CHECK(node_index(scene, scene.contacts[0].a) == 3);
  CHECK(node_index(scene, scene.contacts[0].b) == 3);
  // Default normal: from a's node (1.5, 0) to b's (1.5, 0.5).
  const FrameContactGeometry g0 = frame_contact_geometry(scene, scene.contacts[0]);
  CHECK(g0.normal[0] == Approx(0.0).margin(1e-15));
  CHECK(g0.normal[1] == Approx(1.0));
  CHECK(g0.gap == Approx(0.5));
  // A given normal (normalized) and a node off its line: the gap is along the normal.
  const FrameContactGeometry g1 = frame_contact_geometry(scene, scene.contacts[1]);
  const Point b = node_point(scene, scene.contacts[1].b);
  CHECK(b[0] == Approx(11.0 / 6.0));
  CHECK(g1.gap == Approx(((b[0] - 2.0) + b[1]) / std::sqrt(2.0)));
  CHECK(std::hypot(g1.normal[0], g1.normal[1]) == Approx(1.0).epsilon(1e-15));

  // Writing and reading back keeps every frame key.
  const Scene again = parse_scene(scene_to_toml(scene), "again.toml");
  CHECK(again.loads[1].node == 3);
  CHECK(again.loads[0].moment == 3.5);
  CHECK(again.contacts[1].has_normal);
  CHECK(end_label(again, again.contacts[1].b) == "legR@1");
  CHECK(again.struts[0].pinned_from);
}

TEST_CASE("frame: free motions are the rigid motions supports and joints allow") {
  const std::string text = SceneToml("frame", "[defaults]", kFrameDefaults + ", elements = 2")
                               .strut("float", {0.0, 1.0}, {2.0, 1.0})
                               .strut("lever", {0.0, 0.0}, {2.0, 0.0}, "pinned = ['from']")
                               .strut("clamped", {0.0, -1.0}, {2.0, -1.0}, "fixed = ['from']")
                               .strut("arm", {2.0, -1.0}, {2.0, -2.0})
                               .joint("clamped.to", "arm.from", "kind = 'pinned'")
                               .contact("lever.to", "float.to")
                               .contact("lever@1", "float.from")
                               .contact("clamped@1", "float.from", "normal = [0.6, 0.8]")
                               .contact("clamped@2", "float@1")
                               .contact("clamped@1", "arm.to", "normal = [1.0, 0.0]");
  const Scene scene = parse_scene(text, "motions.toml");
  const FrameKinematics k = frame_kinematics(scene);
  // Groups: float, lever, clamped+arm. Motions: 3 (float) + 1 (lever about its pin) +
  // 1 (arm about the joint).
  CHECK(k.groups.size() == 3);
  REQUIRE(k.motions.size() == 5);
  for (const FreeMotion& m : k.motions) {
    if (m.group == k.group_of_strut[1]) {  // the lever turns about (0, 0)
      const auto pin = motion_at(k, m, 1, {0.0, 0.0});
      CHECK(std::hypot(pin[0], pin[1]) <= 1e-12);
      CHECK(std::abs(pin[2]) > 0.0);
    }
    if (m.group == k.group_of_strut[3]) {  // only the arm moves, about (2, -1)
      const auto hinge = motion_at(k, m, 3, {2.0, -1.0});
      CHECK(std::hypot(hinge[0], hinge[1]) <= 1e-12);
      const auto clamped = motion_at(k, m, 2, {1.0, -1.0});
      CHECK(std::abs(clamped[0]) + std::abs(clamped[1]) + std::abs(clamped[2]) == 0.0);
    }
  }
  // The contacts hold every motion, also the float turning with the lever.
  CHECK(frame_mechanisms(scene).empty());
  // Without the last contact on the float, float and lever can turn together about
  // their pins' line: a mechanism.
  Scene fewer = scene;
  fewer.contacts.erase(fewer.contacts.begin() + 3);
  const auto mechanisms = frame_mechanisms(fewer);
  REQUIRE(mechanisms.size() == 1);
  CHECK(mechanisms[0].struts == std::vector<int>{0, 1});
}

TEST_CASE("frame: generated portal frames are valid and have the requested size") {
  GenerateOptions options;
  options.model = ModelKind::Frame;
  options.pairs = 3;
  options.elements = 10;
  options.subdomains = 2;
  const Scene scene = parse_scene(scene_to_toml(generate_scene(options)), "generated.toml");
  CHECK(scene.struts.size() == 18);
  CHECK(scene.joints.size() == 12);
  CHECK(scene.contacts.size() == 3);
  CHECK(unknowns(scene) == 18LL * 11 * 3);
}

namespace {

// A rope of `count` one-element struts along x, joined by pinned joints, pinned at both
// ends; with `held`, every joint rests on a clamped ground beam below (a contact).
std::string rope(int count, bool held) {
  std::string text = "model = \"frame\"\n[defaults]\nE = 2.0e11\narea = 1.0e-4\ninertia = 1.0e-9\n";
  for (int k = 0; k < count; ++k) {
    text += "[[strut]]\nname = \"r" + std::to_string(k) + "\"\nfrom = [" + std::to_string(k) +
            ".0, 0.0]\nto = [" + std::to_string(k + 1) + ".0, 0.0]\nelements = 1\n";
    if (k == 0) text += "pinned = [\"from\"]\n";
    if (k + 1 == count) text += "pinned = [\"to\"]\n";
  }
  for (int k = 0; k + 1 < count; ++k)
    text += "[[joint]]\nends = [\"r" + std::to_string(k) + ".to\", \"r" + std::to_string(k + 1) +
            ".from\"]\nkind = \"pinned\"\n";
  if (held) {
    text += "[[strut]]\nname = \"ground\"\nfrom = [0.0, -0.001]\nto = [" + std::to_string(count) +
            ".0, -0.001]\nelements = " + std::to_string(count) + "\nfixed = [\"from\", \"to\"]\n";
    for (int k = 0; k + 1 < count; ++k)
      text += "[[contact]]\na = \"r" + std::to_string(k) + ".to\"\nb = \"ground@" +
              std::to_string(k + 1) + "\"\n";
  }
  return text;
}

}  // namespace

// The mechanism check is near-linear (sparse QR for large sets; a dense SVD took 142 s and
// 1.6 GB on this rope): the test would time out, not pass slowly.
TEST_CASE("frame: a 2,000-strut rope is told to be a mechanism, and held by contacts it is not") {
  const Scene held = parse_scene(rope(2000, true), "rope.toml");
  CHECK(frame_mechanisms(held).empty());
  try {
    parse_scene(rope(2000, false), "rope.toml");
    FAIL("a rope pinned at its ends only is a mechanism");
  } catch (const SceneError& error) {
    CHECK_THAT(error.what(), Catch::Contains("form a mechanism"));
  }
  Scene loose = held;
  loose.contacts.pop_back();
  // Without its last contact, the joint above it can move: the struts beside it turn.
  const auto mechanisms = frame_mechanisms(loose);
  REQUIRE(mechanisms.size() == 1);
  CHECK(mechanisms[0].struts == std::vector<int>{1998, 1999});
  CHECK_THAT(mechanisms[0].motion, Catch::Contains("'r1998' turns about (1998, 0)"));
}

TEST_CASE("frame: the free motions of a 200-strut rope (sparse QR) keep its joints and pins") {
  const Scene scene = parse_scene(rope(200, true), "rope.toml");
  const FrameKinematics k = frame_kinematics(scene);
  // A straight chain pinned at both ends: each of its 199 joints can move across it.
  REQUIRE(k.motions.size() == 199);
  double largest_error = 0.0, smallest_motion = 1e300;
  for (const FreeMotion& m : k.motions) {
    double motion = 0.0;
    for (int s = 0; s < 200; ++s) {
      const Strut& strut = scene.struts[static_cast<size_t>(s)];
      const auto from = motion_at(k, m, s, strut.from), to = motion_at(k, m, s, strut.to);
      motion = std::max({motion, std::hypot(from[0], from[1]), std::hypot(to[0], to[1])});
      if (s == 0) largest_error = std::max(largest_error, std::hypot(from[0], from[1]));
      if (s == 199) largest_error = std::max(largest_error, std::hypot(to[0], to[1]));
      if (s + 1 < 200) {
        const auto next = motion_at(k, m, s + 1, strut.to);
        largest_error = std::max(largest_error, std::hypot(to[0] - next[0], to[1] - next[1]));
      }
    }
    smallest_motion = std::min(smallest_motion, motion);
  }
  CHECK(largest_error <= 1e-10);
  CHECK(smallest_motion > 1e-3);
}

TEST_CASE("frame: a linkage's mechanism names a motion every strut of it makes") {
  // Two posts on pins and a beam pinned to their tops: the posts turn about their feet,
  // the beam slides along itself.
  const std::string text =
      SceneToml("frame", "[defaults]", kFrameDefaults)
          .strut("left", {0.0, 0.0}, {0.0, 2.0}, "elements = 2, pinned = ['from']")
          .strut("right", {3.0, 0.0}, {3.0, 2.0}, "elements = 2, pinned = ['from']")
          .strut("top", {0.0, 2.0}, {3.0, 2.0}, "elements = 3")
          .joint("left.to", "top.from", "kind = 'pinned'")
          .joint("top.to", "right.to", "kind = 'pinned'");
  try {
    parse_scene(text, "linkage.toml");
    FAIL("a linkage is a mechanism");
  } catch (const SceneError& error) {
    const std::string message = error.what();
    CHECK_THAT(message, Catch::Contains("'left' turns about (0, 0)"));
    CHECK_THAT(message, Catch::Contains("'right' turns about (3, 0)"));
    CHECK_THAT(message, Catch::Contains("'top' slides along (1, 0)"));
  }
}
