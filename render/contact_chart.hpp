#pragma once
// The per-contact chart (issue 26, item 11): a dense scene - 2,000 pairs drawn as a
// column a few pixels wide - says nothing at a glance, so beside the picture two strips
// show every contact pair in the result file's order (along the scene): its contact force
// and its current gap g - (u_a - u_b) . n, with the active pairs marked in red beneath.
// One bar per pair; at more pairs than pixels the bars overlap, the tallest showing (the
// envelope), and a pixel column is marked active when any of its pairs is.

#include "render/draw_list.hpp"
#include "render/view.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"

namespace fetic::render {

// Scenes with at least this many pairs get the chart unless it is turned off.
inline constexpr int kChartPairs = 200;

// Whether a picture of `model` shows the chart: `wanted` 1 (on), 0 (off) or -1 (automatic:
// at kChartPairs pairs and more).
bool chart_shown(const solver::Model& model, int wanted);

// The chart of `snapshot` in `region`; text_size as the picture's (View text size).
DrawList draw_contact_chart(const solver::Model& model, const solver::Snapshot& snapshot,
                            const Rect& region, float text_size);

}  // namespace fetic::render
