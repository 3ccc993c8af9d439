#pragma once
// Cross-checks of a frame scene whose keys, types and ranges are already valid: joints
// (ends that meet at one point, each end in one joint), contacts (two struts, a normal
// where the nodes coincide, no negative gap, no repeated pair), magnitudes of bending
// stiffness and moments, and mechanisms (frame_kinematics.hpp).

#include <cstddef>
#include <functional>
#include <vector>

#include "scenes/scene.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::scenes {

// Ends per joint: every pair of ends gets a gluing row per shared DOF (k (k-1) / 2 of
// them), and the solver's projection onto range(B) works on at most this many copies.
inline constexpr std::size_t kMaxJointEnds = 64;

// Appends the problems found; adds warnings to scene.warnings.
void validate_frame(Scene& scene, std::vector<Problem>& problems,
                    const std::function<bool()>& stop = {});

}  // namespace fetic::scenes
