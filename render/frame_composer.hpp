#pragma once
// One movie frame: the struts as a scene mesh (static, built on the first frame and kept
// on the GPU) with this frame's values, the glyphs and annotations as a draw list, and,
// when wanted, the overlay panel. The framing (magnification, fit, colour and glyph
// scales) is fixed for the run.

#include <memory>
#include <vector>

#include "render/draw_list.hpp"
#include "render/frame_sequence.hpp"
#include "render/layer.hpp"
#include "render/overlay.hpp"
#include "render/scene_framing.hpp"
#include "render/scene_mesh.hpp"
#include "render/view.hpp"

namespace fetic::render {

struct ComposedFrame {
  std::shared_ptr<const SceneMesh> mesh;
  MeshValues values;
  MeshUniforms uniforms;
  Rect region;  // the scene's part of the image (the mesh and glyphs are clipped to it)
  DrawList glyphs;
  DrawList overlay;  // empty without the overlay
  DrawList chart;    // the per-contact chart (View::show_chart), empty without it
  // The layers to draw, in order.
  std::vector<Layer> layers() const;
  // The whole frame as one draw list (the mesh expanded on the CPU), for tests.
  DrawList flattened() const;
};

class FrameComposer {
 public:
  // `model` must outlive the composer.
  // `load_steps`: how many load factors the plan has (the overlay names the step and plots
  // against the load factor).
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
  SceneFraming placed_;  // framing_ with the view's zoom and centre
  mutable std::shared_ptr<const SceneMesh> mesh_;  // built for the first frame's pieces
};

}  // namespace fetic::render
