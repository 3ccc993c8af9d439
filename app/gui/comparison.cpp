// Two methods solving the same scene at the same load side by side (--compare, the
// "compare with" box, the script's "compare"): the first method's picture on the left,
// the second's on the right, the same iteration of each (or its last, when it needed
// fewer), at the same magnification; below them one residual plot with both curves up to
// the shown iteration. Pan and zoom apply to the single picture only.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/gui/app.hpp"
#include "render/colormap.hpp"
#include "render/gl_renderer.hpp"
#include "render/plot.hpp"
#include "render/scene_drawing.hpp"
#include "render/scene_framing.hpp"
#include "render/text_format.hpp"
#include "render/view.hpp"
#include "solver/method.hpp"

namespace fetic::app::gui {
namespace {

std::string method_name(const SolveState& state) {
  std::string name = solver::to_string(state.method);
  if (solver::is_dual(state.method))
    name += std::string(" (") + solver::to_string(state.preconditioner) + ")";
  return name;
}

// "feti-c (dirichlet): converged at iteration 6, 8 applications of F; showing 3"
std::string label(const SolveState& state, int index) {
  const int last = static_cast<int>(state.iterates.size()) - 1;
  std::string text = method_name(state) + ": ";
  text += state.cancelled   ? "cancelled"
          : !state.finished ? "running"
                            : solver::to_string(state.status);
  text += " at iteration " + std::to_string(last);
  if (!state.history.empty() && state.history.back().f_applications >= 0)
    text += ", " + std::to_string(state.history.back().f_applications) + " applications of F";
  if (index < last) text += "; showing " + std::to_string(index);
  return text;
}

render::Series residuals(const SolveState& state, int index, int which) {
  render::Series series;
  series.name = method_name(state);
  series.color = render::series_color(which);
  series.width = 2.2f;
  series.markers = true;
  for (const solver::HistoryEntry& entry : state.history) {
    if (entry.iteration > index) break;
    if (!(entry.residual > 0.0)) continue;  // a log axis
    series.x.push_back(entry.iteration);
    series.y.push_back(entry.residual);
  }
  return series;
}

}  // namespace

bool App::comparing() const {
  return compare_ && compare_shown_ && !compare_shown_->iterates.empty() &&
         compare_shown_->model == shown_->model;
}

int App::compare_index() const {
  const int last = static_cast<int>(compare_shown_->iterates.size()) - 1;
  return std::clamp(shown_index(), 0, last);
}

void App::draw_comparison(int width, int height) {
  const auto w = static_cast<float>(width), h = static_cast<float>(height);
  render::View v = view(width, height);
  const float text = render::text_size(v);
  v.show_overlay = false;
  const float plot_top = 0.68f * h;
  const SolveState* states[2] = {shown_.get(), compare_shown_.get()};
  const int indices[2] = {shown_index(), compare_index()};
  render::DrawList lists;
  // The first method's survey fixes the magnification of both pictures.
  const render::RunExtent& extent = *shown_->extent;
  for (int side = 0; side < 2; ++side) {
    const SolveState& state = *states[side];
    const float x0 = side * 0.5f * w, x1 = (side + 1) * 0.5f * w;
    const render::Rect region{x0 + text, 2.6f * text, x1 - text, plot_top - text};
    const render::SceneFraming framing = render::frame_scene(*state.model, v, extent, region);
    if (side == 0) shown_magnification_ = framing.magnification;
    const solver::Snapshot& snapshot = *state.iterates[static_cast<std::size_t>(indices[side])];
    lists.append(render::draw_scene(*state.model, snapshot, v, framing));
    lists.text(label(state, indices[side]), {0.5f * (x0 + x1), 0.6f * text}, text,
               render::palette::ink, render::HAlign::Center, render::VAlign::Top, side == 0);
  }
  // A scene zoomed by its framing cannot reach the other half; the separator marks them.
  lists.rect({0.5f * w - 1.0f, 0.0f, 0.5f * w + 1.0f, plot_top}, render::palette::muted);

  render::PlotSpec plot;
  plot.frame = {0.0f, plot_top, w, h};
  plot.title = "relative residual per iteration";
  plot.text_size = text;
  const int longest = std::max(static_cast<int>(shown_->iterates.size()),
                               static_cast<int>(compare_shown_->iterates.size())) -
                      1;
  plot.x = {"iteration", 0.0, std::max(1.0, double(longest)), false, true};
  plot.y = {"residual", std::nan(""), std::nan(""), true, false};
  for (int side = 0; side < 2; ++side)
    plot.series.push_back(residuals(*states[side], indices[side], side));
  lists.append(render::draw_plot(plot));
  renderer_->draw(width, height, {&lists}, render::palette::background);
}

}  // namespace fetic::app::gui
