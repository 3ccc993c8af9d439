#include "scenes/generate_scene.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace fetic::scenes {

namespace {

// Frame model: `pairs` pairs of facing portal frames (see generate_scene.hpp).
Scene generate_portal_pairs(const GenerateOptions& o) {
  std::mt19937 rng(o.seed);
  auto uniform = [&](double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(rng);
  };
  Scene scene;
  scene.model = ModelKind::Frame;
  scene.title = "Generated: " + std::to_string(o.pairs) + " pairs of facing portal frames";
  const double width = 4.0, height = 3.0, spacing = 3.0;
  const double E = 2.1e11, area = 2.85e-3, inertia = 1.94e-5;
  auto add = [&](const std::string& name, Point from, Point to, double modulus, bool clamp_from) {
    scene.struts.push_back({.name = name,
                            .from = from,
                            .to = to,
                            .E = modulus,
                            .area = area,
                            .elements = o.elements,
                            .subdomains = o.subdomains,
                            .fixed_from = clamp_from,
                            .inertia = inertia});
    return static_cast<int>(scene.struts.size()) - 1;
  };
  auto joint = [&](EndRef a, EndRef b) {
    Joint j;
    j.ends = {a, b};
    scene.joints.push_back(j);
  };
  double x = 0.0;
  for (int p = 0; p < o.pairs; ++p) {
    if (p % 1024 == 0 && o.stop && o.stop()) break;
    // Gaps from 1 to 5 mm; the wind would sway each frame by 0.5 to 1.5 gaps on its
    // own; stiffness varies by a factor 2.
    const double gap = uniform(1e-3, 5e-3);
    int beams[2];
    for (int side = 0; side < 2; ++side) {
      const double x0 = x + side * (width + gap);
      const double modulus = E * uniform(0.7, 1.4);
      const std::string tag = std::to_string(p + 1) + (side == 0 ? "L" : "R");
      const int left = add("c" + tag + "a", {x0, 0.0}, {x0, height}, modulus, true);
      const int right =
          add("c" + tag + "b", {x0 + width, 0.0}, {x0 + width, height}, modulus, true);
      const int beam = add("b" + tag, {x0, height}, {x0 + width, height}, modulus, false);
      joint({left, StrutEnd::To}, {beam, StrutEnd::From});
      joint({right, StrutEnd::To}, {beam, StrutEnd::To});
      beams[side] = beam;
      // Wind on the outer column toward the other frame: the corner of a portal with
      // clamped feet and rigid corners moves by about w h^4 / (35 E I) under a wind w
      // per length (measured on these frames); each frame closes 0.3 to 1.2 gaps.
      const double sway = 35.0 * modulus * inertia / (height * height * height);
      const double push = sway * gap * uniform(0.3, 1.2);
      Load wind;
      wind.strut = side == 0 ? left : right;
      wind.per_length = true;
      wind.force = {(side == 0 ? 1.0 : -1.0) * push / height, 0.0};
      scene.loads.push_back(wind);
      Load floor;
      floor.strut = beam;
      floor.per_length = true;
      floor.force = {0.0, -uniform(1e4, 3e4)};
      scene.loads.push_back(floor);
    }
    Contact contact;
    contact.a = {beams[0], StrutEnd::To};
    contact.b = {beams[1], StrutEnd::From};
    scene.contacts.push_back(contact);
    x += 2.0 * width + gap + spacing;
  }
  return scene;
}

}  // namespace

long long generated_unknowns(const GenerateOptions& o) {
  // Frame model: six struts of 3 DOFs per node per pair.
  if (o.model == ModelKind::Frame) return 6LL * o.pairs * (o.elements + 1LL) * 3;
  const bool plane = o.model == ModelKind::Plane;
  const long long nodes = (o.elements + 1LL) * (plane ? o.elements_across + 1LL : 1LL);
  return 2LL * o.pairs * nodes * (plane ? 2 : 1);
}

Scene generate_scene(const GenerateOptions& o) {
  if (o.pairs < 1 || o.elements < 1 || o.subdomains < 1 || o.subdomains > o.elements)
    throw std::invalid_argument("need pairs >= 1 and 1 <= subdomains <= elements");
  if (o.model == ModelKind::Frame) return generate_portal_pairs(o);
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
