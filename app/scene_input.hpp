#pragma once
// Loading a scene and building its model for a command, with the messages and exit
// status every command shares.

#include <optional>
#include <string>

#include "scenes/scene.hpp"
#include "solver/model.hpp"

namespace fetic::app {

// The scene, or nullopt after printing every problem (file:line: message) to stderr.
std::optional<scenes::Scene> load_scene_or_report(const std::string& path);

}  // namespace fetic::app
