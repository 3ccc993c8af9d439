#pragma once
// The random draws and number formatting the random scene generators share: numbers are
// written as the shortest text that reads back the same double (and always as TOML
// floats), so that a scene read back is the scene drawn.

#include <charconv>
#include <random>
#include <string>

namespace fetic::testing {

inline constexpr double kPi = 3.14159265358979323846;

inline double uniform(std::mt19937& rng, double low, double high) {
  return std::uniform_real_distribution<double>(low, high)(rng);
}
inline int integer(std::mt19937& rng, int low, int high) {
  return std::uniform_int_distribution<int>(low, high)(rng);
}
inline bool chance(std::mt19937& rng, double p) {
  return uniform(rng, 0.0, 1.0) < p;
}

// The shortest text that reads back as the same double ("1.001", not "1.0009999999999999").
inline std::string toml_number(double value) {
  char buffer[40];
  std::string text(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

// "[x, y]" with every digit, for scene text.
inline std::string toml_point(double x, double y) {
  return "[" + toml_number(x) + ", " + toml_number(y) + "]";
}

}  // namespace fetic::testing
