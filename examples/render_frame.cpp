// Example 3: one frame of a scene rendered to a PNG file.
//
// `fetic render` runs the same deterministic solve twice: a survey fixes the scales
// (magnification, colours), then each frame is composed (mesh, glyphs, overlay) and
// drawn by OpenGL offscreen. Here the plan has one frame: the final state of a FETI-C
// solve. The GL context is headless EGL (Mesa's software rasterizer will do); without
// one the program says so and exits with 77, which ctest reports as skipped.

#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include "render/colormap.hpp"
#include "render/egl_context.hpp"
#include "render/font.hpp"
#include "render/frame_composer.hpp"
#include "render/gl_renderer.hpp"
#include "render/png_writer.hpp"
#include "scenes/load_scene.hpp"
#include "solver/method.hpp"

using namespace fetic;

int main(int argc, char** argv) {
  const std::string scene = argc > 1 ? argv[1] : FETIC_EXAMPLE_SCENES "/thesis.toml";
  const std::string png = argc > 2 ? argv[2] : "render_frame.png";
  const solver::Model model = solver::build_model(scenes::load_scene_file(scene));
  auto method = solver::make_method(solver::MethodKind::FetiC, model, solver::SolveOptions{});

  render::FramePlan plan;  // load factor 1, its final state only
  plan.every_iteration = false;
  const render::RunExtent extent = render::survey(model, *method, plan);

  std::unique_ptr<render::GlContext> context;
  try {
    context = render::make_egl_context();
  } catch (const render::NoDisplayError& error) {
    std::printf("skipped: no headless GL here (%s)\n", error.what());
    return 77;
  }
  render::View view;  // 1280x720, the magnification chosen from the run
  render::FontAtlas font(render::base_text_size(view.width, view.height) * 1.3f);
  render::GlRenderer renderer(*context, font);
  const render::FrameComposer composer(model, view, extent, {"thesis scene", "feti-c", {}, {}});

  // The render pass: the same run again; the one frame it visits is drawn and encoded.
  render::run_frames(*method, plan, [&](const render::Frame& frame) {
    const render::Image image = renderer.render(
        view.width, view.height, composer.compose(frame).layers(), render::palette::background);
    const render::PngBytes bytes = render::encode_png(image);
    std::ofstream(png, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<long>(bytes.size()));
    std::printf("%s: %dx%d, iteration %d, %zu bytes\n", png.c_str(), view.width, view.height,
                frame.snapshot.iteration, bytes.size());
    return true;
  });
  return 0;
}
