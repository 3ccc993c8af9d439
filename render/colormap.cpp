#include "render/colormap.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace fetic::render {
namespace {

// An opaque colour from its hex code 0xRRGGBB.
constexpr Color rgb(unsigned hex) {
  return {static_cast<std::uint8_t>(hex >> 16), static_cast<std::uint8_t>((hex >> 8) & 0xFF),
          static_cast<std::uint8_t>(hex & 0xFF), 255};
}

// Piecewise linear through equally spaced stops.
template <std::size_t N>
Color through_stops(const std::array<Color, N>& stops, double t) {
  t = std::clamp(t, 0.0, 1.0) * (N - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(t), N - 2);
  return mix(stops[i], stops[i + 1], t - static_cast<double>(i));
}

}  // namespace

Color diverging(double v) {
  // ColorBrewer RdBu, reversed so that compression is blue.
  static constexpr std::array<Color, 7> stops{rgb(0x2166AC), rgb(0x67A9CF), rgb(0xD1E5F0),
                                              rgb(0xECECEC), rgb(0xFDDBC7), rgb(0xEF8A62),
                                              rgb(0xB2182B)};
  if (!std::isfinite(v)) v = 0.0;
  return through_stops(stops, 0.5 * (v + 1.0));
}

Color sequential(double t) {
  // Close to viridis, in five stops.
  static constexpr std::array<Color, 5> stops{rgb(0x440154), rgb(0x3B528B), rgb(0x21918C),
                                              rgb(0x5EC962), rgb(0xFDE725)};
  if (!std::isfinite(t)) t = 0.0;
  return through_stops(stops, t);
}

Color subdomain_color(int strut, int index) {
  // Two families (blues/teals and ambers/oranges) alternate along a strut; the shade
  // alternates from strut to strut.
  static constexpr std::array<Color, 3> cool{rgb(0x2D6EBE), rgb(0x1E96A0), rgb(0x5F5FC8)};
  static constexpr std::array<Color, 3> warm{rgb(0xE68C1E), rgb(0xC85A3C), rgb(0xBEA014)};
  const auto& family = (index % 2 == 0) ? cool : warm;
  return family[static_cast<std::size_t>((strut + index / 2) % 3)];
}

Color series_color(int index) {
  static constexpr std::array<Color, 6> okabe_ito{rgb(0x0072B2), rgb(0xD55E00), rgb(0x009E73),
                                                  rgb(0xCC79A7), rgb(0xE69F00), rgb(0x56B4E9)};
  return okabe_ito[static_cast<std::size_t>(index) % okabe_ito.size()];
}

}  // namespace fetic::render
