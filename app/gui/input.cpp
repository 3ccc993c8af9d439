// The sources of requests besides the panel widgets: keys, the mouse over the picture
// (pan, zoom, double-click), and the --script runner, which pushes the very requests a
// user would.

#include <algorithm>
#include <cmath>
#include <iostream>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "app/gui/app.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::app::gui {

// GLFW calls this for every key event, before ImGui sees it (ImGui chains to it): a press
// and its release within one frame still count, which polling ImGui's key state would miss.
void App::key_event(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  auto* app = static_cast<App*>(glfwGetWindowUserPointer(window));
  if (!app || action == GLFW_RELEASE) return;
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantTextInput) return;
  const bool repeat = action == GLFW_REPEAT;
  switch (key) {
    case GLFW_KEY_SPACE:
      if (!repeat) app->push({RequestKind::TogglePlay, 0.0, {}});
      break;
    case GLFW_KEY_RIGHT:
      app->push({RequestKind::Step, 0.0, {}});
      break;
    case GLFW_KEY_LEFT:
      app->push({RequestKind::StepBack, 0.0, {}});
      break;
    case GLFW_KEY_R:
      if (!repeat) app->push({RequestKind::Reset, 0.0, {}});
      break;
    case GLFW_KEY_S:
      if (!repeat) app->push({RequestKind::Screenshot, 0.0, {}});
      break;
    case GLFW_KEY_C:
      if (!repeat) app->push({RequestKind::Cancel, 0.0, {}});
      break;
    case GLFW_KEY_F5:
      if (!repeat) app->push({RequestKind::Reload, 0.0, {}});
      break;
    case GLFW_KEY_H:
    case GLFW_KEY_F1:
      if (!repeat) app->push({RequestKind::Toggle, 0.0, "help"});
      break;
    case GLFW_KEY_W:
      if (!repeat) app->push({RequestKind::ScreenshotWindow, 0.0, {}});
      break;
    case GLFW_KEY_V:
      if (!repeat) app->push({RequestKind::SaveView, 0.0, {}});
      break;
    case GLFW_KEY_HOME:
      app->push({RequestKind::ResetView, 0.0, {}});
      break;
    case GLFW_KEY_Q:
    case GLFW_KEY_ESCAPE:
      app->push({RequestKind::Quit, 0.0, {}});
      break;
    default:
      break;
  }
}

void App::mouse(float view_x, float view_width, float view_height) {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse) return;
  const render::Point at{io.MousePos.x - view_x, io.MousePos.y};
  if (at.x < 0 || at.y < 0 || at.x > view_width || at.y > view_height) return;
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Left) ||
      ImGui::IsMouseDragging(ImGuiMouseButton_Right)) {
    pan_.x += io.MouseDelta.x;
    pan_.y += io.MouseDelta.y;
    redraw_ = true;
    view_moved_ = Clock::now();
  }
  if (io.MouseWheel != 0.0f) {
    const float factor = std::pow(1.15f, io.MouseWheel);
    const float new_zoom = std::clamp(zoom_ * factor, 0.05f, 200.0f);
    const float f = new_zoom / zoom_;
    // Keep the point under the cursor where it is.
    const float cx = base_center_.x + pan_.x, cy = base_center_.y + pan_.y;
    pan_.x = at.x - (at.x - cx) * f - base_center_.x;
    pan_.y = at.y - (at.y - cy) * f - base_center_.y;
    zoom_ = new_zoom;
    redraw_ = true;
    view_moved_ = Clock::now();
  }
  if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) push({RequestKind::ResetView, 0.0, {}});
}

void App::run_script(std::vector<ScriptAction>& script, std::size_t& next, double now,
                     bool& failed) {
  while (next < script.size()) {
    const ScriptAction& action = script[next];
    if (action.at >= 0 && now < action.at) return;
    if (action.wait) {
      if (wait_started_ < 0) wait_started_ = now;
      // Stepping live, a solve that stopped for the next step counts as settled once its
      // newest iterate is on screen.
      const bool settled_live = live_ && worker_.paused() && shown_ && shown_ == worker_.latest() &&
                                shown_index() == last_index();
      const bool settled = (solved_on_screen_ && !worker_.busy()) || settled_live;
      if (!settled || recording_ || !queue_.empty()) {
        if (now - wait_started_ > 120.0) {
          std::cerr << scenes::printable(args_.script) << ":" << action.line
                    << ": wait: the solve did not finish within 120 s\n";
          failed = true;
          quit_ = true;
        }
        return;
      }
      wait_started_ = -1.0;
    } else {
      push(action.request);
    }
    ++next;
    if (!action.wait) return;  // one request a frame, like a user
  }
}

}  // namespace fetic::app::gui
