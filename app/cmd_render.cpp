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
  bool corners = false;
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

// One `fetic render` run in named phases, as run_render() below reads: read the inputs,
// set up the method and the display, survey the run, lay out the view, draw and write the
// frames, report. Each phase returns an exit status (kExitOk: go on).
class RenderRun {
 public:
  explicit RenderRun(const RenderArgs& args) : args_(args) {}

  int read_inputs();
  int set_up();
  int survey();
  void lay_out_view();
  int write_frames();
  int report(int status) const;

 private:
  void draw_frames(MovieStream* stream);
  void draw_frame(const render::Frame& frame, MovieStream* stream);
  int interrupted_while_writing(bool movie_wanted) const;

  const RenderArgs& args_;
  SavedView saved_;
  std::optional<scenes::Scene> scene_;
  solver::Model model_;
  ImageSize size_;
  render::FramePlan plan_;
  std::unique_ptr<solver::Method> method_;
  std::optional<Headless> headless_;
  std::unique_ptr<ProgressLine> progress_;
  std::chrono::steady_clock::time_point solve_start_, solve_end_;
  render::RunExtent extent_;
  render::View view_;
  std::unique_ptr<render::FrameComposer> composer_;
  bool frames_wanted_ = false, movie_wanted_ = false;
  int status_ = kExitOk;  // a problem that does not stop the run (no ffmpeg: frames only)
  std::unique_ptr<render::PngEncoderPool> pool_;
  std::unique_ptr<VtuSeries> vtu_;
  bool time_is_load_ = false;
  // The final state of a single solve is the survey's own: drawn from the method as the
  // survey left it rather than solved again (the same deterministic state).
  bool survey_state_suffices_ = false;
  int written_ = 0;
  double first_frame_seconds_ = -1.0;
};

// Step 1: the view file, the scene, and the options checked against the scene.
int RenderRun::read_inputs() {
  int status = kExitOk;
  const std::optional<SavedView> view_file = read_view_or_report(args_.view, status);
  if (!view_file) return status;
  saved_ = *view_file;
  scene_ = load_scene_or_report(args_.scene, status);
  if (!scene_) return status;
  if (const std::string problem =
          load_factor_problem(*scene_, args_.method.load_factors(),
                              args_.method.load_steps.empty() ? "--load-factor" : "--load-steps");
      !problem.empty()) {
    std::cerr << scenes::printable(args_.scene) << ": " << problem << '\n';
    return kExitUsage;
  }
  // Only beams carry a bending moment: a picture of bars or plane struts coloured by it
  // would be all grey, so say why rather than draw it.
  const render::ColorBy wanted =
      args_.color_given || !saved_.color_by ? color_by(args_.color) : *saved_.color_by;
  if (wanted == render::ColorBy::Moment && scene_->model != scenes::ModelKind::Frame) {
    std::cerr << scenes::printable(args_.scene) << ": colouring by bending moment needs a frame "
              << "scene (model = \"frame\"); this one is a " << scenes::to_string(scene_->model)
              << " model, whose struts carry no bending moment\n";
    return kExitUsage;
  }
  if (args_.out.empty() && args_.movie.empty()) {
    std::cerr << "fetic render: nothing to write: give --out DIR (PNG frames), --movie "
                 "FILE.mp4, or both\n";
    return kExitUsage;
  }
  if (!memory_suffices(*scene_, args_.scene, {{args_.method.kind()}, false, 0}, status))
    return status;
  return kExitOk;
}

