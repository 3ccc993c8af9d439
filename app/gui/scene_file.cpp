// Reloading the scene file (F5, the "reload" script action, or a change on disk): a new
// model for the solver; the view, the method and the load factor stay.

#include <exception>
#include <memory>
#include <string>

#include "app/gui/app.hpp"
#include "scenes/load_scene.hpp"

namespace fetic::app::gui {

void App::reload() {
  try {
    scenes::Scene scene = scenes::load_scene_file(args_.scene);
    auto model = std::make_shared<const solver::Model>(solver::build_model(scene));
    target_.model = std::move(model);
    ++target_.model_generation;
    follow_ = true;
    send_to_worker();
    status_line_ = "reloaded " + args_.scene;
    log_.write({{"event", "reloaded"}, {"scene", args_.scene}});
  } catch (const std::exception& error) {
    status_line_ = std::string("reload failed: ") + error.what();
    log_.write({{"event", "error"}, {"message", status_line_}});
  }
}

}  // namespace fetic::app::gui
