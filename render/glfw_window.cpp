#include "render/glfw_window.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace fetic::render {
namespace {

std::string last_glfw_error;

void remember_error(int code, const char* description) {
  last_glfw_error = "GLFW error " + std::to_string(code) + ": " + (description ? description : "");
}

std::string no_display_reason() {
  const char* display = std::getenv("DISPLAY");
  std::string reason = display && *display
                           ? "the X display " + std::string(display) + " could not be opened"
                           : "DISPLAY is not set (no X server)";
  if (!last_glfw_error.empty()) reason += " (" + last_glfw_error + ")";
  return reason;
}

}  // namespace

GlfwWindow::GlfwWindow(int width, int height, const std::string& title) {
  glfwSetErrorCallback(remember_error);
  if (!glfwInit()) throw NoDisplayError(no_display_reason());
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, 0);  // the renderer multisamples its own frame buffer
  glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  int x = 0, y = 0;
  const bool fill = width <= 0 || height <= 0;
  if (fill) {
    width = 1280;
    height = 800;
    if (GLFWmonitor* monitor = glfwGetPrimaryMonitor()) {
      int w = 0, h = 0;
      glfwGetMonitorWorkarea(monitor, &x, &y, &w, &h);
      if (w >= 16 && h >= 16) {
        width = w;
        height = h;
      }
    }
  }
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (window_ && fill) glfwSetWindowPos(window_, x, y);
  if (!window_) {
    const std::string reason = "cannot open a " + std::to_string(width) + "x" +
                               std::to_string(height) +
                               " window with OpenGL 3.3: " + no_display_reason();
    glfwTerminate();
    throw NoDisplayError(reason);
  }
  glfwMakeContextCurrent(window_);
}

GlfwWindow::~GlfwWindow() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

float GlfwWindow::content_scale() const {
  float x = 1.0f, y = 1.0f;
  glfwGetWindowContentScale(window_, &x, &y);
  return std::max(x, y) > 0.0f ? std::max(x, y) : 1.0f;
}

void GlfwWindow::make_current() {
  if (glfwGetCurrentContext() != window_) glfwMakeContextCurrent(window_);
}

std::string GlfwWindow::description() const {
  const auto text = [](GLenum name) {
    const auto* value = reinterpret_cast<const char*>(glGetString(name));
    return std::string(value ? value : "?");
  };
  return "GLFW " + std::string(glfwGetVersionString()) + ", OpenGL " + text(GL_VERSION) + ", " +
         text(GL_RENDERER);
}

}  // namespace fetic::render
