// The picture of the shown iterate: the same draw lists as `fetic render` (scene and
// information panel), framed for the window and moved by its pan and zoom.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "app/gui/app.hpp"
#include "render/colormap.hpp"
#include "render/contact_chart.hpp"
#include "render/gl_renderer.hpp"
#include "render/overlay.hpp"
#include "render/scene_drawing.hpp"
#include "render/scene_framing.hpp"
#include "render/scene_mesh.hpp"
#include "solver/method.hpp"

namespace fetic::app::gui {

render::View App::view(int width, int height) const {
  render::View v;
  v.width = width;
  v.height = height;
  v.magnification = magnification_;
  v.color_by = moment_   ? render::ColorBy::Moment
               : stress_ ? render::ColorBy::Stress
                         : (subdomains_ ? render::ColorBy::Subdomain : render::ColorBy::Strut);
  v.show_forces = forces_;
  v.show_gaps = gaps_;
  v.show_overlay = show_overlay_;
  v.show_labels = labels_;
  v.show_corners = corners_;
  v.show_chart = chart_;
  v.min_text_size = std::ceil(kSmallestText / 0.68f * ui_scale_);
  // The scales are fixed for the whole slider (the survey at its top) or by a loaded view.
  char basis[96];
  std::snprintf(basis, sizeof basis, "over loads 0-%g", slider_max_);
  v.scale_basis = scales_ ? "of the loaded view" : basis;
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
  if (comparing()) {
    draw_comparison(width, height);
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
  const render::SceneFraming framing = frame_picture(v, width, height);
  update_mesh(v, framing, index);
  // The pick index (hover, pins, locate) is built when it is next asked for, not with
  // every picture: for millions of nodes it costs more than the picture (panning).
  pick_state_ = shown_;
  pick_iterate_ = index;
  pick_stale_ = true;
  render::OverlayInfo info;
  info.title = title_;
  info.method = solver::to_string(shown_->method);
  if (solver::is_dual(shown_->method))
    info.method += std::string(" (") + solver::to_string(shown_->preconditioner) + ")";
  info.status = shown_status();
  const render::DrawList glyphs =
      render::draw_glyphs(*shown_->model, snapshot, v, framing, {info.method, {}});
  const render::DrawList overlay = picture_overlay(info, snapshot, history, v);
  if (args_.bench > 0 && bench_.phase == 0)
    bench_.lists_ms.push_back(
        std::chrono::duration<double, std::milli>(Clock::now() - lists_start).count());
  const render::DrawList chart =
      v.show_chart ? render::draw_contact_chart(*shown_->model, snapshot, render::chart_region(v),
                                                render::text_size(v))
                   : render::DrawList{};
  const render::Rect region = render::scene_region(v);
  std::vector<render::Layer> layers{
      render::Layer(mesh_.get(), &mesh_values_, render::mesh_uniforms(*mesh_, framing), region),
      render::Layer(&glyphs, region), render::Layer(&overlay)};
  if (!chart.empty()) layers.emplace_back(&chart);
  renderer_->draw(width, height, layers, render::palette::background);
}

render::SceneFraming App::frame_picture(const render::View& v, int width, int height) {
  // The framing (magnification, fit, gap widening) is fixed for a scene, a survey and a
  // view size: computed again only when one of them changes, not for every picture.
  const PictureKey key{shown_->model, shown_->extent, width, height, magnification_, show_overlay_};
  if (!(key == framing_key_)) {
    // The run's scales: the survey's, or those of a loaded view (views.cpp).
    render::RunExtent extent = *shown_->extent;
    apply_scales(scales_, extent);
    framing_ = render::frame_scene(*shown_->model, v, extent, render::scene_region(v));
    framing_key_ = key;
  }
  base_center_ = framing_.pixel_center;
  place_pending_center();
  const render::SceneFraming framing =
      render::zoomed(framing_, zoom_, {base_center_.x + pan_.x, base_center_.y + pan_.y});
  placed_ = framing;
  shown_magnification_ = framing.magnification;
  return framing;
}

void App::update_mesh(const render::View& v, const render::SceneFraming& framing, int index) {
  const solver::Snapshot& snapshot = *shown_->iterates[static_cast<std::size_t>(index)];
  // The struts: a mesh on the GPU, built when the scene, its pieces or the colouring change,
  // or the zoom leaves its level of detail (a power of two; render/mesh_detail.hpp).
  const render::MeshDetail detail = render::mesh_detail(*shown_->model, framing_, framing);
  if (!mesh_ || mesh_model_ != shown_->model || mesh_->color_by != v.color_by ||
      !mesh_->fits(snapshot) || !render::detail_serves(mesh_->detail, detail, framing)) {
    mesh_ = std::make_shared<const render::SceneMesh>(
        render::build_scene_mesh(*shown_->model, snapshot, framing_, v.color_by, detail));
    mesh_model_ = shown_->model;
    ++mesh_builds_;
  }
  // The values change with the iterate, the mesh and the colour scales, not with pan and
  // zoom: on a scene of millions of elements they are not filled again for every picture.
  const auto& iterate = shown_->iterates[static_cast<std::size_t>(index)];
  const std::array<double, 3> values_key{static_cast<double>(mesh_->id), framing.stress_scale,
                                         framing.moment_scale};
  if (iterate != values_iterate_ || values_key != values_key_) {
    render::fill_mesh_values(*mesh_, *shown_->model, snapshot, framing, mesh_values_);
    values_iterate_ = iterate;
    values_key_ = values_key;
  }
}

render::DrawList App::picture_overlay(const render::OverlayInfo& info,
                                      const solver::Snapshot& snapshot,
                                      const std::vector<solver::HistoryEntry>& history,
                                      const render::View& v) {
  render::RunExtent plots = plot_extent();
  apply_scales(scales_, plots);
  drawn_extent_ = *shown_->extent;
  apply_scales(scales_, drawn_extent_);
  drawn_extent_.largest_iteration = plots.largest_iteration;
  if (!v.show_overlay) return {};
  if (recording_ && recording_->sweep && !recording_->steps.empty()) {
    // A load sweep being recorded: plots against the load factor.
    render::StepSeries series;
    series.all = recording_->steps;
    series.shown = recording_->steps;
    series.all.resize(recording_->loads.size());
    for (std::size_t i = 0; i < recording_->loads.size(); ++i)
      series.all[i].load_factor = recording_->loads[i];
    return render::draw_overlay(info, *shown_->model, snapshot, history, plots, v, &series);
  }
  return render::draw_overlay(info, *shown_->model, snapshot, history, plots, v);
}

}  // namespace fetic::app::gui
