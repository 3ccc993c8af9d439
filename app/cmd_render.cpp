// fetic render SCENE --out DIR: solver states as PNG frames (an iteration movie, the final
// state, or a sequence of load steps), optionally assembled into an mp4 by ffmpeg.

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "app/load_factor_check.hpp"
#include "app/method_options.hpp"
#include "app/movie_stream.hpp"
#include "app/out_of_memory.hpp"
#include "app/output_file.hpp"
#include "app/output_options.hpp"
#include "app/progress.hpp"
#include "app/render_output.hpp"
#include "app/scene_input.hpp"
#include "app/view_file.hpp"
#include "app/vtu_export.hpp"
#include "render/colormap.hpp"
#include "render/frame_composer.hpp"
#include "render/frame_sequence.hpp"
#include "scenes/scene_error.hpp"
#include "solver/method.hpp"

namespace fetic::app {
namespace {

struct RenderArgs {
  std::string scene;
  std::string out;
  MethodArgs method;  // --method, --preconditioner, --tol, --load-factor, --load-steps, ...
  std::string size = "1280x720";
  bool every_iteration = false;
  bool final_only = false;
  std::string movie;
  int fps = 8;
  double magnification = 0.0;
  std::string color = "subdomain";
  bool no_overlay = false;
  int max_frames = 2000;
  int threads = 0;
  int samples = 4;
  std::string view;  // a saved view (app/view_file.hpp)
  // Given on the command line: these win over the view's entries.
  bool size_given = false, magnification_given = false, color_given = false;
  bool labels = false;
  std::string vtu;  // also write each frame's state as ParaView files here
  std::string vtu_format = "zlib";
  bool progress = false;
  bool quiet = false;
};

// --color NAME (the CLI11 check admits only known names).
render::ColorBy color_by(const std::string& name) {
  return color_from_name(name).value_or(render::ColorBy::Subdomain);
}

// ---- phase 0: the output targets, before any work ----

int refused_target(const RenderArgs& args) {
  if (args.out.empty() && args.movie.empty()) {
    std::cerr << "fetic render: nothing to write: give --out DIR (PNG frames), --movie "
                 "FILE.mp4, or both\n";
    return kExitUsage;
  }
  try {
    if (!args.out.empty()) check_output_folder(args.out);
    if (!args.vtu.empty()) check_output_folder(args.vtu);
  } catch (const OutputError& error) {
    return report_output_error(error);
  }
  // The movie may go into the frames' folder: made first.
  if (!args.out.empty() && !make_output_directory(args.out)) return kExitOutput;
  try {
    if (!args.movie.empty()) check_output_file(args.movie);
  } catch (const OutputError& error) {
    return report_output_error(error);
  }
  return kExitOk;
}

// ---- phase 1: read the view and the scene ----

int read_view(const RenderArgs& args, SavedView& saved) {
  if (args.view.empty()) return kExitOk;
  try {
    saved = read_view_file(args.view);
  } catch (const ViewFileError& error) {
    std::cerr << error.what() << '\n';
    return kExitUsage;
  }
  return kExitOk;
}

std::optional<scenes::Scene> read_scene(const RenderArgs& args, const SavedView& saved,
                                        int& status) {
  auto scene = load_scene_or_report(args.scene, status);
  if (!scene) return std::nullopt;
  status = kExitUsage;
  if (const std::string problem =
          load_factor_problem(*scene, args.method.load_factors(),
                              args.method.load_steps.empty() ? "--load-factor" : "--load-steps");
      !problem.empty()) {
    std::cerr << scenes::printable(args.scene) << ": " << problem << '\n';
    return std::nullopt;
  }
  // Only beams carry a bending moment: a picture of bars or plane struts coloured by it
  // would be all grey, so say why rather than draw it.
  const render::ColorBy wanted =
      args.color_given || !saved.color_by ? color_by(args.color) : *saved.color_by;
  if (wanted == render::ColorBy::Moment && scene->model != scenes::ModelKind::Frame) {
    std::cerr << scenes::printable(args.scene) << ": colouring by bending moment needs a frame "
              << "scene (model = \"frame\"); this one is a " << scenes::to_string(scene->model)
              << " model, whose struts carry no bending moment\n";
    return std::nullopt;
  }
  status = kExitOk;
  if (!memory_suffices(*scene, args.scene, {{args.method.kind()}, false, 0}, status))
    return std::nullopt;
  return scene;
}

// ---- phase 2: set up the method, the renderer and the survey ----

// The survey pass: the same deterministic run, for fixed scales and the frame count.
int survey_run(const RenderArgs& args, const solver::Model& model, solver::Method& method,
               const render::FramePlan& plan, render::RunExtent& extent) {
  ProgressLine progress(progress_mode(args.progress, args.quiet));
  extent = render::survey(model, method, plan, [&] {
    if (progress.due())
      progress.update("render survey: iteration " + std::to_string(method.iteration()));
    return !interrupted();
  });
  progress.clear();
  if (interrupted()) {
    std::cerr << scenes::printable(args.scene) << ": interrupted by " << interrupt_name()
              << " before any frame\n";
    return kExitInterrupted;
  }
  if (extent.frame_count > args.max_frames) {
    std::cerr << scenes::printable(args.scene) << ": " << extent.frame_count << " frames ("
              << args.method.method << " takes " << extent.largest_iteration
              << " iterations) is more than --max-frames " << args.max_frames
              << "; raise it, or render --final or fewer --load-steps\n";
    return kExitUsage;
  }
  return kExitOk;
}

// The view: a saved view's entries, then the options given on the command line.
render::View make_view(const RenderArgs& args, const SavedView& saved, ImageSize size) {
  render::View view;
  view.magnification = args.magnification;
  view.color_by = color_by(args.color);
  view.show_overlay = !args.no_overlay;
  view.show_labels = args.labels;
  apply_view(saved, view);
  if (saved.width && saved.height && !args.size_given) size = {*saved.width, *saved.height};
  view.width = size.width;
  view.height = size.height;
  if (args.magnification_given) view.magnification = args.magnification;
  if (args.color_given) view.color_by = color_by(args.color);
  if (args.no_overlay) view.show_overlay = false;
  if (args.labels) view.show_labels = true;
  return view;
}

render::OverlayInfo overlay_info(const RenderArgs& args, const solver::Model& model) {
  render::OverlayInfo info;
  info.title =
      model.title.empty() ? std::filesystem::path(args.scene).filename().string() : model.title;
  info.method = args.method.method;
  if (solver::is_dual(args.method.kind())) info.method += " (" + args.method.preconditioner + ")";
  return info;
}

// ---- phase 3: render the frames and write them, all or none ----

struct FrameWriter {
  const RenderArgs& args;
  const solver::Model& model;
  solver::Method& method;
  const render::FramePlan& plan;
  const render::RunExtent& extent;
  const render::FrameComposer& composer;
  Headless& headless;
  int written = 0;

