#include "app/gui/bindings.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace fetic::app::gui {
namespace {

// What a key asks for: a request without a value (the help keys name the panel they toggle).
Request key_asks(RequestKind kind, const char* text = "") {
  return {kind, 0.0, text};
}

}  // namespace

const std::vector<KeyBinding>& key_bindings() {
  static const std::vector<KeyBinding> table{
      {GLFW_KEY_SPACE, "Space", key_asks(RequestKind::TogglePlay), false,
       "play / pause the iterations"},
      {GLFW_KEY_RIGHT, "Right", key_asks(RequestKind::Step), true, "one iteration forward"},
      {GLFW_KEY_LEFT, "Left", key_asks(RequestKind::StepBack), true, "one iteration back"},
      {GLFW_KEY_R, "R", key_asks(RequestKind::Reset), false, "reset to iteration 0"},
      {GLFW_KEY_C, "C", key_asks(RequestKind::Cancel), false, "cancel the running solve"},
      {GLFW_KEY_S, "S", key_asks(RequestKind::Screenshot), false,
       "screenshot of the picture (PNG in --screenshot-dir)"},
      {GLFW_KEY_W, "W", key_asks(RequestKind::ScreenshotWindow), false,
       "screenshot of the whole window"},
      {GLFW_KEY_V, "V", key_asks(RequestKind::SaveView), false,
       "save the view (JSON in --screenshot-dir)"},
      {GLFW_KEY_F5, "F5", key_asks(RequestKind::Reload), false, "reload the scene file"},
      {GLFW_KEY_HOME, "Home", key_asks(RequestKind::ResetView), true, "reset pan and zoom"},
      {GLFW_KEY_H, "H", key_asks(RequestKind::Toggle, "help"), false, "this help"},
      {GLFW_KEY_F1, "F1", key_asks(RequestKind::Toggle, "help"), false, "this help"},
      {GLFW_KEY_Q, "Q", key_asks(RequestKind::Quit), true, "quit"},
      {GLFW_KEY_ESCAPE, "Esc", key_asks(RequestKind::Quit), true, "quit"},
  };
  return table;
}

const std::vector<MouseBinding>& mouse_bindings() {
  static const std::vector<MouseBinding> table{
      {"drag", "pan the picture"},
      {"wheel", "zoom about the pointer"},
      {"double-click", "reset pan and zoom"},
      {"hover", "the values of the node or contact pair under the pointer"},
      {"click", "pin it to the Picked window (click again: unpin)"},
  };
  return table;
}

std::vector<std::pair<std::string, std::string>> help_rows() {
  std::vector<std::pair<std::string, std::string>> rows;
  for (const KeyBinding& key : key_bindings()) {
    if (!rows.empty() && rows.back().second == key.does)
      rows.back().first += std::string(", ") + key.name;
    else
      rows.emplace_back(key.name, key.does);
  }
  for (const MouseBinding& mouse : mouse_bindings())
    rows.emplace_back(std::string("mouse ") + mouse.gesture, mouse.does);
  return rows;
}

}  // namespace fetic::app::gui
