#pragma once
// Test scenes written as TOML from a few calls, so that a test states only what its scene
// has of its own. The text is laid out as a scene file by hand would be: one key a line,
// the tables in the order of the calls, so that the line numbers a message names can be
// counted (the model line is line 1).
//
//   SceneToml("bar", "[defaults]", "E = 2.1e11, area = 1e-4, elements = 2")
//       .strut("L", {0.0, 0.0}, {1.0, 0.0}, "fixed = ['from']")
//       .strut("R", {1.001, 0.0}, {2.0, 0.0})
//       .load("R", "to", {1000.0, 0.0})
//       .contact("L.to", "R.from")
//
// Keys are given as TOML key = value pairs separated by commas; each becomes a line.

#include <array>
#include <string>

#include "tests/support/random_draws.hpp"

namespace fetic::testing {

using TomlPoint = std::array<double, 2>;

// "a = 1, b = [2, 3], c = 'x, y'" -> "a = 1\nb = [2, 3]\nc = 'x, y'\n": splits at the
// commas outside brackets, braces and strings.
inline std::string toml_lines(const std::string& keys) {
  std::string lines, line;
  int depth = 0;
  char quote = 0;
  auto finish = [&] {
    const auto first = line.find_first_not_of(' ');
    if (first != std::string::npos) lines += line.substr(first) + "\n";
    line.clear();
  };
  for (char c : keys) {
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      --depth;
    } else if (c == ',' && depth == 0) {
      finish();
      continue;
    }
    line += c;
  }
  finish();
  return lines;
}

class SceneToml {
 public:
  // `model = "..."`, then an optional first table (e.g. "[defaults]") with its keys.
  explicit SceneToml(const std::string& model, const std::string& header = "",
                     const std::string& keys = "")
      : text_("model = \"" + model + "\"\n") {
    if (!header.empty()) table(header, keys);
  }

  // Any table: "[defaults]", "[[strut]]", "[units]", ...
  SceneToml& table(const std::string& header, const std::string& keys) {
    text_ += header + "\n" + toml_lines(keys);
    return *this;
  }

  SceneToml& strut(const std::string& name, const TomlPoint& from, const TomlPoint& to,
                   const std::string& keys = "") {
    text_ += "[[strut]]\nname = \"" + name + "\"\nfrom = " + toml_point(from[0], from[1]) +
             "\nto = " + toml_point(to[0], to[1]) + "\n" + toml_lines(keys);
    return *this;
  }

  SceneToml& contact(const std::string& a, const std::string& b, const std::string& keys = "") {
    text_ += "[[contact]]\na = \"" + a + "\"\nb = \"" + b + "\"\n" + toml_lines(keys);
    return *this;
  }

  SceneToml& joint(const std::string& a, const std::string& b, const std::string& keys = "") {
    text_ += "[[joint]]\nends = [\"" + a + "\", \"" + b + "\"]\n" + toml_lines(keys);
    return *this;
  }

  // A force at an end ("from", "to") or at a node given as a string ("3").
  SceneToml& load(const std::string& strut, const std::string& at, const TomlPoint& force) {
    text_ += "[[load]]\nstrut = \"" + strut + "\"\nat = \"" + at +
             "\"\nforce = " + toml_point(force[0], force[1]) + "\n";
    return *this;
  }

  SceneToml& per_length(const std::string& strut, const TomlPoint& load) {
    text_ +=
        "[[load]]\nstrut = \"" + strut + "\"\nper_length = " + toml_point(load[0], load[1]) + "\n";
    return *this;
  }

  // Lines as they are (a key the scene's other calls do not write).
  SceneToml& raw(const std::string& lines) {
    text_ += lines;
    return *this;
  }

  const std::string& str() const { return text_; }
  operator std::string() const { return text_; }

 private:
  std::string text_;
};

}  // namespace fetic::testing