// Step 2: the model, the method, the output directory and a display.
int RenderRun::set_up() {
  model_ = solver::build_model(*scene_);
  use_solver_threads_for_pictures(model_);
  size_ = *parse_image_size(args_.size);
  if (saved_.width && saved_.height && !args_.size_given) {
    size_.width = *saved_.width;
    size_.height = *saved_.height;
  }
  plan_.load_factors = args_.method.load_factors();
  // One frame per load step unless every iteration is asked for; one load factor: every
  // iteration unless --final.
  plan_.every_iteration =
      args_.method.load_steps.empty() ? !args_.final_only : args_.every_iteration;
  try {
    method_ = solver::make_method(args_.method.kind(), model_, args_.method.options());
  } catch (const solver::SolverError& error) {
    std::cerr << scenes::printable(args_.scene) << ": " << error.what() << '\n';
    return kExitSolverSetup;
  }
  // Before the (possibly long) survey: the output directory and a display must exist.
  if (!args_.out.empty() && !make_output_directory(args_.out)) return kExitOutput;
  headless_ = open_headless(args_.out.empty() ? args_.movie : args_.out,
                            std::max(render::base_text_size(size_.width, size_.height),
                                     static_cast<float>(saved_.text_size.value_or(0.0))));
  if (!headless_) return kExitNoDisplay;
  progress_ = std::make_unique<ProgressLine>(progress_mode(args_.progress, args_.quiet));
  return kExitOk;
}

// Step 3: the survey - the same deterministic run once, for fixed scales and the frame
// count.
int RenderRun::survey() {
  solve_start_ = std::chrono::steady_clock::now();
  extent_ = render::survey(model_, *method_, plan_, [&] {
    if (progress_->due())
      progress_->update("render survey: iteration " + std::to_string(method_->iteration()));
    return !interrupted();
  });
  progress_->clear();
  solve_end_ = std::chrono::steady_clock::now();
  if (interrupted()) {
    std::cerr << scenes::printable(args_.scene) << ": interrupted by " << interrupt_name()
              << " before any frame\n";
    return kExitInterrupted;
  }
  if (extent_.frame_count > args_.max_frames) {
    std::cerr << scenes::printable(args_.scene) << ": " << extent_.frame_count << " frames ("
              << args_.method.method << " takes " << extent_.largest_iteration
              << " iterations) is more than --max-frames " << args_.max_frames
              << "; raise it, or render --final or fewer --load-steps\n";
    return kExitUsage;
  }
  return kExitOk;
}

// Step 4: the view (a saved view's entries, then the options given on the command line)
// and the composer that lays every frame out in it.
void RenderRun::lay_out_view() {
  view_.magnification = args_.magnification;
  view_.color_by = color_by(args_.color);
  view_.show_overlay = !args_.no_overlay;
  view_.show_labels = args_.labels;
  apply_view(saved_, view_);
  view_.width = size_.width;
  view_.height = size_.height;
  if (args_.magnification_given) view_.magnification = args_.magnification;
  if (args_.color_given) view_.color_by = color_by(args_.color);
  if (args_.no_overlay) view_.show_overlay = false;
  if (args_.labels) view_.show_labels = true;
  if (args_.corners) view_.show_corners = true;
  view_.show_chart = render::chart_shown(model_, args_.chart ? 1 : args_.no_chart ? 0 : -1);
  apply_scales(saved_.scales, extent_);
  // A view the window saved names what its scales are the largest over, as it said.
  view_.scale_basis = saved_.scales && saved_.scale_basis
                          ? *saved_.scale_basis
                          : scale_basis(plan_, extent_, saved_.scales.has_value());
  render::OverlayInfo info;
  info.title =
      model_.title.empty() ? std::filesystem::path(args_.scene).filename().string() : model_.title;
  info.method = args_.method.method;
  if (solver::is_dual(args_.method.kind())) info.method += " (" + args_.method.preconditioner + ")";
  composer_ = std::make_unique<render::FrameComposer>(model_, view_, extent_, info,
                                                      static_cast<int>(plan_.load_factors.size()));
}

