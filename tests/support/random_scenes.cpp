#include "tests/support/random_scenes.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

#include "tests/support/random_draws.hpp"

namespace fetic::testing {
namespace {

std::string point(double x, double y) {
  return "[" + toml_number(x) + ", " + toml_number(y) + "]";
}

struct Writer {
  std::string struts, loads, contacts;
  int count = 0;

  // A strut on the line origin + s * dir for s in [s0, s1]; `reversed` swaps from/to.
  std::string strut(std::mt19937& rng, double ox, double oy, double dx, double dy, double s0,
                    double s1, bool reversed, const std::string& fixed_end_at_s0_or_s1) {
    const std::string name = "S" + std::to_string(++count);
    const double ax = ox + s0 * dx, ay = oy + s0 * dy, bx = ox + s1 * dx, by = oy + s1 * dy;
    const int elements = integer(rng, 1, 5);
    const int subdomains = integer(rng, 1, std::min(3, elements));
    std::string fixed = "[]";
    // fixed_end_at_s0_or_s1: "", "s0" or "s1": which geometric end is clamped.
    if (!fixed_end_at_s0_or_s1.empty()) {
      const bool at_s0 = fixed_end_at_s0_or_s1 == "s0";
      fixed = (at_s0 != reversed) ? "[\"from\"]" : "[\"to\"]";
    }
    struts += "\n[[strut]]\nname = \"" + name + "\"\n";
    struts += "from = " + (reversed ? point(bx, by) : point(ax, ay)) + "\n";
    struts += "to = " + (reversed ? point(ax, ay) : point(bx, by)) + "\n";
    struts += "E = " + toml_number(uniform(rng, 5e10, 3e11)) + "\n";
    struts += "area = " + toml_number(uniform(rng, 2e-5, 4e-4)) + "\n";
    struts += "elements = " + std::to_string(elements) + "\n";
    struts += "subdomains = " + std::to_string(subdomains) + "\n";
    struts += "fixed = " + fixed + "\n";
    return name;
  }

