#pragma once
// Loading a scene file: TOML syntax, keys, types and ranges, [defaults], then the
// cross-checks of validate_scene(). Every problem is reported with file and line.

#include <functional>
#include <string>
#include <string_view>

#include "scenes/scene.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::scenes {

// Largest scene accepted, in unknowns of the assembled problem: beyond it the
// memory of this kind of machine (24 GiB) would not suffice.
inline constexpr long long kMaxUnknowns = 20'000'000;

// Reads (scenes/scene_text.hpp: size limit, no directory) and validates a scene file;
// throws SceneError listing every problem found. `stop` as for read_scene_text().
Scene load_scene_file(const std::string& path, const std::function<bool()>& stop = {});

// Same for a scene given as text; `path` names it in messages.
Scene parse_scene(std::string_view text, const std::string& path);

}  // namespace fetic::scenes
