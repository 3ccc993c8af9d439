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
  const auto mesh_start = Clock::now();
  const int index = shown_index();
  const solver::Snapshot& snapshot = *shown_->iterates[static_cast<std::size_t>(index)];
  const std::vector<solver::HistoryEntry> history(
      shown_->history.begin(),
      shown_->history.begin() +
          std::min<std::ptrdiff_t>(index + 1, static_cast<std::ptrdiff_t>(shown_->history.size())));
  const render::View v = view(width, height);
  const render::SceneFraming framing = frame_picture(v, width, height);
  const MeshSlot& mesh = update_mesh(v, framing, index);
  const auto lists_start = Clock::now();
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
  const render::DrawList& chart = contact_chart(v, index);
  const render::Rect region = render::scene_region(v);
  std::vector<render::Layer> layers{
      render::Layer(mesh.mesh.get(), &mesh.values, render::mesh_uniforms(*mesh.mesh, framing),
                    region),
      render::Layer(&glyphs, region), render::Layer(&overlay)};
  if (!chart.empty()) layers.emplace_back(&chart);
  const auto gl_start = Clock::now();
  renderer_->draw(width, height, layers, render::palette::background);
  if (view_bench_.phase == 0 || view_bench_.phase == 1) {  // the GL part: the rest of the picture
    const auto ms = [](Clock::time_point a, Clock::time_point b) {
      return std::chrono::duration<double, std::milli>(b - a).count();
    };
    view_bench_.mesh_ms.push_back(ms(mesh_start, lists_start));
    view_bench_.lists_ms.push_back(ms(lists_start, gl_start));
  }
}

// The per-contact chart depends on the iterate and the picture's size, not on pan and
// zoom: it is kept between pictures (on ten million unknowns it takes a pass over every
// node's displacement).
const render::DrawList& App::contact_chart(const render::View& v, int index) {
  const ChartKey key{v.show_chart ? shown_->iterates[static_cast<std::size_t>(index)] : nullptr,
                     shown_->model, v.width, v.height, render::text_size(v)};
  if (!(key == chart_key_)) {
    chart_list_ = key.iterate ? render::draw_contact_chart(*shown_->model, *key.iterate,
                                                           render::chart_region(v), key.text_size)
                              : render::DrawList{};
    chart_key_ = key;
  }
  return chart_list_;
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

// A draft (drawn while the view moves) of a scene whose mesh at the picture's level has
// more cells than this is drawn with the mesh a level coarser.
constexpr int kDraftMeshCells = 100000;

const App::MeshSlot& App::update_mesh(const render::View& v, const render::SceneFraming& framing,
                                      int index) {
  const render::MeshDetail detail = render::mesh_detail(*shown_->model, framing_, framing);
  const bool moving = draft_ && Clock::now() - view_moved_ < kViewRest;
  // While the view moves the fine mesh is not built again (zooming past its level): the
  // draft stands in for it until the view rests.
  if (!moving || !fine_mesh_.mesh || fine_mesh_.mesh->element_count <= kDraftMeshCells) {
    update_slot(fine_mesh_, v, framing, detail, index);
    if (!moving || fine_mesh_.mesh->element_count <= kDraftMeshCells) return fine_mesh_;
  }
  // Half the scale: cells of 2 to 4 pixels each way instead of 1 to 2.
  render::SceneFraming coarser = framing;
  coarser.pixels_per_unit *= 0.5;
  const render::MeshDetail draft = render::mesh_detail(*shown_->model, framing_, coarser);
  update_slot(draft_mesh_, v, framing, draft, index);
  return draft_mesh_;
}

void App::update_slot(MeshSlot& slot, const render::View& v, const render::SceneFraming& framing,
                      const render::MeshDetail& detail, int index) {
  const solver::Snapshot& snapshot = *shown_->iterates[static_cast<std::size_t>(index)];
  // The struts: a mesh on the GPU, built when the scene, its pieces or the colouring change,
  // or the zoom leaves its level of detail (a power of two; render/mesh_detail.hpp).
  if (!slot.mesh || slot.model != shown_->model || slot.mesh->color_by != v.color_by ||
      !slot.mesh->fits(snapshot) || !render::detail_serves(slot.mesh->detail, detail, framing)) {
    slot.mesh.reset();  // the old one freed before the new one is built
    slot.mesh = std::make_shared<const render::SceneMesh>(
        render::build_scene_mesh(*shown_->model, snapshot, framing_, v.color_by, detail));
    slot.model = shown_->model;
    ++mesh_builds_;
  }
  // The values change with the iterate, the mesh and the colour scales, not with pan and
  // zoom: on a scene of millions of elements they are not filled again for every picture.
  const auto& iterate = shown_->iterates[static_cast<std::size_t>(index)];
  const std::array<double, 3> values_key{static_cast<double>(slot.mesh->id), framing.stress_scale,
                                         framing.moment_scale};
  if (iterate != slot.values_iterate || values_key != slot.values_key) {
    render::fill_mesh_values(*slot.mesh, *shown_->model, snapshot, framing, slot.values);
    slot.values_iterate = iterate;
    slot.values_key = values_key;
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
