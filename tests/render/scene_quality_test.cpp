// What a picture must get right beyond looking like its golden, measured in its pixels
// (headless EGL, no multisampling, so that every pixel has exactly one colour):
// * no glyph hides the struts: drawn once with every strut in a colour of its own and once
//   more with all glyphs over them, no strut loses more than kMaxCoveredShare of its
//   pixels - on the thesis scene, a dense bar scene (2,000 pairs) and a plane scene of
//   100,000 unknowns, with strut labels on;
// * clamped ends are drawn on their walls: a clamped end's drawn position is its
//   reference position, the strut's last pixel is right there and the wall's first pixel
//   a line width beyond, and every wall of a column of clamped ends is straight;
// * the GPU draws the scene mesh exactly as expand_mesh() computes it on the CPU.

#include <catch2/catch.hpp>

#include <algorithm>
#include <map>

#include "render/colormap.hpp"
#include "render/frame_composer.hpp"
#include "render/scene_drawing.hpp"
#include "render/scene_mesh.hpp"
#include "scenes/generate_scene.hpp"
#include "scenes/load_scene.hpp"
#include "tests/render/golden.hpp"

using namespace fetic;
using namespace fetic::render;

namespace {

// A strut may lose at most this share of its pixels to glyphs (rings, force discs, contact
// marks, load arrows, labels, walls).
constexpr double kMaxCoveredShare = 0.10;

struct Solved {
  solver::Model model;
  solver::Snapshot final;
  RunExtent extent;
};

Solved solve(const scenes::Scene& scene, solver::MethodKind kind) {
  Solved solved{solver::build_model(scene), {}, {}};
  const auto method = solver::make_method(kind, solved.model, {});
  FramePlan plan;
  plan.every_iteration = false;
  solved.extent = survey(solved.model, *method, plan);
  solved.final = method->snapshot();
  return solved;
}

scenes::Scene bundled(const std::string& name) {
  return scenes::load_scene_file(std::string(FETIC_BUNDLED_SCENES_DIR) + "/" + name);
}

scenes::Scene dense_bars() {
  return scenes::generate_scene(
      {.model = scenes::ModelKind::Bar, .pairs = 2000, .elements = 4, .subdomains = 2});
}

scenes::Scene plane_100k() {
  return scenes::generate_scene({.model = scenes::ModelKind::Plane,
                                 .pairs = 10,
                                 .elements = 100,
                                 .elements_across = 24,
                                 .subdomains = 5,
                                 .subdomains_across = 1});
}

Color id_color(int strut) {
  const int id = strut + 1;
  return {static_cast<std::uint8_t>(id & 0xff), static_cast<std::uint8_t>((id >> 8) & 0xff),
          static_cast<std::uint8_t>((id >> 16) & 0xff), 255};
}

int id_of(const std::uint8_t* pixel) {
  return (pixel[0] | (pixel[1] << 8) | (pixel[2] << 16)) - 1;
}

// The strut a node row belongs to.
int strut_of_row(const SceneMesh& mesh, int row) {
  const auto it = std::upper_bound(mesh.first_node.begin(), mesh.first_node.end(), row);
  return mesh.layout[static_cast<std::size_t>(it - mesh.first_node.begin() - 1)].first;
}

// The mesh with every strut in its own colour (rims and outlines included).
SceneMesh id_mesh(const Solved& solved, const SceneFraming& framing) {
  SceneMesh mesh = build_scene_mesh(solved.model, solved.final, framing, ColorBy::Strut);
  for (MeshVertex& v : mesh.vertices) {
    v.color = id_color(strut_of_row(mesh, v.node_a));
    v.element = -1;
  }
  return mesh;
}

// Every glyph in one colour, text included.
DrawList keyed(const DrawList& glyphs, Color key) {
  DrawList out;
  const auto& v = glyphs.vertices();
  for (std::size_t i = 0; i + 2 < v.size(); i += 3)
    out.triangle({v[i].position, key}, {v[i + 1].position, key}, {v[i + 2].position, key});
  for (TextItem text : glyphs.texts()) {
    text.color = key;
    out.text(text);
  }
  return out;
}

struct Coverage {
  double worst = 0.0;  // largest share of a strut's pixels covered by glyphs
  int strut = -1;
  int struts_seen = 0;
};

Coverage glyph_coverage(const Solved& solved, const View& view) {
  const SceneFraming framing = frame_scene(solved.model, view, solved.extent, scene_region(view));
  const SceneMesh mesh = id_mesh(solved, framing);
  MeshValues values;
  fill_mesh_values(mesh, solved.model, solved.final, framing, values);
  MeshUniforms uniforms = mesh_uniforms(mesh, framing);
  const DrawList glyphs = keyed(
      draw_glyphs(solved.model, solved.final, view, framing, {"method", {}}), {255, 0, 255, 255});
  GlRenderer& renderer = fetic::testing::test_renderer();
  renderer.set_samples(1);
  const Color white{255, 255, 255, 255};
  const Image struts =
      renderer.render(view.width, view.height, {Layer(&mesh, &values, uniforms)}, white);
  const Image both = renderer.render(view.width, view.height,
                                     {Layer(&mesh, &values, uniforms), Layer(&glyphs)}, white);
  renderer.set_samples(4);
  std::map<int, std::pair<int, int>> count;  // strut: (pixels, covered)
  for (std::size_t i = 0; i < struts.rgba.size(); i += 4) {
    const std::uint8_t* a = struts.rgba.data() + i;
    if (a[0] == 255 && a[1] == 255 && a[2] == 255) continue;
    const int id = id_of(a);
    auto& [pixels, covered] = count[id];
    ++pixels;
    if (!std::equal(a, a + 3, both.rgba.data() + i)) ++covered;
  }
  Coverage result;
  for (const auto& [id, c] : count) {
    ++result.struts_seen;
    const double share = static_cast<double>(c.second) / c.first;
    if (share > result.worst) {
      result.worst = share;
      result.strut = id;
    }
  }
  return result;
}

View view_of(int width, int height) {
  View view;
  view.width = width;
  view.height = height;
  return view;
}

// The final state drawn at 480x320 with `color`: the scene mesh placed by the GPU (the
// frame's layers) and expanded on the CPU (flattened) give the same picture.
void check_gpu_draws_as_cpu(const Solved& solved, ColorBy color) {
  View view = view_of(480, 320);
  view.color_by = color;
  const FrameComposer composer(solved.model, view, solved.extent, {"t", "m", "", ""});
  std::vector<solver::HistoryEntry> history;
  const ComposedFrame frame = composer.compose(Frame{0, 0, solved.final, history});
  GlRenderer& renderer = fetic::testing::test_renderer();
  const Image gpu = renderer.render(view.width, view.height, frame.layers(), palette::background);
  const DrawList cpu = frame.flattened();
  const Image expanded = renderer.render(view.width, view.height, {&cpu}, palette::background);
  const fetic::testing::Comparison same = fetic::testing::compare(gpu, expanded);
  INFO(same.differing << " pixels differ, by up to " << same.largest);
  CHECK(same.fraction <= 0.001);
}

}  // namespace

