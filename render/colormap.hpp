#pragma once
// Colours with a meaning: the diverging stress map and the palettes that tell subdomains
// and plot series apart.

#include "render/draw_list.hpp"

namespace fetic::render {

// Diverging map for a signed value v in [-1, 1]: blue (compression) - light grey - red
// (tension). Values outside are clamped.
Color diverging(double v);

// Sequential map for t in [0, 1] (dark blue - teal - yellow), for surfaces.
Color sequential(double t);

// Fill colour of subdomain `index` of strut `strut`: neighbouring subdomains of a strut
// alternate between two hue families, so the pieces of one strut and of neighbouring
// struts stay distinguishable.
Color subdomain_color(int strut, int index);

// Colour of plot series `index` (colour-blind safe, Okabe-Ito).
Color series_color(int index);

namespace palette {
inline constexpr Color background{250, 250, 248, 255};
inline constexpr Color ink{34, 34, 38, 255};       // text, outlines
inline constexpr Color muted{110, 110, 118, 255};  // secondary text
inline constexpr Color grid{226, 226, 230, 255};   // plot grid
inline constexpr Color wall{70, 70, 78, 255};      // supports
inline constexpr Color load{0, 110, 50, 255};      // load arrows
inline constexpr Color contact{215, 25, 28, 255};  // active contacts (the thesis' red circles)
inline constexpr Color gap{150, 150, 160, 255};    // open gaps
inline constexpr Color force{120, 30, 140, 255};   // contact force glyphs
inline constexpr Color panel{255, 255, 255, 235};  // overlay panel
// Struts a colouring has no value for (bars and plane struts under bending moment): a
// mid grey, apart from the diverging map's light grey zero.
inline constexpr Color no_value{165, 165, 170, 255};
}  // namespace palette

}  // namespace fetic::render
