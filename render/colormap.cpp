#include "render/colormap.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace fetic::render {
namespace {

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
  static constexpr std::array<Color, 7> stops{{{33, 102, 172, 255},
                                               {103, 169, 207, 255},
                                               {209, 229, 240, 255},
                                               {236, 236, 236, 255},
                                               {253, 219, 199, 255},
                                               {239, 138, 98, 255},
                                               {178, 24, 43, 255}}};
  if (!std::isfinite(v)) v = 0.0;
  return through_stops(stops, 0.5 * (v + 1.0));
}

Color sequential(double t) {
  // Close to viridis, in five stops.
  static constexpr std::array<Color, 5> stops{{{68, 1, 84, 255},
                                               {59, 82, 139, 255},
                                               {33, 145, 140, 255},
                                               {94, 201, 98, 255},
                                               {253, 231, 37, 255}}};
  if (!std::isfinite(t)) t = 0.0;
  return through_stops(stops, t);
}

Color subdomain_color(int strut, int index) {
  // Two families (blues/teals and ambers/oranges) alternate along a strut; the shade
  // alternates from strut to strut.
  static constexpr std::array<Color, 3> cool{
      {{45, 110, 190, 255}, {30, 150, 160, 255}, {95, 95, 200, 255}}};
  static constexpr std::array<Color, 3> warm{
      {{230, 140, 30, 255}, {200, 90, 60, 255}, {190, 160, 20, 255}}};
  const auto& family = (index % 2 == 0) ? cool : warm;
  return family[static_cast<std::size_t>((strut + index / 2) % 3)];
}

Color series_color(int index) {
  static constexpr std::array<Color, 6> okabe_ito{{{0, 114, 178, 255},
                                                   {213, 94, 0, 255},
                                                   {0, 158, 115, 255},
                                                   {204, 121, 167, 255},
                                                   {230, 159, 0, 255},
                                                   {86, 180, 233, 255}}};
  return okabe_ito[static_cast<std::size_t>(index) % okabe_ito.size()];
}

}  // namespace fetic::render
