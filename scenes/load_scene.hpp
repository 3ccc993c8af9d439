#pragma once
// Loading a scene file: TOML syntax, keys, types and ranges, [defaults], then the
// cross-checks of validate_scene(). Every problem is reported with file and line.

#include <string>
#include <string_view>

#include "scenes/scene.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::scenes {

// Largest scene accepted, in unknowns of the assembled problem: beyond it the
// memory of this kind of machine (24 GiB) would not suffice.
inline constexpr long long kMaxUnknowns = 20'000'000;

// Reads and validates a scene file; throws SceneError listing every problem found.
Scene load_scene_file(const std::string& path);

// Same for a scene given as text; `path` names it in messages.
Scene parse_scene(std::string_view text, const std::string& path);

}  // namespace fetic::scenes
