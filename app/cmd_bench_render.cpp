// fetic bench-render: frames per second of an iteration movie, measured in one run on the
// same frames: the split between drawing (draw lists, GL, read-back) and PNG encoding,
// libspng against the stb_image_write encoder fetic used before, PNG frames on worker
// threads with either, and the movie streamed into ffmpeg. A benchmark, not a test: it
// asserts nothing.

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

#include "app/commands.hpp"
#include "app/data_paths.hpp"
#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "app/method_options.hpp"
#include "app/movie_stream.hpp"
#include "app/out_of_memory.hpp"
#include "app/output_file.hpp"
#include "app/output_options.hpp"
#include "app/render_output.hpp"
#include "app/scene_input.hpp"
#include "render/colormap.hpp"
#include "render/frame_composer.hpp"
#include "render/frame_sequence.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::app {
namespace {

using Clock = std::chrono::steady_clock;

struct BenchArgs {
  std::string scene = bundled_scene("thesis.toml");
  std::string method = "active-set";
  std::string size = "1280x720";
  int frames = 40;
  int threads = 0;
  int samples = 4;
  std::string out;
};

double seconds(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Timing {
  double compose = 0, render = 0, encode = 0, write = 0, total = 0;
};

// How busy the machine was (benchmarks here share it): /proc/loadavg's first three.
std::string load_average() {
  std::ifstream in("/proc/loadavg");
  double one = 0, five = 0, fifteen = 0;
  if (!(in >> one >> five >> fifteen)) return "unknown";
  char text[96];
  std::snprintf(text, sizeof text, "load average %.2f, %.2f, %.2f (1, 5, 15 min) on %u cores", one,
                five, fifteen, std::thread::hardware_concurrency());
  return text;
}

// The measurements, each a phase over the same frames of the iteration movie.
struct RenderBench {
  const BenchArgs& args;
  const solver::Model& model;
  solver::Method& method;
  const std::string& directory;
  Headless& headless;
  ImageSize size;
  render::RunExtent extent = render::survey(model, method, plan());
  render::FrameComposer composer{model, view(size), extent,
                                 render::OverlayInfo{model.title, args.method, {}, {}}};
  int threads = args.threads > 0 ? args.threads : default_encoder_threads();
  Timing serial{}, serial_stb{}, pooled{}, pooled_stb{}, streamed{};
  std::size_t spng_bytes = 0, stb_bytes = 0;
  bool have_ffmpeg = program_on_path("ffmpeg");

  // Every iteration at load factor 1.
  static const render::FramePlan& plan() {
    static const render::FramePlan every_iteration;
    return every_iteration;
  }
  static render::View view(ImageSize size) {
    render::View v;
    v.width = size.width;
    v.height = size.height;
    return v;
  }
  // Frames of the iteration movie, repeated until there are enough.
  void for_each_frame(const std::function<void(const render::Frame&, int)>& use) {
    int index = 0;
    while (index < args.frames && !interrupted())
      render::run_frames(method, plan(), [&](const render::Frame& frame) {
        if (interrupted()) return false;
        use(frame, index);
        return ++index < args.frames;
      });
  }
  render::Image draw(const render::Frame& frame, Timing& timing) {
    auto start = Clock::now();
    const render::ComposedFrame composed = composer.compose(frame);
    timing.compose += seconds(start);
    start = Clock::now();
    render::Image image = headless.renderer->render(size.width, size.height, composed.layers(),
                                                    render::palette::background);
    timing.render += seconds(start);
    return image;
  }
  std::string path_of(int index) const {
    return (std::filesystem::path(directory) / frame_name(index, args.frames)).string();
  }

  // Warm-up: caches, llvmpipe's shader compilation.
  void warm_up() {
    for_each_frame([&](const render::Frame& frame, int) {
      Timing ignored;
      draw(frame, ignored);
    });
  }
  // One after another on this thread: drawing, then both encoders on the same image.
  void measure_serial() {
    for_each_frame([&](const render::Frame& frame, int index) {
      const render::Image image = draw(frame, serial);
      auto step = Clock::now();
      const render::PngBytes reference = render::encode_png_stb(image);
      serial_stb.encode += seconds(step);
      stb_bytes += reference.size();
      step = Clock::now();
      const render::PngBytes png = render::encode_png(image);
      serial.encode += seconds(step);
      spng_bytes += png.size();
      step = Clock::now();
      write_png_atomically(path_of(index), png);
      serial.write += seconds(step);
    });
  }
  // The PNG frames of `fetic render`: drawing here, encoding and writing on the pool.
  void measure_pooled(render::PngEncoderPool::Encoder encoder, Timing& timing) {
    const auto start = Clock::now();
    render::PngEncoderPool pool(threads, 0, encoder);
    for_each_frame([&](const render::Frame& frame, int index) {
      render::Image image = draw(frame, timing);
      const std::string path = path_of(index);
      pool.submit(std::move(image),
                  [path](render::PngBytes png) { write_png_atomically(path, png); });
    });
    pool.finish();
    timing.total = seconds(start);
  }
  // The movie of `fetic render --movie` (no PNG): frames streamed into ffmpeg.
  void measure_movie() {
    if (!have_ffmpeg) return;
    const std::string movie = (std::filesystem::path(directory) / "bench.mp4").string();
    const auto start = Clock::now();
    write_output_by(movie, [&](const ExternalTarget& target) {
      MovieStream stream(target, size.width, size.height, 30);
      for_each_frame(
          [&](const render::Frame& frame, int) { stream.submit(draw(frame, streamed)); });
      return stream.finish();
    });
    streamed.total = seconds(start);
  }
  void print() const;
};

void RenderBench::print() const {
  const double n = args.frames;
  const auto ms = [&](double total) { return 1e3 * total / n; };
  std::printf("bench-render %s, %s, %dx%d, %d frames (iteration movie of %d frames, repeated)\n",
              args.scene.c_str(), args.method.c_str(), size.width, size.height, args.frames,
              extent.frame_count);
  std::printf("renderer     %s, %d samples per pixel\n", headless.context->description().c_str(),
              headless.renderer->samples());
  std::printf(
      "per frame    draw lists %.2f ms, GL render + read-back %.2f ms, file write %.2f ms\n",
      ms(serial.compose), ms(serial.render), ms(serial.write));
  std::printf(
      "PNG encode   libspng %.2f ms (%.0f kB) against stb_image_write %.2f ms (%.0f kB): "
      "%.1fx faster, %.2fx the size\n",
      ms(serial.encode), spng_bytes / n / 1e3, ms(serial_stb.encode), stb_bytes / n / 1e3,
      serial_stb.encode / serial.encode, static_cast<double>(spng_bytes) / stb_bytes);
  const double serial_total = serial.compose + serial.render + serial.encode + serial.write;
  std::printf("single thread  %.2f frames/s (render, encode and write one after another)\n",
              n / serial_total);
  std::printf(
      "PNG frames   %d encoder threads: %.2f frames/s with libspng, %.2f with "
      "stb_image_write (before): %.2fx\n",
      threads, n / pooled.total, n / pooled_stb.total, pooled_stb.total / pooled.total);
  if (have_ffmpeg)
    std::printf(
        "movie        streamed to ffmpeg (H.264, no PNG): %.2f frames/s (%.2fx the PNG "
        "frames with libspng); drawing took %.2f ms per frame meanwhile\n",
        n / streamed.total, pooled.total / streamed.total, ms(streamed.compose + streamed.render));
  else
    std::printf("movie        not measured: ffmpeg is not installed\n");
  std::printf("load         %s\n", load_average().c_str());
}

// The phases: read, set up (method, folder, renderer), measure, report.
int run_bench(const BenchArgs& args) {
  int status = kExitOk;
  const auto scene = load_scene_or_report(args.scene, status);
  if (!scene) return status;
  if (!memory_suffices(*scene, args.scene, {{*solver::parse_method(args.method)}, false, 0},
                       status))
    return status;
  Activity rendering("rendering");
  const solver::Model model = solver::build_model(*scene);
  use_solver_threads_for_pictures(model);
  const ImageSize size = *parse_image_size(args.size);
  std::unique_ptr<solver::Method> method;
  try {
    method = solver::make_method(*solver::parse_method(args.method), model, solver::SolveOptions{});
  } catch (const solver::SolverError& error) {
    std::cerr << scenes::printable(args.scene) << ": " << error.what() << '\n';
    return kExitSolverSetup;
  }
  const bool temporary = args.out.empty();
  const std::string directory = temporary ? (std::filesystem::temp_directory_path() /
                                             ("fetic-bench-render-" + std::to_string(::getpid())))
                                                .string()
                                          : args.out;
  if (!make_output_directory(directory)) return kExitOutput;
  auto headless = open_headless(directory, render::base_text_size(size.width, size.height));
  if (!headless) return kExitNoDisplay;
  try {
    headless->renderer->set_samples(args.samples);
    RenderBench bench{args, model, *method, directory, *headless, size};
    bench.warm_up();
    bench.measure_serial();
    bench.measure_pooled(&render::encode_png_stb, bench.pooled_stb);
    bench.measure_pooled(&render::encode_png, bench.pooled);
    bench.measure_movie();
    if (interrupted()) {
      std::cerr << scenes::printable(directory) << ": fetic bench-render interrupted by "
                << interrupt_name() << "; the frames written are complete\n";
      if (temporary) std::filesystem::remove_all(directory);
      return kExitInterrupted;
    }
    bench.print();
  } catch (const OutputError& error) {
    return report_output_error(error);
  } catch (const render::RenderError& error) {
    std::cerr << scenes::printable(directory) << ": rendering failed: " << error.what() << '\n';
    return kExitOutput;
  }
  if (temporary) std::filesystem::remove_all(directory);
  return kExitOk;
}

}  // namespace

void register_bench_render(CLI::App& app, int& exit_code) {
  const auto [command, args] = add_command(
      app, "bench-render", "Measure frames per second of an iteration movie, including PNG writing",
      exit_code, run_bench);
  look_up_bundled_scenes(
      command->add_option("scene", args->scene, "Scene file or bundled scene name"))
      ->capture_default_str();
  add_method_option(command, args->method, "Method");
  add_image_size_option(command, args->size);
  command->add_option("--frames", args->frames, "Frames per measurement")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  command->add_option("--threads", args->threads, "Encoder threads (0: one per core)")
      ->check(CLI::Range(0, 64));
  command->add_option("--samples", args->samples, "Multisampling: samples per pixel")
      ->check(CLI::Range(1, 32))
      ->capture_default_str();
  command
      ->add_option("--out", args->out,
                   "Keep the frames here (default: a temporary directory, removed after)")
      ->check(output_name(OutputKind::Folder));
}

}  // namespace fetic::app
