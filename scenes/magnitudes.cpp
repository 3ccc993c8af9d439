#include "scenes/magnitudes.hpp"

#include <cmath>

#include "scenes/message_text.hpp"
#include "scenes/scene_geometry.hpp"

namespace fetic::scenes {

bool outside_magnitude_range(double value) {
  const double magnitude = std::abs(value);
  return magnitude > kMagnitudeLimit || magnitude < 1.0 / kMagnitudeLimit;
}

std::string magnitude_range_text() {
  return "outside the range double precision solves reliably (" +
         number_text(1.0 / kMagnitudeLimit) + " to " + number_text(kMagnitudeLimit) + ")";
}

double load_magnitude(const Scene& scene, const Load& load) {
  const double size = std::hypot(load.force[0], load.force[1]);
  return load.per_length ? size * length(scene.struts.at(load.strut)) : size;
}

}  // namespace fetic::scenes
