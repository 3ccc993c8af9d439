#include "app/scene_input.hpp"

#include <iostream>

#include "scenes/load_scene.hpp"

namespace fetic::app {

std::optional<scenes::Scene> load_scene_or_report(const std::string& path) {
  try {
    scenes::Scene scene = scenes::load_scene_file(path);
    for (const scenes::Problem& warning : scene.warnings)
      std::cerr << scenes::format_problems(path, {{warning.line, "warning: " + warning.message}})
                << '\n';
    return scene;
  } catch (const scenes::SceneError& error) {
    std::cerr << error.what() << '\n';
    return std::nullopt;
  }
}

}  // namespace fetic::app
