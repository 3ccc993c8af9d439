// fetic bench-render: frames per second of an iteration movie including PNG writing, with
// the split between drawing (draw lists, GL, read-back) and encoding (PNG, file), and the
// speed-up of encoding on worker threads over encoding on the rendering thread, measured
// in the same run on the same frames. A benchmark, not a test: it asserts nothing.

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "app/data_paths.hpp"
#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "app/method_options.hpp"
#include "app/output_file.hpp"
#include "app/render_output.hpp"
#include "app/scene_input.hpp"
#include "render/colormap.hpp"
#include "render/frame_composer.hpp"
#include "render/frame_sequence.hpp"

namespace fetic::app {
namespace {

using Clock = std::chrono::steady_clock;

struct BenchArgs {
  std::string scene = bundled_scene("thesis.toml");
  std::string method = "active-set";
  std::string size = "1280x720";
  int frames = 40;
  int threads = 0;
  std::string out;
};

double seconds(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Timing {
  double compose = 0, render = 0, encode = 0, write = 0, total = 0;
};

int run_bench(const BenchArgs& args) {
  int status = kExitOk;
  const auto scene = load_scene_or_report(args.scene, status);
  if (!scene) return status;
  const solver::Model model = solver::build_model(*scene);
  const ImageSize size = *parse_image_size(args.size);
  std::unique_ptr<solver::Method> method;
  try {
    method = solver::make_method(*solver::parse_method(args.method), model, solver::SolveOptions{});
  } catch (const solver::SolverError& error) {
    std::cerr << args.scene << ": " << error.what() << '\n';
    return kExitSolverSetup;
  }
  std::string directory = args.out;
  const bool temporary = directory.empty();
  if (temporary)
    directory = (std::filesystem::temp_directory_path() /
                 ("fetic-bench-render-" + std::to_string(::getpid())))
                    .string();
  if (!make_output_directory(directory)) return kExitOutput;
  auto headless = open_headless(directory);
  if (!headless) return kExitNoDisplay;

  const render::FramePlan plan;  // every iteration at load factor 1
  const render::RunExtent extent = render::survey(model, *method, plan);
  render::View view;
  view.width = size.width;
  view.height = size.height;
  const render::FrameComposer composer(model, view, extent,
                                       {model.title, args.method, std::string()});
  // Frames of the iteration movie, repeated until there are enough.
  const auto for_each_frame = [&](const std::function<void(const render::Frame&, int)>& use) {
    int index = 0;
    while (index < args.frames && !interrupted())
      render::run_frames(*method, plan, [&](const render::Frame& frame) {
        if (interrupted()) return false;
        use(frame, index);
        return ++index < args.frames;
      });
  };
  const auto draw = [&](const render::Frame& frame, Timing& timing) {
    auto start = Clock::now();
    const render::ComposedFrame composed = composer.compose(frame);
    timing.compose += seconds(start);
    start = Clock::now();
    render::Image image = headless->renderer->render(
        size.width, size.height, {&composed.scene, &composed.overlay}, render::palette::background);
    timing.render += seconds(start);
    return image;
  };
  const auto path_of = [&](int index) {
    return (std::filesystem::path(directory) / frame_name(index, args.frames)).string();
  };

  try {
    // Warm-up: caches, llvmpipe's shader compilation.
    for_each_frame([&](const render::Frame& frame, int) {
      Timing ignored;
      draw(frame, ignored);
    });

    Timing serial;
    auto start = Clock::now();
    for_each_frame([&](const render::Frame& frame, int index) {
      const render::Image image = draw(frame, serial);
      auto step = Clock::now();
      const render::PngBytes png = render::encode_png(image);
      serial.encode += seconds(step);
      step = Clock::now();
      write_png_atomically(path_of(index), png);
      serial.write += seconds(step);
    });
    serial.total = seconds(start);

    const int threads = args.threads > 0 ? args.threads : default_encoder_threads();
    Timing pooled;
    start = Clock::now();
    {
      render::PngEncoderPool pool(threads);
      for_each_frame([&](const render::Frame& frame, int index) {
        render::Image image = draw(frame, pooled);
        const std::string path = path_of(index);
        pool.submit(std::move(image),
                    [path](render::PngBytes png) { write_png_atomically(path, png); });
      });
      pool.finish();
    }
    pooled.total = seconds(start);
    if (interrupted()) {
      std::cerr << directory << ": fetic bench-render interrupted by " << interrupt_name()
                << "; the frames written are complete\n";
      if (temporary) std::filesystem::remove_all(directory);
      return kExitInterrupted;
    }

    const double n = args.frames;
    const auto ms = [&](double total) { return 1e3 * total / n; };
    std::printf("bench-render %s, %s, %dx%d, %d frames (iteration movie of %d frames, repeated)\n",
                args.scene.c_str(), args.method.c_str(), size.width, size.height, args.frames,
                extent.frame_count);
    std::printf("renderer     %s\n", headless->context->description().c_str());
    std::printf(
        "per frame    draw lists %.2f ms, GL render + read-back %.2f ms, PNG encode %.2f ms, "
        "file write %.2f ms\n",
        ms(serial.compose), ms(serial.render), ms(serial.encode), ms(serial.write));
    std::printf("split        render %.0f%% / encode+write %.0f%% of the single-threaded time\n",
                100.0 * (serial.compose + serial.render) / serial.total,
                100.0 * (serial.encode + serial.write) / serial.total);
    std::printf("single thread  %.2f frames/s (render, encode and write one after another)\n",
                n / serial.total);
    std::printf("%d encoder threads  %.2f frames/s (rendering on the main thread)\n", threads,
                n / pooled.total);
    std::printf("             (rendering on the main thread took %.2f ms per frame meanwhile)\n",
                ms(pooled.compose + pooled.render));
    std::printf("speed-up     %.2fx\n", serial.total / pooled.total);
  } catch (const OutputError& error) {
    return report_output_error(error);
  } catch (const render::RenderError& error) {
    std::cerr << directory << ": rendering failed: " << error.what() << '\n';
    return kExitOutput;
  }
  if (temporary) std::filesystem::remove_all(directory);
  return kExitOk;
}

}  // namespace

void register_bench_render(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* command = app.add_subcommand(
      "bench-render", "Measure frames per second of an iteration movie, including PNG writing");
  command->add_option("scene", args->scene, "Scene file")->capture_default_str();
  command->add_option("--method", args->method, "Method")
      ->check(method_name())
      ->capture_default_str();
  command->add_option("--size", args->size, "Image size in pixels")
      ->check(image_size_check())
      ->capture_default_str();
  command->add_option("--frames", args->frames, "Frames per measurement")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  command->add_option("--threads", args->threads, "Encoder threads (0: one per core)")
      ->check(CLI::Range(0, 64));
  command->add_option("--out", args->out,
                      "Keep the frames here (default: a temporary directory, removed after)");
  command->callback([args, &exit_code] { exit_code = run_bench(*args); });
}

}  // namespace fetic::app