TEST_CASE("no glyph hides more than a tenth of any strut") {
  SECTION("the thesis scene, 1280x720, labels on") {
    View view = view_of(1280, 720);
    view.show_labels = true;
    const Coverage c =
        glyph_coverage(solve(bundled("thesis.toml"), solver::MethodKind::ActiveSet), view);
    INFO("strut " << c.strut << ": " << 100.0 * c.worst << "% covered");
    CHECK(c.struts_seen == 100);
    CHECK(c.worst <= kMaxCoveredShare);
  }
  SECTION("the thesis scene, 400x300 (thin bars, no room for rings)") {
    const Coverage c = glyph_coverage(solve(bundled("thesis.toml"), solver::MethodKind::ActiveSet),
                                      view_of(400, 300));
    INFO("strut " << c.strut << ": " << 100.0 * c.worst << "% covered");
    CHECK(c.worst <= kMaxCoveredShare);
  }
  SECTION("2,000 pairs of bars, 1280x720") {
    const Coverage c =
        glyph_coverage(solve(dense_bars(), solver::MethodKind::FetiC), view_of(1280, 720));
    INFO("strut " << c.strut << ": " << 100.0 * c.worst << "% covered");
    CHECK(c.struts_seen > 100);
    CHECK(c.worst <= kMaxCoveredShare);
  }
  SECTION("a plane scene of 100,000 unknowns, 1280x720, stress colours") {
    View view = view_of(1280, 720);
    view.color_by = ColorBy::Stress;
    view.show_labels = true;
    const Coverage c = glyph_coverage(solve(plane_100k(), solver::MethodKind::FetiC), view);
    INFO("strut " << c.strut << ": " << 100.0 * c.worst << "% covered");
    CHECK(c.struts_seen == 20);
    CHECK(c.worst <= kMaxCoveredShare);
  }
}

