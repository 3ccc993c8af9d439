#pragma once
// What the mouse, the keyboard and scripts may ask of `fetic gui`. They only queue
// requests; the frame loop applies them all at one sync point per frame, so the three
// inputs cannot disagree and a script drives exactly what a user drives.

#include <string>
#include <vector>

namespace fetic::app::gui {

enum class RequestKind {
  SetLoad,            // value: load factor (0 .. the slider's maximum; a script's beyond it fails)
  SetMethod,          // text: "feti-c", "active-set", ...
  SetPreconditioner,  // text: "dirichlet", "lumped", "none"
  SetCompare,         // text: a second method solving beside the first, or "none"
  SetMagnification,   // value: factor; 0 = automatic
  TogglePlay,
  Play,
  Pause,
  Step,              // one iteration forward in the history of the current solve
  StepBack,          // one iteration back
  Reset,             // back to iteration 0, paused
  SetLive,           // value: 1 = Step and Play advance the solver itself, 0 = solve at once
  Cancel,            // stop the running solve (it stays on screen, marked cancelled)
  Scrub,             // value: iteration to show
  Toggle,            // text: subdomains | forces | gaps | stress | moment | overlay | labels | help
  SetColor,          // text: subdomain | strut | stress | moment (app/view_file.hpp names)
  Screenshot,        // text: file (empty: next name in the screenshot directory)
  RecordIterations,  // every iteration of the current solve as frames
  RecordSweep,       // value: steps; a load sweep 0 .. maximum as frames
  Reload,            // reload the scene file, keeping the view
  ResetView,         // undo pan and zoom
  SaveView,          // text: file (empty: the next fetic_view_NNNN.json in --screenshot-dir)
  LoadView,          // text: a view file (app/view_file.hpp)
  ScreenshotWindow,  // text: file; the whole window, panels included
  Locate,            // text: "pair:K" | "node:STRUT:N": report where it is drawn
  ExportParaView,    // text: directory (empty: --vtu-dir); the shown iterate as a .vtu frame
  Quit,
};

struct Request {
  RequestKind kind = RequestKind::Quit;
  double value = 0.0;
  std::string text;
  int script_line = 0;  // > 0: from this line of --script; a failure ends the run (App::fail)
};

using RequestQueue = std::vector<Request>;

}  // namespace fetic::app::gui
