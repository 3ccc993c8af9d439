// Level of detail of the scene mesh (render/mesh_detail.hpp), without GL: the level
// follows the zoom in powers of two, pictures whose elements are at least a pixel are
// built exactly as without a level, merged cells carry the mean of the elements they
// cover (found here by position, not by index), and a scene too large for its level is
// kept in detail only near the view. The pictures themselves: lod_picture_test.cpp.

#include <catch2/catch.hpp>

#include <cmath>

#include "render/frame_sequence.hpp"
#include "render/mesh_detail.hpp"
#include "render/overlay.hpp"
#include "render/scene_framing.hpp"
#include "render/scene_mesh.hpp"
#include "scenes/generate_scene.hpp"

using namespace fetic;
using namespace fetic::render;

namespace {

struct Solved {
  solver::Model model;
  solver::Snapshot final;
  RunExtent extent;
};

// Two pairs of plane struts, 64 x 16 elements each, in 4 x 2 subdomains.
const Solved& fine_planes() {
  static const Solved solved = [] {
    const scenes::GenerateOptions options{
        .pairs = 2, .elements = 64, .elements_across = 16, .subdomains = 4, .subdomains_across = 2};
    Solved s{solver::build_model(scenes::generate_scene(options)), {}, {}};
    const auto method = solver::make_method(solver::MethodKind::FetiC, s.model, {});
    FramePlan plan;
    plan.every_iteration = false;
    s.extent = survey(s.model, *method, plan);
    s.final = method->snapshot();
    return s;
  }();
  return solved;
}

SceneFraming framing_of(const Solved& solved, int width, int height) {
  View view;
  view.width = width;
  view.height = height;
  view.color_by = ColorBy::Stress;
  return frame_scene(solved.model, view, solved.extent, scene_region(view));
}

}  // namespace

TEST_CASE(
    "level of detail: a merged cell is the smallest power of two of elements that is a pixel") {
  CHECK(merge_stride(1.0, 64) == 1);
  CHECK(merge_stride(7.5, 64) == 1);
  CHECK(merge_stride(0.3, 64) == 4);     // 2 x 0.3 = 0.6 < 1 <= 4 x 0.3
  CHECK(merge_stride(0.5, 64) == 2);     // exactly a pixel
  CHECK(merge_stride(0.001, 20) == 20);  // never more than the piece: one cell
  CHECK(kept_nodes(3, 10, 4) == std::vector<int>{3, 7, 10});
  CHECK(kept_nodes(0, 8, 1).size() == 9);
  CHECK(kept_nodes(5, 5, 2) == std::vector<int>{5});
}

TEST_CASE("level of detail: the level follows the zoom in powers of two") {
  const Solved& s = fine_planes();
  const SceneFraming fitted = framing_of(s, 640, 360);
  const double base = mesh_detail(s.model, fitted, fitted).pixels_per_unit;
  CHECK(base == Approx(fitted.pixels_per_unit));
  for (const float zoom : {1.0f, 1.3f, 1.99f})
    CHECK(mesh_detail(s.model, fitted, zoomed(fitted, zoom, fitted.pixel_center)).pixels_per_unit ==
          Approx(base));
  CHECK(mesh_detail(s.model, fitted, zoomed(fitted, 2.0f, fitted.pixel_center)).pixels_per_unit ==
        Approx(2 * base));
  CHECK(mesh_detail(s.model, fitted, zoomed(fitted, 5.0f, fitted.pixel_center)).pixels_per_unit ==
        Approx(4 * base));
  CHECK(mesh_detail(s.model, fitted, zoomed(fitted, 0.7f, fitted.pixel_center)).pixels_per_unit ==
        Approx(0.5 * base));
  // Panning within a level: the same detail serves (the whole scene is within budget).
  const MeshDetail built = mesh_detail(s.model, fitted, fitted);
  const SceneFraming panned = zoomed(fitted, 1.5f, {fitted.pixel_center.x + 400, 0});
  CHECK(detail_serves(built, mesh_detail(s.model, fitted, panned), panned));
  const SceneFraming deeper = zoomed(fitted, 2.5f, fitted.pixel_center);
  CHECK_FALSE(detail_serves(built, mesh_detail(s.model, fitted, deeper), deeper));
}

TEST_CASE("level of detail: elements of a pixel or more are drawn as they are") {
  const Solved& s = fine_planes();
  const SceneFraming framing = framing_of(s, 1280, 720);
  const double element = s.model.struts[0].height / s.model.struts[0].ny;
  REQUIRE(element * framing.pixels_per_unit >= 1.0);  // the premise: no element below a pixel
  const SceneMesh full = build_scene_mesh(s.model, s.final, framing, ColorBy::Stress);
  const SceneMesh lod = build_scene_mesh(s.model, s.final, framing, ColorBy::Stress,
                                         mesh_detail(s.model, framing, framing));
  CHECK(lod.nodes.size() == full.nodes.size());
  CHECK(lod.element_count == full.element_count);
  REQUIRE(lod.vertices.size() == full.vertices.size());
  bool same = true;
  for (std::size_t v = 0; v < full.vertices.size(); ++v)
    same = same && lod.vertices[v].node_a == full.vertices[v].node_a &&
           lod.vertices[v].node_b == full.vertices[v].node_b &&
           lod.vertices[v].offset == full.vertices[v].offset &&
           lod.vertices[v].element == full.vertices[v].element;
  CHECK(same);
}

