#include "app/parse_number.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace fetic::app {

std::optional<double> parse_number(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  // strtod flags a subnormal result (1e-320) with ERANGE too: that one is a number.
  if (end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace fetic::app
