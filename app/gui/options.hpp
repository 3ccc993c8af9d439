#pragma once
// The command line of `fetic gui` (registered in cmd_gui.cpp).

#include <string>

namespace fetic::app::gui {

struct Options {
  std::string scene;
  std::string method = "feti-c";
  std::string preconditioner = "dirichlet";
  std::string compare;  // a second method solving beside the first; empty: none
  double load = 1.0;
  double max_load = 0.0;  // 0: chosen from the scene (solver::automatic_max_load)
  double magnification = 0.0;
  std::string size;         // "WxH"; empty: the monitor's work area
  bool size_given = false;  // --size on the command line (it wins over a view's size)
  double ui_scale = 0.0;    // text and controls; 0: the monitor's content scale
  std::string state_file;
  std::string script;
  std::string screenshot_dir = ".";
  std::string view;  // a saved view to start with (app/view_file.hpp)
  std::string record_dir = "fetic-recordings";
  std::string monitor;   // --monitor: the solve's JSON lines (app/solve_monitor.hpp)
  int monitor_full = 0;  // --monitor-full N: the state every N-th iteration
  std::string vtu_dir = "fetic-paraview";  // where "ParaView export" writes
  bool no_overlay = false;
  int bench = 0;       // load changes of the benchmark drag; 0: no benchmark
  int bench_view = 0;  // frames of the pan-and-zoom benchmark; 0: none
};

}  // namespace fetic::app::gui
