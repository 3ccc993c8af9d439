#include "scenes/generate_scene.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace fetic::scenes {

long long generated_unknowns(const GenerateOptions& o) {
  const bool plane = o.model == ModelKind::Plane;
  const long long nodes = (o.elements + 1LL) * (plane ? o.elements_across + 1LL : 1LL);
  return 2LL * o.pairs * nodes * (plane ? 2 : 1);
}

Scene generate_scene(const GenerateOptions& o) {
  if (o.pairs < 1 || o.elements < 1 || o.subdomains < 1 || o.subdomains > o.elements)
    throw std::invalid_argument("need pairs >= 1 and 1 <= subdomains <= elements");
  const bool plane = o.model == ModelKind::Plane;
  if (plane &&
      (o.elements_across < 1 || o.subdomains_across < 1 || o.subdomains_across > o.elements_across))
    throw std::invalid_argument("need 1 <= subdomains across <= elements across");
  std::mt19937 rng(o.seed);
  auto uniform = [&](double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(rng);
  };

  Scene scene;
  scene.model = o.model;
  scene.title = "Generated: " + std::to_string(o.pairs) + " pairs of opposing " +
                (plane ? "plane" : "bar") + " struts";
  const double length = 1.0;
  // Square elements in the plane model.
  const double height = plane ? length * o.elements_across / o.elements : 0.0;
  const double spacing = plane ? 2.0 * height : 0.1;
  const double E = 2.1e11, thickness = 0.01, area = 1e-4;
  scene.struts.reserve(2 * static_cast<size_t>(o.pairs));
  scene.loads.reserve((plane ? 2 : 1) * static_cast<size_t>(o.pairs));
  scene.contacts.reserve(static_cast<size_t>(o.pairs));
  for (int p = 0; p < o.pairs; ++p) {
    if (p % 1024 == 0 && o.stop && o.stop()) break;
    const double y = spacing * p;
    // Gaps from 0.3 to 1.2 per mille of the length; a right strut's push would close
    // 0.5 to 2.5 gaps; stiffness varies by a factor 2 around E.
    const double gap = length * uniform(0.3e-3, 1.2e-3);
    const double phase = 2.0 * M_PI * p / std::max(1, o.pairs);
    const double closing = gap * (1.5 + std::sin(phase) + uniform(-0.3, 0.3));
    Strut left, right;
    for (Strut* s : {&left, &right}) {
      s->E = E * uniform(0.7, 1.4);
      s->elements = o.elements;
      s->subdomains = o.subdomains;
      s->area = area;
      s->height = height;
      s->thickness = thickness;
      s->nu = 0.3;
      s->elements_across = plane ? o.elements_across : 0;
      s->subdomains_across = plane ? o.subdomains_across : 1;
    }
    left.name = "L" + std::to_string(p + 1);
    left.from = {0.0, y};
    left.to = {length, y};
    left.fixed_from = true;
    right.name = "R" + std::to_string(p + 1);
    right.from = {length + gap, y};
    right.to = {2.0 * length + gap, y};
    right.fixed_to = true;
    const int li = static_cast<int>(scene.struts.size());
    scene.struts.push_back(left);
    scene.struts.push_back(right);
    const double axial_stiffness = right.E * (plane ? height * thickness : area) / length;
    Load push;
    push.strut = li + 1;
    push.at = StrutEnd::From;
    push.force = {-closing * axial_stiffness, 0.0};
    scene.loads.push_back(push);
    if (plane) {
      // Tilt the left end face by about as much as the closing, across the height.
      const double I = thickness * height * height * height / 12.0;
      const double tilt = closing / height * uniform(0.5, 2.0);
      Load bend;
      bend.strut = li;
      bend.per_length = true;
      bend.force = {0.0,
                    (p % 2 ? 1.0 : -1.0) * tilt * 6.0 * left.E * I / (length * length * length)};
      scene.loads.push_back(bend);
    }
    scene.contacts.push_back({{li, StrutEnd::To}, {li + 1, StrutEnd::From}, 0});
  }
  return scene;
}

}  // namespace fetic::scenes