TEST_CASE("level of detail: merged cells carry the mean stress of the elements they cover") {
  const Solved& s = fine_planes();
  // An eighth of the scale at which no element is below a pixel: cells of 2 to 8 elements.
  const SceneFraming large = framing_of(s, 1280, 720);
  const SceneFraming framing = zoomed(large, 0.125f, large.pixel_center);
  const MeshDetail detail = mesh_detail(s.model, framing, framing);
  const SceneMesh mesh = build_scene_mesh(s.model, s.final, framing, ColorBy::Stress, detail);
  const SceneMesh full = build_scene_mesh(s.model, s.final, framing, ColorBy::Stress);
  INFO("cells " << mesh.element_count << " of " << full.element_count << " elements");
  CHECK(mesh.element_count * 4 <= full.element_count);  // far fewer: elements are sub-pixel
  MeshValues values;
  fill_mesh_values(mesh, s.model, s.final, framing, values);
  const auto stresses = piece_stresses(s.model, s.final);
  // Each cell's reference corners (from its first quad) against each element's centre.
  int cells_checked = 0;
  for (std::int32_t v = mesh.plane_fills.first; v < mesh.plane_fills.first + mesh.plane_fills.count;
       v += 6) {
    const MeshVertex& corner0 = mesh.vertices[static_cast<std::size_t>(v)];
    const MeshVertex& corner2 = mesh.vertices[static_cast<std::size_t>(v + 2)];
    const auto& a = mesh.nodes[static_cast<std::size_t>(corner0.node_a)];
    const auto& c = mesh.nodes[static_cast<std::size_t>(corner2.node_a)];
    const double x0 = std::min(a[0], c[0]), x1 = std::max(a[0], c[0]);
    const double y0 = std::min(a[1], c[1]), y1 = std::max(a[1], c[1]);
    // The piece the cell belongs to: the last whose first element row is at most its own.
    std::size_t p = 0;
    while (p + 1 < mesh.first_element.size() && mesh.first_element[p + 1] <= corner0.element)
      ++p;
    const solver::Piece& piece = s.final.pieces[p];
    const solver::StrutMesh& strut = s.model.struts[static_cast<std::size_t>(piece.strut)];
    double sum = 0.0;
    int count = 0, e = 0;
    for (int i = piece.box.i0; i < piece.box.i1; ++i)
      for (int k = piece.box.k0; k < piece.box.k1; ++k, ++e) {
        const solver::Vec2 centre =
            0.25 * (strut.nodes[static_cast<std::size_t>(strut.node(i, k))] +
                    strut.nodes[static_cast<std::size_t>(strut.node(i + 1, k + 1))] +
                    strut.nodes[static_cast<std::size_t>(strut.node(i + 1, k))] +
                    strut.nodes[static_cast<std::size_t>(strut.node(i, k + 1))]) -
            mesh.origin;
        if (centre.x() > x0 && centre.x() < x1 && centre.y() > y0 && centre.y() < y1) {
          sum += stresses[p][static_cast<std::size_t>(e)];
          ++count;
        }
      }
    REQUIRE(count > 0);
    const double expected = sum / count / framing.stress_scale;
    CHECK(values.elements[static_cast<std::size_t>(corner0.element)][0] ==
          Approx(expected).margin(1e-5));
    ++cells_checked;
  }
  CHECK(cells_checked == mesh.element_count);
}

TEST_CASE("level of detail: beyond its budget a mesh keeps detail only near the view") {
  const Solved& s = fine_planes();
  const SceneFraming fitted = framing_of(s, 640, 360);
  // Zoomed 16x about the middle of the first strut: a small part of the scene is seen.
  View view;
  view.zoom = 16.0;
  view.centered = true;
  view.center_x = 0.5 * (s.model.struts[0].nodes.front().x() + s.model.struts[0].nodes.back().x());
  view.center_y = 0.5 * (s.model.struts[0].nodes.front().y() + s.model.struts[0].nodes.back().y());
  const SceneFraming placed = render::placed(fitted, view);
  const MeshDetail everywhere = mesh_detail(s.model, fitted, placed);
  CHECK(std::isinf(everywhere.keep.high.x()));
  const MeshDetail near = mesh_detail(s.model, fitted, placed, 100.0);
  INFO("fitted " << fitted.pixels_per_unit << " px/unit, level " << near.pixels_per_unit
                 << ", keep " << near.keep.low.transpose() << " .. " << near.keep.high.transpose());
  REQUIRE(std::isfinite(near.keep.high.x()));
  CHECK(near.keep.contains(visible_world(placed)));
  const SceneMesh kept = build_scene_mesh(s.model, s.final, fitted, ColorBy::Stress, near);
  const SceneMesh all = build_scene_mesh(s.model, s.final, fitted, ColorBy::Stress, everywhere);
  int single = 0;
  for (std::size_t p = 0; p < kept.merged.size(); ++p) {
    const solver::NodeBox& box = kept.layout[p].second;
    if (kept.merged[p] == std::array<int, 2>{box.i1 - box.i0, box.k1 - box.k0}) ++single;
  }
  CHECK(single > 0);                                     // pieces away from the view: one cell each
  CHECK(single < static_cast<int>(kept.merged.size()));  // the one in view is not
  CHECK(kept.element_count < all.element_count);
  // Panning within the margin keeps it; beyond, the mesh is built again.
  const auto pan = [&](float dx) {
    return zoomed(fitted, 16.0f, {placed.pixel_center.x + dx, placed.pixel_center.y});
  };
  CHECK(detail_serves(near, mesh_detail(s.model, fitted, pan(20.0f), 100.0), pan(20.0f)));
  CHECK_FALSE(detail_serves(near, mesh_detail(s.model, fitted, pan(400.0f), 100.0), pan(400.0f)));
}