  // Axial force `axial` along +dir (plus a component across the axis the bar ignores).
  void end_load(std::mt19937& rng, const std::string& name, const std::string& end, double dx,
                double dy, double axial) {
    const double across = uniform(rng, -1.0, 1.0) * std::abs(axial);
    loads += "\n[[load]]\nstrut = \"" + name + "\"\nat = \"" + end +
             "\"\nforce = " + point(axial * dx - across * dy, axial * dy + across * dx) + "\n";
  }
  void distributed_load(const std::string& name, double dx, double dy, double axial) {
    loads += "\n[[load]]\nstrut = \"" + name + "\"\nper_length = " + point(axial * dx, axial * dy) +
             "\n";
  }
  void contact(std::mt19937& rng, const std::string& a, const std::string& b) {
    if (chance(rng, 0.5))
      contacts += "\n[[contact]]\na = \"" + a + "\"\nb = \"" + b + "\"\n";
    else
      contacts += "\n[[contact]]\na = \"" + b + "\"\nb = \"" + a + "\"\n";
  }
  std::string text() const {
    return "title = \"random\"\nmodel = \"bar\"\n" + struts + loads + contacts;
  }
};

double random_gap(std::mt19937& rng) {
  return chance(rng, 0.25) ? 0.0 : uniform(rng, 1e-4, 3e-3);
}

// Force of the size that moves a strut of typical stiffness by about a gap.
double typical_force(std::mt19937& rng) {
  return uniform(rng, 0.3, 3.0) * 2e7 * 1.5e-3;
}

// "NAME.from" or "NAME.to" of the end at the larger (s1) or smaller (s0) line coordinate.
std::string end_ref(const std::string& name, bool reversed, bool at_s1) {
  return name + ((at_s1 != reversed) ? ".to" : ".from");
}

void add_pair(std::mt19937& rng, Writer& w, double ox, double oy) {
  const double angle = uniform(rng, 0.0, 2.0 * kPi);
  const double dx = std::cos(angle), dy = std::sin(angle);
  const double l1 = uniform(rng, 0.4, 1.5), l2 = uniform(rng, 0.4, 1.5), gap = random_gap(rng);
  const bool r1 = chance(rng, 0.5), r2 = chance(rng, 0.5);
  const std::string left = w.strut(rng, ox, oy, dx, dy, 0.0, l1, r1, "s0");
  const std::string right = w.strut(rng, ox, oy, dx, dy, l1 + gap, l1 + gap + l2, r2, "s1");
  // Push the right strut toward the left one (mostly), sometimes pull it away.
  const double push = (chance(rng, 0.85) ? -1.0 : 1.0) * typical_force(rng);
  w.end_load(rng, right, end_ref(right, r2, false).substr(right.size() + 1), dx, dy, push);
  if (chance(rng, 0.4))
    w.distributed_load(left, dx, dy, uniform(rng, -1.0, 1.0) * typical_force(rng));
  w.contact(rng, end_ref(left, r1, true), end_ref(right, r2, false));
}

void add_chain(std::mt19937& rng, Writer& w, double ox, double oy) {
  const double angle = uniform(rng, 0.0, 2.0 * kPi);
  const double dx = std::cos(angle), dy = std::sin(angle);
  const int floating = integer(rng, 1, 3);
  const bool closed = chance(rng, 0.6);  // a clamped strut at both ends of the chain
  double s = 0.0;
  std::vector<std::string> names;
  std::vector<bool> reversed;
  const int total = floating + (closed ? 2 : 1);
  for (int i = 0; i < total; ++i) {
    const double length = uniform(rng, 0.3, 1.2);
    const bool r = chance(rng, 0.5);
    const std::string fixed = i == 0 ? "s0" : (closed && i == total - 1 ? "s1" : "");
    names.push_back(w.strut(rng, ox, oy, dx, dy, s, s + length, r, fixed));
    reversed.push_back(r);
    s += length + random_gap(rng);
  }
  for (int i = 0; i + 1 < total; ++i)
    w.contact(rng, end_ref(names[i], reversed[i], true),
              end_ref(names[i + 1], reversed[i + 1], false));
  // Floating struts (1..floating) carry nonzero axial loads; an open chain's tail is
  // pushed back toward its clamped strut so that it stays bounded.
  for (int i = 1; i <= floating; ++i) {
    const double magnitude = typical_force(rng);
    const double sign = closed ? (chance(rng, 0.5) ? 1.0 : -1.0) : -1.0;
    if (chance(rng, 0.5))
      w.end_load(rng, names[i], chance(rng, 0.5) ? "from" : "to", dx, dy, sign * magnitude);
    else
      w.distributed_load(names[i], dx, dy, sign * magnitude);
  }
  if (chance(rng, 0.5))
    w.end_load(rng, names[0], reversed[0] ? "from" : "to", dx, dy,
               uniform(rng, -1.0, 1.0) * typical_force(rng));
}

}  // namespace

std::string random_opposing_pairs(std::mt19937& rng, int pairs) {
  Writer w;
  for (int i = 0; i < pairs; ++i)
    add_pair(rng, w, 10.0 * i, uniform(rng, -5.0, 5.0));
  return w.text();
}

std::string random_chain(std::mt19937& rng) {
  Writer w;
  add_chain(rng, w, 0.0, 0.0);
  return w.text();
}

std::string random_bar_scene(std::mt19937& rng) {
  Writer w;
  const int pairs = integer(rng, 0, 3);
  const int chains = integer(rng, pairs == 0 ? 1 : 0, 2);
  for (int i = 0; i < pairs; ++i)
    add_pair(rng, w, 10.0 * i, 0.0);
  for (int i = 0; i < chains; ++i)
    add_chain(rng, w, 10.0 * i, 20.0);
  return w.text();
}

std::string random_plane_pairs(std::mt19937& rng, int pairs) {
  std::string struts, loads, contacts;
  for (int p = 0; p < pairs; ++p) {
    const double angle = uniform(rng, 0.0, 2.0 * kPi);
    const double dx = std::cos(angle), dy = std::sin(angle);
    const double ox = 5.0 * p, oy = 0.0;
    const double E = uniform(rng, 5e10, 3e11), nu = uniform(rng, 0.2, 0.35), t = 0.01;
    const double h = uniform(rng, 0.05, 0.2), l1 = uniform(rng, 0.5, 1.5),
                 l2 = uniform(rng, 0.5, 1.5);
    const int across = integer(rng, 1, 4);
    const double gap = chance(rng, 0.25) ? 0.0 : uniform(rng, 1e-5, 5e-4);
    const bool r1 = chance(rng, 0.5), r2 = chance(rng, 0.5);
    auto strut = [&](const std::string& name, double s0, double s1, bool reversed, bool clamp_s0) {
      const int elements = integer(rng, 2, 8);
      const double ax = ox + s0 * dx, ay = oy + s0 * dy, bx = ox + s1 * dx, by = oy + s1 * dy;
      struts += "\n[[strut]]\nname = \"" + name + "\"\n";
      struts += "from = " + (reversed ? point(bx, by) : point(ax, ay)) + "\n";
      struts += "to = " + (reversed ? point(ax, ay) : point(bx, by)) + "\n";
      struts +=
          "E = " + toml_number(E * uniform(rng, 0.5, 1.5)) + "\nnu = " + toml_number(nu) + "\n";
      struts += "height = " + toml_number(h) + "\nthickness = " + toml_number(t) + "\n";
      struts += "elements = " + std::to_string(elements) +
                "\nelements_across = " + std::to_string(across) + "\n";
      struts += "subdomains = " + std::to_string(integer(rng, 1, std::min(3, elements))) + "\n";
      struts +=
          "subdomains_across = " + std::to_string(integer(rng, 1, std::min(2, across))) + "\n";
      struts += std::string("fixed = [\"") + ((clamp_s0 != reversed) ? "from" : "to") + "\"]\n";
    };
    const std::string a = "A" + std::to_string(p), b = "B" + std::to_string(p);
    strut(a, 0.0, l1, r1, true);
    strut(b, l1 + gap, l1 + gap + l2, r2, false);
    // Axial push on b's near end that would close about 0.5-3 gaps; a bending load on a
    // that tilts its end face by about as much across the height.
    const double EA = E * h * t, EI = E * t * h * h * h / 12.0;
    const double closing = (gap > 0.0 ? gap : 2e-4 * l2) * uniform(rng, 0.5, 3.0);
    const double push = (chance(rng, 0.85) ? 1.0 : -1.0) * closing * EA / l2;
    const double across_push = uniform(rng, -0.2, 0.2) * push;
    const std::string b_near = (r2 ? "to" : "from");
    loads += "\n[[load]]\nstrut = \"" + b + "\"\nat = \"" + b_near +
             "\"\nforce = " + point(-push * dx - across_push * dy, -push * dy + across_push * dx) +
             "\n";
    const double tilt = closing / h * uniform(rng, 0.5, 3.0);
    const double q = (chance(rng, 0.5) ? 1.0 : -1.0) * tilt * 6.0 * EI / (l1 * l1 * l1);
    loads += "\n[[load]]\nstrut = \"" + a + "\"\nper_length = " + point(-q * dy, q * dx) + "\n";
    const std::string a_end = a + (r1 ? ".from" : ".to"), b_end = b + (r2 ? ".to" : ".from");
    contacts += chance(rng, 0.5) ? "\n[[contact]]\na = \"" + a_end + "\"\nb = \"" + b_end + "\"\n"
                                 : "\n[[contact]]\na = \"" + b_end + "\"\nb = \"" + a_end + "\"\n";
  }
  return "title = \"random plane\"\nmodel = \"plane\"\n" + struts + loads + contacts;
}

std::string random_contact_free_scene(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::string text = "model = \"bar\"\n";
  const int struts = 1 + static_cast<int>(unit(rng) * 4);
  for (int s = 0; s < struts; ++s) {
    const double angle = 6.28 * unit(rng), length = 0.5 + unit(rng);
    char buffer[600];
    std::snprintf(buffer, sizeof buffer,
                  "[[strut]]\nname = \"S%d\"\nfrom = [%.17g, %.17g]\nto = [%.17g, %.17g]\n"
                  "E = %.17g\narea = 1e-4\nelements = %d\nfixed = [%s]\n"
                  "[[load]]\nstrut = \"S%d\"\nper_length = [%.17g, %.17g]\n",
                  s, 3.0 * s, 0.0, 3.0 * s + length * std::cos(angle), length * std::sin(angle),
                  1e10 + 2e11 * unit(rng), 2 + static_cast<int>(unit(rng) * 12),
                  unit(rng) < 0.3 ? "\"from\", \"to\"" : (unit(rng) < 0.5 ? "\"from\"" : "\"to\""),
                  s, 1e4 * (unit(rng) - 0.5), 1e4 * (unit(rng) - 0.5));
    text += buffer;
  }
  return text;
}

}  // namespace fetic::testing