// One frame: its ParaView files, its picture, then the picture to the movie and the PNG
// encoders.
void RenderRun::draw_frame(const render::Frame& frame, MovieStream* stream) {
  progress_->update("render frame " + std::to_string(frame.index + 1) + " of " +
                    std::to_string(extent_.frame_count));
  if (vtu_)
    vtu_->write(frame.snapshot, time_is_load_
                                    ? plan_.load_factors[static_cast<size_t>(frame.load_step)]
                                    : frame.index);
  const render::ComposedFrame composed = composer_->compose(frame);
  render::Image image = headless_->renderer->render(size_.width, size_.height, composed.layers(),
                                                    render::palette::background);
  if (stream && pool_) {
    stream->submit(image);  // a copy: the PNG encoder takes the other
  } else if (stream) {
    stream->submit(std::move(image));
  }
  if (pool_) {
    const std::string path =
        (std::filesystem::path(args_.out) / frame_name(frame.index, extent_.frame_count)).string();
    pool_->submit(std::move(image),
                  [path](render::PngBytes png) { write_png_atomically(path, png); });
  }
  if (written_++ == 0)
    first_frame_seconds_ =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - solve_end_).count();
}

void RenderRun::draw_frames(MovieStream* stream) {
  const auto visit = [&](const render::Frame& frame) {
    if (interrupted()) return false;
    draw_frame(frame, stream);
    return true;
  };
  if (survey_state_suffices_)
    visit(render::Frame{0, 0, method_->snapshot(), method_->history()});
  else
    render::run_frames(*method_, plan_, visit);
  if (pool_) pool_->finish();
  progress_->clear();
}

int RenderRun::interrupted_while_writing(bool movie_wanted) const {
  std::cerr << scenes::printable(movie_wanted ? args_.movie : args_.out) << ": interrupted by "
            << interrupt_name()
            << (movie_wanted ? " while streaming frames to ffmpeg; no movie written" : "")
            << (frames_wanted_
                    ? ", " + std::to_string(written_) + " complete frames in " + args_.out
                    : std::string())
            << "\n";
  return kExitInterrupted;
}

// Step 5: draw every frame once, to PNG frames (--out), a movie streamed to ffmpeg
// (--movie), or both from the same images, and to ParaView files (--vtu).
int RenderRun::write_frames() {
  frames_wanted_ = !args_.out.empty();
  movie_wanted_ = !args_.movie.empty();
  if (movie_wanted_ && !program_on_path("ffmpeg")) {
    std::cerr << scenes::printable(args_.movie)
              << ": ffmpeg is not installed, so no movie can be made"
              << (frames_wanted_ ? "; writing the PNG frames only" : "")
              << " (apt-get install ffmpeg)\n";
    if (!frames_wanted_) return kExitOutput;
    movie_wanted_ = false;
    status_ = kExitOutput;
  }
  headless_->renderer->set_samples(args_.samples);
  const int threads = args_.threads > 0 ? args_.threads : default_encoder_threads();
  if (frames_wanted_) pool_ = std::make_unique<render::PngEncoderPool>(threads);
  // ParaView's time: the load factor for a rising sweep of one frame per step, else the
  // frame number.
  time_is_load_ = !plan_.every_iteration;
  for (size_t k = 1; k < plan_.load_factors.size(); ++k)
    time_is_load_ = time_is_load_ && plan_.load_factors[k] > plan_.load_factors[k - 1];
  survey_state_suffices_ = !plan_.every_iteration && plan_.load_factors.size() == 1;
  try {
    if (!args_.vtu.empty())
      vtu_ = std::make_unique<VtuSeries>(args_.vtu, model_, *parse_vtk_encoding(args_.vtu_format));
    if (movie_wanted_) {
      write_output_by(args_.movie, [&](const ExternalTarget& target) {
        MovieStream stream(target, size_.width, size_.height, args_.fps);
        draw_frames(&stream);
        return stream.finish();
      });
    } else {
      draw_frames(nullptr);
    }
  } catch (const OutputError& error) {
    progress_->clear();
    if (interrupted()) return interrupted_while_writing(movie_wanted_);
    return report_output_error(error);
  } catch (const render::RenderError& error) {
    std::cerr << scenes::printable(frames_wanted_ ? args_.out : args_.movie)
              << ": rendering failed: " << error.what() << '\n';
    return kExitOutput;
  }
  if (interrupted()) {
    std::cerr << scenes::printable(args_.out) << ": interrupted by " << interrupt_name()
              << " after " << written_ << " complete frames\n";
    return kExitInterrupted;
  }
  return kExitOk;
}

