#pragma once
// Numbers as the images print them. Locale-independent, so frames are identical
// everywhere.

#include <string>
#include <vector>

namespace fetic::render {

// printf-style formatting of one number, e.g. format("%.3g", x).
std::string format(const char* pattern, double value);
// "10⁻³" (Unicode superscripts; DejaVu Sans has them).
std::string power_of_ten(int exponent);
// "×50", "×0.5", "×2000".
std::string times(double factor);

// A unit with an SI prefix so that `largest` reads between 1 and 1000: returns the divisor
// and sets `unit` to e.g. "MPa" for base "Pa".
double si_scale(double largest, const std::string& base, std::string& unit);

// Greedy word wrap for layout, by estimated text width.
std::vector<std::string> wrap(const std::string& text, float max_width, float size, bool bold);

}  // namespace fetic::render
