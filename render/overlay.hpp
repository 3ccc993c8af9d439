#pragma once
// The information panel beside the scene: title, method, load factor, iteration,
// residual, active-set size, and small plots of the residual (log scale) and of the
// active-set size over the iterations so far. Drawn as a draw list whose text goes
// through ImGui's font rendering like every other text.

#include <string>
#include <vector>

#include "render/draw_list.hpp"
#include "render/frame_sequence.hpp"
#include "render/view.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"

namespace fetic::render {

struct OverlayInfo {
  std::string title;
  std::string method;     // e.g. "feti-c (dirichlet)"
  std::string load_step;  // e.g. "step 3 of 10"; empty for a single load factor
  // The status row; empty: the snapshot's own status. A window that shows an earlier
  // iterate of a finished solve says so ("converged at iteration 6; showing 3").
  std::string status;
};

// The panel's place (right side of the image) and the scene's (the rest).
Rect overlay_panel(const View& view);
Rect scene_region(const View& view);

DrawList draw_overlay(const OverlayInfo& info, const solver::Model& model,
                      const solver::Snapshot& snapshot,
                      const std::vector<solver::HistoryEntry>& history, const RunExtent& extent,
                      const View& view);

}  // namespace fetic::render
