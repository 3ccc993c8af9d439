#pragma once
// Every key and mouse action of the window, in one table: the key handler looks a key up
// here, and the help overlay (H, F1) lists these rows, so the two cannot disagree.

#include <string>
#include <utility>
#include <vector>

#include "app/gui/requests.hpp"

namespace fetic::app::gui {

struct KeyBinding {
  int key;           // GLFW_KEY_...
  const char* name;  // "Space", "Right", ...
  Request request;   // what the key asks for
  bool repeats;      // held down, it repeats (Right, Left, Home)
  const char* does;  // for the help; keys with the same text share a row ("H, F1")
};

struct MouseBinding {
  const char* gesture;  // "drag", "wheel", ...
  const char* does;
};

const std::vector<KeyBinding>& key_bindings();
// The mouse over the picture (App::mouse, App::picking handle these).
const std::vector<MouseBinding>& mouse_bindings();

// The help's rows: keys that do the same joined ("H, F1"), then the mouse gestures.
std::vector<std::pair<std::string, std::string>> help_rows();

}  // namespace fetic::app::gui
