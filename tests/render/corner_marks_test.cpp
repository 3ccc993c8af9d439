// `fetic render --corners`: FETI-DP's primal corners are marked where solver/corners.hpp
// puts them - checked in the pixels of the whole frame (headless EGL, no multisampling)
// against the corner positions worked out by hand for a strut of 4x2 boxes.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>

#include "render/colormap.hpp"
#include "render/corner_marks.hpp"
#include "render/frame_composer.hpp"
#include "render/frame_sequence.hpp"
#include "render/overlay.hpp"
#include "render/scene_framing.hpp"
#include "scenes/load_scene.hpp"
#include "solver/method.hpp"
#include "tests/render/golden.hpp"

using namespace fetic;
using namespace fetic::render;

namespace {

// One clamped plane strut of 16x4 elements in 4x2 boxes, unloaded (so drawn in place).
constexpr const char* kCornerStrut = R"(
model = "plane"
[[strut]]
name = "a"
from = [0.0, 0.0]
to = [1.0, 0.0]
E = 2.1e11
nu = 0.3
thickness = 0.01
height = 0.1
elements = 16
elements_across = 4
subdomains = 4
subdomains_across = 2
fixed = ["from"]
)";

bool amber(const Image& image, int x, int y) {
  const std::uint8_t* p = image.rgba.data() + 4 * (static_cast<std::size_t>(y) * image.width + x);
  return std::abs(p[0] - kCornerMark.r) <= 24 && std::abs(p[1] - kCornerMark.g) <= 24 &&
         std::abs(p[2] - kCornerMark.b) <= 24;
}

}  // namespace

TEST_CASE("render --corners: a mark at every FETI-DP corner and nowhere else") {
  const solver::Model model = solver::build_model(scenes::parse_scene(kCornerStrut, "a.toml"));
  const auto method = solver::make_method(solver::MethodKind::FetiDp, model, {});
  FramePlan plan;
  plan.every_iteration = false;
  const RunExtent extent = survey(model, *method, plan);
  const solver::Snapshot final = method->snapshot();

  View view;
  view.width = 640;
  view.height = 360;
  view.show_overlay = false;
  view.show_legend = false;
  view.show_scale = false;
  // The interface lines x = 0.25, 0.5, 0.75 at their ends and the middle line y = 0, and
  // the middle line's ends on the end faces: 3 x 3 + 2 corners.
  const SceneFraming framing = frame_scene(model, view, extent, scene_region(view));
  std::vector<Point> expected;
  for (double x : {0.25, 0.5, 0.75})
    for (double y : {-0.05, 0.0, 0.05})
      expected.push_back(framing.to_pixel({x, y}));
  expected.push_back(framing.to_pixel({0.0, 0.0}));
  expected.push_back(framing.to_pixel({1.0, 0.0}));
  REQUIRE(corner_points(model, final, framing).size() == expected.size());

  GlRenderer& renderer = fetic::testing::test_renderer();
  renderer.set_samples(1);
  std::vector<solver::HistoryEntry> history;
  for (bool marked : {false, true}) {
    view.show_corners = marked;
    const FrameComposer composer(model, view, extent, {"t", "m", "", ""});
    const ComposedFrame frame = composer.compose(Frame{0, 0, final, history});
    const Image image =
        renderer.render(view.width, view.height, frame.layers(), palette::background);
    INFO((marked ? "with" : "without") << " --corners");
    for (const Point& p : expected)
      CHECK(amber(image, static_cast<int>(p.x), static_cast<int>(p.y)) == marked);
    // Every amber pixel lies on the mark of an expected corner.
    const float reach = corner_mark_radius(framing) + 2.0f;
    int stray = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        if (!amber(image, x, y)) continue;
        bool near = false;
        for (const Point& p : expected)
          near = near || std::hypot(x + 0.5f - p.x, y + 0.5f - p.y) <= reach;
        stray += near ? 0 : 1;
      }
    CHECK(stray == 0);
  }
  renderer.set_samples(4);
}
