// fetic gui --bench-view N: pans, then zooms, the picture of the solved scene as a
// pointer would, one step a frame, and measures the frame rate (see bench.hpp).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/gui/app.hpp"
#include "render/glfw_window.hpp"
#include "render/scene_mesh.hpp"

namespace fetic::app::gui {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Zoom steps per frame while zooming: 1.1x, 36 steps in (about 31x), 36 out, repeated.
constexpr float kZoomStep = 1.1f;
constexpr int kZoomRun = 36;

}  // namespace

void App::view_bench_step() {
  ViewBench& b = view_bench_;
  const auto now = Clock::now();
  if (b.phase == -1) {
    if (!solved_on_screen_ || worker_.busy()) return;
    b.phase = 0;
    b.start = b.last = now;
    b.mesh_builds = mesh_builds_;
  } else {
    b.frame_ms[b.phase].push_back(std::chrono::duration<double, std::milli>(now - b.last).count());
    ++b.frames[b.phase];
    b.last = now;
  }
  if (b.phase == 2) return;
  const int half = std::max(1, args_.bench_view / 2);
  if (b.frame == half || b.frame == 2 * half) {
    b.seconds[b.phase] = std::chrono::duration<double>(now - b.start).count();
    b.start = now;
    ++b.phase;
    if (b.phase == 2) {
      b.mesh_builds = mesh_builds_ - b.mesh_builds;
      quit_ = true;
      return;
    }
  }
  if (b.phase == 0) {
    // Sideways and up and down by 6 pixels a frame, turning every 40 frames.
    const int leg = (b.frame / 40) % 4;
    pan_.x += leg == 0 ? 6.0f : leg == 2 ? -6.0f : 0.0f;
    pan_.y += leg == 1 ? 6.0f : leg == 3 ? -6.0f : 0.0f;
  } else {
    // About the middle of the view: in for kZoomRun steps, then out again.
    const int step = b.frame - half;
    const float factor = (step / kZoomRun) % 2 ? 1.0f / kZoomStep : kZoomStep;
    const float cx = base_center_.x + pan_.x, cy = base_center_.y + pan_.y;
    const float mx = 0.5f * static_cast<float>(view_width_),
                my = 0.5f * static_cast<float>(view_height_);
    pan_.x = mx - (mx - cx) * factor - base_center_.x;
    pan_.y = my - (my - cy) * factor - base_center_.y;
    zoom_ *= factor;
  }
  ++b.frame;
  redraw_ = true;
  view_moved_ = now;
}

void App::print_view_bench(const render::GlfwWindow& window) const {
  const ViewBench& b = view_bench_;
  std::printf("scene          %s (%zu struts, %lld unknowns)\n", args_.scene.c_str(),
              target_.model->struts.size(), static_cast<long long>(target_.model->dof_count()));
  std::printf("renderer       %s, window %dx%d\n", window.description().c_str(),
              view_width_ + static_cast<int>(panel_width()), view_height_);
  const char* names[2] = {"panning", "zooming"};
  for (int p = 0; p < 2; ++p) {
    const double s = b.seconds[p];
    std::printf(
        "%-14s %d frames in %.2f s: %.1f frames/s, %.1f pictures/s (frame time median %.2f ms, "
        "max %.2f ms)\n",
        names[p], b.frames[p], s, s > 0 ? b.frames[p] / s : 0.0, s > 0 ? b.pictures[p] / s : 0.0,
        median(b.frame_ms[p]),
        b.frame_ms[p].empty() ? 0.0
                              : *std::max_element(b.frame_ms[p].begin(), b.frame_ms[p].end()));
  }
  const auto spread = [](const std::vector<double>& ms) {
    char text[64];
    std::snprintf(text, sizeof text, "%.2f ms (max %.2f)", median(ms),
                  ms.empty() ? 0.0 : *std::max_element(ms.begin(), ms.end()));
    return std::string(text);
  };
  std::printf("per picture    median %s: mesh and its values %s, draw lists %s, the rest GL\n",
              spread(b.picture_ms).c_str(), spread(b.mesh_ms).c_str(), spread(b.lists_ms).c_str());
  std::printf(
      "mesh           built %d times while panning and zooming (levels of detail); the last: %zu "
      "vertices, %d cells\n",
      b.mesh_builds, fine_mesh_.mesh ? fine_mesh_.mesh->vertices.size() : std::size_t{0},
      fine_mesh_.mesh ? fine_mesh_.mesh->element_count : 0);
}

}  // namespace fetic::app::gui
