#pragma once
// Draws with OpenGL 3.3 core into a multisampled frame buffer object (4 samples unless
// set otherwise) that is resolved before it is read back. Two kinds of layers: draw lists
// (one streamed vertex buffer, a shader that multiplies the vertex colour by the font
// atlas, whose white texel serves solid triangles) and scene meshes (SceneMesh): their
// vertices and reference nodes stay on the GPU from one frame to the next, only the node
// and element values are uploaded per frame, and the vertex shader applies the
// magnification, pan and zoom. Works in any current context (EGL headless or a window).

#include <cstdint>
#include <vector>

#include "render/draw_list.hpp"
#include "render/font.hpp"
#include "render/gl_context.hpp"
#include "render/image.hpp"
#include "render/layer.hpp"
#include "render/scene_mesh.hpp"

namespace fetic::render {

class GlRenderer {
 public:
  // The context must be current; the font atlas must outlive the renderer.
  GlRenderer(GlContext& context, const FontAtlas& font);
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  // Draws the layers in order over the background and reads the pixels back (alpha 255):
  // draw() then read_back().
  Image render(int width, int height, const std::vector<Layer>& layers, Color background);
  Image render(int width, int height, const std::vector<const DrawList*>& lists, Color background);
  // Draws the layers into the multisampled buffer and resolves it; the picture stays in
  // the renderer until the next draw (a window re-shows it without drawing again).
  void draw(int width, int height, const std::vector<Layer>& layers, Color background);
  void draw(int width, int height, const std::vector<const DrawList*>& lists, Color background);
  // The last drawn picture, rows top to bottom, alpha 255.
  Image read_back();
  // Copies the last drawn picture into the default frame buffer (a window's back buffer)
  // with its top-left corner at pixel (x, y) from the top-left of a frame buffer
  // `target_height` pixels high.
  void blit_to_default(int x, int y, int target_height);
  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }
  // Samples per pixel of the next draws (1 .. the GL maximum, at most 4 by default): an
  // interactive window may draw with 1 while the user drags and 4 when the picture rests.
  void set_samples(int samples);

 private:
  void resize(int width, int height);
  void release_targets();
  void append(const DrawList& list, std::vector<TexturedVertex>& out) const;
  void draw_list(const DrawList& list, int width, int height);
  void draw_mesh(const SceneMesh& mesh, const MeshValues& values, const MeshUniforms& uniforms,
                 int width, int height);
  void upload_mesh(const SceneMesh& mesh);

  GlContext& context_;
  const FontAtlas& font_;
  unsigned program_ = 0, vao_ = 0, vbo_ = 0, texture_ = 0;
  unsigned msaa_fbo_ = 0, msaa_color_ = 0, resolve_fbo_ = 0, resolve_color_ = 0;
  int viewport_location_ = -1;
  int width_ = 0, height_ = 0, samples_ = 0, max_samples_ = 1;
  std::vector<TexturedVertex> vertices_;
  // Scene meshes: the program, the static vertex buffer and three texture buffers
  // (reference nodes; per frame node values and element values).
  unsigned mesh_program_ = 0, mesh_vao_ = 0, mesh_vbo_ = 0;
  unsigned reference_buffer_ = 0, reference_texture_ = 0;
  unsigned values_buffer_ = 0, values_texture_ = 0;
  unsigned elements_buffer_ = 0, elements_texture_ = 0;
  std::uint64_t uploaded_mesh_ = 0;  // SceneMesh::id on the GPU
};

}  // namespace fetic::render
