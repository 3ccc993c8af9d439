#include "tests/support/random_frames.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "tests/support/random_draws.hpp"

namespace fetic::testing {
namespace {

struct V {
  double x = 0.0, y = 0.0;
};
V operator+(V a, V b) {
  return {a.x + b.x, a.y + b.y};
}
V operator-(V a, V b) {
  return {a.x - b.x, a.y - b.y};
}
V operator*(double s, V a) {
  return {s * a.x, s * a.y};
}
V unit(double angle) {
  return {std::cos(angle), std::sin(angle)};
}

// Writes a scene drawn in local axes, turned by `angle` and moved to `origin`.
class FrameWriter {
 public:
  explicit FrameWriter(std::mt19937& rng) : rng_(rng) {
    angle_ = uniform(rng, 0.0, 2.0 * kPi);
    origin_ = {uniform(rng, -5.0, 5.0), uniform(rng, -5.0, 5.0)};
  }

  // A strut between local points a and b, written either way round; `support_a` and
  // `support_b` are "", "fixed" or "pinned". Returns its name; end(name, at_a) gives the
  // reference of its end at a or b.
  std::string strut(V a, V b, double E, double area, double inertia, int elements,
                    const std::string& support_a, const std::string& support_b) {
    const std::string name = "S" + std::to_string(++count_);
    const bool reversed = chance(rng_, 0.5);
    reversed_.push_back(reversed);
    elements_.push_back(elements);
    const V from = reversed ? b : a, to = reversed ? a : b;
    const std::string& s_from = reversed ? support_b : support_a;
    const std::string& s_to = reversed ? support_a : support_b;
    text_ += "\n[[strut]]\nname = \"" + name + "\"\nfrom = " + point(from) + "\nto = " + point(to) +
             "\nE = " + toml_number(E) + "\narea = " + toml_number(area) +
             "\ninertia = " + toml_number(inertia) + "\nelements = " + std::to_string(elements) +
             "\nsubdomains = " + std::to_string(integer(rng_, 1, std::min(3, elements))) + "\n";
    for (const char* kind : {"fixed", "pinned"}) {
      std::string list;
      if (s_from == kind) list += "\"from\"";
      if (s_to == kind) list += std::string(list.empty() ? "" : ", ") + "\"to\"";
      if (!list.empty()) text_ += std::string(kind) + " = [" + list + "]\n";
    }
    return name;
  }

  // The end of a strut at its local point a (true) or b (false), sometimes as "NAME@k".
  std::string end(const std::string& name, bool at_a, bool allow_index = true) {
    const int s = std::stoi(name.substr(1)) - 1;
    const bool from = at_a != reversed_[s];
    if (allow_index && chance(rng_, 0.3))
      return name + "@" + std::to_string(from ? 0 : elements_[s]);
    return name + (from ? ".from" : ".to");
  }
  // Node k counted from the strut's local point a.
  std::string node(const std::string& name, int k_from_a) {
    const int s = std::stoi(name.substr(1)) - 1;
    const int k = reversed_[s] ? elements_[s] - k_from_a : k_from_a;
    if (k == 0 && chance(rng_, 0.5)) return name + ".from";
    if (k == elements_[s] && chance(rng_, 0.5)) return name + ".to";
    return name + "@" + std::to_string(k);
  }

  void joint(const std::vector<std::string>& ends, bool rigid) {
    text_ += "\n[[joint]]\nends = [";
    for (size_t i = 0; i < ends.size(); ++i)
      text_ += (i ? ", \"" : "\"") + ends[i] + "\"";
    text_ += "]\n";
    if (!rigid || chance(rng_, 0.5))
      text_ += std::string("kind = \"") + (rigid ? "rigid" : "pinned") + "\"\n";
  }

  void force(const std::string& strut, const std::string& at, V f, double moment = 0.0) {
    text_ += "\n[[load]]\nstrut = \"" + strut + "\"\nat = " + at + "\nforce = " + vector(f) + "\n";
    if (moment != 0.0) text_ += "moment = " + toml_number(moment) + "\n";
  }
  // 'at' as TOML for node k counted from the strut's local point a (-1: its point b):
  // "\"from\"", "\"to\"" or the node index.
  std::string at(const std::string& name, int k_from_a) {
    const int s = std::stoi(name.substr(1)) - 1;
    if (k_from_a < 0) k_from_a = elements_[s];
    const int k = reversed_[s] ? elements_[s] - k_from_a : k_from_a;
    if (k == 0 && chance(rng_, 0.5)) return "\"from\"";
    if (k == elements_[s] && chance(rng_, 0.5)) return "\"to\"";
    return std::to_string(k);
  }
  int elements(const std::string& name) const { return elements_[std::stoi(name.substr(1)) - 1]; }
  void per_length(const std::string& strut, V q) {
    text_ += "\n[[load]]\nstrut = \"" + strut + "\"\nper_length = " + vector(q) + "\n";
  }