// Step 6: what was written, on stdout (on stderr when the movie goes to stdout; nothing
// with --quiet: problems are still said on stderr), and the final status.
int RenderRun::report(int status) const {
  std::ostream null_stream(nullptr);
  std::ostream& out = args_.quiet ? null_stream : is_stdout(args_.movie) ? std::cerr : std::cout;
  const double magnification = composer_->framing().magnification;
  if (frames_wanted_) {
    out << "frames       " << written_ << " in " << args_.out << " ("
        << frame_name(0, extent_.frame_count) << " .. "
        << frame_name(written_ - 1, extent_.frame_count) << "), " << size_.width << "x"
        << size_.height << ", magnification " << magnification << "\n";
    const std::string next =
        (std::filesystem::path(args_.out) / frame_name(written_, extent_.frame_count)).string();
    if (std::filesystem::exists(next))
      out << "note         " << next
          << " and later frames are from an earlier run; they were left alone\n";
  }
  if (movie_wanted_)
    out << "movie        " << args_.movie << " (" << written_ << " frames at " << args_.fps
        << " per second, " << size_.width << "x" << size_.height << ", magnification "
        << magnification << ")\n";
  out << "renderer     " << headless_->context->description() << ", " << args_.samples
      << (args_.samples == 1 ? " sample" : " samples") << " per pixel\n";
  if (survey_state_suffices_ && first_frame_seconds_ >= 0.0)
    out << "time         solve " << std::fixed << std::setprecision(2)
        << std::chrono::duration<double>(solve_end_ - solve_start_).count()
        << " s, first frame rendered " << first_frame_seconds_ << " s after it\n"
        << std::defaultfloat;
  if (status == kExitOk) status = status_;
  if (extent_.final_status != solver::Status::Converged) {
    std::cerr << scenes::printable(args_.scene) << ": " << args_.method.method
              << " did not converge: " << extent_.final_message << " (the frames show it)\n";
    if (status == kExitOk) status = kExitNotConverged;
  }
  return status;
}

int run_render(const RenderArgs& args) {
  RenderRun run(args);
  if (const int status = run.read_inputs(); status != kExitOk) return status;
  Activity rendering("rendering");
  if (const int status = run.set_up(); status != kExitOk) return status;
  if (const int status = run.survey(); status != kExitOk) return status;
  run.lay_out_view();
  if (const int status = run.write_frames(); status != kExitOk) return status;
  return run.report(kExitOk);
}

}  // namespace

void register_render(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* command = app.add_subcommand(
      "render",
      "Render solver states as PNG frames and/or a movie: an iteration movie, the final state "
      "or load steps");
  look_up_bundled_scenes(command->add_option("scene", args->scene, kSceneArgumentHelp))->required();
  command
      ->add_option("--out", args->out,
                   "Write PNG frames frame_0000.png, frame_0001.png, ... into this directory")
      ->check(output_name(OutputKind::Folder));
  add_method_options(command, args->method);
  CLI::Option* size = add_image_size_option(command, args->size);
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
  CLI::Option* chart =
      command->add_flag("--chart", args->chart,
                        "Beside the picture, the contact force and current gap of every pair "
                        "along the scene, the active ones marked (on by itself at 200 pairs)");
  command->add_flag("--no-chart", args->no_chart, "No per-contact chart")->excludes(chart);
  command->add_flag("--labels", args->labels,
                    "Strut names beside the struts (where there is room)");
  command->add_flag("--corners", args->corners,
                    "Mark FETI-DP's primal corners (amber discs) at the nodes solver/corners.hpp "
                    "chooses for the scene's subdomains");
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
