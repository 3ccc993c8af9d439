#include "render/gl_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

namespace fetic::render {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec2 position;
layout(location = 1) in vec2 uv;
layout(location = 2) in vec4 color;
uniform vec2 viewport;
out vec2 fragment_uv;
out vec4 fragment_color;
void main() {
  fragment_uv = uv;
  fragment_color = color;
  gl_Position = vec4(2.0 * position.x / viewport.x - 1.0, 1.0 - 2.0 * position.y / viewport.y,
                     0.0, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec2 fragment_uv;
in vec4 fragment_color;
uniform sampler2D atlas;
out vec4 output_color;
void main() { output_color = fragment_color * texture(atlas, fragment_uv); }
)";

// Scene meshes (render/scene_mesh.hpp): the same formulas as expand_mesh().
constexpr const char* kMeshVertexShader = R"(#version 330 core
layout(location = 0) in ivec2 nodes;
layout(location = 1) in float t;
layout(location = 2) in vec4 offset;
layout(location = 3) in int element;
layout(location = 4) in vec4 color;
uniform samplerBuffer reference;       // per node row: x, y, widening x, widening y
uniform samplerBuffer node_values;     // per node row: ux, uy, rotation, 0
uniform samplerBuffer element_values;  // per element row: value / scale at t = 0 and t = 1
uniform vec2 viewport;
uniform float magnification, widening, pixels_per_unit, half_bar_width, rim, line_width;
uniform vec2 center, pixel_center;
uniform bool by_value;
out vec4 fragment_color;
// The diverging map of colormap.cpp: ColorBrewer RdBu reversed, compression blue.
const vec3 stops[7] = vec3[7](vec3(33, 102, 172), vec3(103, 169, 207), vec3(209, 229, 240),
                              vec3(236, 236, 236), vec3(253, 219, 199), vec3(239, 138, 98),
                              vec3(178, 24, 43));
vec3 diverging(float v) {
  float x = clamp(0.5 * (v + 1.0), 0.0, 1.0) * 6.0;
  int i = min(int(x), 5);
  return mix(stops[i], stops[i + 1], x - float(i)) / 255.0;
}
vec2 world(int row) {
  vec4 r = texelFetch(reference, row);
  vec4 v = texelFetch(node_values, row);
  return r.xy + widening * r.zw + magnification * v.xy;
}
vec2 screen(vec2 w) { return pixel_center + (w - center) * vec2(pixels_per_unit, -pixels_per_unit); }
// The Hermite shape of a beam element between the rows (world, magnified) minus the
// straight line: zero at t = 0 and 1, so bars and planes are unchanged.
vec2 bending(int row_a, int row_b) {
  vec4 ra = texelFetch(reference, row_a), rb = texelFetch(reference, row_b);
  vec4 va = texelFetch(node_values, row_a), vb = texelFetch(node_values, row_b);
  vec2 e = rb.xy - ra.xy;
  float h = length(e);
  if (!(h > 0.0)) return vec2(0.0);
  vec2 n = vec2(-e.y, e.x) / h;
  float wa = dot(va.xy, n), wb = dot(vb.xy, n);
  float c = (1.0 - 3.0 * t * t + 2.0 * t * t * t - (1.0 - t)) * wa +
            (3.0 * t * t - 2.0 * t * t * t - t) * wb +
            h * ((t - 2.0 * t * t + t * t * t) * va.z + (t * t * t - t * t) * vb.z);
  return magnification * c * n;
}
void main() {
  vec2 a = screen(world(nodes.x)), b = screen(world(nodes.y));
  vec2 d = b - a;
  float l = length(d);
  d = l > 0.0 ? d / l : vec2(1.0, 0.0);
  vec2 across = vec2(-d.y, d.x);
  vec2 bend = bending(nodes.x, nodes.y) * vec2(pixels_per_unit, -pixels_per_unit);
  vec2 p = a + t * (b - a) + bend +
           (offset.x * half_bar_width + offset.y * rim + offset.w * line_width) * across +
           offset.z * rim * d;
  vec2 ends = element >= 0 && by_value ? texelFetch(element_values, element).rg : vec2(0.0);
  fragment_color = element >= 0 && by_value ? vec4(diverging(mix(ends.x, ends.y, t)), 1.0) : color;
  gl_Position = vec4(2.0 * p.x / viewport.x - 1.0, 1.0 - 2.0 * p.y / viewport.y, 0.0, 1.0);
}
)";

constexpr const char* kMeshFragmentShader = R"(#version 330 core
in vec4 fragment_color;
out vec4 output_color;
void main() { output_color = fragment_color; }
)";

