#pragma once
// An OpenGL 3.3 core context to draw in. Implementations are interchangeable: the EGL one
// is headless (an offscreen frame buffer object is the only target); a windowed one
// (GLFW) can implement the same interface, and GlRenderer works with either.

#include <stdexcept>
#include <string>

namespace fetic::render {

// No display or EGL device could be had; the message says what was tried.
class NoDisplayError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Any other GL failure (shader, frame buffer, GL error).
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class GlContext {
 public:
  virtual ~GlContext() = default;
  // Makes the context current on the calling thread.
  virtual void make_current() = 0;
  // E.g. "EGL 1.5 (surfaceless), OpenGL 4.5 (Core Profile) Mesa 22.3.6, llvmpipe".
  virtual std::string description() const = 0;
};

}  // namespace fetic::render
