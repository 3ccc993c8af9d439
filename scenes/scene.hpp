#pragma once
// The scene: struts, loads and contacts exactly as ../spec/SCENES.md defines them.
// Plain data, validated by load_scene(); the solver builds its model from it.

#include <array>

#include <string>
#include <vector>
#include "scenes/scene_error.hpp"
#include "scenes/units.hpp"

namespace fetic::scenes {

using Point = std::array<double, 2>;

enum class ModelKind { Bar, Plane };
enum class StrutEnd { From, To };

struct Strut {
  std::string name;
  Point from{};
  Point to{};
  double E = 0.0;      // Young's modulus
  double area = 0.0;   // bar model: cross-section area
  int elements = 0;    // finite elements along the strut
  int subdomains = 1;  // FETI subdomains along the strut
  bool fixed_from = false;
  bool fixed_to = false;
  // plane model only
  double height = 0.0;
  double thickness = 0.0;
  double nu = 0.0;
  int elements_across = 0;
  int subdomains_across = 1;
  int line = 0;  // line of the [[strut]] header, for messages

  bool fixed(StrutEnd end) const { return end == StrutEnd::From ? fixed_from : fixed_to; }
  bool clamped() const { return fixed_from || fixed_to; }
};

struct EndRef {
  int strut = -1;
  StrutEnd end = StrutEnd::From;
};

struct Load {
  int strut = -1;
  bool per_length = false;  // true: force per unit length along the whole strut
  StrutEnd at = StrutEnd::From;
  Point force{};  // [N] at an end, or [N/m] along the strut
  int line = 0;
};

struct Contact {
  EndRef a;
  EndRef b;
  int line = 0;
};

struct Scene {
  std::string path;  // as the user gave it; every message names it
  std::string title;
  ModelKind model = ModelKind::Bar;
  std::vector<Strut> struts;
  std::vector<Load> loads;
  std::vector<Contact> contacts;
  Units units;  // [units]: what the numbers are in (default m and N)
  // Things that are valid but worth knowing (e.g. a gap at the resolution of the
  // coordinates); the commands print them as "file:line: warning: ...".
  std::vector<Problem> warnings;
};

const char* to_string(ModelKind model);
const char* to_string(StrutEnd end);
// "L01.to"
std::string end_label(const Scene& scene, EndRef ref);
// Nodes per strut face across the axis: 1 in the bar model.
int nodes_across(const Scene& scene, const Strut& strut);
// Unknowns of the assembled problem before supports are removed.
long long unknowns(const Scene& scene);

}  // namespace fetic::scenes