  // PNG frames when --out is given, a movie streamed to ffmpeg when --movie is: both
  // from the same rendered images; the ParaView files beside them with --vtu.
  void render_frames(MovieStream* stream, VtuSeries* vtu) {
    const int width = composer.view().width, height = composer.view().height;
    std::unique_ptr<render::PngEncoderPool> pool;
    if (!args.out.empty())
      pool = std::make_unique<render::PngEncoderPool>(args.threads > 0 ? args.threads
                                                                       : default_encoder_threads());
    // ParaView's time: the load factor for a rising sweep of one frame per step, else the
    // frame number.
    bool time_is_load = !plan.every_iteration;
    for (size_t k = 1; k < plan.load_factors.size(); ++k)
      time_is_load = time_is_load && plan.load_factors[k] > plan.load_factors[k - 1];
    ProgressLine progress(progress_mode(args.progress, args.quiet));
    render::run_frames(method, plan, [&](const render::Frame& frame) {
      if (interrupted()) return false;
      progress.update("render frame " + std::to_string(frame.index + 1) + " of " +
                      std::to_string(extent.frame_count));
      if (vtu)
        vtu->write(frame.snapshot, time_is_load
                                       ? plan.load_factors[static_cast<size_t>(frame.load_step)]
                                       : frame.index);
      render::Image image = headless.renderer->render(
          width, height, composer.compose(frame).layers(), render::palette::background);
      if (stream && pool) {
        stream->submit(image);  // a copy: the PNG encoder takes the other
      } else if (stream) {
        stream->submit(std::move(image));
      }
      if (pool) {
        const std::string path =
            (std::filesystem::path(args.out) / frame_name(frame.index, extent.frame_count))
                .string();
        pool->submit(std::move(image),
                     [path](render::PngBytes png) { write_png_atomically(path, png); });
      }
      ++written;
      return true;
    });
    if (pool) pool->finish();
    progress.clear();
  }