// Asks the driver whether a shader compiled (GL_COMPILE_STATUS) or a program linked
// (GL_LINK_STATUS); one that did not is deleted and the driver's log thrown.
void throw_unless_built(GLuint object, GLenum status, void (*get_status)(GLuint, GLenum, GLint*),
                        void (*info_log)(GLuint, GLsizei, GLsizei*, GLchar*),
                        void (*destroy)(GLuint), const char* what) {
  GLint built = 0;
  get_status(object, status, &built);
  if (built) return;
  char log[1024] = {};
  info_log(object, sizeof log, nullptr, log);
  destroy(object);
  throw RenderError(std::string("cannot ") + what + ": " + log);
}

GLuint compile(GLenum kind, const char* source) {
  const GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  throw_unless_built(shader, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, glDeleteShader,
                     "compile the renderer's shader");
  return shader;
}

GLuint link(const char* vertex_source, const char* fragment_source) {
  const GLuint vertex = compile(GL_VERTEX_SHADER, vertex_source);
  const GLuint fragment = compile(GL_FRAGMENT_SHADER, fragment_source);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  throw_unless_built(program, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, glDeleteProgram,
                     "link the renderer's shader program");
  return program;
}

// A texture buffer (samplerBuffer) of `format` over a new buffer object.
void make_texture_buffer(GLuint& buffer, GLuint& texture, GLenum format) {
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_TEXTURE_BUFFER, buffer);
  glBufferData(GL_TEXTURE_BUFFER, 16, nullptr, GL_STATIC_DRAW);
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_BUFFER, texture);
  glTexBuffer(GL_TEXTURE_BUFFER, format, buffer);
}

template <class T>
void upload(GLuint buffer, const std::vector<T>& data, GLenum usage) {
  glBindBuffer(GL_TEXTURE_BUFFER, buffer);
  // At least one texel, so that the texture buffer is never empty.
  const std::size_t bytes = std::max<std::size_t>(16, data.size() * sizeof(T));
  glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, usage);
  if (!data.empty())
    glBufferSubData(GL_TEXTURE_BUFFER, 0, static_cast<GLsizeiptr>(data.size() * sizeof(T)),
                    data.data());
}

// Vertex attribute `index` of the bound vertex array: `size` components of `type` at
// `offset` in each `stride`-byte vertex, read as floats (normalized: bytes to 0..1).
void float_attribute(GLuint index, GLint size, GLenum type, bool normalized, GLsizei stride,
                     std::size_t offset) {
  glEnableVertexAttribArray(index);
  glVertexAttribPointer(index, size, type, normalized ? GL_TRUE : GL_FALSE, stride,
                        reinterpret_cast<void*>(offset));
}

// The same for `size` ints, read as ints.
void int_attribute(GLuint index, GLint size, GLsizei stride, std::size_t offset) {
  glEnableVertexAttribArray(index);
  glVertexAttribIPointer(index, size, GL_INT, stride, reinterpret_cast<void*>(offset));
}

void check(const char* what) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
    throw RenderError(std::string("OpenGL error ") + std::to_string(error) + " " + what);
}

}  // namespace

GlRenderer::GlRenderer(GlContext& context, const FontAtlas& font) : context_(context), font_(font) {
  context_.make_current();
  program_ = link(kVertexShader, kFragmentShader);
  viewport_location_ = glGetUniformLocation(program_, "viewport");

  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  const auto stride = static_cast<GLsizei>(sizeof(TexturedVertex));
  float_attribute(0, 2, GL_FLOAT, false, stride, offsetof(TexturedVertex, x));
  float_attribute(1, 2, GL_FLOAT, false, stride, offsetof(TexturedVertex, u));
  float_attribute(2, 4, GL_UNSIGNED_BYTE, true, stride, offsetof(TexturedVertex, rgba));

  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, font_.texture_width(), font_.texture_height(), 0,
               GL_RGBA, GL_UNSIGNED_BYTE, font_.texture_rgba());
  // Scene meshes.
  mesh_program_ = link(kMeshVertexShader, kMeshFragmentShader);
  glGenVertexArrays(1, &mesh_vao_);
  glGenBuffers(1, &mesh_vbo_);
  glBindVertexArray(mesh_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, mesh_vbo_);
  const auto mesh_stride = static_cast<GLsizei>(sizeof(MeshVertex));
  int_attribute(0, 2, mesh_stride, offsetof(MeshVertex, node_a));
  float_attribute(1, 1, GL_FLOAT, false, mesh_stride, offsetof(MeshVertex, t));
  float_attribute(2, 4, GL_FLOAT, false, mesh_stride, offsetof(MeshVertex, offset));
  int_attribute(3, 1, mesh_stride, offsetof(MeshVertex, element));
  float_attribute(4, 4, GL_UNSIGNED_BYTE, true, mesh_stride, offsetof(MeshVertex, color));
  make_texture_buffer(reference_buffer_, reference_texture_, GL_RGBA32F);
  make_texture_buffer(values_buffer_, values_texture_, GL_RGBA32F);
  make_texture_buffer(elements_buffer_, elements_texture_, GL_RG32F);
  glUseProgram(mesh_program_);
  glUniform1i(glGetUniformLocation(mesh_program_, "reference"), 1);
  glUniform1i(glGetUniformLocation(mesh_program_, "node_values"), 2);
  glUniform1i(glGetUniformLocation(mesh_program_, "element_values"), 3);
  glUseProgram(0);
  glBindVertexArray(0);

  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  max_samples_ = std::max(1, static_cast<int>(max_samples));
  samples_ = std::min(4, max_samples_);
  check("while setting up the renderer");
}

