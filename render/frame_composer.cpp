#include "render/frame_composer.hpp"

#include <algorithm>

#include "render/contact_chart.hpp"
#include "render/overlay.hpp"
#include "render/scene_drawing.hpp"

namespace fetic::render {

std::vector<Layer> ComposedFrame::layers() const {
  std::vector<Layer> out;
  if (mesh) out.emplace_back(mesh.get(), &values, uniforms, region);
  out.emplace_back(&glyphs, region);
  if (!overlay.empty()) out.emplace_back(&overlay);
  if (!chart.empty()) out.emplace_back(&chart);
  return out;
}

DrawList ComposedFrame::flattened() const {
  DrawList list;
  if (mesh) expand_mesh(*mesh, values, uniforms, list);
  list.append(glyphs);
  list.append(overlay);
  list.append(chart);
  return list;
}

FrameComposer::FrameComposer(const solver::Model& model, const View& view, const RunExtent& extent,
                             OverlayInfo info, int load_steps)
    : model_(model),
      view_(view),
      extent_(extent),
      info_(std::move(info)),
      load_steps_(load_steps),
      framing_(frame_scene(model, view, extent, scene_region(view))),
      placed_(view.zoom != 1.0 || view.centered ? placed(framing_, view) : framing_) {}

ComposedFrame FrameComposer::compose(const Frame& frame) const {
  ComposedFrame composed;
  if (!mesh_ || !mesh_->fits(frame.snapshot))
    // At the detail of the drawn scale: plane elements below a pixel merged.
    mesh_ = std::make_shared<const SceneMesh>(build_scene_mesh(
        model_, frame.snapshot, framing_, view_.color_by, mesh_detail(model_, placed_, placed_)));
  composed.mesh = mesh_;
  // The mesh is built for the fitted framing and drawn zoomed and moved, as the window does.
  fill_mesh_values(*mesh_, model_, frame.snapshot, placed_, composed.values);
  composed.uniforms = mesh_uniforms(*mesh_, placed_);
  composed.region = placed_.region;
  SceneCaption caption{info_.method, {}};
  OverlayInfo info = info_;
  if (load_steps_ > 1) {
    info.load_step =
        "step " + std::to_string(frame.load_step + 1) + " of " + std::to_string(load_steps_);
    caption.load_step = info.load_step;
  }
  composed.glyphs = draw_glyphs(model_, frame.snapshot, view_, placed_, caption);
  if (view_.show_chart)
    composed.chart =
        draw_contact_chart(model_, frame.snapshot, chart_region(view_), text_size(view_));
  if (view_.show_overlay) {
    if (load_steps_ > 1) {
      // Plots against the load factor: the steps done so far, this one as it stands.
      StepSeries series;
      series.all = extent_.steps;
      series.shown.assign(extent_.steps.begin(),
                          extent_.steps.begin() +
                              std::min<std::ptrdiff_t>(frame.load_step, static_cast<std::ptrdiff_t>(
                                                                            extent_.steps.size())));
      series.shown.push_back(summarize(frame.snapshot));
      composed.overlay =
          draw_overlay(info, model_, frame.snapshot, frame.history, extent_, view_, &series);
    } else {
      composed.overlay = draw_overlay(info, model_, frame.snapshot, frame.history, extent_, view_);
    }
  }
  return composed;
}

}  // namespace fetic::render
