#pragma once
// Loading a scene for a command, with the messages and exit statuses every command shares.

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "app/memory_estimate.hpp"
#include "scenes/scene.hpp"

namespace fetic::app {

// Makes a scene argument (or each of a list) name a bundled scene when no such path
// exists relative to the working directory (data_paths.hpp, find_scene).
CLI::Option* look_up_bundled_scenes(CLI::Option* option);

// The help text of a command's scene argument.
inline constexpr const char* kSceneArgumentHelp =
    "Scene file (TOML, see docs/SCENES.md), or a bundled scene's name (fetic scenes)";

// The scene, or nullopt after printing every problem (file:line: message) to stderr, with
// `status` set: kExitInvalidScene, kExitInterrupted (a signal while waiting on a FIFO) or
// kExitOutOfMemory. Warnings are printed as file:line: warning: message.
// A regular file whose parsing would need more memory than is available is refused before
// it is read (kExitOutOfMemory).
std::optional<scenes::Scene> load_scene_or_report(const std::string& path, int& status);

// False, after printing the estimate, what is available and what limits it (status
// kExitOutOfMemory), when `use` of the scene needs more memory than the process may
// have. Called before the model is built (docs/RELIABILITY.md, "Memory").
// The refusal's text ("not enough memory: ... needs about ..., and ... is available (...)"),
// or "" when the scene fits.
std::string memory_problem(const scenes::Scene& scene, const MemoryUse& use);
bool memory_suffices(const scenes::Scene& scene, const std::string& path, const MemoryUse& use,
                     int& status);

}  // namespace fetic::app
