#pragma once
// Scripted runs of `fetic gui` (--script FILE), for tests and demos. One action a line:
//
//   [TIME] ACTION [ARGUMENT]     # TIME: seconds after the window opened (optional)
//
// Actions run in order; one with a TIME waits until then. Actions: load T, method NAME,
// preconditioner NAME, magnification M|auto, play, pause, step, back, reset, scrub I,
// live on|off, cancel, toggle subdomains|forces|gaps|stress|moment|overlay|labels|help,
// color subdomain|strut|stress|moment, screenshot [FILE], view FILE (a saved view, applied before
// the next picture), save-view [FILE], record-iterations, record-sweep N, export-vtu [DIR], reload,
// wait (until the current solve has finished - or, stepping live, has stopped for the next step -
// and is on screen), quit. Each becomes the same request a key or a panel widget makes. Method and
// preconditioner names are checked here, so a misspelt one is refused before the window opens
// rather than ignored at run time.

#include <optional>
#include <string>
#include <vector>

#include "app/gui/requests.hpp"

namespace fetic::app::gui {

struct ScriptAction {
  int line = 0;
  double at = -1.0;   // seconds after start; < 0: as soon as the previous one is done
  bool wait = false;  // "wait": until the solver is idle and its state is shown
  Request request;    // otherwise
};

struct ScriptError {
  int line = 0;
  std::string message;
};

// Parses a script; on errors returns them all (file:line: message style, without file).
std::vector<ScriptAction> parse_script(const std::string& text, std::vector<ScriptError>& errors);

}  // namespace fetic::app::gui