TEST_CASE("clamped ends are drawn on their walls, the walls where the supports are") {
  const Solved solved = solve(bundled("thesis.toml"), solver::MethodKind::ActiveSet);
  const View view = view_of(1280, 720);
  const SceneFraming framing = frame_scene(solved.model, view, solved.extent, scene_region(view));
  REQUIRE(framing.gaps_magnified);  // gaps drawn magnified: the struts make room, not the walls
  const SceneMesh mesh = id_mesh(solved, framing);
  MeshValues values;
  fill_mesh_values(mesh, solved.model, solved.final, framing, values);
  View glyphs_only = view;
  glyphs_only.show_loads = glyphs_only.show_gaps = glyphs_only.show_contacts =
      glyphs_only.show_forces = glyphs_only.show_legend = glyphs_only.show_scale = false;
  const DrawList walls = draw_glyphs(solved.model, solved.final, glyphs_only, framing, {});
  GlRenderer& renderer = fetic::testing::test_renderer();
  renderer.set_samples(1);
  const Image image = renderer.render(
      view.width, view.height, {Layer(&mesh, &values, mesh_uniforms(mesh, framing)), Layer(&walls)},
      {255, 255, 255, 255});
  renderer.set_samples(4);
  const auto pixel = [&](Point p) {
    return image.pixel(static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y)));
  };
  std::vector<float> right_walls;
  int checked = 0;
  for (std::size_t s = 0; s < solved.model.struts.size(); ++s) {
    const solver::StrutMesh& strut = solved.model.struts[s];
    const auto displacements = solver::strut_displacements(solved.model, solved.final);
    for (const bool at_to : {false, true}) {
      const int node = at_to ? strut.nx : 0;
      const auto& clamped = solved.model.clamped_nodes[s];
      if (!std::binary_search(clamped.begin(), clamped.end(), node)) continue;
      // Drawn where it is: the reference position, whatever the magnification and the gaps.
      const Point drawn = framing.node(solved.model, static_cast<int>(s), node,
                                       displacements[s][static_cast<std::size_t>(node)]);
      const Point reference = framing.to_pixel(strut.nodes[static_cast<std::size_t>(node)]);
      CHECK(length(drawn - reference) < 0.01f);
      // The strut's colour just inside the end, the wall's a line width or two outside.
      const Point outward = framing.direction(at_to ? strut.e1 : solver::Vec2(-strut.e1));
      const std::uint8_t* inside = pixel(drawn - 1.5f * outward);
      CHECK(id_of(inside) == static_cast<int>(s));
      bool wall = false;
      for (float d = 1.0f; d <= 2.0f + 3.0f * framing.line_width; d += 0.5f) {
        const std::uint8_t* out = pixel(drawn + d * outward);
        wall = wall || (out[0] == palette::wall.r && out[1] == palette::wall.g &&
                        out[2] == palette::wall.b);
      }
      CHECK(wall);
      if (at_to) right_walls.push_back(drawn.x);
      ++checked;
    }
  }
  CHECK(checked == 100);
  // The thesis' right struts all end at x = 2: one straight wall, not a slanted one.
  REQUIRE(right_walls.size() == 50);
  const auto [low, high] = std::minmax_element(right_walls.begin(), right_walls.end());
  CHECK(*high - *low < 0.01f);
}

TEST_CASE("the GPU draws the scene mesh where the CPU puts it") {
  const Solved solved = solve(bundled("plane_pair.toml"), solver::MethodKind::FetiC);
  for (const ColorBy color : {ColorBy::Subdomain, ColorBy::Stress})
    check_gpu_draws_as_cpu(solved, color);
}

