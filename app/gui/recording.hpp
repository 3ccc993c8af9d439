#pragma once
// A recording in progress in `fetic gui` (the R-buttons of the panel, record-* script
// actions): the iterations of one solve, or a load sweep, as numbered PNG frames.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "app/gui/solver_worker.hpp"
#include "render/frame_sequence.hpp"
#include "render/png_writer.hpp"

namespace fetic::app::gui {

// Frames are rendered one per UI frame and encoded on worker threads.
struct Recording {
  bool sweep = false;
  std::filesystem::path directory;
  std::vector<double> loads;               // sweep: load factors still to solve and record
  std::uint64_t awaiting = 0;              // sweep: request whose finished solve is the next frame
  std::vector<render::StepSummary> steps;  // sweep: the loads recorded so far (for the plots)
  std::shared_ptr<const SolveState> iterations;  // iterations: the solve to record
  int next = 0;                                  // next frame index
  std::unique_ptr<render::PngEncoderPool> pool;
};

}  // namespace fetic::app::gui
