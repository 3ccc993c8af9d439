// Golden images: small fixed-size renders of bundled scenes and of thesis figures through
// the headless EGL renderer, compared with tests/golden/*.png (tolerance in golden.hpp).
// Regenerate with scripts/update-goldens.sh.

#include <catch2/catch.hpp>

#include <cstdlib>
#include <string>

#include "render/colormap.hpp"
#include "render/figures.hpp"
#include "render/frame_composer.hpp"
#include "render/png_writer.hpp"
#include "scenes/generate_scene.hpp"
#include "scenes/load_scene.hpp"
#include "tests/render/golden.hpp"

using namespace fetic;
using namespace fetic::render;
using fetic::testing::check_golden;

namespace {

struct Shot {
  std::string scene;  // path
  solver::MethodKind method = solver::MethodKind::ActiveSet;
  double load_factor = 1.0;
  View view;
};

View view_of(int width, int height) {
  View view;
  view.width = width;
  view.height = height;
  return view;
}

// The final state of the solve, as `fetic render --final` draws it, at each of `views`.
std::vector<Image> render_final(const scenes::Scene& scene, solver::MethodKind kind,
                                const std::vector<View>& views) {
  const solver::Model model = solver::build_model(scene);
  const auto method = solver::make_method(kind, model, {});
  FramePlan plan;
  plan.every_iteration = false;
  const RunExtent extent = survey(model, *method, plan);
  std::vector<Image> images;
  run_frames(*method, plan, [&](const Frame& frame) {
    for (const View& view : views) {
      const FrameComposer composer(model, view, extent,
                                   {model.title, solver::to_string(kind), "", ""});
      const ComposedFrame composed = composer.compose(frame);
      images.push_back(fetic::testing::test_renderer().render(
          view.width, view.height, composed.layers(), palette::background));
    }
    return true;
  });
  return images;
}

// The final state of the solve, as `fetic render --final` draws it.
Image render_final(const Shot& shot) {
  const solver::Model model = solver::build_model(scenes::load_scene_file(shot.scene));
  const auto method = solver::make_method(shot.method, model, {});
  FramePlan plan;
  plan.load_factors = {shot.load_factor};
  plan.every_iteration = false;
  const RunExtent extent = survey(model, *method, plan);
  const FrameComposer composer(model, shot.view, extent,
                               {model.title, solver::to_string(shot.method), "", ""});
  Image image;
  run_frames(*method, plan, [&](const Frame& frame) {
    const ComposedFrame composed = composer.compose(frame);
    image = fetic::testing::test_renderer().render(shot.view.width, shot.view.height,
                                                   composed.layers(), palette::background);
    return true;
  });
  return image;
}

Image render_drawing(const DrawList& drawing, int width, int height) {
  return fetic::testing::test_renderer().render(width, height, {&drawing}, {255, 255, 255, 255});
}

std::string bundled(const std::string& name) {
  return std::string(FETIC_BUNDLED_SCENES_DIR) + "/" + name;
}

Shot thesis_shot(double load_factor) {
  Shot shot{bundled("thesis.toml"), solver::MethodKind::ActiveSet, load_factor, view_of(400, 300)};
  shot.view.magnification = 50.0;  // fixed, so that a different load shows as a difference
  return shot;
}

bool updating() {
  const char* update = std::getenv("FETIC_UPDATE_GOLDENS");
  return update && std::string(update) == "1";
}

}  // namespace

TEST_CASE("golden: thesis scene solved, with the overlay") {
  const std::string problem =
      check_golden("thesis_active_set_400x300", render_final(thesis_shot(1.0)));
  INFO(problem);
  CHECK(problem.empty());
}

TEST_CASE("golden: chain scene coloured by axial stress, no overlay") {
  Shot shot{bundled("chain.toml"), solver::MethodKind::ActiveSet, 1.0, view_of(320, 200)};
  shot.view.color_by = ColorBy::Stress;
  shot.view.show_overlay = false;
  const std::string problem = check_golden("chain_stress_320x200", render_final(shot));
  INFO(problem);
  CHECK(problem.empty());
}

TEST_CASE("golden: plane model, deformed meshes in contact") {
  Shot shot{std::string(FETIC_RENDER_TEST_SCENES_DIR) + "/plane_contact.toml",
            solver::MethodKind::ActiveSet, 1.0, view_of(400, 300)};
  shot.view.color_by = ColorBy::Stress;
  const std::string problem = check_golden("plane_contact_400x300", render_final(shot));
  INFO(problem);
  CHECK(problem.empty());
}

