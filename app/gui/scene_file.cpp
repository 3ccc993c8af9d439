// Reloading the scene file (F5, the "reload" script action, or a change on disk): a new
// model for the solver; the view, the method and the load factor stay.

#include <exception>
#include <filesystem>
#include <memory>
#include <new>
#include <string>

#include "app/gui/app.hpp"
#include "app/scene_input.hpp"
#include "scenes/load_scene.hpp"

namespace fetic::app::gui {

namespace fs = std::filesystem;

void App::reload() {
  try {
    scenes::Scene scene = scenes::load_scene_file(args_.scene);
    // As at the start (cmd_gui.cpp): a scene grown beyond the memory is refused.
    if (const std::string problem = memory_problem(
            scene, {{solver::MethodKind::FetiC, solver::MethodKind::ActiveSet}, false, 100});
        !problem.empty()) {
      say("reload failed: " + problem, true);
      log_.write({{"event", "error"}, {"message", status_line_}});
      return;
    }
    auto model = std::make_shared<const solver::Model>(solver::build_model(scene));
    target_.model = std::move(model);
    ++target_.model_generation;
    follow_ = true;
    send_to_worker();
    say("reloaded " + args_.scene);
    log_.write({{"event", "reloaded"}, {"scene", args_.scene}});
  } catch (const std::bad_alloc&) {
    say("reload failed: out of memory while reading the scene or assembling its model", true);
    log_.write({{"event", "error"}, {"message", status_line_}});
  } catch (const std::exception& error) {
    say(std::string("reload failed: ") + error.what(), true);
    log_.write({{"event", "error"}, {"message", status_line_}});
  }
}

// A change of the scene file on disk (checked twice a second) reloads it, keeping the view.
void App::watch_scene_file(double now) {
  if (now < next_file_check_) return;
  next_file_check_ = now + 0.5;
  std::error_code error;
  const auto time = fs::last_write_time(args_.scene, error);
  if (!error && time != scene_time_) {
    scene_time_ = time;
    push({RequestKind::Reload, 0.0, {}});
  }
}

}  // namespace fetic::app::gui
