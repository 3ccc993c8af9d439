// fetic render SCENE --out DIR: solver states as PNG frames (an iteration movie, the final
// state, or a sequence of load steps), optionally assembled into an mp4 by ffmpeg.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
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
#include "render/contact_chart.hpp"
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
  bool chart = false, no_chart = false;  // neither: the chart at 200 pairs and more
  std::string vtu;                       // also write each frame's state as ParaView files here
  std::string vtu_format = "zlib";
  bool progress = false;
  bool quiet = false;
};

// --color NAME (the CLI11 check admits only known names).
render::ColorBy color_by(const std::string& name) {
  return color_from_name(name).value_or(render::ColorBy::Subdomain);
}

// What the legends' scales are: the run's largest values over every frame (a movie's
// common scale), or the view file's; "" for one frame, whose own largest they are.
std::string scale_basis(const render::FramePlan& plan, const render::RunExtent& extent,
                        bool from_view) {
  if (from_view) return "of the view file";
  if (plan.load_factors.size() > 1) {
    char text[96];
    std::snprintf(text, sizeof text, "over loads %g-%g", plan.load_factors.front(),
                  plan.load_factors.back());
    return text;
  }
  if (extent.frame_count > 1) return "over all " + std::to_string(extent.frame_count) + " frames";
  return "";
}