GlRenderer::~GlRenderer() {
  release_targets();
  const GLuint textures[] = {reference_texture_, values_texture_, elements_texture_};
  const GLuint buffers[] = {reference_buffer_, values_buffer_, elements_buffer_, mesh_vbo_};
  glDeleteTextures(3, textures);
  glDeleteBuffers(4, buffers);
  glDeleteVertexArrays(1, &mesh_vao_);
  glDeleteProgram(mesh_program_);
  glDeleteTextures(1, &texture_);
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteProgram(program_);
}

void GlRenderer::set_samples(int samples) {
  samples = std::clamp(samples, 1, max_samples_);
  if (samples == samples_) return;
  context_.make_current();
  samples_ = samples;
  release_targets();  // resize() makes them again
}

void GlRenderer::release_targets() {
  glDeleteFramebuffers(1, &msaa_fbo_);
  glDeleteRenderbuffers(1, &msaa_color_);
  glDeleteFramebuffers(1, &resolve_fbo_);
  glDeleteRenderbuffers(1, &resolve_color_);
  msaa_fbo_ = msaa_color_ = resolve_fbo_ = resolve_color_ = 0;
}

void GlRenderer::resize(int width, int height) {
  if (width == width_ && height == height_ && resolve_fbo_ != 0) return;
  release_targets();
  const auto target = [&](GLuint& fbo, GLuint& color, int samples) {
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(1, &color);
    glBindRenderbuffer(GL_RENDERBUFFER, color);
    if (samples > 1)
      glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    else
      glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw RenderError("frame buffer of " + std::to_string(width) + "x" + std::to_string(height) +
                        " pixels is incomplete");
  };
  target(msaa_fbo_, msaa_color_, samples_);
  target(resolve_fbo_, resolve_color_, 0);
  width_ = width;
  height_ = height;
}

void GlRenderer::append(const DrawList& list, std::vector<TexturedVertex>& out) const {
  const auto& vertices = list.vertices();
  const auto& texts = list.texts();
  std::size_t next_text = 0;
  for (std::size_t i = 0; i <= vertices.size(); ++i) {
    while (next_text < texts.size() && texts[next_text].after_vertex == i)
      font_.layout(texts[next_text++], out);
    if (i == vertices.size()) break;
    const Vertex& v = vertices[i];
    out.push_back({v.position.x,
                   v.position.y,
                   font_.white_u(),
                   font_.white_v(),
                   {v.color.r, v.color.g, v.color.b, v.color.a}});
  }
}

Image GlRenderer::render(int width, int height, const std::vector<Layer>& layers,
                         Color background) {
  draw(width, height, layers, background);
  return read_back();
}

Image GlRenderer::render(int width, int height, const std::vector<const DrawList*>& lists,
                         Color background) {
  draw(width, height, lists, background);
  return read_back();
}

void GlRenderer::draw(int width, int height, const std::vector<const DrawList*>& lists,
                      Color background) {
  std::vector<Layer> layers;
  for (const DrawList* list : lists)
    if (list) layers.emplace_back(list);
  draw(width, height, layers, background);
}