TEST_CASE("golden: dense scenes stay readable, at two frame sizes") {
  // 2,000 pairs of bars (20,000 unknowns): a column of struts a fraction of a pixel apart;
  // glyphs too dense to draw are left out and counted, the stress colours show.
  const scenes::GenerateOptions bars{
      .model = scenes::ModelKind::Bar, .pairs = 2000, .elements = 4, .subdomains = 2};
  View small = view_of(640, 360), large = view_of(1280, 720);
  small.color_by = large.color_by = ColorBy::Stress;
  auto images =
      render_final(scenes::generate_scene(bars), solver::MethodKind::FetiC, {small, large});
  REQUIRE(images.size() == 2);
  std::string problem = check_golden("dense_bars_640x360", images[0]);
  INFO(problem);
  CHECK(problem.empty());
  problem = check_golden("dense_bars_1280x720", images[1]);
  INFO(problem);
  CHECK(problem.empty());

  // A plane scene of 101,000 unknowns (10 pairs of 100x24-element struts, bent and pushed
  // together): one row of load arrows per strut side, contact faces marked along the face.
  const scenes::GenerateOptions plane{.model = scenes::ModelKind::Plane,
                                      .pairs = 10,
                                      .elements = 100,
                                      .elements_across = 24,
                                      .subdomains = 5};
  images = render_final(scenes::generate_scene(plane), solver::MethodKind::FetiC, {small, large});
  REQUIRE(images.size() == 2);
  problem = check_golden("plane_100k_640x360", images[0]);
  INFO(problem);
  CHECK(problem.empty());
  problem = check_golden("plane_100k_1280x720", images[1]);
  INFO(problem);
  CHECK(problem.empty());
}

TEST_CASE("golden: a scene in mm and N, stresses in MPa") {
  View view = view_of(640, 360);
  view.color_by = ColorBy::Stress;
  view.show_labels = true;
  const auto images = render_final(scenes::load_scene_file(bundled("press_mm.toml")),
                                   solver::MethodKind::ActiveSet, {view});
  const std::string problem = check_golden("press_mm_640x360", images.at(0));
  INFO(problem);
  CHECK(problem.empty());
}

TEST_CASE("golden: figure 3.2, the steepest-descent path") {
  const IteratePath path = gradient_path(solver::MethodKind::SteepestDescent);
  const std::string problem =
      check_golden("figure_3_2_400x300",
                   render_drawing(figure_gradient_path(path, "Figure 3.2", 400, 300), 400, 300));
  INFO(problem);
  CHECK(problem.empty());
}

TEST_CASE("golden: figure 2.1, shapes of quadratic forms") {
  const std::string problem = check_golden(
      "figure_2_1_400x300", render_drawing(figure_quadratic_forms(400, 300), 400, 300));
  INFO(problem);
  CHECK(problem.empty());
}

TEST_CASE("golden negative control: load factor 0.8 does not pass as the 1.0 golden") {
  if (updating()) return;  // the golden may be being rewritten right now
  const Image golden =
      fetic::testing::read_png(std::string(FETIC_GOLDEN_DIR) + "/thesis_active_set_400x300.png");
  REQUIRE_FALSE(golden.rgba.empty());
  const fetic::testing::Comparison same =
      fetic::testing::compare(render_final(thesis_shot(1.0)), golden);
  const fetic::testing::Comparison changed =
      fetic::testing::compare(render_final(thesis_shot(0.8)), golden);
  INFO("1.0: " << same.differing << " pixels differ; 0.8: " << changed.differing << " ("
               << 100.0 * changed.fraction << "%)");
  CHECK(same.matches());
  CHECK_FALSE(changed.matches());
  // Not a near miss: a real change is far outside the tolerance.
  CHECK(changed.fraction > 5.0 * fetic::testing::kMaxDifferingFraction);
}

TEST_CASE("rendering is deterministic: the same state gives the same PNG bytes") {
  const Image first = render_final(thesis_shot(1.0));
  const Image second = render_final(thesis_shot(1.0));
  CHECK(first.rgba == second.rgba);
  CHECK(encode_png(first) == encode_png(second));
  // Read back opaque (alpha is kept at 1 by the blend, not patched afterwards).
  bool opaque = true;
  for (std::size_t i = 3; i < first.rgba.size(); i += 4)
    opaque = opaque && first.rgba[i] == 255;
  CHECK(opaque);
}

TEST_CASE("golden: the bundled frame scenes, beams along their Hermite curves") {
  for (const std::string name :
       {"frame_post_on_beam", "frame_apex_stop", "frame_portal_sway", "frame_beam_on_contacts",
        "frame_truss_bridge", "frame_scaffold"}) {
    Shot shot{bundled(name + ".toml"), solver::MethodKind::ActiveSet, 1.0, view_of(400, 300)};
    const std::string problem = check_golden(name + "_400x300", render_final(shot));
    INFO(name << ": " << problem);
    CHECK(problem.empty());
  }
}

TEST_CASE("golden: the portal frame coloured by bending moment") {
  // Sagging beam red in its middle, hogging blue at the rigid corners; the legend in kN m.
  Shot shot{bundled("frame_portal_sway.toml"), solver::MethodKind::ActiveSet, 1.0,
            view_of(400, 300)};
  shot.view.color_by = ColorBy::Moment;
  const std::string problem = check_golden("frame_portal_sway_moment_400x300", render_final(shot));
  INFO(problem);
  CHECK(problem.empty());
}
