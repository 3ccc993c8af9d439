// Turning solver states into draw lists, without GL: magnification and gap shifts, closed
// contacts drawn closed, FETI pieces drawn apart until they agree, frames of a run.

#include <catch2/catch.hpp>

#include <cmath>

#include "render/colormap.hpp"
#include "render/frame_sequence.hpp"
#include "render/overlay.hpp"
#include "render/scene_drawing.hpp"
#include "render/scene_framing.hpp"
#include "render/text_format.hpp"
#include "scenes/load_scene.hpp"
#include "solver/method.hpp"

using namespace fetic;
using namespace fetic::render;

namespace {

struct Solved {
  solver::Model model;
  std::unique_ptr<solver::Method> method;
  solver::Snapshot final;
  RunExtent extent;
};

std::unique_ptr<Solved> solve(const std::string& scene_file, solver::MethodKind kind) {
  auto solved = std::make_unique<Solved>();
  solved->model = solver::build_model(
      scenes::load_scene_file(std::string(FETIC_BUNDLED_SCENES_DIR) + "/" + scene_file));
  solved->method = solver::make_method(kind, solved->model, {});
  solved->extent = survey(solved->model, *solved->method, FramePlan{});
  solved->final = solved->method->snapshot();
  return solved;
}

View small_view() {
  View view;
  view.width = 400;
  view.height = 300;
  return view;
}

}  // namespace

TEST_CASE("magnification: round numbers, the largest displacement or gap at 8% of the scene") {
  CHECK(round_magnification(73.0) == 50.0);
  CHECK(round_magnification(199.0) == 100.0);
  CHECK(round_magnification(0.3) == 0.2);
  CHECK(round_magnification(0.0) == 1.0);
  const auto solved = solve("thesis.toml", solver::MethodKind::ActiveSet);
  const double m =
      automatic_magnification(solved->model, solved->extent, true, gap_widening(solved->model),
                              side_clearances(solved->model))
          .magnification;
  double largest_gap = 0.0;
  for (const auto& pair : solved->model.pairs)
    largest_gap = std::max(largest_gap, pair.gap);
  const double raw = 0.08 * 4.9 / std::max(largest_gap, solved->extent.largest_displacement);
  CHECK(m == round_magnification(raw));
}

TEST_CASE("gap widening opens every gap to m times itself and leaves clamped ends in place") {
  for (const char* scene : {"chain.toml", "thesis.toml", "plane_pair.toml"}) {
    INFO(scene);
    const auto solved = solve(scene, solver::MethodKind::ActiveSet);
    const solver::Model& model = solved->model;
    const auto q = gap_widening(model);
    // Per unit of m - 1: each pair's gap widens by the gap itself (to 1e-5 of it).
    for (const auto& pair : model.pairs) {
      const double widened =
          (q[pair.strut_b][pair.node_b] - q[pair.strut_a][pair.node_a]).dot(pair.normal);
      CHECK(widened == Approx(pair.gap).epsilon(1e-5));
    }
    // Clamped nodes stay in place (the supports are weighted rows of a least-squares fit:
    // to a millionth of the largest gap); a strut's widening runs along its axis.
    double largest_gap = 0.0;
    for (const auto& pair : model.pairs)
      largest_gap = std::max(largest_gap, pair.gap);
    for (std::size_t s = 0; s < model.struts.size(); ++s) {
      for (int node : model.clamped_nodes[s])
        CHECK(q[s][node].norm() < 1e-5 * largest_gap);
      for (const solver::Vec2& v : q[s])
        CHECK(std::abs(v.dot(model.struts[s].e2)) < 1e-12 * model.struts[s].length);
    }
  }
  // The thesis' pairs are clamped at both outer ends: the two struts share the gap by the
  // least change of strain, a = g La^2 / (La^2 + Lb^2) and b = g Lb^2 / (La^2 + Lb^2).
  const auto thesis = solve("thesis.toml", solver::MethodKind::ActiveSet);
  const auto q = gap_widening(thesis->model);
  for (const auto& pair : thesis->model.pairs) {
    const double la = thesis->model.struts[pair.strut_a].length;
    const double lb = thesis->model.struts[pair.strut_b].length;
    const double share_a = la * la / (la * la + lb * lb);
    CHECK(q[pair.strut_a][pair.node_a].x() == Approx(-share_a * pair.gap).epsilon(1e-4));
    CHECK(q[pair.strut_b][pair.node_b].x() == Approx((1.0 - share_a) * pair.gap).epsilon(1e-4));
  }
}

