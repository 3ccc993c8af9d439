#pragma once
// Random bar scenes for cross-checks, as TOML text (so the loader is exercised too):
// opposing pairs and collinear chains with floating struts, on lines of any direction,
// struts of either orientation, zero and positive gaps, 1 to 3 subdomains per strut,
// end and distributed loads (with components across the axis, which a bar ignores).
// Every floating strut is loaded so that the scene is bounded and its solution unique.

#include <random>
#include <string>

namespace fetic::testing {

std::string random_opposing_pairs(std::mt19937& rng, int pairs);
std::string random_chain(std::mt19937& rng);
// One of the above, or both in one scene.
std::string random_bar_scene(std::mt19937& rng);
// Plane model: `pairs` pairs of facing plane struts on lines of any direction, bent
// across their axis and pushed together so that their end faces often close over only
// part of their height; 1-3 subdomains along, 1-2 across.
std::string random_plane_pairs(std::mt19937& rng, int pairs);
// 1 to 4 clamped struts in any direction with distributed loads, no contacts.
std::string random_contact_free_scene(std::mt19937& rng);

}  // namespace fetic::testing
