#pragma once
// What `fetic gui --bench N` measures: a slider drag over N load changes at a pointer's
// pace (frame rate, cost of a picture), then 30 isolated load changes (latency to the
// converged frame). Driven by App::bench_step, printed by App::print_bench.

#include <chrono>
#include <cstdint>
#include <vector>

namespace fetic::app::gui {

struct BenchMeasurement {
  // -1 first solve, 0 drag, 1 settle, 2 isolated changes, 3 panning during solves, 4 done
  int phase = -1;
  int k = 0;
  std::vector<double> frame_ms, draw_ms, lists_ms, swap_ms;  // during the drag
  std::vector<double> solved_latency_ms, first_latency_ms, solve_ms;
  std::vector<int> iterations;
  std::chrono::steady_clock::time_point last_frame{};
  std::chrono::steady_clock::time_point drag_start{};
  double drag_seconds = 0.0;
  int drag_frames = 0;
  std::uint64_t waiting = 0;
  // Panning while the solver works: frames and pictures drawn during the solves.
  bool pan_solving = false;
  int pan_solves = 0, pan_frames = 0, pan_pictures = 0;
  double pan_seconds = 0.0;
  std::chrono::steady_clock::time_point pan_start{};
};

// What `fetic gui --bench-view N` measures: once the first solve is on screen, N frames
// of panning (half) then zooming in and out over several powers of two (half), every
// frame a new picture when it can: frames and pictures per second, frame times, and how
// often the zoom made the struts' mesh rebuild at another level of detail.
struct ViewBench {
  int phase = -1;  // -1 first solve, 0 panning, 1 zooming, 2 done
  int frame = 0;
  std::chrono::steady_clock::time_point start{}, last{};
  double seconds[2] = {0, 0};
  int frames[2] = {0, 0}, pictures[2] = {0, 0};
  std::vector<double> frame_ms[2];
  int mesh_builds = 0;  // during the measurement
  // Per picture drawn while moving: the struts' mesh (built again or not) and its values,
  // the draw lists (glyphs, panel, chart), the whole picture until the GL work finished.
  std::vector<double> mesh_ms, lists_ms, picture_ms;
};

}  // namespace fetic::app::gui