TEST_CASE("the automatic magnification never draws struts crossing or gaps eating struts") {
  const auto solved = solve("thesis.toml", solver::MethodKind::ActiveSet);
  const solver::Model& model = solved->model;
  const auto widening = gap_widening(model);
  const auto clearance = side_clearances(model);
  const MagnificationChoice free =
      automatic_magnification(model, solved->extent, true, widening, clearance);
  // Make the struts sway sideways by a tenth of their clearance: a magnification of 4 at
  // most keeps them 40% apart.
  RunExtent swaying = solved->extent;
  swaying.strut_lateral.assign(model.struts.size(), 0.0);
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < model.struts.size(); ++s)
    if (std::isfinite(clearance[s])) {
      swaying.strut_lateral[s] = 0.1 * clearance[s];
      smallest = std::min(smallest, clearance[s]);
    }
  REQUIRE(std::isfinite(smallest));
  const MagnificationChoice limited =
      automatic_magnification(model, swaying, true, widening, clearance);
  CHECK(limited.magnification <= 4.0);
  CHECK(limited.magnification == round_magnification(std::min(4.0, free.magnification)));
  CHECK(limited.limited_by == "crossing");
}

TEST_CASE("closed contacts are drawn closed, open ones as wide as m times their gap") {
  const auto solved = solve("thesis.toml", solver::MethodKind::ActiveSet);
  const View view = small_view();
  const SceneFraming framing = frame_scene(solved->model, view, solved->extent, scene_region(view));
  const auto displacements = solver::strut_displacements(solved->model, solved->final);
  const auto marks = contact_marks(solved->model, solved->final, framing);
  REQUIRE(marks.size() == solved->model.pairs.size());
  int active = 0;
  for (const ContactMark& mark : marks) {
    const auto& pair = solved->model.pairs[static_cast<std::size_t>(mark.pair)];
    const double closing =
        (displacements[pair.strut_a][pair.node_a] - displacements[pair.strut_b][pair.node_b])
            .dot(pair.normal);
    const double drawn_gap = framing.magnification * (pair.gap - closing) * framing.pixels_per_unit;
    CHECK(length(mark.b - mark.a) == Approx(drawn_gap).margin(0.05));
    if (mark.active) {
      ++active;
      CHECK(length(mark.b - mark.a) < 0.05f);
      CHECK(mark.force > 0.0);
    }
  }
  CHECK(active == solved->final.active_set_size());
  CHECK(active > 0);
}

TEST_CASE("the pieces of a strut are drawn where each puts the shared node: torn apart") {
  const auto solved = solve("two_bars.toml", solver::MethodKind::ActiveSet);
  // Split the left strut's single piece into two that disagree at node 2.
  solver::Snapshot torn = solved->final;
  const solver::Piece whole = torn.pieces[0];
  REQUIRE(whole.box.i1 >= 2);
  solver::Piece first = whole, second = whole;
  first.box.i1 = 2;
  first.displacement.resize(3);
  second.box.i0 = 2;
  second.displacement.assign(whole.displacement.begin() + 2, whole.displacement.end());
  second.displacement[0] += solver::Vec2(2e-4, 0.0);
  torn.pieces[0] = first;
  torn.pieces.push_back(second);

  const View view = small_view();
  const SceneFraming framing = frame_scene(solved->model, view, solved->extent, scene_region(view));
  const auto nodes = piece_outline_nodes(solved->model, torn, framing);
  const Point end_of_first = nodes[0].back();
  const Point start_of_second = nodes.back().front();
  CHECK(length(start_of_second - end_of_first) ==
        Approx(framing.magnification * 2e-4 * framing.pixels_per_unit).epsilon(1e-4));

  // Once they agree, the ends meet.
  torn.pieces.back().displacement[0] -= solver::Vec2(2e-4, 0.0);
  const auto agreed = piece_outline_nodes(solved->model, torn, framing);
  CHECK(length(agreed.back().front() - agreed[0].back()) < 1e-3f);
}

