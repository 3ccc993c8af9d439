#include "render/frame_composer.hpp"

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
    composed.overlay = draw_overlay(info, model_, frame.snapshot, frame.history, extent_, view_);
  }
  return composed;
}

}  // namespace fetic::render