void GlRenderer::draw(int width, int height, const std::vector<Layer>& layers, Color background) {
  context_.make_current();
  resize(width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(background.r / 255.0f, background.g / 255.0f, background.b / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  for (const Layer& layer : layers) {
    const bool clipped = layer.clip.width() > 0.0f && layer.clip.height() > 0.0f;
    if (clipped) {
      // Scissor boxes count from the bottom left.
      const int x0 = std::clamp(static_cast<int>(std::floor(layer.clip.x0)), 0, width);
      const int x1 = std::clamp(static_cast<int>(std::ceil(layer.clip.x1)), 0, width);
      const int y0 = std::clamp(static_cast<int>(std::floor(layer.clip.y0)), 0, height);
      const int y1 = std::clamp(static_cast<int>(std::ceil(layer.clip.y1)), 0, height);
      glEnable(GL_SCISSOR_TEST);
      glScissor(x0, height - y1, x1 - x0, y1 - y0);
    }
    if (layer.mesh && layer.values)
      draw_mesh(*layer.mesh, *layer.values, layer.uniforms, width, height);
    if (layer.list) draw_list(*layer.list, width, height);
    if (clipped) glDisable(GL_SCISSOR_TEST);
  }
  glBindVertexArray(0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
  glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check("while drawing a frame");
}

void GlRenderer::draw_list(const DrawList& list, int width, int height) {
  vertices_.clear();
  append(list, vertices_);
  if (vertices_.empty()) return;
  glUseProgram(program_);
  glUniform2f(viewport_location_, static_cast<float>(width), static_cast<float>(height));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices_.size() * sizeof(TexturedVertex)),
               vertices_.data(), GL_STREAM_DRAW);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_.size()));
}

void GlRenderer::upload_mesh(const SceneMesh& mesh) {
  if (mesh.id == uploaded_mesh_) return;
  glBindBuffer(GL_ARRAY_BUFFER, mesh_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(MeshVertex)),
               mesh.vertices.data(), GL_STATIC_DRAW);
  upload(reference_buffer_, mesh.nodes, GL_STATIC_DRAW);
  uploaded_mesh_ = mesh.id;
}

void GlRenderer::draw_mesh(const SceneMesh& mesh, const MeshValues& values, const MeshUniforms& u,
                           int width, int height) {
  if (mesh.vertices.empty() || values.nodes.size() < mesh.nodes.size()) return;
  upload_mesh(mesh);
  upload(values_buffer_, values.nodes, GL_STREAM_DRAW);
  upload(elements_buffer_, values.elements, GL_STREAM_DRAW);
  glUseProgram(mesh_program_);
  const auto location = [&](const char* name) { return glGetUniformLocation(mesh_program_, name); };
  glUniform2f(location("viewport"), static_cast<float>(width), static_cast<float>(height));
  glUniform1f(location("magnification"), u.magnification);
  glUniform1f(location("widening"), u.widening);
  glUniform1f(location("pixels_per_unit"), u.pixels_per_unit);
  glUniform1f(location("half_bar_width"), u.half_bar_width);
  glUniform1f(location("rim"), u.rim);
  glUniform1f(location("line_width"), u.line_width);
  glUniform2f(location("center"), u.center[0], u.center[1]);
  glUniform2f(location("pixel_center"), u.pixel_center[0], u.pixel_center[1]);
  glUniform1i(location("by_value"), u.by_value ? 1 : 0);
  const GLuint textures[] = {reference_texture_, values_texture_, elements_texture_};
  for (int i = 0; i < 3; ++i) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE1 + i));
    glBindTexture(GL_TEXTURE_BUFFER, textures[i]);
  }
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(mesh_vao_);
  const auto range = [](const MeshRange& r) {
    if (r.count > 0) glDrawArrays(GL_TRIANGLES, r.first, r.count);
  };
  if (u.rim > 0.0f) range(mesh.bar_rims);
  range(mesh.bar_fills);
  range(mesh.plane_fills);
  if (u.mesh_lines) range(mesh.plane_lines);
  range(mesh.plane_outlines);
}

Image GlRenderer::read_back() {
  context_.make_current();
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_);
  Image image;
  image.width = width_;
  image.height = height_;
  image.rgba.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  // Alpha is 1 everywhere: cleared to 1, and the blend keeps it (1 * a + 1 * (1 - a)).
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  check("while reading a frame back");
  // GL's rows run bottom to top: turn them over in place (no second frame-sized buffer,
  // whose allocation and zeroing cost more than the copy).
  const std::size_t row = static_cast<std::size_t>(width_) * 4;
  std::vector<std::uint8_t> spare(row);
  for (int top = 0, bottom = height_ - 1; top < bottom; ++top, --bottom) {
    std::uint8_t* a = image.rgba.data() + static_cast<std::size_t>(top) * row;
    std::uint8_t* b = image.rgba.data() + static_cast<std::size_t>(bottom) * row;
    std::memcpy(spare.data(), a, row);
    std::memcpy(a, b, row);
    std::memcpy(b, spare.data(), row);
  }
  return image;
}

void GlRenderer::blit_to_default(int x, int y, int target_height) {
  context_.make_current();
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  const int bottom = target_height - y - height_;
  glBlitFramebuffer(0, 0, width_, height_, x, bottom, x + width_, bottom + height_,
                    GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check("while showing a frame");
}

}  // namespace fetic::render
