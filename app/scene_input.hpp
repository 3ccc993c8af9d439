#pragma once
// Loading a scene for a command, with the messages and exit statuses every command shares.

#include <optional>
#include <string>

#include "scenes/scene.hpp"

namespace fetic::app {

// The scene, or nullopt after printing every problem (file:line: message) to stderr, with
// `status` set: kExitInvalidScene, kExitInterrupted (a signal while waiting on a FIFO) or
// kExitOutOfMemory. Warnings are printed as file:line: warning: message.
std::optional<scenes::Scene> load_scene_or_report(const std::string& path, int& status);

}  // namespace fetic::app