  // Each file appears whole (frames, movie, ParaView files), frame by frame as the run
  // goes, so that an interrupted run leaves the complete frames it made.
  int run(bool movie_wanted) {
    const bool frames_wanted = !args.out.empty();
    try {
      std::unique_ptr<VtuSeries> vtu;
      if (!args.vtu.empty())
        vtu = std::make_unique<VtuSeries>(args.vtu, model, *parse_vtk_encoding(args.vtu_format));
      if (movie_wanted) {
        write_output_by(args.movie, [&](const ExternalTarget& target) {
          MovieStream stream(target, composer.view().width, composer.view().height, args.fps);
          render_frames(&stream, vtu.get());
          return stream.finish();
        });
      } else {
        render_frames(nullptr, vtu.get());
      }
    } catch (const OutputError& error) {
      if (!interrupted()) return report_output_error(error);
      std::cerr << scenes::printable(movie_wanted ? args.movie : args.out) << ": interrupted by "
                << interrupt_name()
                << (movie_wanted ? " while streaming frames to ffmpeg; no movie written" : "")
                << (frames_wanted
                        ? ", " + std::to_string(written) + " complete frames in " + args.out
                        : std::string())
                << "\n";
      return kExitInterrupted;
    } catch (const render::RenderError& error) {
      std::cerr << scenes::printable(frames_wanted ? args.out : args.movie)
                << ": rendering failed: " << error.what() << '\n';
      return kExitOutput;
    }
    if (interrupted()) {
      std::cerr << scenes::printable(args.out) << ": interrupted by " << interrupt_name()
                << " after " << written << " complete frames\n";
      return kExitInterrupted;
    }
    return kExitOk;
  }
};

// ffmpeg missing: the frames alone when --out is given (status 5 at the end), else 5 now.
int movie_problem(const RenderArgs& args, bool& movie_wanted) {
  movie_wanted = !args.movie.empty();
  if (!movie_wanted || program_on_path("ffmpeg")) return kExitOk;
  const bool frames_wanted = !args.out.empty();
  std::cerr << scenes::printable(args.movie) << ": ffmpeg is not installed, so no movie can be made"
            << (frames_wanted ? "; writing the PNG frames only" : "")
            << " (apt-get install ffmpeg)\n";
  movie_wanted = false;
  return kExitOutput;
}

// ---- phase 4: report ----

void print_report(const RenderArgs& args, const FrameWriter& frames, bool movie_wanted) {
  // With --movie - the movie goes to stdout: the report goes to stderr then.
  std::ostream& report = is_stdout(args.movie) ? std::cerr : std::cout;
  const render::View& view = frames.composer.view();
  const int count = frames.extent.frame_count;
  const double magnification = frames.composer.framing().magnification;
  if (!args.out.empty()) {
    report << "frames       " << frames.written << " in " << args.out << " ("
           << frame_name(0, count) << " .. " << frame_name(frames.written - 1, count) << "), "
           << view.width << "x" << view.height << ", magnification " << magnification << "\n";
    const std::string next =
        (std::filesystem::path(args.out) / frame_name(frames.written, count)).string();
    if (std::filesystem::exists(next))
      report << "note         " << next
             << " and later frames are from an earlier run; they were left alone\n";
  }
  if (movie_wanted)
    report << "movie        " << args.movie << " (" << frames.written << " frames at " << args.fps
           << " per second, " << view.width << "x" << view.height << ", magnification "
           << magnification << ")\n";
  report << "renderer     " << frames.headless.context->description() << ", " << args.samples
         << (args.samples == 1 ? " sample" : " samples") << " per pixel\n";
}

// The phases: check the targets, read, set up (method, renderer, survey), render and
// write, report.
int run_render(const RenderArgs& args) {
  if (const int status = refused_target(args)) return status;
  SavedView saved;
  if (const int status = read_view(args, saved)) return status;
  int status = kExitOk;
  const auto scene = read_scene(args, saved, status);
  if (!scene) return status;
  Activity rendering("rendering");
  const solver::Model model = solver::build_model(*scene);
  use_solver_threads_for_pictures(model);
  const render::View view = make_view(args, saved, *parse_image_size(args.size));

  render::FramePlan plan;
  plan.load_factors = args.method.load_factors();
  // One frame per load step unless every iteration is asked for; one load factor: every
  // iteration unless --final.
  plan.every_iteration = args.method.load_steps.empty() ? !args.final_only : args.every_iteration;
  std::unique_ptr<solver::Method> method;
  try {
    method = solver::make_method(args.method.kind(), model, args.method.options());
  } catch (const solver::SolverError& error) {
    std::cerr << scenes::printable(args.scene) << ": " << error.what() << '\n';
    return kExitSolverSetup;
  }
  // Before the (possibly long) survey: the output directory and a display must exist.
  if (!args.out.empty() && !make_output_directory(args.out)) return kExitOutput;
  auto headless = open_headless(args.out.empty() ? args.movie : args.out,
                                render::base_text_size(view.width, view.height));
  if (!headless) return kExitNoDisplay;
  render::RunExtent extent;
  if (const int failed = survey_run(args, model, *method, plan, extent)) return failed;
  apply_scales(saved.scales, extent);
  const render::FrameComposer composer(model, view, extent, overlay_info(args, model),
                                       static_cast<int>(plan.load_factors.size()));

  bool movie_wanted = false;
  status = movie_problem(args, movie_wanted);
  if (status != kExitOk && args.out.empty()) return status;
  headless->renderer->set_samples(args.samples);
  FrameWriter frames{args, model, *method, plan, extent, composer, *headless};
  if (const int failed = frames.run(movie_wanted)) return failed;
  print_report(args, frames, movie_wanted);
  if (extent.final_status != solver::Status::Converged) {
    std::cerr << scenes::printable(args.scene) << ": " << args.method.method
              << " did not converge: " << extent.final_message << " (the frames show it)\n";
    if (status == kExitOk) status = kExitNotConverged;
  }
  return status;
}

}  // namespace

void register_render(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* command = app.add_subcommand(
      "render",
      "Render solver states as PNG frames and/or a movie: an iteration movie, the final state "
      "or load steps");
  command->add_option("scene", args->scene, "Scene file (TOML, see docs/SCENES.md)")->required();
  command
      ->add_option("--out", args->out,
                   "Write PNG frames frame_0000.png, frame_0001.png, ... into this directory")
      ->check(output_name(OutputKind::Folder));
  add_method_options(command, args->method);
  CLI::Option* size = command->add_option("--size", args->size, "Image size in pixels")
                          ->check(image_size_check())
                          ->capture_default_str();
  command->add_option("--view", args->view,
                      "Draw with a view saved in the window (size, centre, zoom, magnification, "
                      "colouring, toggles, scales; options given here win)");
  auto* every = command->add_flag("--every-iteration", args->every_iteration,
                                  "One frame per iteration, from the initial state (default for "
                                  "one load factor)");
  auto* final_only =
      command->add_flag("--final", args->final_only, "Only the final state of each solve");
  every->excludes(final_only);
  command
      ->add_option("--movie", args->movie,
                   "Stream the frames into this H.264 mp4 (ffmpeg; - for stdout; no PNG files "
                   "unless --out)")
      ->check(output_name());
  command->add_option("--fps", args->fps, "Frames per second of the movie")
      ->check(CLI::Range(1, 120))
      ->capture_default_str();
  CLI::Option* magnification =
      command
          ->add_option("--magnification", args->magnification,
                       "Displacement (and gap) magnification; 0 chooses one from the largest")
          ->check(number_in(0.0, 0.0, Bound::Closed, Bound::None))
          ->capture_default_str();
  CLI::Option* color =
      command
          ->add_option("--color", args->color,
                       "Colour struts by subdomain, one colour per strut, by axial stress or by "
                       "bending moment (frame scenes only)")
          ->check(CLI::IsMember({"subdomain", "strut", "stress", "moment"}))
          ->capture_default_str();
  command->add_flag("--no-overlay", args->no_overlay, "No information panel");
  command->add_flag("--labels", args->labels,
                    "Strut names beside the struts (where there is room)");
  command->add_option("--max-frames", args->max_frames, "Refuse runs with more frames")
      ->check(integer_in(1, 1'000'000))
      ->capture_default_str();
  command->add_option("--threads", args->threads, "PNG encoding threads (0: one per core)")
      ->check(CLI::Range(0, 64));
  command
      ->add_option("--samples", args->samples,
                   "Multisampling: samples per pixel (1: none; the GL's maximum at most)")
      ->check(CLI::Range(1, 32))
      ->capture_default_str();
  command
      ->add_option("--vtu", args->vtu,
                   "Also write every frame's state as ParaView files here (struts.pvd, "
                   "contacts.pvd)")
      ->check(output_name(OutputKind::Folder));
  command->add_option("--vtu-format", args->vtu_format, "Data encoding of the .vtu files")
      ->check(CLI::IsMember({"ascii", "binary", "zlib"}))
      ->capture_default_str();
  command->add_flag("--progress", args->progress,
                    "Show the progress line on stderr even when it is not a terminal");
  command->add_flag("--quiet", args->quiet, "No progress line");
  command->callback([args, size, magnification, color, &exit_code] {
    args->size_given = size->count() > 0;
    args->magnification_given = magnification->count() > 0;
    args->color_given = color->count() > 0;
    exit_code = run_render(*args);
  });
}

}  // namespace fetic::app
