// fetic gui --bench N: drives the window like a user dragging the slider, then makes
// isolated load changes, each waiting for its converged frame (see bench.hpp).

#include <algorithm>
#include <chrono>

#include "app/gui/app.hpp"

namespace fetic::app::gui {

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
      quit_ = true;
      return;
    }
    const double t = slider_max_ * (0.5 + 0.01 * ((b.k % 2) ? b.k : -b.k));
    push({RequestKind::SetLoad, t, {}});
    b.waiting = requests_sent_ + 1;
    solved_on_screen_ = false;
    ++b.k;
  }
}

}  // namespace fetic::app::gui
