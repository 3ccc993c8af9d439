#pragma once
// What the rendering commands (render, figures, bench-render) share: image sizes on the
// command line, the headless renderer with its error messages, PNG files written
// atomically.

#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "app/image_size.hpp"
#include "render/egl_context.hpp"
#include "render/font.hpp"
#include "render/gl_renderer.hpp"
#include "render/png_writer.hpp"
#include "solver/model.hpp"

namespace fetic::app {

struct ImageSize {
  int width = 1280;
  int height = 720;
};

// "WxH" with 16 <= W, H <= 8192.
std::optional<ImageSize> parse_image_size(const std::string& text);
CLI::Validator image_size_check();
// The picture commands' --size option (WxH in pixels), its default shown in the help.
CLI::Option* add_image_size_option(CLI::App* command, std::string& size);

// frame_0000.png ... with at least 4 digits, more when `count` needs them.
std::string frame_name(int index, int count);

// Writes the PNG through write_output (app/output_file.hpp): a reader never sees a
// half-written PNG. Throws OutputError naming the file.
void write_png_atomically(const std::string& path, const render::PngBytes& png);

// Worker threads for PNG encoding: one per core.
int default_encoder_threads();

// The solver's OpenMP threads while pictures are drawn beside it: one below 200,000
// unknowns. On 2 cores a team's start-up and its spinning at barriers cost more than the
// work and take the core the software rasterizer and the encoders need (a perf profile of
// `fetic render` on the thesis scene: 19% of the time in libgomp's spin loop).
void use_solver_threads_for_pictures(const solver::Model& model);

struct Headless {
  std::unique_ptr<render::GlContext> context;
  std::unique_ptr<render::FontAtlas> font;
  std::unique_ptr<render::GlRenderer> renderer;
};
// The EGL context, fonts and renderer, or nullopt after printing why (the caller exits
// with kExitNoDisplay). `output` names what was to be rendered, for the message.
// `text_size`: the base text size of the frames (render::base_text_size), so that the
// font atlas has sizes for it.
std::optional<Headless> open_headless(const std::string& output, float text_size = 14.0f);

// Creates the directory (and parents); prints the problem and returns false on failure.
bool make_output_directory(const std::string& directory);

// True when an executable `name` is on PATH.
bool program_on_path(const std::string& name);

// Runs ffmpeg on frames 0 .. count-1 of `directory` (frame_0000.png, ...): an H.264 mp4 at
// `fps` is written to `movie` through write_output_by (app/output_file.hpp: atomically to
// a file; a fragmented mp4 to a FIFO, a device or "-", stdout). Prints what it made to
// `report`. Returns an exit status (kExitOutput when ffmpeg is missing or fails, saying so).
int assemble_movie(const std::string& directory, int count, int fps, const std::string& movie,
                   std::ostream& report);

}  // namespace fetic::app
