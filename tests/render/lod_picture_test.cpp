// Level of detail against the full picture (headless EGL): a plane scene whose elements
// are below a pixel, drawn with merged cells (render/mesh_detail.hpp) at a small size,
// and drawn with every element at 8x that size and box-filtered down to the small one -
// which is what the screen would show if it had the pixels. The two must agree within
// kMeanTolerance (mean of the largest channel difference per pixel, of 255) and
// kFarTolerance (share of pixels off by more than kFarLevels), both over the pixels where
// either shows a strut, by subdomain and by stress.
// A control shows the measure is not blind: the same comparison against the unloaded
// state of the same scene fails it by a wide margin.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>

#include "render/frame_sequence.hpp"
#include "render/mesh_detail.hpp"
#include "render/overlay.hpp"
#include "render/scene_framing.hpp"
#include "render/scene_mesh.hpp"
#include "scenes/generate_scene.hpp"
#include "tests/render/golden.hpp"

using namespace fetic;
using namespace fetic::render;

namespace {

constexpr int kWidth = 240, kHeight = 135, kScale = 8;
// Measured: 8.1 (subdomain) and 9.4 (stress) levels, 0% and 0.12% far; the control 19.3
// and 22.2 levels, 13% and 15% far. The mean is mostly anti-aliased edges (4 samples per
// pixel against 64 averaged); the far share is what tells a wrong picture.
constexpr double kMeanTolerance = 12.0;
constexpr int kFarLevels = 48;
constexpr double kFarTolerance = 0.01;

struct Difference {
  double mean = 0.0;  // largest channel difference per pixel, averaged
  double far = 0.0;   // share of pixels with one over kFarLevels
};

// Box filter: each kScale x kScale block of `big` averaged into one pixel.
Image downsampled(const Image& big) {
  Image small;
  small.width = big.width / kScale;
  small.height = big.height / kScale;
  small.rgba.assign(static_cast<std::size_t>(small.width * small.height) * 4, 255);
  for (int y = 0; y < small.height; ++y)
    for (int x = 0; x < small.width; ++x)
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int dy = 0; dy < kScale; ++dy)
          for (int dx = 0; dx < kScale; ++dx)
            sum += big.pixel(x * kScale + dx, y * kScale + dy)[c];
        small.rgba[(static_cast<std::size_t>(y * small.width + x)) * 4 + c] =
            static_cast<std::uint8_t>((sum + kScale * kScale / 2) / (kScale * kScale));
      }
  return small;
}

// Over the pixels where either picture shows something (not the white background).
Difference difference(const Image& a, const Image& b) {
  Difference d;
  long far = 0, pixels = 0;
  double sum = 0.0;
  const auto white = [](const std::uint8_t* p) {
    return p[0] == 255 && p[1] == 255 && p[2] == 255;
  };
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (white(a.pixel(x, y)) && white(b.pixel(x, y))) continue;
      ++pixels;
      int largest = 0;
      for (int c = 0; c < 3; ++c)
        largest = std::max(largest, std::abs(a.pixel(x, y)[c] - b.pixel(x, y)[c]));
      sum += largest;
      if (largest > kFarLevels) ++far;
    }
  d.mean = pixels > 0 ? sum / static_cast<double>(pixels) : 0.0;
  d.far = pixels > 0 ? static_cast<double>(far) / static_cast<double>(pixels) : 0.0;
  return d;
}

struct Scene {
  solver::Model model;
  solver::Snapshot initial, final;
  RunExtent extent;
};

// Three pairs of plane struts of 192 x 40 elements in 4 x 2 subdomains (61,000 unknowns).
const Scene& fine_scene() {
  static const Scene scene = [] {
    const scenes::GenerateOptions options{.pairs = 3,
                                          .elements = 192,
                                          .elements_across = 40,
                                          .subdomains = 4,
                                          .subdomains_across = 2};
    Scene s{solver::build_model(scenes::generate_scene(options)), {}, {}, {}};
    const auto method = solver::make_method(solver::MethodKind::FetiC, s.model, {});
    FramePlan plan;
    plan.every_iteration = false;
    s.extent = survey(s.model, *method, plan);
    s.final = method->snapshot();
    method->start(0.0);
    s.initial = method->snapshot();
    return s;
  }();
  return scene;
}

// The mesh layer alone: at kWidth x kHeight with merged cells, or with every element at
// kScale times the size (scales, widths and centre scaled alike), filtered down.
Image picture(const Scene& s, const solver::Snapshot& state, ColorBy color, bool full) {
  View view;
  view.width = kWidth;
  view.height = kHeight;
  view.color_by = color;
  const SceneFraming framing = frame_scene(s.model, view, s.extent, scene_region(view));
  const MeshDetail detail = full ? MeshDetail{} : mesh_detail(s.model, framing, framing);
  const SceneMesh mesh = build_scene_mesh(s.model, state, framing, color, detail);
  if (!full) {
    int merged = 0;
    for (const auto& m : mesh.merged)
      merged += m != std::array<int, 2>{1, 1};
    REQUIRE(merged == static_cast<int>(mesh.merged.size()));  // the premise: all merged
  }
  MeshValues values;
  fill_mesh_values(mesh, s.model, state, framing, values);
  MeshUniforms u = mesh_uniforms(mesh, framing);
  const int scale = full ? kScale : 1;
  u.pixels_per_unit *= static_cast<float>(scale);
  u.pixel_center = {u.pixel_center[0] * scale, u.pixel_center[1] * scale};
  u.half_bar_width *= static_cast<float>(scale);
  u.line_width *= static_cast<float>(scale);
  u.mesh_lines = false;  // lines are drawn only from 6 pixels per element: not at the small size
  GlRenderer& renderer = fetic::testing::test_renderer();
  const Image image = renderer.render(kWidth * scale, kHeight * scale, {Layer(&mesh, &values, u)},
                                      {255, 255, 255, 255});
  return full ? downsampled(image) : image;
}

}  // namespace

TEST_CASE("level of detail: merged cells draw what every element drawn finer and filtered shows") {
  const Scene& s = fine_scene();
  for (const ColorBy color : {ColorBy::Subdomain, ColorBy::Stress}) {
    const Image lod = picture(s, s.final, color, false);
    const Image reference = picture(s, s.final, color, true);
    const Difference d = difference(lod, reference);
    INFO((color == ColorBy::Stress ? "stress" : "subdomain")
         << ": mean " << d.mean << " levels, " << 100.0 * d.far << "% of pixels beyond "
         << kFarLevels);
    CHECK(d.mean <= kMeanTolerance);
    CHECK(d.far <= kFarTolerance);
    // The control: the unloaded state drawn with merged cells is far from it.
    const Difference control = difference(picture(s, s.initial, color, false), reference);
    INFO("control: mean " << control.mean << " levels, " << 100.0 * control.far << "%");
    CHECK(control.mean > kMeanTolerance);
    CHECK(control.far > 5.0 * kFarTolerance);
  }
}
