#pragma once
// Cross-checks of a scene whose keys, types and ranges are already valid: references,
// contact geometry (facing, collinear, no overlap, matching faces) and whether every
// strut can be held by a support, directly or through contacts.

#include <functional>
#include <vector>

#include "scenes/scene.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::scenes {

// Returns the problems that make the scene invalid; fills scene.warnings.
// `stop`: asked between the steps of long checks (frame_kinematics.hpp).
std::vector<Problem> validate_scene(Scene& scene, const std::function<bool()>& stop = {});

}  // namespace fetic::scenes