int run_render(const RenderArgs& args) {
  int status = kExitOk;
  const std::optional<SavedView> view_file = read_view_or_report(args.view, status);
  if (!view_file) return status;
  const SavedView& saved = *view_file;
  const auto scene = load_scene_or_report(args.scene, status);
  if (!scene) return status;
  if (const std::string problem =
          load_factor_problem(*scene, args.method.load_factors(),
                              args.method.load_steps.empty() ? "--load-factor" : "--load-steps");
      !problem.empty()) {
    std::cerr << scenes::printable(args.scene) << ": " << problem << '\n';
    return kExitUsage;
  }
  // Only beams carry a bending moment: a picture of bars or plane struts coloured by it
  // would be all grey, so say why rather than draw it.
  const render::ColorBy wanted =
      args.color_given || !saved.color_by ? color_by(args.color) : *saved.color_by;
  if (wanted == render::ColorBy::Moment && scene->model != scenes::ModelKind::Frame) {
    std::cerr << scenes::printable(args.scene) << ": colouring by bending moment needs a frame "
              << "scene (model = \"frame\"); this one is a " << scenes::to_string(scene->model)
              << " model, whose struts carry no bending moment\n";
    return kExitUsage;
  }
  if (!memory_suffices(*scene, args.scene, {{args.method.kind()}, false, 0}, status)) return status;
  Activity rendering("rendering");
  const solver::Model model = solver::build_model(*scene);
  use_solver_threads_for_pictures(model);
  ImageSize size = *parse_image_size(args.size);
  if (saved.width && saved.height && !args.size_given) {
    size.width = *saved.width;
    size.height = *saved.height;
  }

  render::FramePlan plan;
  plan.load_factors = args.method.load_factors();
  // One frame per load step unless every iteration is asked for; one load factor: every
  // iteration unless --final.
  plan.every_iteration = args.method.load_steps.empty() ? !args.final_only : args.every_iteration;

  const solver::MethodKind kind = args.method.kind();
  const std::string& method_name = args.method.method;
  std::unique_ptr<solver::Method> method;
  try {
    method = solver::make_method(kind, model, args.method.options());
  } catch (const solver::SolverError& error) {
    std::cerr << scenes::printable(args.scene) << ": " << error.what() << '\n';
    return kExitSolverSetup;
  }
  // Before the (possibly long) survey: the output directory and a display must exist.
  if (args.out.empty() && args.movie.empty()) {
    std::cerr << "fetic render: nothing to write: give --out DIR (PNG frames), --movie "
                 "FILE.mp4, or both\n";
    return kExitUsage;
  }
  if (!args.out.empty() && !make_output_directory(args.out)) return kExitOutput;
  auto headless = open_headless(args.out.empty() ? args.movie : args.out,
                                std::max(render::base_text_size(size.width, size.height),
                                         static_cast<float>(saved.text_size.value_or(0.0))));
  if (!headless) return kExitNoDisplay;

  ProgressLine progress(progress_mode(args.progress, args.quiet));
  const auto solve_start = std::chrono::steady_clock::now();
  // Survey pass: the same deterministic run, for fixed scales and the frame count.
  render::RunExtent extent = render::survey(model, *method, plan, [&] {
    if (progress.due())
      progress.update("render survey: iteration " + std::to_string(method->iteration()));
    return !interrupted();
  });
  progress.clear();
  const auto solve_end = std::chrono::steady_clock::now();
  double first_frame_seconds = -1.0;
  if (interrupted()) {
    std::cerr << scenes::printable(args.scene) << ": interrupted by " << interrupt_name()
              << " before any frame\n";
    return kExitInterrupted;
  }
  if (extent.frame_count > args.max_frames) {
    std::cerr << scenes::printable(args.scene) << ": " << extent.frame_count << " frames ("
              << method_name << " takes " << extent.largest_iteration
              << " iterations) is more than --max-frames " << args.max_frames
              << "; raise it, or render --final or fewer --load-steps\n";
    return kExitUsage;
  }
  render::View view;
  view.width = size.width;
  view.height = size.height;
  view.magnification = args.magnification;
  view.color_by = color_by(args.color);
  view.show_overlay = !args.no_overlay;
  view.show_labels = args.labels;
  // A saved view: its entries, then the options given on the command line.
  apply_view(saved, view);
  view.width = size.width;
  view.height = size.height;
  if (args.magnification_given) view.magnification = args.magnification;
  if (args.color_given) view.color_by = color_by(args.color);
  if (args.no_overlay) view.show_overlay = false;
  if (args.labels) view.show_labels = true;
  view.show_chart = render::chart_shown(model, args.chart ? 1 : args.no_chart ? 0 : -1);
  apply_scales(saved.scales, extent);
  view.scale_basis = scale_basis(plan, extent, saved.scales.has_value());
  render::OverlayInfo info;
  info.title =
      model.title.empty() ? std::filesystem::path(args.scene).filename().string() : model.title;
  info.method = method_name;
  if (solver::is_dual(kind)) info.method += " (" + args.method.preconditioner + ")";
  const render::FrameComposer composer(model, view, extent, info,
                                       static_cast<int>(plan.load_factors.size()));

  // PNG frames when --out is given, a movie streamed to ffmpeg when --movie is: both
  // from the same rendered images.
  const bool frames_wanted = !args.out.empty();
  bool movie_wanted = !args.movie.empty();
  status = kExitOk;
  if (movie_wanted && !program_on_path("ffmpeg")) {
    std::cerr << scenes::printable(args.movie)
              << ": ffmpeg is not installed, so no movie can be made"
              << (frames_wanted ? "; writing the PNG frames only" : "")
              << " (apt-get install ffmpeg)\n";
    if (!frames_wanted) return kExitOutput;
    movie_wanted = false;
    status = kExitOutput;
  }
  headless->renderer->set_samples(args.samples);
  const int threads = args.threads > 0 ? args.threads : default_encoder_threads();
  std::unique_ptr<render::PngEncoderPool> pool;
  if (frames_wanted) pool = std::make_unique<render::PngEncoderPool>(threads);
  int written = 0;
  // ParaView's time: the load factor for a rising sweep of one frame per step, else the
  // frame number.
  bool time_is_load = !plan.every_iteration;
  for (size_t k = 1; k < plan.load_factors.size(); ++k)
    time_is_load = time_is_load && plan.load_factors[k] > plan.load_factors[k - 1];
  std::unique_ptr<VtuSeries> vtu;
  // The final state of a single solve is the survey's own: drawn from the method as the
  // survey left it rather than solved again (the same deterministic state).
  const bool survey_state_suffices = !plan.every_iteration && plan.load_factors.size() == 1;
  const auto render_frames = [&](MovieStream* stream) {
    const auto frames = [&](const std::function<bool(const render::Frame&)>& visit) {
      if (!survey_state_suffices) return render::run_frames(*method, plan, visit);
      const solver::Snapshot final_state = method->snapshot();
      visit(render::Frame{0, 0, final_state, method->history()});
      return 1;
    };
    frames([&](const render::Frame& frame) {
      if (interrupted()) return false;
      progress.update("render frame " + std::to_string(frame.index + 1) + " of " +
                      std::to_string(extent.frame_count));
      if (vtu)
        vtu->write(frame.snapshot, time_is_load
                                       ? plan.load_factors[static_cast<size_t>(frame.load_step)]
                                       : frame.index);
      const render::ComposedFrame composed = composer.compose(frame);
      render::Image image = headless->renderer->render(size.width, size.height, composed.layers(),
                                                       render::palette::background);
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
      if (written++ == 0)
        first_frame_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - solve_end).count();
      return true;
    });
    if (pool) pool->finish();
    progress.clear();
  };
  try {
    if (!args.vtu.empty())
      vtu = std::make_unique<VtuSeries>(args.vtu, model, *parse_vtk_encoding(args.vtu_format));
    if (movie_wanted) {
      write_output_by(args.movie, [&](const ExternalTarget& target) {
        MovieStream stream(target, size.width, size.height, args.fps);
        render_frames(&stream);
        return stream.finish();
      });
    } else {
      render_frames(nullptr);
    }
  } catch (const OutputError& error) {
    progress.clear();
    if (interrupted()) {
      std::cerr << scenes::printable(movie_wanted ? args.movie : args.out) << ": interrupted by "
                << interrupt_name()
                << (movie_wanted ? " while streaming frames to ffmpeg; no movie written" : "")
                << (frames_wanted
                        ? ", " + std::to_string(written) + " complete frames in " + args.out
                        : std::string())
                << "\n";
      return kExitInterrupted;
    }
    return report_output_error(error);
  } catch (const render::RenderError& error) {
    std::cerr << scenes::printable(frames_wanted ? args.out : args.movie)
              << ": rendering failed: " << error.what() << '\n';
    return kExitOutput;
  }
  if (interrupted()) {
    std::cerr << scenes::printable(args.out) << ": interrupted by " << interrupt_name() << " after "
              << written << " complete frames\n";
    return kExitInterrupted;
  }

  // With --movie - the movie goes to stdout: the report goes to stderr then; --quiet: none
  // (problems are still said on stderr).
  std::ostream null_stream(nullptr);
  std::ostream& report = args.quiet ? null_stream : is_stdout(args.movie) ? std::cerr : std::cout;
  if (frames_wanted) {
    report << "frames       " << written << " in " << args.out << " ("
           << frame_name(0, extent.frame_count) << " .. "
           << frame_name(written - 1, extent.frame_count) << "), " << size.width << "x"
           << size.height << ", magnification " << composer.framing().magnification << "\n";
    const std::string next =
        (std::filesystem::path(args.out) / frame_name(written, extent.frame_count)).string();
    if (std::filesystem::exists(next))
      report << "note         " << next
             << " and later frames are from an earlier run; they were left alone\n";
  }
  if (movie_wanted)
    report << "movie        " << args.movie << " (" << written << " frames at " << args.fps
           << " per second, " << size.width << "x" << size.height << ", magnification "
           << composer.framing().magnification << ")\n";
  report << "renderer     " << headless->context->description() << ", " << args.samples
         << (args.samples == 1 ? " sample" : " samples") << " per pixel\n";
  if (survey_state_suffices && first_frame_seconds >= 0.0)
    report << "time         solve " << std::fixed << std::setprecision(2)
           << std::chrono::duration<double>(solve_end - solve_start).count()
           << " s, first frame rendered " << first_frame_seconds << " s after it\n"
           << std::defaultfloat;

  if (extent.final_status != solver::Status::Converged) {
    std::cerr << scenes::printable(args.scene) << ": " << method_name
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
  look_up_bundled_scenes(command->add_option("scene", args->scene, kSceneArgumentHelp))->required();
  command->add_option("--out", args->out,
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
  command->add_option("--movie", args->movie,
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
  CLI::Option* chart =
      command->add_flag("--chart", args->chart,
                        "Beside the picture, the contact force and current gap of every pair "
                        "along the scene, the active ones marked (on by itself at 200 pairs)");
  command->add_flag("--no-chart", args->no_chart, "No per-contact chart")->excludes(chart);
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
  command->add_option("--vtu", args->vtu,
                      "Also write every frame's state as ParaView files here (struts.pvd, "
                      "contacts.pvd)")
      ->check(output_name(OutputKind::Folder));
  command->add_option("--vtu-format", args->vtu_format, "Data encoding of the .vtu files")
      ->check(CLI::IsMember({"ascii", "binary", "zlib"}))
      ->capture_default_str();
  command->add_flag("--progress", args->progress,
                    "Show the progress line on stderr even when it is not a terminal");
  command->add_flag("--quiet", args->quiet,
                    "No progress line and no report of what was written (problems are still "
                    "said on stderr)");
  command->callback([args, size, magnification, color, &exit_code] {
    args->size_given = size->count() > 0;
    args->magnification_given = magnification->count() > 0;
    args->color_given = color->count() > 0;
    exit_code = run_render(*args);
  });
}

}  // namespace fetic::app
