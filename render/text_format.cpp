#include "render/text_format.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "render/draw_list.hpp"

namespace fetic::render {

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

std::string power_of_ten(int exponent) {
  static constexpr std::array<const char*, 10> digits{"⁰", "¹", "²", "³", "⁴",
                                                      "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string result = "10";
  if (exponent < 0) result += "⁻";
  const std::string magnitude = std::to_string(std::abs(exponent));
  for (char c : magnitude)
    result += digits[static_cast<std::size_t>(c - '0')];
  return result;
}

std::string times(double factor) {
  if (factor >= 1.0 && factor == std::floor(factor) && factor < 1e15)
    return "×" + format("%.0f", factor);
  return "×" + format("%.3g", factor);
}

double si_scale(double largest, const std::string& base, std::string& unit) {
  static constexpr std::array<std::pair<double, const char*>, 5> prefixes{
      {{1e9, "G"}, {1e6, "M"}, {1e3, "k"}, {1.0, ""}, {1e-3, "m"}}};
  for (const auto& [divisor, prefix] : prefixes)
    if (largest >= divisor) {
      unit = std::string(prefix) + base;
      return divisor;
    }
  unit = base;
  return 1.0;
}

std::vector<std::string> wrap(const std::string& text, float max_width, float size, bool bold) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string word, line;
  while (words >> word) {
    const std::string candidate = line.empty() ? word : line + " " + word;
    if (!line.empty() && estimated_text_width(candidate, size, bold) > max_width) {
      lines.push_back(line);
      line = word;
    } else {
      line = candidate;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

}  // namespace fetic::render
