#pragma once
// The information panel beside the scene: title, method, load factor, iteration,
// residual, active-set size, and small plots of the residual (log scale) and of the
// active-set size over the iterations so far. Drawn as a draw list whose text goes
// through ImGui's font rendering like every other text.

#include <string>
#include <vector>

#include "render/draw_list.hpp"
#include "render/frame_sequence.hpp"
#include "render/plot.hpp"
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
// The per-contact chart's part (View::show_chart; empty without it): right of the scene,
// left of the panel.
Rect chart_region(const View& view);

// A run over several load factors (load steps, a sweep): the plots show the final state
// of each step against the load factor instead of the iterations of one solve.
struct StepSeries {
  std::vector<StepSummary> all;    // every step of the run (fixes the axes)
  std::vector<StepSummary> shown;  // the steps so far, the current one last
};

// The plots' axes hold every point they show: a fixed range for the run (the extent)
// widened by the data where it reaches beyond (a window's solve at another load); a
// residual of exactly 0, which a log axis cannot show, is drawn at the axis' floor with a
// mark and a "0" label. `areas`, when given, receives the plots' areas (their ranges), top
// to bottom.
DrawList draw_overlay(const OverlayInfo& info, const solver::Model& model,
                      const solver::Snapshot& snapshot,
                      const std::vector<solver::HistoryEntry>& history, const RunExtent& extent,
                      const View& view, const StepSeries* steps = nullptr,
                      std::vector<PlotArea>* areas = nullptr);

}  // namespace fetic::render