TEST_CASE("a scene stays inside its region and its layers follow the view") {
  const auto solved = solve("chain.toml", solver::MethodKind::ActiveSet);
  View view = small_view();
  view.color_by = ColorBy::Stress;
  const Rect region = scene_region(view);
  const SceneFraming framing = frame_scene(solved->model, view, solved->extent, region);
  const DrawList list = draw_scene(solved->model, solved->final, view, framing);
  for (const Vertex& v : list.vertices()) {
    CHECK(v.position.x >= region.x0 - 1.0f);
    CHECK(v.position.x <= region.x1 + 1.0f);
    CHECK(v.position.y >= region.y0 - 1.0f);
    CHECK(v.position.y <= region.y1 + 1.0f);
  }
  bool legend = false, magnification = false;
  for (const TextItem& text : list.texts()) {
    legend = legend || text.text.find("axial stress") != std::string::npos;
    magnification = magnification || text.text.find("×") != std::string::npos;
  }
  CHECK(legend);
  CHECK(magnification);

  View bare = view;
  bare.show_loads = bare.show_supports = bare.show_gaps = bare.show_contacts = bare.show_forces =
      false;
  CHECK(draw_scene(solved->model, solved->final, bare, framing).triangle_count() <
        list.triangle_count());
}

TEST_CASE("frames: the initial state and one per iteration, load steps one per step") {
  const solver::Model model = solver::build_model(
      scenes::load_scene_file(std::string(FETIC_BUNDLED_SCENES_DIR) + "/thesis.toml"));
  const auto method = solver::make_method(solver::MethodKind::ActiveSet, model, {});
  std::vector<int> iterations;
  const int count = run_frames(*method, FramePlan{}, [&](const Frame& frame) {
    CHECK(frame.index == static_cast<int>(iterations.size()));
    CHECK(frame.history.size() == static_cast<std::size_t>(frame.snapshot.iteration + 1));
    iterations.push_back(frame.snapshot.iteration);
    return true;
  });
  CHECK(count == static_cast<int>(method->history().size()));
  CHECK(iterations.front() == 0);
  CHECK(iterations.back() == method->iteration());

  const std::vector<double> factors{0.2, 0.4, 0.6, 0.8, 1.0};
  FramePlan steps;
  steps.load_factors = factors;
  steps.every_iteration = false;
  std::vector<double> seen;
  CHECK(run_frames(*method, steps, [&](const Frame& frame) {
          CHECK(frame.snapshot.status == solver::Status::Converged);
          seen.push_back(frame.snapshot.load_factor);
          return true;
        }) == 5);
  CHECK(seen == factors);
  CHECK(run_frames(*method, FramePlan{}, [](const Frame&) { return false; }) == 1);  // stops
}

TEST_CASE("the overlay names method, iteration, residual and active set") {
  const auto solved = solve("thesis.toml", solver::MethodKind::ActiveSet);
  const View view = small_view();
  const DrawList overlay =
      draw_overlay({"Thesis", "active-set", "", ""}, solved->model, solved->final,
                   solved->method->history(), solved->extent, view);
  std::string all;
  for (const TextItem& text : overlay.texts())
    all += text.text + "|";
  CHECK_THAT(all, Catch::Contains("active-set|"));
  CHECK_THAT(all, Catch::Contains("|" + std::to_string(solved->final.iteration) + "|"));
  CHECK_THAT(all, Catch::Contains(std::to_string(solved->final.active_set_size()) + " of 50|"));
  CHECK_THAT(all, Catch::Contains("relative residual"));
  CHECK_THAT(all, Catch::Contains("converged"));
  const Rect panel = overlay_panel(view);
  const Rect around{panel.x0 - 1.0f, panel.y0 - 1.0f, panel.x1 + 1.0f, panel.y1 + 1.0f};
  for (const Vertex& v : overlay.vertices())
    CHECK(around.contains(v.position));
}

