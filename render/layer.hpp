#pragma once
// What a picture is made of, in drawing order (GlRenderer draws them; no GL here).

#include "render/draw_list.hpp"
#include "render/scene_mesh.hpp"

namespace fetic::render {

// One layer of a picture: a draw list, or a scene mesh with its values and uniforms;
// optionally clipped to a rectangle (pixels; an empty one clips nothing).
struct Layer {
  const DrawList* list = nullptr;
  const SceneMesh* mesh = nullptr;
  const MeshValues* values = nullptr;
  MeshUniforms uniforms;
  Rect clip;

  Layer() = default;
  explicit Layer(const DrawList* draw_list, Rect clip_to = {}) : list(draw_list), clip(clip_to) {}
  Layer(const SceneMesh* scene, const MeshValues* scene_values, const MeshUniforms& scene_uniforms,
        Rect clip_to = {})
      : mesh(scene), values(scene_values), uniforms(scene_uniforms), clip(clip_to) {}
};

}  // namespace fetic::render
