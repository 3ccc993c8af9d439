#include "app/scene_input.hpp"

#include <iostream>
#include <new>

#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "scenes/load_scene.hpp"

namespace fetic::app {

std::optional<scenes::Scene> load_scene_or_report(const std::string& path, int& status) {
  try {
    scenes::Scene scene = scenes::load_scene_file(path, [] { return interrupted(); });
    for (const scenes::Problem& warning : scene.warnings)
      std::cerr << scenes::format_problems(path, {{warning.line, "warning: " + warning.message}})
                << '\n';
    return scene;
  } catch (const scenes::SceneError& error) {
    if (interrupted()) {
      std::cerr << scenes::printable(path) << ": interrupted by " << interrupt_name()
                << " while opening or reading the scene file\n";
      status = kExitInterrupted;
    } else {
      std::cerr << error.what() << '\n';
      status = kExitInvalidScene;
    }
  } catch (const std::bad_alloc&) {
    std::cerr << scenes::printable(path) << ": out of memory while reading the scene\n";
    status = kExitOutOfMemory;
  }
  return std::nullopt;
}

}  // namespace fetic::app
