#include "app/render_output.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <thread>

#include "app/atomic_file.hpp"

namespace fetic::app {
std::optional<ImageSize> parse_image_size(const std::string& text) {
  int width = 0, height = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &width, &x, &height, &extra) != 3 ||
      (x != 'x' && x != 'X'))
    return std::nullopt;
  if (width < 16 || height < 16 || width > 8192 || height > 8192) return std::nullopt;
  return ImageSize{width, height};
}

CLI::Validator image_size_check() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return parse_image_size(text)
                   ? std::string()
                   : "must be WIDTHxHEIGHT with 16..8192 pixels each, got " + text;
      },
      "WxH");
}

std::string frame_name(int index, int count) {
  int digits = 4;
  for (int limit = 10000; count > limit && digits < 9; limit *= 10)
    ++digits;
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "frame_%0*d.png", digits, index);
  return buffer;
}

void write_png_atomically(const std::string& path, const render::PngBytes& png) {
  if (png.empty()) throw OutputError(path + ": PNG encoding failed");
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  });
}

int default_encoder_threads() {
  const unsigned cores = std::thread::hardware_concurrency();
  return cores > 0 ? static_cast<int>(cores) : 2;
}

std::optional<Headless> open_headless(const std::string& output) {
  Headless headless;
  try {
    headless.context = render::make_egl_context();
  } catch (const render::NoDisplayError& error) {
    std::cerr << output << ": cannot render: " << error.what() << '\n';
    return std::nullopt;
  }
  headless.font = std::make_unique<render::FontAtlas>();
  if (!headless.font->note().empty()) std::cerr << "note: " << headless.font->note() << '\n';
  try {
    headless.renderer = std::make_unique<render::GlRenderer>(*headless.context, *headless.font);
  } catch (const render::RenderError& error) {
    std::cerr << output << ": cannot render: " << error.what() << '\n';
    return std::nullopt;
  }
  return headless;
}

bool make_output_directory(const std::string& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory)) {
    std::cerr << directory << ": cannot create the output directory"
              << (error ? " (" + error.message() + ")" : std::string()) << '\n';
    return false;
  }
  return true;
}

}  // namespace fetic::app
