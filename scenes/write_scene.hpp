#pragma once
// A scene as TOML text in the format load_scene() reads (round trip: parsing the text
// gives the same scene). Numbers are written with 17 significant digits.

#include <string>

#include "scenes/scene.hpp"

namespace fetic::scenes {

std::string scene_to_toml(const Scene& scene);

}  // namespace fetic::scenes