TEST_CASE("the stress legend speaks the scene's units: N and mm give MPa") {
  const auto solved = solve("press_mm.toml", solver::MethodKind::ActiveSet);
  View view = small_view();
  view.color_by = ColorBy::Stress;
  const SceneFraming framing = frame_scene(solved->model, view, solved->extent, scene_region(view));
  // Stresses of a few hundred N/mm²: the legend's ends are the largest, in MPa as they are.
  REQUIRE(framing.stress_scale > 100.0);
  REQUIRE(framing.stress_scale < 1000.0);
  const DrawList list = draw_scene(solved->model, solved->final, view, framing);
  std::string all;
  for (const TextItem& text : list.texts())
    all += text.text + "|";
  CHECK_THAT(all, Catch::Contains(format("%.3g", framing.stress_scale) + " MPa   axial stress"));
  CHECK_THAT(all, Catch::Contains("mm, N, MPa"));  // the caption
  CHECK_THAT(all, Catch::Contains(" mm|"));        // the scale bar
}

TEST_CASE("the moment legend: kN m for a frame in m and N, bars drawn grey with a note why") {
  View view;  // 1280x720: room for the legend's name
  view.color_by = ColorBy::Moment;
  const auto frame = solve("frame_post_on_beam.toml", solver::MethodKind::ActiveSet);
  SceneFraming framing = frame_scene(frame->model, view, frame->extent, scene_region(view));
  // The post pushes the clamped-clamped beam down: tens of kN m at most.
  REQUIRE(framing.moment_scale > 1e3);
  REQUIRE(framing.moment_scale < 1e6);
  DrawList list = draw_scene(frame->model, frame->final, view, framing);
  std::string all;
  for (const TextItem& text : list.texts())
    all += text.text + "|";
  CHECK_THAT(
      all, Catch::Contains(format("%.3g", framing.moment_scale / 1e3) + " kN m   bending moment"));

  const auto bars = solve("two_bars.toml", solver::MethodKind::ActiveSet);
  CHECK(bars->extent.largest_moment == 0.0);
  framing = frame_scene(bars->model, view, bars->extent, scene_region(view));
  const SceneMesh mesh = build_scene_mesh(bars->model, bars->final, framing, ColorBy::Moment);
  int grey = 0;
  for (const MeshVertex& v : mesh.vertices) {
    CHECK(v.element == -1);  // no value colours
    grey += v.color == palette::no_value;
  }
  CHECK(grey > 0);
  list = draw_scene(bars->model, bars->final, view, framing);
  all.clear();
  for (const TextItem& text : list.texts())
    all += text.text + "|";
  CHECK_THAT(all, Catch::Contains("no bending moment"));
}

// Issue 23, item 4: a legend says what its scale is - the largest of the state shown, or
// a fixed scale named as such with the state's own largest beside it.
TEST_CASE("legends name their scale: the state's largest, or a fixed one and now") {
  const auto solved = solve("thesis.toml", solver::MethodKind::FetiC);
  View view;  // 1280x720
  view.color_by = ColorBy::Stress;
  SceneFraming framing = frame_scene(solved->model, view, solved->extent, scene_region(view));
  const auto texts = [&](const View& v, const SceneFraming& f) {
    std::string all;
    const DrawList list = draw_scene(solved->model, solved->final, v, f);
    for (const TextItem& text : list.texts())
      all += text.text + "|";
    return all;
  };
  // One frame's own scales: "largest".
  double largest_force = 0.0;
  for (const double f : solved->final.force)
    largest_force = std::max(largest_force, std::abs(f));
  framing.force_scale = largest_force;
  const std::string own = texts(view, framing);
  CHECK_THAT(own, Catch::Contains("contact force (largest ") && Catch::Contains("(largest shown)"));
  CHECK_THAT(own, !Catch::Contains("now"));
  // A scale fixed beyond the state (twice its force): named, with the state's largest.
  framing.force_scale = 2.0 * largest_force;
  view.scale_basis = "over loads 0-2";
  const std::string fixed = texts(view, framing);
  CHECK_THAT(fixed, Catch::Contains("contact force (scale ") &&
                        Catch::Contains(": largest over loads 0-2; now "));
  CHECK_THAT(fixed, Catch::Contains("axial stress (largest over loads 0-2; now "));
}
