#pragma once
// The range of magnitudes fetic solves reliably, shared by the scene checks
// (validate_scene) and the commands that scale the scene's loads (the load factor).

#include <string>

#include "scenes/scene.hpp"

namespace fetic::scenes {

// Double precision squares and sums these scales during the iterations (energies, norms,
// lambda' F lambda); keeping each within [1/kMagnitudeLimit, kMagnitudeLimit] keeps every
// such product far from overflow and underflow. Outside it fetic refuses rather than
// return NaN or a silently rounded answer.
inline constexpr double kMagnitudeLimit = 1e60;

// |value| outside [1/kMagnitudeLimit, kMagnitudeLimit] (also 0), and the words a problem
// says it with: "outside the range double precision solves reliably (1e-60 to 1e+60)".
bool outside_magnitude_range(double value);
std::string magnitude_range_text();

// The total force of a load in N: the force at an end, or the per-length load times the
// strut's length.
double load_magnitude(const Scene& scene, const Load& load);

}  // namespace fetic::scenes
