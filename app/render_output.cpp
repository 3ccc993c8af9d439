#include "app/render_output.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <thread>
#include <vector>

#include <omp.h>

#include "app/child_process.hpp"
#include "app/data_paths.hpp"
#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "app/movie_stream.hpp"
#include "app/output_file.hpp"
#include "scenes/scene_error.hpp"
#include "solver/threads.hpp"

extern char** environ;

namespace fetic::app {
std::optional<ImageSize> parse_image_size(const std::string& text) {
  int width = 0, height = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &width, &x, &height, &extra) != 3 ||
      (x != 'x' && x != 'X'))
    return std::nullopt;
  if (width < kMinImageSide || height < kMinImageSide || width > kMaxImageSide ||
      height > kMaxImageSide)
    return std::nullopt;
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

CLI::Option* add_image_size_option(CLI::App* command, std::string& size) {
  return command->add_option("--size", size, "Image size in pixels")
      ->check(image_size_check())
      ->capture_default_str();
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
  write_output(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  });
}

void use_solver_threads_for_pictures(const solver::Model& model) {
  constexpr long long kParallelFrom = 200000;
  solver::set_thread_budget(model.dof_count() < kParallelFrom ? 1 : omp_get_num_procs());
}

int default_encoder_threads() {
  const unsigned cores = std::thread::hardware_concurrency();
  return cores > 0 ? static_cast<int>(cores) : 2;
}

std::optional<Headless> open_headless(const std::string& output, float text_size) {
  Headless headless;
  try {
    headless.context = render::make_egl_context();
  } catch (const render::NoDisplayError& error) {
    std::cerr << scenes::printable(output) << ": cannot render: " << error.what() << '\n';
    return std::nullopt;
  }
  headless.font = std::make_unique<render::FontAtlas>(1.3f * text_size, font_file("DejaVuSans.ttf"),
                                                      font_file("DejaVuSans-Bold.ttf"));
  if (!headless.font->note().empty()) std::cerr << "note: " << headless.font->note() << '\n';
  try {
    headless.renderer = std::make_unique<render::GlRenderer>(*headless.context, *headless.font);
  } catch (const render::RenderError& error) {
    std::cerr << scenes::printable(output) << ": cannot render: " << error.what() << '\n';
    return std::nullopt;
  }
  return headless;
}

bool make_output_directory(const std::string& directory) {
  namespace fs = std::filesystem;
  if (directory.empty()) {
    std::cerr << "the output directory is an empty name; give the name of a directory\n";
    return false;
  }
  std::error_code error;
  // What is there already, named: "File exists" or "Not a directory" would not say it.
  const fs::file_status there = fs::symlink_status(directory, error);
  if (fs::is_symlink(there) && !fs::exists(fs::status(directory, error))) {
    std::cerr << scenes::printable(directory) << ": is a symbolic link to '"
              << scenes::printable(fs::read_symlink(directory, error).string())
              << "', which does not exist; give the name of a directory\n";
    return false;
  }
  if (fs::exists(there) && !fs::is_directory(fs::status(directory, error))) {
    std::cerr << scenes::printable(directory)
              << ": is not a directory; the frames need a directory of their own\n";
    return false;
  }
  fs::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory)) {
    std::cerr << scenes::printable(directory) << ": cannot create the output directory"
              << (error ? " (" + error.message() + ")" : std::string()) << '\n';
    return false;
  }
  return true;
}

bool program_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::string directories = path;
  std::size_t start = 0;
  while (start <= directories.size()) {
    const std::size_t end = std::min(directories.find(':', start), directories.size());
    const std::filesystem::path candidate =
        std::filesystem::path(directories.substr(start, end - start)) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

// Runs ffmpeg on frames 0 .. count-1 of `directory`; the movie appears atomically.
int assemble_movie(const std::string& directory, int count, int fps, const std::string& movie,
                   std::ostream& report) {
  if (!program_on_path("ffmpeg")) {
    std::cerr << scenes::printable(movie) << ": ffmpeg is not installed, so no movie was made; the "
              << count << " frames are in " << directory << " (apt-get install ffmpeg)\n";
    return kExitOutput;
  }
  // frame_0000.png -> frame_%04d.png
  const std::string name = frame_name(0, count);
  const std::string digits = std::to_string(name.size() - std::string("frame_.png").size());
  const std::string input =
      (std::filesystem::path(directory) / ("frame_%0" + digits + "d.png")).string();
  try {
    write_output_by(movie, [&](const ExternalTarget& target) {
      pid_t child = 0;
      const int spawned = spawn_ffmpeg({"-framerate", std::to_string(fps), "-start_number", "0",
                                        "-i", input, "-frames:v", std::to_string(count)},
                                       {}, target, -1, child);
      if (spawned != 0) return false;
      // SIGINT/SIGTERM interrupt waitpid (no SA_RESTART): stop ffmpeg then, and wait for
      // it, so that its temporary file is removed only once nobody writes it any more.
      int status = 0;
      while (waitpid(child, &status, 0) < 0) {
        if (errno != EINTR) return false;
        if (interrupted()) {
          stop_child(child);
          return false;
        }
      }
      return !interrupted() && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    });
  } catch (const OutputError& error) {
    if (interrupted()) {
      std::cerr << scenes::printable(movie) << ": interrupted by " << interrupt_name()
                << " while ffmpeg was assembling the movie; no movie written, the " << count
                << " frames are complete\n";
      return kExitInterrupted;
    }
    std::cerr << error.what() << " (ffmpeg failed)\n";
    return kExitOutput;
  }
  report << "movie        " << movie << " (" << count << " frames at " << fps << " per second)\n";
  return kExitOk;
}

}  // namespace fetic::app
