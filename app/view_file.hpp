#pragma once
// A saved view (docs/WINDOW.md, "Views"): what the window shows and how - the picture
// size, the world point at the centre of the scene region and the zoom, magnification,
// colouring, the toggles and the scales of the run (displacement, force and stress ends,
// the plots' axes) - as a small JSON file. The window saves and loads it; `fetic render
// --view` and `fetic gui --view` start from it, so a picture framed by hand is rendered
// again headless. Every entry is optional: what a file leaves out stays as the command
// would have it.

#include <optional>
#include <stdexcept>
#include <string>

#include "render/frame_sequence.hpp"
#include "render/view.hpp"

namespace fetic::app {

struct SavedView {
  std::optional<int> width, height;          // the picture (the window: without its panel)
  std::optional<double> center_x, center_y;  // world point at the centre of the scene region
  std::optional<double> zoom;                // 1: the scene fits the region
  std::optional<double> magnification;       // 0: automatic
  std::optional<double> text_size;           // the smallest base text size (the window's)
  std::optional<render::ColorBy> color_by;
  std::optional<bool> forces, gaps, overlay, labels;
  std::optional<bool> corners;  // FETI-DP's primal corners (render/corner_marks.hpp)
  // The run's scales the picture was drawn with (colour map and glyph ends, axes).
  std::optional<render::RunExtent> scales;
  // What those scales are the largest over, as the window's legends say ("over loads 0-2").
  std::optional<std::string> scale_basis;
};

// A view file that cannot be read or has a bad entry: the message names the file (and the
// line for a JSON syntax error) and the problem.
class ViewFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A colouring's name in view files, `fetic render --color` and window scripts:
// "subdomain", "strut", "stress", "moment"; nullopt for another name.
const char* color_name(render::ColorBy color);
std::optional<render::ColorBy> color_from_name(const std::string& name);

// Reads the file through app/json_input.hpp (8 MiB, FIFOs, signals); throws ViewFileError.
SavedView read_view_file(const std::string& path);
SavedView parse_view(const std::string& text, const std::string& path);  // the file's text
// read_view_file() for a command: its error told on stderr, nullopt and `status` the exit
// status (usage, or interrupted when a signal stopped the reading). An empty path: no
// file, an empty view.
std::optional<SavedView> read_view_or_report(const std::string& path, int& status);
std::string view_json(const SavedView& view);  // the file's text
// Writes atomically through the output targets (throws OutputError).
void write_view_file(const std::string& path, const SavedView& view);

// Applies the entries a view has to a render::View (size, magnification, colouring,
// toggles, zoom and centre) and to the scales of a run.
void apply_view(const SavedView& saved, render::View& view);
void apply_scales(const std::optional<render::RunExtent>& scales, render::RunExtent& extent);

}  // namespace fetic::app
