// The scene writer and the generator: what they write loads back as the same scene.

#include <catch2/catch.hpp>

#include <filesystem>

#include "scenes/generate_scene.hpp"
#include "scenes/load_scene.hpp"
#include "scenes/write_scene.hpp"

using namespace fetic::scenes;

namespace {

void require_same(const Scene& a, const Scene& b) {
  REQUIRE(a.model == b.model);
  CHECK(a.title == b.title);
  CHECK(a.units == b.units);
  REQUIRE(a.struts.size() == b.struts.size());
  for (size_t i = 0; i < a.struts.size(); ++i) {
    const Strut& x = a.struts[i];
    const Strut& y = b.struts[i];
    CHECK(x.name == y.name);
    CHECK(x.from == y.from);
    CHECK(x.to == y.to);
    CHECK(x.E == y.E);
    CHECK(x.elements == y.elements);
    CHECK(x.subdomains == y.subdomains);
    CHECK(x.fixed_from == y.fixed_from);
    CHECK(x.fixed_to == y.fixed_to);
    if (a.model == ModelKind::Frame) {
      CHECK(x.area == y.area);
      CHECK(x.inertia == y.inertia);
      CHECK(x.pinned_from == y.pinned_from);
      CHECK(x.pinned_to == y.pinned_to);
    } else if (a.model == ModelKind::Bar) {
      CHECK(x.area == y.area);
    } else {
      CHECK(x.height == y.height);
      CHECK(x.thickness == y.thickness);
      CHECK(x.nu == y.nu);
      CHECK(x.elements_across == y.elements_across);
      CHECK(x.subdomains_across == y.subdomains_across);
    }
  }
  REQUIRE(a.loads.size() == b.loads.size());
  for (size_t i = 0; i < a.loads.size(); ++i) {
    CHECK(a.loads[i].strut == b.loads[i].strut);
    CHECK(a.loads[i].per_length == b.loads[i].per_length);
    CHECK(a.loads[i].force == b.loads[i].force);
    if (!a.loads[i].per_length) CHECK(a.loads[i].at == b.loads[i].at);
    CHECK(a.loads[i].node == b.loads[i].node);
    CHECK(a.loads[i].moment == b.loads[i].moment);
  }
  REQUIRE(a.joints.size() == b.joints.size());
  for (size_t i = 0; i < a.joints.size(); ++i) {
    CHECK(a.joints[i].kind == b.joints[i].kind);
    REQUIRE(a.joints[i].ends.size() == b.joints[i].ends.size());
    for (size_t e = 0; e < a.joints[i].ends.size(); ++e) {
      CHECK(a.joints[i].ends[e].strut == b.joints[i].ends[e].strut);
      CHECK(a.joints[i].ends[e].end == b.joints[i].ends[e].end);
    }
  }
  REQUIRE(a.contacts.size() == b.contacts.size());
  for (size_t i = 0; i < a.contacts.size(); ++i) {
    CHECK(a.contacts[i].a.strut == b.contacts[i].a.strut);
    CHECK(a.contacts[i].a.end == b.contacts[i].a.end);
    CHECK(a.contacts[i].b.strut == b.contacts[i].b.strut);
    CHECK(a.contacts[i].b.end == b.contacts[i].b.end);
    CHECK(a.contacts[i].a.node == b.contacts[i].a.node);
    CHECK(a.contacts[i].b.node == b.contacts[i].b.node);
    CHECK(a.contacts[i].has_normal == b.contacts[i].has_normal);
    CHECK(a.contacts[i].normal == b.contacts[i].normal);
  }
}

}  // namespace

TEST_CASE("every bundled scene survives writing and reading back unchanged") {
  for (const auto& entry : std::filesystem::directory_iterator(FETIC_BUNDLED_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    INFO(entry.path());
    const Scene original = load_scene_file(entry.path().string());
    require_same(original, parse_scene(scene_to_toml(original), "written.toml"));
  }
}

TEST_CASE("generated scenes are valid and have the requested size") {
  GenerateOptions options{.model = ModelKind::Plane,
                          .pairs = 3,
                          .elements = 20,
                          .elements_across = 6,
                          .subdomains = 4,
                          .subdomains_across = 2};
  const Scene scene = generate_scene(options);
  const Scene read = parse_scene(scene_to_toml(scene), "generated.toml");
  require_same(scene, read);
  CHECK(read.struts.size() == 6);
  CHECK(read.contacts.size() == 3);
  CHECK(unknowns(read) == 6LL * 21 * 7 * 2);
  options.model = ModelKind::Bar;
  CHECK(unknowns(parse_scene(scene_to_toml(generate_scene(options)), "bar.toml")) == 6LL * 21);
  options.subdomains = 30;
  CHECK_THROWS_AS(generate_scene(options), std::invalid_argument);
}