TEST_CASE("moment colours: a cantilever is coloured most strongly at its clamped end") {
  // Clamped at x = 0, pushed down at its tip x = L: it hogs, M = -P (L - x), so the colour
  // runs from the map's blue end (-|M|max) at the wall to its neutral middle at the tip.
  const std::string text =
      "model = \"frame\"\n[[strut]]\nname = \"C\"\nfrom = [0.0, 0.0]\nto = [2.0, 0.0]\n"
      "E = 2.1e11\narea = 2.0e-3\ninertia = 3.0e-6\nelements = 6\nsubdomains = 2\n"
      "fixed = [\"from\"]\n[[load]]\nstrut = \"C\"\nat = \"to\"\nforce = [0.0, -40.0]\n";
  const Solved solved =
      solve(scenes::parse_scene(text, "cantilever.toml"), solver::MethodKind::ActiveSet);
  REQUIRE(solved.extent.largest_moment == Approx(40.0 * 2.0).epsilon(1e-9));
  View view = view_of(480, 240);
  // Unmagnified, the tip moves 0.5 mm: a straight strut on screen, its axis one pixel row.
  view.magnification = 1.0;
  view.color_by = ColorBy::Moment;
  const SceneFraming framing = frame_scene(solved.model, view, solved.extent, scene_region(view));
  const SceneMesh mesh = build_scene_mesh(solved.model, solved.final, framing, ColorBy::Moment);
  MeshValues values;
  fill_mesh_values(mesh, solved.model, solved.final, framing, values);
  GlRenderer& renderer = fetic::testing::test_renderer();
  renderer.set_samples(1);
  const Image image =
      renderer.render(view.width, view.height,
                      {Layer(&mesh, &values, mesh_uniforms(mesh, framing))}, {255, 255, 255, 255});
  renderer.set_samples(4);
  const solver::StrutMesh& strut = solved.model.struts[0];
  const Point wall = framing.to_pixel(strut.nodes.front()),
              tip = framing.to_pixel(strut.nodes.back());
  // How far a colour is from the map's neutral middle (zero moment).
  const Color zero = diverging(0.0);
  const auto strength = [&](const std::uint8_t* p) {
    return std::abs(p[0] - zero.r) + std::abs(p[1] - zero.g) + std::abs(p[2] - zero.b);
  };
  const auto near = [](const std::uint8_t* p, Color c) {
    return std::abs(p[0] - c.r) <= 10 && std::abs(p[1] - c.g) <= 10 && std::abs(p[2] - c.b) <= 10;
  };
  constexpr int kSamples = 50;
  std::vector<int> strengths;
  for (int j = 0; j < kSamples; ++j) {
    const float s = 0.02f + 0.96f * j / (kSamples - 1);  // clear of the rim at both ends
    const Point p = wall + s * (tip - wall);
    const std::uint8_t* pixel =
        image.pixel(static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y)));
    INFO("at " << s << " of the length: " << int(pixel[0]) << " " << int(pixel[1]) << " "
               << int(pixel[2]));
    // Linear along the strut: the colour of M / |M|max = -(1 - s).
    CHECK(near(pixel, diverging(-(1.0 - s))));
    strengths.push_back(strength(pixel));
  }
  // The strongest colour at the wall, and never stronger further from it.
  CHECK(std::max_element(strengths.begin(), strengths.end()) == strengths.begin());
  for (int j = 1; j < kSamples; ++j)
    CHECK(strengths[static_cast<std::size_t>(j)] <= strengths[static_cast<std::size_t>(j - 1)] + 2);
}

TEST_CASE("the GPU colours beams by moment as the CPU does") {
  const Solved solved = solve(bundled("frame_portal_sway.toml"), solver::MethodKind::ActiveSet);
  REQUIRE(solved.extent.largest_moment > 0.0);
  check_gpu_draws_as_cpu(solved, ColorBy::Moment);
}

// Issue 26 item 2: in the window (which sets View::min_text_size so that its smallest
// text, 0.68 of the base size, is 11 px at UI scale 1: app/gui/picture.cpp) no text of
// the picture - caption, legends with their scale notes, overlay plots, chart - is drawn
// smaller than 11 px, at the picture sizes of 1280x800, 1366x768 and a small window.
TEST_CASE("the window's picture has no text under 11 pixels") {
  const float smallest = 11.0f;
  for (const char* name : {"thesis.toml", "frame_portal_sway.toml", "plane_pair.toml"}) {
    const Solved solved = solve(bundled(name), solver::MethodKind::ActiveSet);
    for (const auto& [width, height] : {std::pair{950, 800}, {1036, 740}, {560, 480}}) {
      View view = view_of(width, height);
      view.min_text_size = std::ceil(smallest / 0.68f);
      view.show_overlay = true;
      view.show_chart = true;
      view.color_by = ColorBy::Stress;
      view.scale_basis = "over loads 0-2";
      const FrameComposer composer(solved.model, view, solved.extent,
                                   {"feti-c (dirichlet)", "a scene with a long title", "", ""});
      std::vector<solver::HistoryEntry> history;
      const ComposedFrame frame = composer.compose(Frame{0, 0, solved.final, history});
      for (const DrawList* list : {&frame.glyphs, &frame.overlay, &frame.chart})
        for (const TextItem& text : list->texts()) {
          INFO(name << " at " << width << "x" << height << ": '" << text.text << "'");
          CHECK(text.size >= smallest);
        }
    }
  }
}
