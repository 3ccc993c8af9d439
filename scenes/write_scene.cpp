#include "scenes/write_scene.hpp"

#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace fetic::scenes {
namespace {

// The shortest of %.15g / %.17g that reads back as the same double.
std::string number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.15g", value);
  if (std::strtod(buffer, nullptr) != value) std::snprintf(buffer, sizeof buffer, "%.17g", value);
  std::string text = buffer;
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

std::string point(Point p) {
  return "[" + number(p[0]) + ", " + number(p[1]) + "]";
}

// A TOML basic string. Control characters (a title may hold them as \u escapes) must be
// escaped again, or the text does not load (found by fuzz/fuzz_scene's round trip).
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte == 0x7f) {
      char escape[12];
      std::snprintf(escape, sizeof escape, "\\u%04X", static_cast<unsigned>(byte));
      out += escape;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

std::string scene_to_toml(const Scene& scene) {
  std::ostringstream out;
  if (!scene.title.empty()) out << "title = " << quoted(scene.title) << "\n";
  out << "model = \"" << to_string(scene.model) << "\"\n";
  if (scene.units != Units{})
    out << "\n[units]\nlength = " << quoted(scene.units.length)
        << "\nforce = " << quoted(scene.units.force) << "\n";
  const bool plane = scene.model == ModelKind::Plane;
  for (const Strut& s : scene.struts) {
    out << "\n[[strut]]\nname = " << quoted(s.name) << "\nfrom = " << point(s.from)
        << "\nto = " << point(s.to) << "\nE = " << number(s.E) << "\nelements = " << s.elements
        << "\nsubdomains = " << s.subdomains << "\nfixed = [";
    if (s.fixed_from) out << "\"from\"" << (s.fixed_to ? ", " : "");
    if (s.fixed_to) out << "\"to\"";
    out << "]\n";
    if (plane)
      out << "height = " << number(s.height) << "\nthickness = " << number(s.thickness)
          << "\nnu = " << number(s.nu) << "\nelements_across = " << s.elements_across
          << "\nsubdomains_across = " << s.subdomains_across << "\n";
    else
      out << "area = " << number(s.area) << "\n";
  }
  for (const Load& load : scene.loads) {
    out << "\n[[load]]\nstrut = " << quoted(scene.struts.at(load.strut).name) << "\n";
    if (load.per_length)
      out << "per_length = " << point(load.force) << "\n";
    else
      out << "at = \"" << to_string(load.at) << "\"\nforce = " << point(load.force) << "\n";
  }
  for (const Contact& contact : scene.contacts)
    out << "\n[[contact]]\na = " << quoted(end_label(scene, contact.a))
        << "\nb = " << quoted(end_label(scene, contact.b)) << "\n";
  return out.str();
}

}  // namespace fetic::scenes
