#include "app/gui/bindings.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace fetic::app::gui {

const std::vector<KeyBinding>& key_bindings() {
  static const std::vector<KeyBinding> table{
      {GLFW_KEY_SPACE,
       "Space",
       {RequestKind::TogglePlay, 0.0, {}},
       false,
       "play / pause the iterations"},
      {GLFW_KEY_RIGHT, "Right", {RequestKind::Step, 0.0, {}}, true, "one iteration forward"},
      {GLFW_KEY_LEFT, "Left", {RequestKind::StepBack, 0.0, {}}, true, "one iteration back"},
      {GLFW_KEY_R, "R", {RequestKind::Reset, 0.0, {}}, false, "reset to iteration 0"},
      {GLFW_KEY_C, "C", {RequestKind::Cancel, 0.0, {}}, false, "cancel the running solve"},
      {GLFW_KEY_S,
       "S",
       {RequestKind::Screenshot, 0.0, {}},
       false,
       "screenshot of the picture (PNG in --screenshot-dir)"},
      {GLFW_KEY_W,
       "W",
       {RequestKind::ScreenshotWindow, 0.0, {}},
       false,
       "screenshot of the whole window"},
      {GLFW_KEY_V,
       "V",
       {RequestKind::SaveView, 0.0, {}},
       false,
       "save the view (JSON in --screenshot-dir)"},
      {GLFW_KEY_F5, "F5", {RequestKind::Reload, 0.0, {}}, false, "reload the scene file"},
      {GLFW_KEY_HOME, "Home", {RequestKind::ResetView, 0.0, {}}, true, "reset pan and zoom"},
      {GLFW_KEY_H, "H", {RequestKind::Toggle, 0.0, "help"}, false, "this help"},
      {GLFW_KEY_F1, "F1", {RequestKind::Toggle, 0.0, "help"}, false, "this help"},
      {GLFW_KEY_Q, "Q", {RequestKind::Quit, 0.0, {}}, true, "quit"},
      {GLFW_KEY_ESCAPE, "Esc", {RequestKind::Quit, 0.0, {}}, true, "quit"},
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