  // A contact from node a toward node b along the local unit normal n; the normal is
  // written when asked (always needed where the nodes coincide), and a and b are swapped
  // half of the time.
  void contact(const std::string& a, const std::string& b, V n, bool write_normal) {
    const bool swap = chance(rng_, 0.5);
    text_ += "\n[[contact]]\na = \"" + (swap ? b : a) + "\"\nb = \"" + (swap ? a : b) + "\"\n";
    if (write_normal) text_ += "normal = " + vector(swap ? -1.0 * n : n) + "\n";
  }

  std::string text() const { return "title = \"random frame\"\nmodel = \"frame\"\n" + text_; }

 private:
  V turn(V v) const {
    const double c = std::cos(angle_), s = std::sin(angle_);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
  }
  std::string point(V p) const {
    const V q = turn(p) + origin_;
    return "[" + toml_number(q.x) + ", " + toml_number(q.y) + "]";
  }
  std::string vector(V v) const {
    const V q = turn(v);
    return "[" + toml_number(q.x) + ", " + toml_number(q.y) + "]";
  }

  std::mt19937& rng_;
  double angle_ = 0.0;
  V origin_;
  int count_ = 0;
  std::vector<bool> reversed_;
  std::vector<int> elements_;
  std::string text_;
};

double random_gap(std::mt19937& rng) {
  return chance(rng, 0.25) ? 0.0 : uniform(rng, 2e-4, 2e-3);
}
// Loads scaled to move a part of stiffness k by about a gap (or a millimetre).
double sized_force(std::mt19937& rng, double k, double gap) {
  return k * std::max(gap, 1e-3) * uniform(rng, 0.3, 3.0);
}

// Supports of a strut's two ends that never leave it a mechanism on its own.
const char* kBeamSupports[5][2] = {{"fixed", "fixed"},
                                   {"fixed", "pinned"},
                                   {"pinned", "fixed"},
                                   {"pinned", "pinned"},
                                   {"fixed", ""}};

void post_on_beam(std::mt19937& rng, FrameWriter& w) {
  const double L = uniform(rng, 1.5, 3.0), E = uniform(rng, 1e11, 3e11);
  const double Ab = uniform(rng, 1e-3, 4e-3), Ib = uniform(rng, 2e-6, 2e-5);
  const int eb = integer(rng, 2, 6);
  const auto& sup = kBeamSupports[integer(rng, 0, 4)];
  const std::string beam = w.strut({0, 0}, {L, 0}, E, Ab, Ib, eb, sup[0], sup[1]);
  const bool cantilever = std::string(sup[1]).empty();
  const int k = cantilever ? integer(rng, 1, eb) : integer(rng, 1, eb - 1);
  const double x = L * k / eb, g = random_gap(rng), H = uniform(rng, 0.5, 1.5);
  // Sometimes the tip is offset along the beam: the normal is then given, not implied.
  const double offset = chance(rng, 0.3) ? uniform(rng, -0.05, 0.05) : 0.0;
  const double Ap = uniform(rng, 5e-4, 2e-3), Ip = uniform(rng, 1e-7, 2e-6);
  const V top{x + offset, H}, tip{x + offset, g};
  std::string lower;
  if (chance(rng, 0.3)) {  // the post in two pieces, joined rigidly
    const V middle{x + offset, 0.5 * (H + g)};
    const std::string upper = w.strut(top, middle, E, Ap, Ip, integer(rng, 1, 4), "fixed", "");
    lower = w.strut(middle, tip, E, Ap, Ip, integer(rng, 1, 4), "", "");
    w.joint({w.end(upper, false, false), w.end(lower, true, false)}, true);
  } else {
    lower = w.strut(top, tip, E, Ap, Ip, integer(rng, 1, 5), "fixed", "");
  }
  w.contact(w.node(beam, k), w.end(lower, false), {0, 1},
            g == 0.0 || offset != 0.0 || chance(rng, 0.3));
  // Down onto the beam (mostly), with a sideways part the post takes in bending.
  const double P = (chance(rng, 0.85) ? -1.0 : 1.0) * sized_force(rng, E * Ap / (H - g), g);
  w.force(lower, w.at(lower, -1), {uniform(rng, -0.2, 0.2) * std::abs(P), P});
  const double stiffness = 48.0 * E * Ib / (L * L * L);
  if (chance(rng, 0.5))
    w.per_length(beam,
                 (stiffness * 1e-3 / L) * V{uniform(rng, -0.2, 0.2), uniform(rng, -1.0, 1.0)});
  if (chance(rng, 0.3))
    w.force(beam, w.at(beam, integer(rng, 1, eb - 1)), {0, 0},
            uniform(rng, -1.0, 1.0) * stiffness * 1e-3 * L);
}

void apex_on_stop(std::mt19937& rng, FrameWriter& w) {
  const double H = uniform(rng, 1.0, 2.0), E = uniform(rng, 1e11, 3e11);
  const double A = uniform(rng, 3e-4, 2e-3), I = uniform(rng, 1e-7, 2e-6);
  const V apex{0, H};
  std::vector<V> feet = {{-uniform(rng, 0.6, 1.5), 0}, {uniform(rng, 0.6, 1.5), 0}};
  if (chance(rng, 0.3)) feet.push_back({uniform(rng, -0.3, 0.3), 0});  // a third leg
  const bool rigid = chance(rng, 0.5);
  std::vector<std::string> legs, ends;
  for (const V& foot : feet) {
    legs.push_back(w.strut(foot, apex, E, A, I, integer(rng, 2, 6),
                           chance(rng, 0.5) ? "pinned" : "fixed", ""));
    ends.push_back(w.end(legs.back(), false, false));
  }
  w.joint(ends, rigid);
  // A stop from a random direction above the feet, clamped at its far end.
  const V u = unit(uniform(rng, -0.25 * kPi, 1.25 * kPi));
  const double g = random_gap(rng), length = uniform(rng, 0.3, 0.6);
  const std::string stop =
      w.strut(apex + (g + length) * u, apex + g * u, E, A, I, integer(rng, 1, 3), "fixed", "");
  const std::string& leg = legs[integer(rng, 0, static_cast<int>(legs.size()) - 1)];
  w.contact(w.end(leg, false), w.end(stop, false), u, g == 0.0 || chance(rng, 0.3));
  // Toward the stop (mostly), with a random part across.
  const double P = sized_force(rng, E * A / H, g);
  const V across = unit(uniform(rng, 0.0, 2.0 * kPi));
  const V f = (chance(rng, 0.85) ? P : -P) * u + uniform(rng, 0.0, 0.7) * P * across;
  w.force(leg, w.at(leg, -1), f, chance(rng, 0.3) ? uniform(rng, -0.1, 0.1) * P : 0.0);
  if (chance(rng, 0.4))
    w.per_length(legs[0], uniform(rng, -0.3, 0.3) * (P / H) * unit(uniform(rng, 0.0, 2.0 * kPi)));
}

void portal_on_stop(std::mt19937& rng, FrameWriter& w) {
  const double B = uniform(rng, 2.0, 5.0), H = uniform(rng, 2.0, 4.0), E = uniform(rng, 1e11, 3e11);
  const double A = uniform(rng, 1e-3, 4e-3), I = uniform(rng, 2e-6, 2e-5);
  // Pinned feet and pinned corners together would make a mechanism.
  bool feet_pinned[2], corners_rigid[2];
  do {
    for (int i = 0; i < 2; ++i) {
      feet_pinned[i] = chance(rng, 0.5);
      corners_rigid[i] = chance(rng, 0.6);
    }
  } while (feet_pinned[0] && feet_pinned[1] && !corners_rigid[0] && !corners_rigid[1]);
  const std::string left =
      w.strut({0, 0}, {0, H}, E, A, I, integer(rng, 2, 6), feet_pinned[0] ? "pinned" : "fixed", "");
  const std::string right =
      w.strut({B, 0}, {B, H}, E, A, I, integer(rng, 2, 6), feet_pinned[1] ? "pinned" : "fixed", "");
  const std::string beam = w.strut({0, H}, {B, H}, E, A, I, integer(rng, 2, 6), "", "");
  w.joint({w.end(left, false, false), w.end(beam, true, false)}, corners_rigid[0]);
  w.joint({w.end(beam, false, false), w.end(right, false, false)}, corners_rigid[1]);
  // A stop beside one corner, roughly along the beam's line.
  const bool at_right = chance(rng, 0.5);
  const V corner = at_right ? V{B, H} : V{0, H};
  const double angle = (at_right ? 0.0 : kPi) + uniform(rng, -kPi / 3, kPi / 3);
  const V u = unit(angle);
  const double g = random_gap(rng), length = uniform(rng, 0.3, 0.8);
  const std::string stop =
      w.strut(corner + (g + length) * u, corner + g * u, E, A, I, integer(rng, 1, 3), "fixed", "");
  const std::string corner_node =
      chance(rng, 0.5) ? w.end(beam, !at_right) : w.end(at_right ? right : left, false);
  w.contact(corner_node, w.end(stop, false), u, g == 0.0 || chance(rng, 0.3));
  // Wind toward the stop (mostly) and a floor load.
  const double sway = 6.0 * E * I / (H * H * H);
  const double P = sized_force(rng, sway, g) * (chance(rng, 0.85) ? 1.0 : -1.0);
  w.per_length(chance(rng, 0.5) ? left : right, {P * (at_right ? 1.0 : -1.0) / H, 0});
  if (chance(rng, 0.6)) w.per_length(beam, {0, -uniform(rng, 0.0, 2.0) * P / B});
  if (chance(rng, 0.3)) w.force(beam, w.at(beam, integer(rng, 0, w.elements(beam))), {0, -P});
}

void floating_beam(std::mt19937& rng, FrameWriter& w) {
  const double L = uniform(rng, 2.0, 4.0), E = uniform(rng, 1e11, 3e11);
  const double A = uniform(rng, 1e-3, 4e-3), I = uniform(rng, 2e-6, 2e-5);
  const int e = integer(rng, 4, 8);
  const std::string beam = w.strut({0, 0}, {L, 0}, E, A, I, e, "", "");
  // Two posts below, on either side of the middle, their normals tilted a little.
  const int k1 = integer(rng, 1, (e - 1) / 2), k2 = integer(rng, e / 2 + 1, e - 1);
  std::vector<double> gaps;
  for (int k : {k1, k2}) {
    const double x = L * k / e, g = random_gap(rng);
    gaps.push_back(g);
    const double tilt = chance(rng, 0.5) ? uniform(rng, -0.05, 0.05) : 0.0;
    const V n{std::sin(tilt), std::cos(tilt)};
    const V tip = V{x, 0} - g * n;
    const std::string post = w.strut(tip - uniform(rng, 0.5, 1.2) * V{0, 1}, tip, E, A, I,
                                     integer(rng, 1, 4), "fixed", "");
    w.contact(w.end(post, false), w.node(beam, k), n, g == 0.0 || tilt != 0.0 || chance(rng, 0.3));
  }
  // A stop at one end, along the beam.
  const bool at_left = chance(rng, 0.5);
  const double g = random_gap(rng);
  const V end = at_left ? V{0, 0} : V{L, 0}, out = at_left ? V{-1, 0} : V{1, 0};
  const std::string stop = w.strut(end + (g + uniform(rng, 0.2, 0.5)) * out, end + g * out, E, A, I,
                                   integer(rng, 1, 3), "fixed", "");
  w.contact(w.end(stop, false), w.end(beam, at_left), -1.0 * out, g == 0.0 || chance(rng, 0.3));
  // Loaded into all three contacts: down between the posts, and toward the stop.
  const double q = uniform(rng, 0.3, 3.0) * 384.0 * E * I * 1e-3 / (5.0 * L * L * L * L);
  w.per_length(beam, {0, -q});
  w.force(beam, w.at(beam, at_left ? e : 0), uniform(rng, 0.2, 0.5) * q * L * out);
  if (chance(rng, 0.5))
    w.force(beam, w.at(beam, integer(rng, k1, k2)), {0, -uniform(rng, 0.0, 1.0) * q * L},
            chance(rng, 0.3) ? uniform(rng, -0.05, 0.05) * q * L * L : 0.0);
}

}  // namespace

std::string random_frame_scene(std::mt19937& rng, FrameKind kind) {
  // In the order of FrameKind.
  static constexpr void (*kWriters[])(std::mt19937&, FrameWriter&) = {
      post_on_beam, apex_on_stop, portal_on_stop, floating_beam};
  FrameWriter w(rng);
  kWriters[static_cast<int>(kind)](rng, w);
  return w.text();
}

}  // namespace fetic::testing
