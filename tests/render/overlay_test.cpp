// The overlay's plots hold every point they show: iteration 0 of a --final run, residuals
// below the run's floor (a window solve at another load), exact zeros (at the floor, with a
// mark), and load-step runs plotted against the load factor.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "render/colormap.hpp"
#include "render/frame_sequence.hpp"
#include "render/overlay.hpp"
#include "scenes/load_scene.hpp"
#include "scenes/units.hpp"
#include "solver/method.hpp"

using namespace fetic;
using namespace fetic::render;

namespace {

View view_of(int width, int height) {
  View view;
  view.width = width;
  view.height = height;
  return view;
}

solver::Model thesis() {
  return solver::build_model(
      scenes::load_scene_file(std::string(FETIC_BUNDLED_SCENES_DIR) + "/thesis.toml"));
}

bool holds(const PlotArea& area, double x, double y) {
  return x >= area.x_min() && x <= area.x_max() && y >= area.y_min() && y <= area.y_max();
}

}  // namespace

TEST_CASE("plots hold iteration 0 of a final-state frame (the active set starts at 50)") {
  const solver::Model model = thesis();
  const auto method = solver::make_method(solver::MethodKind::FetiC, model, {});
  FramePlan plan;
  plan.every_iteration = false;  // render --final: one frame, the whole history in its plots
  const RunExtent extent = survey(model, *method, plan);
  const auto& history = method->history();
  REQUIRE(history.front().active_set > history.back().active_set);  // the set shrinks
  std::vector<PlotArea> areas;
  draw_overlay({"t", "feti-c", "", ""}, model, method->snapshot(), history, extent,
               view_of(1280, 720), nullptr, &areas);
  REQUIRE(areas.size() == 2);
  for (const solver::HistoryEntry& entry : history) {
    CHECK(holds(areas[0], entry.iteration, entry.residual));
    CHECK(holds(areas[1], entry.iteration, entry.active_set));
  }
}

TEST_CASE("a residual below the run's floor widens the axis, an exact zero sits on the floor") {
  const solver::Model model = thesis();
  const auto method = solver::make_method(solver::MethodKind::FetiC, model, {});
  RunExtent extent = survey(model, *method, FramePlan{});
  solver::Snapshot snapshot = method->snapshot();
  std::vector<solver::HistoryEntry> history = method->history();
  // As in the window at load 1.8: the survey's floor is 1e-11, this solve reaches 1.6e-12.
  extent.smallest_residual = 1e-11;
  history.back().residual = 1.6e-12;
  std::vector<PlotArea> areas;
  draw_overlay({"t", "feti-c", "", ""}, model, snapshot, history, extent, view_of(1280, 720),
               nullptr, &areas);
  REQUIRE(!areas.empty());
  CHECK(areas[0].y_min() <= 1.6e-12);
  for (const solver::HistoryEntry& entry : history)
    CHECK(holds(areas[0], entry.iteration, entry.residual));

  // An exact zero: drawn at the floor, marked, labelled "0"; the axis stays positive.
  history.back().residual = 0.0;
  areas.clear();
  const DrawList list = draw_overlay({"t", "feti-c", "", ""}, model, snapshot, history, extent,
                                     view_of(1280, 720), nullptr, &areas);
  CHECK(areas[0].y_min() > 0.0);
  bool zero_label = false;
  for (const TextItem& text : list.texts())
    zero_label = zero_label || text.text == "0";
  CHECK(zero_label);
  // The mark is on the floor, at the last iteration.
  const Point floor = areas[0].to_pixel(history.back().iteration, areas[0].y_min());
  bool marked = false;
  for (const Vertex& v : list.vertices())
    marked = marked || (std::abs(v.position.x - floor.x) < 6.0f &&
                        std::abs(v.position.y - floor.y) < 6.0f && v.color == series_color(0));
  CHECK(marked);
}

TEST_CASE("load steps are plotted against the load factor") {
  const solver::Model model = thesis();
  const auto method = solver::make_method(solver::MethodKind::FetiC, model, {});
  FramePlan plan;
  plan.load_factors = {0.25, 0.5, 0.75, 1.0, 1.25};
  plan.every_iteration = false;
  const RunExtent extent = survey(model, *method, plan);
  REQUIRE(extent.steps.size() == 5);
  CHECK(extent.steps.back().load_factor == 1.25);
  CHECK(extent.steps.back().active_set >= extent.steps.front().active_set);
  CHECK(extent.steps.back().total_force > 0.0);
  StepSeries series;
  series.all = extent.steps;
  series.shown.assign(extent.steps.begin(), extent.steps.begin() + 3);
  std::vector<PlotArea> areas;
  const DrawList list =
      draw_overlay({"t", "feti-c", "step 3 of 5", ""}, model, method->snapshot(), method->history(),
                   extent, view_of(1280, 720), &series, &areas);
  REQUIRE(areas.size() == 3);  // iterations, active set, total contact force
  for (const PlotArea& area : areas) {
    CHECK(area.x_min() <= 0.25);
    CHECK(area.x_max() >= 1.25);
  }
  for (const StepSummary& step : extent.steps) {
    CHECK(holds(areas[0], step.load_factor, step.iterations));
    CHECK(holds(areas[1], step.load_factor, step.active_set));
  }
  std::string all;
  for (const TextItem& text : list.texts())
    all += text.text + "|";
  CHECK_THAT(all, Catch::Contains("load factor|"));
  double most = 0.0;
  for (const StepSummary& step : extent.steps)
    most = std::max(most, step.total_force);
  const std::string unit = scenes::display_unit(scenes::Quantity::Force, model.units, most).name;
  CHECK_THAT(all, Catch::Contains("total contact force [" + unit + "]|"));
}
