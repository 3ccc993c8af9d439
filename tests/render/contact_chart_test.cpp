// The per-contact chart (render/contact_chart.hpp): one bar per pair with a contact force,
// one red mark per active pair, from the state it is drawn for; shown by itself at 200
// pairs and more; it takes its room from the scene, left of the information panel.

#include <catch2/catch.hpp>

#include <string>

#include "render/colormap.hpp"
#include "render/contact_chart.hpp"
#include "render/overlay.hpp"
#include "scenes/generate_scene.hpp"
#include "scenes/load_scene.hpp"
#include "solver/method.hpp"

using namespace fetic;
using namespace fetic::render;

namespace {

// Vertices of the colour: a line is a quad of two triangles, 6 vertices.
std::size_t vertices_of(const DrawList& list, Color color) {
  std::size_t count = 0;
  for (const Vertex& v : list.vertices())
    count += v.color.r == color.r && v.color.g == color.g && v.color.b == color.b ? 1 : 0;
  return count;
}

}  // namespace

TEST_CASE("the chart has a bar per loaded pair and a red mark per active pair") {
  const solver::Model model = solver::build_model(
      scenes::load_scene_file(std::string(FETIC_BUNDLED_SCENES_DIR) + "/thesis.toml"));
  const auto method = solver::make_method(solver::MethodKind::FetiC, model, {});
  method->start(1.0);
  solver::run_to_end(*method);
  const solver::Snapshot& state = method->snapshot();
  std::size_t active = 0, loaded = 0;
  for (std::size_t k = 0; k < model.pairs.size(); ++k) {
    active += state.in_working_set[k] ? 1 : 0;
    loaded += state.force[k] != 0.0 ? 1 : 0;
  }
  REQUIRE(active > 0);
  REQUIRE(active < model.pairs.size());
  const DrawList chart = draw_contact_chart(model, state, {800, 10, 1270, 710}, 14.0f);
  CHECK(vertices_of(chart, palette::contact) == 6 * active);
  CHECK(vertices_of(chart, palette::force) == 6 * loaded);
  bool says_active = false;
  for (const TextItem& text : chart.texts())
    says_active =
        says_active || text.text.find("active (red): " + std::to_string(active) + " of " +
                                      std::to_string(model.pairs.size())) != std::string::npos;
  CHECK(says_active);
}

TEST_CASE("the chart is shown at 200 pairs and more, and takes its room from the scene") {
  scenes::GenerateOptions options;
  options.model = scenes::ModelKind::Bar;
  options.pairs = 200;
  options.elements = 4;
  options.subdomains = 1;
  const solver::Model dense = solver::build_model(scenes::generate_scene(options));
  CHECK(dense.pairs.size() >= 200);
  CHECK(chart_shown(dense, -1));
  CHECK_FALSE(chart_shown(dense, 0));
  const solver::Model thesis = solver::build_model(
      scenes::load_scene_file(std::string(FETIC_BUNDLED_SCENES_DIR) + "/thesis.toml"));
  CHECK(thesis.pairs.size() < 200);
  CHECK_FALSE(chart_shown(thesis, -1));
  CHECK(chart_shown(thesis, 1));
  View view;
  view.width = 1280;
  view.height = 720;
  const Rect whole = scene_region(view);
  view.show_chart = true;
  const Rect chart = chart_region(view), scene = scene_region(view);
  CHECK(scene.x1 == chart.x0);
  CHECK(scene.x1 < whole.x1);
  CHECK(chart.x1 <= overlay_panel(view).x0);
  CHECK(chart.width() >= 0.35f * whole.x1);  // 40% of it, less a margin
}
