#pragma once
// One movie frame as draw lists: the scene in its region and, when wanted, the overlay
// panel. The framing (magnification, fit, colour and glyph scales) is fixed for the run.

#include "render/draw_list.hpp"
#include "render/frame_sequence.hpp"
#include "render/overlay.hpp"
#include "render/scene_framing.hpp"
#include "render/view.hpp"

namespace fetic::render {

struct ComposedFrame {
  DrawList scene;
  DrawList overlay;  // empty without the overlay
};

class FrameComposer {
 public:
  // `model` must outlive the composer.
  // `load_steps`: how many load factors the plan has (the overlay names the step).
  FrameComposer(const solver::Model& model, const View& view, const RunExtent& extent,
                OverlayInfo info, int load_steps = 1);
  ComposedFrame compose(const Frame& frame) const;
  const SceneFraming& framing() const { return framing_; }
  const View& view() const { return view_; }

 private:
  const solver::Model& model_;
  View view_;
  RunExtent extent_;
  OverlayInfo info_;
  int load_steps_ = 1;
  SceneFraming framing_;
};

}  // namespace fetic::render
