// fetic gui SCENE: the command line of the interactive window. Reads the script and the
// scene, opens the window (or explains how to do without a display) and runs gui::App
// (app/gui/app.hpp), which is the window itself.

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/gui/app.hpp"
#include "app/gui/iterate_store.hpp"
#include "app/gui/options.hpp"
#include "app/gui/script.hpp"
#include "app/interrupt.hpp"
#include "app/json_input.hpp"
#include "app/load_factor_check.hpp"
#include "app/method_options.hpp"
#include "app/out_of_memory.hpp"
#include "app/output_file.hpp"
#include "app/render_output.hpp"
#include "app/scene_input.hpp"
#include "app/solve_monitor.hpp"
#include "app/view_file.hpp"
#include "render/glfw_window.hpp"
#include "scenes/load_scene.hpp"

namespace fetic::app {
namespace {

namespace fs = std::filesystem;

int run_gui(const gui::Options& args) {
  if (args.size_given && !parse_image_size(args.size)) {
    std::cerr << "--size: expected WxH\n";
    return kExitUsage;
  }
  std::vector<gui::ScriptAction> script;
  if (!args.script.empty()) {
    std::string text;
    try {  // bounded like a view file: a FIFO fed from /dev/zero ends at the limit
      text = read_input_file(args.script, "script");
    } catch (const InputFileError& error) {
      std::cerr << error.what() << '\n';
      return interrupted() ? kExitInterrupted : kExitUsage;
    }
    std::vector<gui::ScriptError> errors;
    script = gui::parse_script(text, errors);
    for (const gui::ScriptError& error : errors)
      std::cerr << scenes::printable(args.script) << ":" << error.line << ": " << error.message
                << '\n';
    if (!errors.empty()) return kExitUsage;
  }
  if (args.monitor_full > 0 && args.monitor.empty()) {
    std::cerr << "fetic gui: --monitor-full needs --monitor FILE\n";
    return kExitUsage;
  }
  if (is_stdout(args.monitor) && is_stdout(args.state_file)) {
    std::cerr << "fetic gui: --monitor - and --state-file - cannot both go to standard output\n";
    return kExitUsage;
  }
  // 0 x 0: the monitor's work area (render::GlfwWindow).
  ImageSize size = args.size_given ? *parse_image_size(args.size) : ImageSize{0, 0};
  int status = kExitOk;
  const std::optional<SavedView> view = read_view_or_report(args.view, status);
  if (!view) return status;
  // The window is the view's picture and the panel beside it (unless --size is given).
  if (view->width && view->height && !args.size_given) {
    size.width = *view->width +
                 static_cast<int>(gui::kPanelWidth * (args.ui_scale > 0.0 ? args.ui_scale : 1.0));
    size.height = *view->height;
  }
  const auto scene = load_scene_or_report(args.scene, status);
  if (!scene) return status;
  for (const auto& [option, value] :
       {std::pair<std::string, double>{"--load", args.load}, {"--max-load", args.max_load}})
    if (const std::string problem = load_factor_problem(*scene, {value}, option);
        !problem.empty()) {
      std::cerr << scenes::printable(args.scene) << ": " << problem << '\n';
      return kExitUsage;
    }
  // The script's loads are held to the same range as --load (a typed 1e300 would overflow
  // the solve; 1e-320 underflows it).
  for (const gui::ScriptAction& action : script)
    if (action.request.kind == gui::RequestKind::SetLoad)
      if (const std::string problem = load_factor_problem(*scene, {action.request.value}, "load");
          !problem.empty()) {
        std::cerr << scenes::printable(args.script) << ":" << action.line << ": " << problem
                  << '\n';
        return kExitUsage;
      }
  // Memory: the methods the window starts with must fit, with the iterates it keeps (a
  // solve's, thinned to kIterateBudget); a method the user may pick later that would not
  // fit is refused when picked (App::refuse_methods), not at the start.
  MemoryUse use;
  use.methods = {*solver::parse_method(args.method)};
  if (!args.compare.empty()) use.methods.push_back(*solver::parse_method(args.compare));
  use.kept_iterates = 100;
  use.kept_iterate_budget = static_cast<double>(gui::kIterateBudget);
  if (!memory_suffices(*scene, args.scene, use, status)) return status;
  std::map<solver::MethodKind, std::string> refusals;
  for (const solver::MethodKind kind : solver::all_methods()) {
    use.methods = {kind};
    if (std::string problem = memory_problem(*scene, use); !problem.empty())
      refusals.emplace(kind, std::move(problem));
  }
  Activity running("running the window");
  auto model = std::make_shared<const solver::Model>(solver::build_model(*scene));
  const std::string title =
      model->title.empty() ? fs::path(args.scene).filename().string() : model->title;
  std::unique_ptr<render::GlfwWindow> window;
  try {
    window = std::make_unique<render::GlfwWindow>(size.width, size.height, "fetic - " + title);
  } catch (const render::NoDisplayError& error) {
    std::cerr << "fetic gui: no display: " << error.what()
              << ".\nThe window needs an X server: run it in a desktop session, or under a "
                 "virtual one (xvfb-run -a fetic gui "
              << args.scene << ").\nWithout a display, render the same pictures to PNG files: "
              << "fetic render " << args.scene << " --out DIR\n";
    return kExitNoDisplay;
  } catch (const render::RenderError& error) {
    std::cerr << "fetic gui: " << error.what() << '\n';
    return kExitNoDisplay;
  }
  gui::App app(args, std::move(model), title);
  app.refuse_methods(std::move(refusals));
  return app.run(*window, std::move(script));
}

}  // namespace

void register_gui(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<gui::Options>();
  CLI::App* command = app.add_subcommand(
      "gui", "Interactive window: load slider, live warm-started FETI-C, iteration history");
  look_up_bundled_scenes(command->add_option("scene", args->scene, kSceneArgumentHelp))->required();
  add_method_option(command, args->method, "Method to start with");
  command
      ->add_option("--compare", args->compare,
                   "A second method solving the same scene at the same load beside the first: "
                   "two pictures, one residual plot with both curves")
      ->check(method_name());
  add_preconditioner_option(command, args->preconditioner, "FETI preconditioner");
  command->add_option("--load", args->load, "Load factor to start at")
      ->check(number_in(0.0, 0.0, Bound::Closed, Bound::None))
      ->capture_default_str();
  command
      ->add_option("--max-load", args->max_load,
                   "Top of the load slider (0: 2, twice the scene's loads)")
      ->check(number_in(0.0, 0.0, Bound::Closed, Bound::None));
  command->add_option("--magnification", args->magnification, "Lock the magnification (0: auto)")
      ->check(number_in(0.0, 0.0, Bound::Closed, Bound::None));
  CLI::Option* size =
      command
          ->add_option("--size", args->size,
                       "Window size in pixels, WxH (default: the monitor's work area)")
          ->check(image_size_check());
  command
      ->add_option("--ui-scale", args->ui_scale,
                   "Scale of the text, controls and lines (default: the monitor's content scale, "
                   "1 on most screens, 2 on doubled ones)")
      ->check(number_in(0.5, 4.0, Bound::Closed, Bound::Closed));
  command->add_option("--view", args->view,
                      "Start with a saved view (JSON; the window's Save view, docs/WINDOW.md)");
  command->add_option("--state-file", args->state_file,
                      "Write what the app does as JSON lines to this file (- for stdout)");
  add_monitor_options(command, args->monitor, args->monitor_full,
                      "Write one JSON line per iteration of every solve the window performs, as "
                      "fetic solve --monitor does (- for stdout)");
  command->add_option("--script", args->script,
                      "Run timed actions from this file (see docs/WINDOW.md)");
  command->add_option("--screenshot-dir", args->screenshot_dir, "Where S saves screenshots")
      ->capture_default_str();
  command->add_option("--record-dir", args->record_dir, "Where recordings go")
      ->capture_default_str();
  command
      ->add_option("--vtu-dir", args->vtu_dir,
                   "Where the ParaView export button writes struts.pvd, contacts.pvd")
      ->capture_default_str();
  command->add_flag("--no-overlay", args->no_overlay, "Start without the information panel");
  command
      ->add_option("--bench", args->bench,
                   "Benchmark: drag the slider over N load changes, then time 30 isolated "
                   "changes; print latency and frame rate, quit")
      ->check(CLI::Range(2, 100000));
  command
      ->add_option("--bench-view", args->bench_view,
                   "Benchmark: after the first solve, pan and zoom the picture over N frames; "
                   "print frames and pictures per second, quit")
      ->check(CLI::Range(2, 100000));
  command->callback([args, size, &exit_code] {
    args->size_given = size->count() > 0;
    exit_code = run_gui(*args);
  });
}

}  // namespace fetic::app
