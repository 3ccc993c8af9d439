#pragma once
// A window with an OpenGL 3.3 core context (GLFW, X11): the interactive app draws into it
// with the same GlRenderer as the headless path and blits the picture to its back buffer.

#include <string>

#include "render/gl_context.hpp"

struct GLFWwindow;

namespace fetic::render {

class GlfwWindow final : public GlContext {
 public:
  // Opens a resizable window of width x height pixels; width or height 0: the primary
  // monitor's work area (the screen without panels and docks), placed on it. Throws
  // NoDisplayError when GLFW cannot reach a display (no X server, DISPLAY unset), naming
  // GLFW's reason.
  GlfwWindow(int width, int height, const std::string& title);
  ~GlfwWindow() override;
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;

  void make_current() override;
  std::string description() const override;
  GLFWwindow* handle() const { return window_; }
  // The monitor's content scale (1 on an ordinary screen, 2 on a doubled "HiDPI" one).
  float content_scale() const;

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace fetic::render
