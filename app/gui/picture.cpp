// The picture of the shown iterate: the same draw lists as `fetic render` (scene and
// information panel), framed for the window and moved by its pan and zoom.

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "app/gui/app.hpp"
#include "render/colormap.hpp"
#include "render/gl_renderer.hpp"
#include "render/overlay.hpp"
#include "render/scene_drawing.hpp"
#include "render/scene_framing.hpp"
#include "solver/method.hpp"

namespace fetic::app::gui {

render::View App::view(int width, int height) const {
  render::View v;
  v.width = width;
  v.height = height;
  v.magnification = magnification_;
  v.color_by = stress_ ? render::ColorBy::Stress
                       : (subdomains_ ? render::ColorBy::Subdomain : render::ColorBy::Strut);
  v.show_forces = forces_;
  v.show_gaps = gaps_;
  v.show_overlay = show_overlay_;
  return v;
}

// The survey (a solve at the top of the slider) fixes the plots' iteration axis, so that
// frames line up. A solve shown since that needs more iterations (another load, a poorer
// warm start) widens the axis rather than run off its end; it stays that wide for as long
// as the survey holds, so scrubbing or moving the slider does not rescale it.
render::RunExtent App::plot_extent() {
  if (shown_->extent != axis_survey_) {
    axis_survey_ = shown_->extent;
    longest_history_ = 0;
  }
  if (!shown_->history.empty())
    longest_history_ = std::max(longest_history_, shown_->history.back().iteration);
  render::RunExtent extent = *shown_->extent;
  extent.largest_iteration = std::max(extent.largest_iteration, longest_history_);
  return extent;
}

void App::draw_picture(int width, int height) {
  if (!shown_ || !shown_->extent || shown_->iterates.empty()) {
    const render::DrawList empty;
    renderer_->draw(width, height, {&empty}, render::palette::background);
    return;
  }
  const auto lists_start = Clock::now();
  const int index = shown_index();
  const solver::Snapshot& snapshot = *shown_->iterates[static_cast<std::size_t>(index)];
  const std::vector<solver::HistoryEntry> history(
      shown_->history.begin(),
      shown_->history.begin() +
          std::min<std::ptrdiff_t>(index + 1, static_cast<std::ptrdiff_t>(shown_->history.size())));
  const render::View v = view(width, height);
  render::SceneFraming framing =
      render::frame_scene(*shown_->model, v, *shown_->extent, render::scene_region(v));
  base_center_ = framing.pixel_center;
  framing.pixels_per_unit *= zoom_;
  framing.pixel_center = {base_center_.x + pan_.x, base_center_.y + pan_.y};
  shown_magnification_ = framing.magnification;
  const render::DrawList scene = render::draw_scene(*shown_->model, snapshot, v, framing);
  render::DrawList overlay;
  if (v.show_overlay) {
    render::OverlayInfo info;
    info.title = title_;
    info.method = solver::to_string(shown_->method);
    if (solver::is_dual(shown_->method))
      info.method += std::string(" (") + solver::to_string(shown_->preconditioner) + ")";
    info.status = shown_status();
    overlay = render::draw_overlay(info, *shown_->model, snapshot, history, plot_extent(), v);
  }
  if (args_.bench > 0 && bench_.phase == 0)
    bench_.lists_ms.push_back(
        std::chrono::duration<double, std::milli>(Clock::now() - lists_start).count());
  // Panned or zoomed, the scene may reach under the information panel: mask it there.
  render::DrawList mask;
  if (v.show_overlay)
    mask.rect(
        {render::scene_region(v).x1, 0.0f, static_cast<float>(width), static_cast<float>(height)},
        render::palette::background);
  renderer_->draw(width, height, {&scene, &mask, &overlay}, render::palette::background);
}

}  // namespace fetic::app::gui
