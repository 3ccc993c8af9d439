// The sources of requests besides the panel widgets: keys, the mouse over the picture
// (pan, zoom, double-click), and the --script runner, which pushes the very requests a
// user would.

#include <algorithm>
#include <cmath>
#include <iostream>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "app/exit_codes.hpp"
#include "app/gui/app.hpp"
#include "app/gui/bindings.hpp"
#include "app/json_input.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::app::gui {

// GLFW calls this for every key event, before ImGui sees it (ImGui chains to it): a press
// and its release within one frame still count, which polling ImGui's key state would miss.
void App::key_event(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  auto* app = static_cast<App*>(glfwGetWindowUserPointer(window));
  if (!app || action == GLFW_RELEASE) return;
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantTextInput) return;
  for (const KeyBinding& binding : key_bindings())
    if (binding.key == key && (binding.repeats || action != GLFW_REPEAT)) {
      app->push(binding.request);
      return;
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

void App::run_script(std::vector<ScriptAction>& script, std::size_t& next, double now) {
  while (next < script.size()) {
    const ScriptAction& action = script[next];
    if (action.at >= 0 && now < action.at) return;
    if (action.wait) {
      if (wait_started_ < 0) wait_started_ = now;
      // Stepping live, a solve that stopped for the next step counts as settled once its
      // newest iterate is on screen.
      const bool settled_live = live_ && worker_.paused() && shown_ && shown_ == worker_.latest() &&
                                shown_index() == last_index();
      // On screen: with the picture's scales (the survey at the slider's top) too.
      const bool pictured = !shown_ || shown_->extent != nullptr;
      const bool settled = (solved_on_screen_ && !worker_.busy() && pictured) || settled_live;
      if (!settled || recording_ || !queue_.empty()) {
        if (now - wait_started_ > 120.0) {
          std::cerr << scenes::printable(args_.script) << ":" << action.line
                    << ": wait: the solve did not finish within 120 s\n";
          if (script_status_ == 0) script_status_ = kExitNotConverged;
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

void App::fail(const Request& request, const std::string& message, int status) {
  say(message, true);
  nlohmann::json event{{"event", "error"}, {"message", message}};
  if (request.script_line > 0) {
    event["script_line"] = request.script_line;
    std::cerr << scenes::printable(args_.script) << ":" << request.script_line << ": "
              << quoted_value(message, 400) << '\n';
    if (script_status_ == 0) script_status_ = status;
    quit_ = true;
  }
  if (status == kExitOutput)  // the run ends with status 5, scripted or not
    log_.output_lost(message);
  else
    log_.write(event);
}

}  // namespace fetic::app::gui
