// fetic gui --bench N: drives the window like a user dragging the slider, then makes
// isolated load changes, each waiting for its converged frame (see bench.hpp).

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "app/gui/app.hpp"
#include "render/glfw_window.hpp"

namespace fetic::app::gui {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

void App::bench_step(double /*now*/) {
  BenchMeasurement& b = bench_;
  const auto now = Clock::now();
  if (b.phase == -1) {
    if (solved_on_screen_ && !worker_.busy()) b.phase = 0;  // set up and first solve done
    return;
  }
  if (b.phase == 0) {
    // A drag at a pointer's pace: a new load factor every 1/60 s, 0 .. maximum; frames
    // run as fast as they can in between (no vsync in the benchmark).
    if (b.drag_frames == 0) {
      b.drag_start = now;
    } else {
      b.frame_ms.push_back(std::chrono::duration<double, std::milli>(now - b.last_frame).count());
    }
    b.last_frame = now;
    ++b.drag_frames;
    const double elapsed = std::chrono::duration<double>(now - b.drag_start).count();
    if (b.k < args_.bench) {
      if (elapsed >= b.k / 60.0) {
        push({RequestKind::SetLoad, slider_max_ * b.k / std::max(1, args_.bench - 1), {}});
        ++b.k;
      }
    } else {
      b.drag_seconds = elapsed;
      b.phase = 1;
    }
  } else if (b.phase == 1) {
    if (solved_on_screen_ && !worker_.busy()) {
      b.phase = 2;
      b.k = 0;
    }
  } else if (b.phase == 2) {
    // Isolated changes: each waits for its converged frame before the next.
    if (b.waiting != 0 && !(solved_on_screen_ && !worker_.busy())) return;
    if (b.k >= 30) {
      b.phase = 3;
      b.k = 0;
      return;
    }
    const double t = slider_max_ * (0.5 + 0.01 * ((b.k % 2) ? b.k : -b.k));
    push({RequestKind::SetLoad, t, {}});
    b.waiting = requests_sent_ + 1;
    solved_on_screen_ = false;
    ++b.k;
  } else if (b.phase == 3) {
    // A load change, then the picture dragged sideways a few pixels a frame (as a mouse
    // drag pans it) for as long as the solver works on it; five such solves.
    if (!b.pan_solving) {
      if (b.pan_solves >= 5) {
        b.phase = 4;
        quit_ = true;
        return;
      }
      push({RequestKind::SetLoad, slider_max_ * (b.pan_solves % 2 ? 0.95 : 0.75), {}});
      solved_on_screen_ = false;
      b.pan_solving = true;
      b.pan_start = now;
      return;
    }
    if (worker_.busy() || !solved_on_screen_) {
      pan_.x += (b.pan_frames / 30) % 2 ? -3.0f : 3.0f;
      redraw_ = true;
      ++b.pan_frames;
    } else {
      b.pan_seconds += std::chrono::duration<double>(now - b.pan_start).count();
      b.pan_solving = false;
      ++b.pan_solves;
    }
  }
}

void App::print_bench(const render::GlfwWindow& window) const {
  const BenchMeasurement& b = bench_;
  std::printf("scene          %s (%zu struts, %zu contact pairs)\n", args_.scene.c_str(),
              target_.model->struts.size(), target_.model->pairs.size());
  std::printf("renderer       %s, window %dx%d\n", window.description().c_str(),
              view_width_ + static_cast<int>(panel_width()), view_height_);
  std::printf(
      "drag           %d load changes at 60 per second: %.1f frames/s (frame time median "
      "%.2f ms, max %.2f ms)\n",
      args_.bench, b.drag_seconds > 0 ? b.drag_frames / b.drag_seconds : 0.0, median(b.frame_ms),
      b.frame_ms.empty() ? 0.0 : *std::max_element(b.frame_ms.begin(), b.frame_ms.end()));
  std::printf(
      "per frame      picture median %.2f ms (draw lists %.2f ms, the rest GL until "
      "finished; %zu of the %d frames drew a new picture); ImGui + blit + swap median "
      "%.2f ms\n",
      median(b.draw_ms), median(b.lists_ms), b.draw_ms.size(), b.drag_frames, median(b.swap_ms));
  std::printf(
      "latency        load change -> frame with the converged solve: median %.2f ms, "
      "max %.2f ms (%zu changes)\n",
      median(b.solved_latency_ms),
      b.solved_latency_ms.empty()
          ? 0.0
          : *std::max_element(b.solved_latency_ms.begin(), b.solved_latency_ms.end()),
      b.solved_latency_ms.size());
  std::printf("               load change -> first frame at the new load: median %.2f ms\n",
              median(b.first_latency_ms));
  std::printf(
      "panning        during %d solves (%.2f s): %.1f frames/s, %.1f pictures/s (%d frames, %d "
      "pictures)\n",
      b.pan_solves, b.pan_seconds, b.pan_seconds > 0 ? b.pan_frames / b.pan_seconds : 0.0,
      b.pan_seconds > 0 ? b.pan_pictures / b.pan_seconds : 0.0, b.pan_frames, b.pan_pictures);
  std::printf("solve          median %.2f ms, median %.0f iterations (warm-started FETI-C)\n",
              median(b.solve_ms),
              median(std::vector<double>(b.iterations.begin(), b.iterations.end())));
}

}  // namespace fetic::app::gui
