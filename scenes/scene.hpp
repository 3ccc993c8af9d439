#pragma once
// The scene: struts, loads, joints and contacts exactly as docs/SCENES.md defines
// them. Plain data, validated by load_scene(); the solver builds its model from it.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scenes/scene_error.hpp"
#include "scenes/units.hpp"

namespace fetic::scenes {

using Point = std::array<double, 2>;

enum class ModelKind { Bar, Plane, Frame };
enum class StrutEnd { From, To };
enum class JointKind { Rigid, Pinned };

struct Strut {
  std::string name;
  Point from{};
  Point to{};
  double E = 0.0;      // Young's modulus
  double area = 0.0;   // bar and frame model: cross-section area
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
  // frame model only
  double inertia = 0.0;      // second moment of area of the cross-section
  bool pinned_from = false;  // pinned support: ux, uy held, rotation free
  bool pinned_to = false;
  int line = 0;  // line of the [[strut]] header, for messages

  bool fixed(StrutEnd end) const { return end == StrutEnd::From ? fixed_from : fixed_to; }
  bool pinned(StrutEnd end) const { return end == StrutEnd::From ? pinned_from : pinned_to; }
  bool clamped() const { return fixed_from || fixed_to; }
};

// A strut end ("NAME.from", "NAME.to") or, in the frame model, any node ("NAME@k").
struct EndRef {
  int strut = -1;
  StrutEnd end = StrutEnd::From;
  int node = -1;  // "NAME@k": node k (0 at 'from'); -1 for an end
};

struct Load {
  int strut = -1;
  bool per_length = false;  // true: force per unit length along the whole strut
  StrutEnd at = StrutEnd::From;
  int node = -1;        // frame model: 'at' given as a node index; -1 for an end
  Point force{};        // [N] at an end, or [N/m] along the strut
  double moment = 0.0;  // frame model: [N m] at the node, counter-clockwise
  int line = 0;
};

struct Contact {
  EndRef a;
  EndRef b;
  bool has_normal = false;  // frame model: 'normal' given
  Point normal{};           // as given (the loader checks it is a unit vector)
  int line = 0;
};

// Frame model: strut ends that meet at one point, connected.
struct Joint {
  std::vector<EndRef> ends;
  JointKind kind = JointKind::Rigid;
  int line = 0;
};

struct Scene {
  std::string path;  // as the user gave it; every message names it
  std::string title;
  ModelKind model = ModelKind::Bar;
  std::vector<Strut> struts;
  std::vector<Load> loads;
  std::vector<Contact> contacts;
  std::vector<Joint> joints;  // frame model
  Units units;                // [units]: what the numbers are in (default m and N)
  // Things that are valid but worth knowing (e.g. a gap at the resolution of the
  // coordinates); the commands print them as "file:line: warning: ...".
  std::vector<Problem> warnings;
};

const char* to_string(ModelKind model);
// The model named "bar", "plane" or "frame".
std::optional<ModelKind> parse_model(std::string_view name);
const char* to_string(StrutEnd end);
const char* to_string(JointKind kind);
// "L01.to", or "beam@4" for a node given by its index
std::string end_label(const Scene& scene, EndRef ref);
// Node of the reference along its strut: 0 at 'from', elements at 'to' (frame and bar).
int node_index(const Scene& scene, EndRef ref);
// Nodes per strut face across the axis: 1 in the bar and frame models.
int nodes_across(const Scene& scene, const Strut& strut);
// Unknowns of the assembled problem before supports are removed.
long long unknowns(const Scene& scene);

}  // namespace fetic::scenes
