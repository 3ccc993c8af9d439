#pragma once
// Numbers typed by a user - on the command line, in a window script - read one way.

#include <optional>
#include <string>

namespace fetic::app {

// A finite number: the whole text, as strtod reads it (subnormal values such as 1e-320
// included), or nullopt.
std::optional<double> parse_number(const std::string& text);

}  // namespace fetic::app
