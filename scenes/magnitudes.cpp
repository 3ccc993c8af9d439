#include "scenes/magnitudes.hpp"

#include <cmath>

#include "scenes/scene_geometry.hpp"

namespace fetic::scenes {

double load_magnitude(const Scene& scene, const Load& load) {
  const double size = std::hypot(load.force[0], load.force[1]);
  return load.per_length ? size * length(scene.struts.at(load.strut)) : size;
}

}  // namespace fetic::scenes
