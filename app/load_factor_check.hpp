#pragma once
// A solve applies the scene's loads times the load factor: those must stay in the range
// the scene's own loads are held to (scenes::kMagnitudeLimit), or the iterations underflow
// to zero or overflow to NaN. A load factor of 0 (no load) is always fine.

#include <string>
#include <vector>

#include "scenes/scene.hpp"

namespace fetic::app {

// "" when every factor fits, else the problem, naming `option` (e.g. "--load-factor"),
// the factor, the load and the product.
std::string load_factor_problem(const scenes::Scene& scene, const std::vector<double>& factors,
                                const std::string& option);

}  // namespace fetic::app
