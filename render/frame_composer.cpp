#include "render/frame_composer.hpp"

#include "render/colormap.hpp"
#include "render/scene_drawing.hpp"

namespace fetic::render {

FrameComposer::FrameComposer(const solver::Model& model, const View& view, const RunExtent& extent,
                             OverlayInfo info, int load_steps)
    : model_(model),
      view_(view),
      extent_(extent),
      info_(std::move(info)),
      load_steps_(load_steps),
      framing_(frame_scene(model, view, extent, scene_region(view))) {}

ComposedFrame FrameComposer::compose(const Frame& frame) const {
  ComposedFrame composed;
  composed.scene = draw_scene(model_, frame.snapshot, view_, framing_);
  if (view_.show_overlay) {
    OverlayInfo info = info_;
    if (load_steps_ > 1)
      info.load_step =
          "step " + std::to_string(frame.load_step + 1) + " of " + std::to_string(load_steps_);
    // Zoomed or moved, the scene may reach under the panel: mask it there, as the window does.
    if (view_.zoom != 1.0 || view_.centered) {
      const Rect region = scene_region(view_);
      composed.overlay.rect({region.x1, 0.0f, static_cast<float>(view_.width),
                             static_cast<float>(view_.height)},
                            palette::background);
    }
    composed.overlay.append(
        draw_overlay(info, model_, frame.snapshot, frame.history, extent_, view_));
  }
  return composed;
}

}  // namespace fetic::render
