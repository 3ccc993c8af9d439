#include "app/load_factor_check.hpp"

#include <cmath>
#include <cstdio>

#include "scenes/magnitudes.hpp"

namespace fetic::app {
namespace {

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace

std::string load_factor_problem(const scenes::Scene& scene, const std::vector<double>& factors,
                                const std::string& option) {
  for (const double t : factors) {
    if (t == 0.0) continue;
    for (const scenes::Load& load : scene.loads) {
      const double magnitude = scenes::load_magnitude(scene, load);
      if (magnitude == 0.0) continue;
      const double scaled = std::abs(t) * magnitude;
      if (scaled >= 1.0 / scenes::kMagnitudeLimit && scaled <= scenes::kMagnitudeLimit) continue;
      return option + " " + number(t) + ": times the load on strut '" +
             scene.struts[load.strut].name + "' (line " + std::to_string(load.line) + ", " +
             number(magnitude) + " N) it gives " + number(scaled) +
             " N, outside the range double precision solves reliably (" +
             number(1.0 / scenes::kMagnitudeLimit) + " to " + number(scenes::kMagnitudeLimit) +
             " N); use a load factor of 0 or one that keeps every load in it";
    }
  }
  return "";
}

}  // namespace fetic::app
