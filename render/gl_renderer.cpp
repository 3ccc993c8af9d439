#include "render/gl_renderer.hpp"

#include <algorithm>
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

GLuint compile(GLenum kind, const char* source) {
  const GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw RenderError(std::string("cannot compile the renderer's shader: ") + log);
  }
  return shader;
}

void check(const char* what) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
    throw RenderError(std::string("OpenGL error ") + std::to_string(error) + " " + what);
}

}  // namespace

GlRenderer::GlRenderer(GlContext& context, const FontAtlas& font) : context_(context), font_(font) {
  context_.make_current();
  const GLuint vertex = compile(GL_VERTEX_SHADER, kVertexShader);
  const GLuint fragment = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  program_ = glCreateProgram();
  glAttachShader(program_, vertex);
  glAttachShader(program_, fragment);
  glLinkProgram(program_);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint linked = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &linked);
  if (!linked) throw RenderError("cannot link the renderer's shader program");
  viewport_location_ = glGetUniformLocation(program_, "viewport");

  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  const auto stride = static_cast<GLsizei>(sizeof(TexturedVertex));
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<void*>(offsetof(TexturedVertex, x)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<void*>(offsetof(TexturedVertex, u)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride,
                        reinterpret_cast<void*>(offsetof(TexturedVertex, rgba)));

  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, font_.texture_width(), font_.texture_height(), 0,
               GL_RGBA, GL_UNSIGNED_BYTE, font_.texture_rgba());
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  max_samples_ = std::max(1, static_cast<int>(max_samples));
  samples_ = std::min(4, max_samples_);
  check("while setting up the renderer");
}

GlRenderer::~GlRenderer() {
  release_targets();
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

Image GlRenderer::render(int width, int height, const std::vector<const DrawList*>& layers,
                         Color background) {
  draw(width, height, layers, background);
  return read_back();
}

void GlRenderer::draw(int width, int height, const std::vector<const DrawList*>& layers,
                      Color background) {
  context_.make_current();
  resize(width, height);
  vertices_.clear();
  for (const DrawList* layer : layers)
    if (layer) append(*layer, vertices_);

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
  glUseProgram(program_);
  glUniform2f(viewport_location_, static_cast<float>(width), static_cast<float>(height));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices_.size() * sizeof(TexturedVertex)),
               vertices_.data(), GL_STREAM_DRAW);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_.size()));

  glBindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
  glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check("while drawing a frame");
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
