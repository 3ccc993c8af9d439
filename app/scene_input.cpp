#include "app/scene_input.hpp"

#include <iostream>

#include "scenes/load_scene.hpp"

namespace fetic::app {

std::optional<scenes::Scene> load_scene_or_report(const std::string& path) {
  try {
    return scenes::load_scene_file(path);
  } catch (const scenes::SceneError& error) {
    std::cerr << error.what() << '\n';
    return std::nullopt;
  }
}

}  // namespace fetic::app
