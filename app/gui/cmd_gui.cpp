// fetic gui SCENE: the interactive window. A GLFW window shows the headless renderer's
// picture (same draw lists, same GlRenderer, blitted to the back buffer) beside ImGui
// panels. Mouse, keyboard and --script only queue requests; once per frame one sync point
// applies them; the solver runs on its own thread (SolverWorker) and publishes immutable
// states, so the window never waits for a solve.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/gui/requests.hpp"
#include "app/gui/script.hpp"
#include "app/gui/solver_worker.hpp"
#include "app/gui/state_log.hpp"
#include "app/interrupt.hpp"
#include "app/render_output.hpp"
#include "app/scene_input.hpp"
#include "render/colormap.hpp"
#include "render/font.hpp"
#include "render/gl_renderer.hpp"
#include "render/glfw_window.hpp"
#include "render/overlay.hpp"
#include "render/scene_drawing.hpp"
#include "render/scene_framing.hpp"
#include "scenes/load_scene.hpp"
#include "solver/method.hpp"

namespace fetic::app {
namespace {

using Clock = std::chrono::steady_clock;
using gui::Request;
using gui::RequestKind;
namespace fs = std::filesystem;

constexpr float kPanelWidth = 330.0f;  // ImGui panel on the left; the picture fills the rest
// How long the sync point waits for a quick solve to finish within the frame.
constexpr std::chrono::microseconds kQuickSolve{5000};

struct GuiArgs {
  std::string scene;
  std::string method = "feti-c";
  std::string preconditioner = "dirichlet";
  double load = 1.0;
  double max_load = 0.0;  // 0: chosen from the scene (solver::automatic_max_load)
  double magnification = 0.0;
  std::string size = "1280x800";
  std::string state_file;
  std::string script;
  std::string screenshot_dir = ".";
  std::string record_dir = "fetic-recordings";
  bool no_overlay = false;
  int bench = 0;  // load changes of the benchmark drag; 0: no benchmark
};

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::vector<int> active_contacts(const solver::Snapshot& snapshot) {
  std::vector<int> active;
  for (std::size_t i = 0; i < snapshot.in_working_set.size(); ++i)
    if (snapshot.in_working_set[i]) active.push_back(static_cast<int>(i));
  return active;
}

// A recording in progress: frames rendered one per UI frame, encoded on worker threads.
struct Recording {
  bool sweep = false;
  fs::path directory;
  std::vector<double> loads;   // sweep: load factors still to solve and record
  std::uint64_t awaiting = 0;  // sweep: request whose finished solve is the next frame
  std::shared_ptr<const gui::SolveState> iterations;  // iterations: the solve to record
  int next = 0;                                       // next frame index
  std::unique_ptr<render::PngEncoderPool> pool;
};

class GuiApp {
 public:
  GuiApp(const GuiArgs& args, std::shared_ptr<const solver::Model> model, std::string title)
      : args_(args), title_(std::move(title)), worker_([] { glfwPostEmptyEvent(); }) {
    target_.model = std::move(model);
    target_.model_generation = 1;
    target_.method = *solver::parse_method(args.method);
    target_.options.preconditioner = *solver::parse_preconditioner(args.preconditioner);
    target_.max_load = args.max_load;  // 0: the worker chooses from the scene
    slider_max_ = args.max_load > 0.0 ? args.max_load : 2.0;
    target_.load_factor = args.max_load > 0.0 ? std::min(args.load, args.max_load) : args.load;
    magnification_ = args.magnification;
    show_overlay_ = !args.no_overlay;
    std::error_code ignored;
    scene_time_ = fs::last_write_time(args.scene, ignored);
  }

  int run(render::GlfwWindow& window, std::vector<gui::ScriptAction> script);

 private:
  void push(Request request) { queue_.push_back(std::move(request)); }
  void send_to_worker() {
    target_.request = ++requests_sent_;
    requested_at_[target_.request] = Clock::now();
    worker_.request(target_);
  }
  void apply(const Request& request);
  void sync();  // the sync point: applies the queued requests, takes the newest state
  void panels(float height);
  static void key_event(GLFWwindow* window, int key, int scancode, int action, int mods);
  void mouse(float view_x, float view_width, float view_height);
  void draw_picture(int width, int height);
  render::View view(int width, int height) const;
  void reload();
  void screenshot(const std::string& path);
  void step_recording();
  void run_script(std::vector<gui::ScriptAction>& script, std::size_t& next, double now,
                  bool& failed);
  void bench_step(double now);
  void report_frame();
  int shown_index() const;

  const GuiArgs& args_;
  std::string title_;
  gui::SolverWorker worker_;
  gui::SolverTarget target_;
  gui::RequestQueue queue_;
  gui::StateLog log_;
  std::uint64_t requests_sent_ = 0;
  std::map<std::uint64_t, Clock::time_point> requested_at_;

  // What is on screen.
  std::shared_ptr<const gui::SolveState> shown_;
  std::shared_ptr<const gui::SolveState> error_;  // the newest request could not be solved
  bool follow_ = true;                            // show the newest iterate
  bool playing_ = false;
  int cursor_ = 0;
  double play_rate_ = 4.0;  // iterations per second
  double next_tick_ = 0.0;
  bool redraw_ = true;
  std::uint64_t reported_request_ = 0;     // last "solved" event
  std::uint64_t first_frame_request_ = 0;  // last request seen in a frame
  bool solved_on_screen_ = false;          // newest request finished and swapped

  // View settings.
  double magnification_ = 0.0;  // 0: automatic
  double shown_magnification_ = 0.0;
  bool subdomains_ = true, stress_ = false, forces_ = true, gaps_ = true, show_overlay_ = true;
  bool help_ = false;
  bool dragging_slider_ = false, draft_ = false;
  bool typing_load_ = false;
  std::uint64_t drafted_request_ = 0;
  double slider_max_ = 2.0;  // top of the load slider
  double last_picture_ms_ = 0.0;
  Clock::time_point last_picture_end_{};
  double typed_load_ = 0.0;
  float zoom_ = 1.0f;
  render::Point pan_{0.0f, 0.0f};
  render::Point base_center_{0.0f, 0.0f};
  int view_width_ = 0, view_height_ = 0;

  // Scene file.
  fs::file_time_type scene_time_{};
  double next_file_check_ = 0.0;
  std::string status_line_;

  // Screenshots and recordings.
  std::unique_ptr<render::PngEncoderPool> screenshot_pool_;
  int screenshot_count_ = 0;
  std::string pending_screenshot_;
  bool screenshot_requested_ = false;
  std::unique_ptr<Recording> recording_;
  std::vector<std::thread> finishers_;
  int recordings_ = 0;
  int sweep_steps_ = 20;

  render::GlRenderer* renderer_ = nullptr;
  bool quit_ = false;
  double wait_started_ = -1.0;  // when the script's current "wait" began
  float slider_[4] = {0, 0, 0, 0};
  bool ready_reported_ = false;
  Clock::time_point start_ = Clock::now();

  // Benchmark.
  struct Bench {
    int phase = -1;  // -1 first solve, 0 drag, 1 settle, 2 isolated changes, 3 done
    int k = 0;
    std::vector<double> frame_ms, draw_ms, lists_ms, swap_ms;  // during the drag
    std::vector<double> solved_latency_ms, first_latency_ms, solve_ms;
    std::vector<int> iterations;
    Clock::time_point last_frame{};
    Clock::time_point drag_start{};
    double drag_seconds = 0.0;
    int drag_frames = 0;
    std::uint64_t waiting = 0;
  } bench_;
};

render::View GuiApp::view(int width, int height) const {
  render::View v;
  v.width = width;
  v.height = height;
  v.magnification = magnification_;
  v.color_by = stress_ ? render::ColorBy::Stress
                       : (subdomains_ ? render::ColorBy::Subdomain : render::ColorBy::Strut);
  v.show_forces = forces_;
  v.show_gaps = gaps_;
  v.show_overlay = show_overlay_;
  return v;
}

int GuiApp::shown_index() const {
  if (!shown_ || shown_->iterates.empty()) return 0;
  const int last = static_cast<int>(shown_->iterates.size()) - 1;
  return follow_ ? last : std::clamp(cursor_, 0, last);
}

void GuiApp::apply(const Request& r) {
  const int last = shown_ ? std::max(0, static_cast<int>(shown_->iterates.size()) - 1) : 0;
  const bool finished = shown_ && shown_->finished;
  switch (r.kind) {
    case RequestKind::SetLoad: {
      const double t = std::clamp(r.value, 0.0, slider_max_);
      if (t == target_.load_factor && requests_sent_ > 0) break;
      target_.load_factor = t;
      follow_ = true;
      playing_ = false;
      send_to_worker();
      break;
    }
    case RequestKind::SetMethod:
      if (const auto kind = solver::parse_method(r.text)) {
        target_.method = *kind;
        follow_ = true;
        send_to_worker();
      } else {
        status_line_ = "unknown method " + r.text;
      }
      break;
    case RequestKind::SetPreconditioner:
      if (const auto p = solver::parse_preconditioner(r.text)) {
        target_.options.preconditioner = *p;
        follow_ = true;
        send_to_worker();
      } else {
        status_line_ = "unknown preconditioner " + r.text;
      }
      break;
    case RequestKind::SetMagnification:
      magnification_ = r.value;
      redraw_ = true;
      break;
    case RequestKind::TogglePlay:
      apply(Request{playing_ ? RequestKind::Pause : RequestKind::Play, 0.0, {}});
      break;
    case RequestKind::Play:
      if (shown_index() >= last)
        cursor_ = 0;  // like a video player: from the start again
      else
        cursor_ = shown_index();
      follow_ = false;
      playing_ = true;
      next_tick_ = seconds_since(start_) + 1.0 / play_rate_;
      redraw_ = true;
      break;
    case RequestKind::Pause:
      cursor_ = shown_index();
      playing_ = false;
      follow_ = false;
      break;
    case RequestKind::Step:
      cursor_ = std::min(shown_index() + 1, last);
      playing_ = false;
      follow_ = cursor_ == last && finished;
      redraw_ = true;
      break;
    case RequestKind::StepBack:
      cursor_ = std::max(shown_index() - 1, 0);
      playing_ = false;
      follow_ = false;
      redraw_ = true;
      break;
    case RequestKind::Reset:
      cursor_ = 0;
      playing_ = false;
      follow_ = false;
      redraw_ = true;
      break;
    case RequestKind::Scrub:
      cursor_ = std::clamp(static_cast<int>(r.value), 0, last);
      playing_ = false;
      follow_ = cursor_ == last && finished;
      redraw_ = true;
      break;
    case RequestKind::Toggle:
      if (r.text == "subdomains") subdomains_ = !subdomains_;
      if (r.text == "forces") forces_ = !forces_;
      if (r.text == "gaps") gaps_ = !gaps_;
      if (r.text == "stress") stress_ = !stress_;
      if (r.text == "overlay") show_overlay_ = !show_overlay_;
      if (r.text == "help") help_ = !help_;
      redraw_ = true;
      break;
    case RequestKind::Screenshot:
      screenshot_requested_ = true;
      pending_screenshot_ = r.text;
      break;
    case RequestKind::RecordIterations:
    case RequestKind::RecordSweep: {
      if (recording_) {
        status_line_ = "a recording is already running";
        break;
      }
      auto rec = std::make_unique<Recording>();
      rec->sweep = r.kind == RequestKind::RecordSweep;
      char name[64];
      std::snprintf(name, sizeof name, "%s_%03d", rec->sweep ? "sweep" : "iterations",
                    ++recordings_);
      rec->directory = fs::path(args_.record_dir) / name;
      std::error_code error;
      fs::create_directories(rec->directory, error);
      if (error) {
        status_line_ = rec->directory.string() + ": " + error.message();
        break;
      }
      rec->pool = std::make_unique<render::PngEncoderPool>(default_encoder_threads(), 8);
      if (rec->sweep) {
        const int n = r.value >= 2 ? static_cast<int>(r.value) : sweep_steps_;
        for (int i = 0; i < n; ++i)
          rec->loads.push_back(slider_max_ * i / (n - 1));
      } else {
        if (!shown_ || shown_->iterates.empty()) {
          status_line_ = "nothing to record yet";
          break;
        }
        rec->iterations = shown_;
      }
      status_line_ = "recording into " + rec->directory.string();
      recording_ = std::move(rec);
      break;
    }
    case RequestKind::Reload:
      reload();
      break;
    case RequestKind::ResetView:
      zoom_ = 1.0f;
      pan_ = {0.0f, 0.0f};
      redraw_ = true;
      break;
    case RequestKind::Quit:
      quit_ = true;
      break;
  }
}

void GuiApp::reload() {
  try {
    scenes::Scene scene = scenes::load_scene_file(args_.scene);
    auto model = std::make_shared<const solver::Model>(solver::build_model(scene));
    target_.model = std::move(model);
    ++target_.model_generation;
    follow_ = true;
    send_to_worker();
    status_line_ = "reloaded " + args_.scene;
    log_.write({{"event", "reloaded"}, {"scene", args_.scene}});
  } catch (const std::exception& error) {
    status_line_ = std::string("reload failed: ") + error.what();
    log_.write({{"event", "error"}, {"message", status_line_}});
  }
}

void GuiApp::sync() {
  const std::uint64_t sent_before = requests_sent_;
  for (std::size_t i = 0; i < queue_.size(); ++i)  // apply() may queue more
    apply(queue_[i]);
  queue_.clear();
  // A solve that is quick (the last one took less than the budget) lands in this very
  // frame: wait for it a little rather than show it one frame later. Slow solves are not
  // waited for; their iterates appear as they come.
  std::shared_ptr<const gui::SolveState> latest;
  if (requests_sent_ != sent_before && shown_ && shown_->finished &&
      shown_->solve_seconds < kQuickSolve.count() * 1e-6)
    latest = worker_.wait_for(requests_sent_, kQuickSolve);
  else
    latest = worker_.latest();
  if (latest && latest->iterates.empty() && latest->finished) {
    // The method cannot solve this scene: say so, keep the last picture.
    error_ = std::move(latest);
  } else if (latest != shown_) {
    shown_ = std::move(latest);
    if (shown_ && shown_->max_load > 0.0) slider_max_ = shown_->max_load;
    if (shown_ && error_ && shown_->request > error_->request) error_.reset();
    redraw_ = true;
  }
  // Playback of the iterations of the current solve.
  if (playing_ && shown_) {
    const double now = seconds_since(start_);
    const int last = static_cast<int>(shown_->iterates.size()) - 1;
    while (now >= next_tick_ && playing_) {
      next_tick_ += 1.0 / play_rate_;
      if (cursor_ < last) {
        ++cursor_;
        redraw_ = true;
      } else if (shown_->finished) {
        playing_ = false;
        follow_ = true;
      } else {
        break;  // wait for the solver
      }
    }
  }
}

void GuiApp::draw_picture(int width, int height) {
  if (!shown_ || !shown_->extent || shown_->iterates.empty()) {
    const render::DrawList empty;
    renderer_->draw(width, height, {&empty}, render::palette::background);
    return;
  }
  const auto lists_start = Clock::now();
  const int index = shown_index();
  const solver::Snapshot& snapshot = *shown_->iterates[static_cast<std::size_t>(index)];
  const std::vector<solver::HistoryEntry> history(
      shown_->history.begin(),
      shown_->history.begin() +
          std::min<std::ptrdiff_t>(index + 1, static_cast<std::ptrdiff_t>(shown_->history.size())));
  const render::View v = view(width, height);
  render::SceneFraming framing =
      render::frame_scene(*shown_->model, v, *shown_->extent, render::scene_region(v));
  base_center_ = framing.pixel_center;
  framing.pixels_per_unit *= zoom_;
  framing.pixel_center = {base_center_.x + pan_.x, base_center_.y + pan_.y};
  shown_magnification_ = framing.magnification;
  const render::DrawList scene = render::draw_scene(*shown_->model, snapshot, v, framing);
  render::DrawList overlay;
  if (v.show_overlay) {
    render::OverlayInfo info;
    info.title = title_;
    info.method = solver::to_string(shown_->method);
    if (shown_->method == solver::MethodKind::Feti || shown_->method == solver::MethodKind::FetiC)
      info.method += std::string(" (") + solver::to_string(shown_->preconditioner) + ")";
    overlay = render::draw_overlay(info, *shown_->model, snapshot, history, *shown_->extent, v);
  }
  if (args_.bench > 0 && bench_.phase == 0)
    bench_.lists_ms.push_back(
        std::chrono::duration<double, std::milli>(Clock::now() - lists_start).count());
  // Panned or zoomed, the scene may reach under the information panel: mask it there.
  render::DrawList mask;
  if (v.show_overlay)
    mask.rect(
        {render::scene_region(v).x1, 0.0f, static_cast<float>(width), static_cast<float>(height)},
        render::palette::background);
  renderer_->draw(width, height, {&scene, &mask, &overlay}, render::palette::background);
}

void GuiApp::screenshot(const std::string& requested) {
  std::string path = requested;
  if (path.empty()) {
    char name[64];
    std::snprintf(name, sizeof name, "fetic_screenshot_%04d.png", screenshot_count_++);
    path = (fs::path(args_.screenshot_dir) / name).string();
  }
  if (!screenshot_pool_) screenshot_pool_ = std::make_unique<render::PngEncoderPool>(1, 4);
  const double load = shown_ ? shown_->load_factor : 0.0;
  const int iteration = shown_index();
  status_line_ = "screenshot " + path;
  screenshot_pool_->submit(renderer_->read_back(),
                           [this, path, load, iteration](render::PngBytes png) {
                             try {
                               write_png_atomically(path, png);
                               log_.write({{"event", "screenshot"},
                                           {"path", path},
                                           {"load_factor", load},
                                           {"iteration", iteration}});
                             } catch (const std::exception& error) {
                               log_.write({{"event", "error"}, {"message", error.what()}});
                             }
                           });
}

void GuiApp::step_recording() {
  if (!recording_) return;
  Recording& rec = *recording_;
  const int total = rec.sweep ? static_cast<int>(rec.loads.size())
                              : static_cast<int>(rec.iterations->iterates.size());
  const auto frame_path = [&] { return (rec.directory / frame_name(rec.next, total)).string(); };
  bool done = false;
  if (!rec.sweep) {
    // One iteration a UI frame: bounded work, the window stays live.
    const auto saved = shown_;
    const bool saved_follow = follow_;
    const int saved_cursor = cursor_;
    shown_ = rec.iterations;
    follow_ = false;
    cursor_ = rec.next;
    draw_picture(view_width_, view_height_);
    rec.pool->submit(renderer_->read_back(), [path = frame_path()](render::PngBytes png) {
      write_png_atomically(path, png);
    });
    shown_ = saved;
    follow_ = saved_follow;
    cursor_ = saved_cursor;
    redraw_ = true;
    ++rec.next;
    done = rec.next >= static_cast<int>(rec.iterations->iterates.size());
  } else {
    if (rec.awaiting == 0) {
      push(Request{RequestKind::SetLoad, rec.loads[static_cast<std::size_t>(rec.next)], {}});
      rec.awaiting = requests_sent_ + 1;
      // SetLoad of the current value sends nothing: record what is shown.
      if (rec.loads[static_cast<std::size_t>(rec.next)] == target_.load_factor)
        rec.awaiting = requests_sent_;
      return;
    }
    if (!shown_ || shown_->request < rec.awaiting || !shown_->finished) return;
    follow_ = true;
    draw_picture(view_width_, view_height_);
    rec.pool->submit(renderer_->read_back(), [path = frame_path()](render::PngBytes png) {
      write_png_atomically(path, png);
    });
    redraw_ = true;
    ++rec.next;
    rec.awaiting = 0;
    done = rec.next >= static_cast<int>(rec.loads.size());
  }
  if (!done) return;
  // Encoding and the movie finish off the UI thread.
  auto finished = std::shared_ptr<Recording>(std::move(recording_));
  status_line_ =
      "recorded " + std::to_string(finished->next) + " frames in " + finished->directory.string();
  finishers_.emplace_back([this, finished] {
    nlohmann::json event{{"event", "recorded"},
                         {"directory", finished->directory.string()},
                         {"frames", finished->next}};
    try {
      finished->pool->finish();
      if (program_on_path("ffmpeg")) {
        const std::string movie = (finished->directory / "movie.mp4").string();
        if (assemble_movie(finished->directory.string(), finished->next, 8, movie) == kExitOk)
          event["movie"] = movie;
      }
    } catch (const std::exception& error) {
      event["error"] = error.what();
    }
    log_.write(event);
  });
}

// GLFW calls this for every key event, before ImGui sees it (ImGui chains to it): a press
// and its release within one frame still count, which polling ImGui's key state would miss.
void GuiApp::key_event(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  auto* app = static_cast<GuiApp*>(glfwGetWindowUserPointer(window));
  if (!app || action == GLFW_RELEASE) return;
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantTextInput) return;
  const bool repeat = action == GLFW_REPEAT;
  switch (key) {
    case GLFW_KEY_SPACE:
      if (!repeat) app->push({RequestKind::TogglePlay, 0.0, {}});
      break;
    case GLFW_KEY_RIGHT:
      app->push({RequestKind::Step, 0.0, {}});
      break;
    case GLFW_KEY_LEFT:
      app->push({RequestKind::StepBack, 0.0, {}});
      break;
    case GLFW_KEY_R:
      if (!repeat) app->push({RequestKind::Reset, 0.0, {}});
      break;
    case GLFW_KEY_S:
      if (!repeat) app->push({RequestKind::Screenshot, 0.0, {}});
      break;
    case GLFW_KEY_F5:
      if (!repeat) app->push({RequestKind::Reload, 0.0, {}});
      break;
    case GLFW_KEY_H:
    case GLFW_KEY_F1:
      if (!repeat) app->push({RequestKind::Toggle, 0.0, "help"});
      break;
    case GLFW_KEY_HOME:
      app->push({RequestKind::ResetView, 0.0, {}});
      break;
    case GLFW_KEY_Q:
    case GLFW_KEY_ESCAPE:
      app->push({RequestKind::Quit, 0.0, {}});
      break;
    default:
      break;
  }
}

void GuiApp::mouse(float view_x, float view_width, float view_height) {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse) return;
  const render::Point at{io.MousePos.x - view_x, io.MousePos.y};
  if (at.x < 0 || at.y < 0 || at.x > view_width || at.y > view_height) return;
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Left) ||
      ImGui::IsMouseDragging(ImGuiMouseButton_Right)) {
    pan_.x += io.MouseDelta.x;
    pan_.y += io.MouseDelta.y;
    redraw_ = true;
  }
  if (io.MouseWheel != 0.0f) {
    const float factor = std::pow(1.15f, io.MouseWheel);
    const float new_zoom = std::clamp(zoom_ * factor, 0.05f, 200.0f);
    const float f = new_zoom / zoom_;
    // Keep the point under the cursor where it is.
    const float cx = base_center_.x + pan_.x, cy = base_center_.y + pan_.y;
    pan_.x = at.x - (at.x - cx) * f - base_center_.x;
    pan_.y = at.y - (at.y - cy) * f - base_center_.y;
    zoom_ = new_zoom;
    redraw_ = true;
  }
  if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) push({RequestKind::ResetView, 0.0, {}});
}

void GuiApp::panels(float height) {
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, height));
  ImGui::Begin("fetic", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  ImGui::TextWrapped("%s", title_.c_str());
  ImGui::Separator();

  ImGui::Text("Load factor (0 .. %.3g)", slider_max_);
  double load = target_.load_factor;
  const double zero = 0.0;
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderScalar("##load", ImGuiDataType_Double, &load, &zero, &slider_max_, "%.4f"))
    push({RequestKind::SetLoad, load, {}});
  if (ImGui::IsItemActive() != dragging_slider_) {
    dragging_slider_ = ImGui::IsItemActive();
    log_.write({{"event", "slider"}, {"held", dragging_slider_}, {"load_factor", load}});
  }
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  slider_[0] = lo.x, slider_[1] = lo.y, slider_[2] = hi.x, slider_[3] = hi.y;
  // The typed value shows the current load factor unless the user is typing.
  if (!typing_load_) typed_load_ = target_.load_factor;
  ImGui::SetNextItemWidth(120);
  if (ImGui::InputDouble("type + Enter", &typed_load_, 0.0, 0.0, "%.4f",
                         ImGuiInputTextFlags_EnterReturnsTrue))
    push({RequestKind::SetLoad, typed_load_, {}});
  typing_load_ = ImGui::IsItemActive();

  ImGui::Separator();
  static const char* methods[] = {"feti-c", "active-set", "feti", "cg", "sd"};
  static const char* preconditioners[] = {"dirichlet", "lumped", "none"};
  int method = 0;
  for (int i = 0; i < 5; ++i)
    if (solver::to_string(target_.method) == std::string(methods[i])) method = i;
  ImGui::SetNextItemWidth(140);
  if (ImGui::Combo("method", &method, methods, 5))
    push({RequestKind::SetMethod, 0.0, methods[method]});
  int pre =
      static_cast<int>(target_.options.preconditioner == solver::Preconditioner::Dirichlet ? 0
                       : target_.options.preconditioner == solver::Preconditioner::Lumped  ? 1
                                                                                           : 2);
  ImGui::SetNextItemWidth(140);
  if (ImGui::Combo("preconditioner", &pre, preconditioners, 3))
    push({RequestKind::SetPreconditioner, 0.0, preconditioners[pre]});
  bool locked = magnification_ > 0.0;
  if (ImGui::Checkbox("lock magnification", &locked))
    push({RequestKind::SetMagnification, locked ? shown_magnification_ : 0.0, {}});
  ImGui::SameLine();
  if (locked) {
    double m = magnification_;
    ImGui::SetNextItemWidth(90);
    if (ImGui::InputDouble("##mag", &m, 0.0, 0.0, "%.3g", ImGuiInputTextFlags_EnterReturnsTrue) &&
        m > 0.0)
      push({RequestKind::SetMagnification, m, {}});
  } else {
    ImGui::Text("auto: %g", shown_magnification_);
  }

  ImGui::Separator();
  ImGui::Text("Iterations of this solve");
  if (ImGui::Button(playing_ ? "Pause" : "Play")) push({RequestKind::TogglePlay, 0.0, {}});
  ImGui::SameLine();
  if (ImGui::Button("Step")) push({RequestKind::Step, 0.0, {}});
  ImGui::SameLine();
  if (ImGui::Button("Reset")) push({RequestKind::Reset, 0.0, {}});
  ImGui::SameLine();
  float rate = static_cast<float>(play_rate_);
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderFloat("##rate", &rate, 1.0f, 30.0f, "%.0f it/s")) play_rate_ = rate;
  const int last = shown_ ? std::max(0, static_cast<int>(shown_->iterates.size()) - 1) : 0;
  int iteration = shown_index();
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderInt("##history", &iteration, 0, last, "iteration %d"))
    push({RequestKind::Scrub, static_cast<double>(iteration), {}});

  ImGui::Separator();
  bool value = subdomains_;
  if (ImGui::Checkbox("subdomains", &value)) push({RequestKind::Toggle, 0.0, "subdomains"});
  ImGui::SameLine();
  value = stress_;
  if (ImGui::Checkbox("stress colours", &value)) push({RequestKind::Toggle, 0.0, "stress"});
  value = forces_;
  if (ImGui::Checkbox("forces", &value)) push({RequestKind::Toggle, 0.0, "forces"});
  ImGui::SameLine();
  value = gaps_;
  if (ImGui::Checkbox("gaps", &value)) push({RequestKind::Toggle, 0.0, "gaps"});
  ImGui::SameLine();
  value = show_overlay_;
  if (ImGui::Checkbox("info", &value)) push({RequestKind::Toggle, 0.0, "overlay"});

  ImGui::Separator();
  if (ImGui::Button("Screenshot (S)")) push({RequestKind::Screenshot, 0.0, {}});
  ImGui::SameLine();
  if (ImGui::Button("Reload (F5)")) push({RequestKind::Reload, 0.0, {}});
  if (ImGui::Button("Record iterations")) push({RequestKind::RecordIterations, 0.0, {}});
  if (ImGui::Button("Record load sweep"))
    push({RequestKind::RecordSweep, static_cast<double>(sweep_steps_), {}});
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  ImGui::SliderInt("##steps", &sweep_steps_, 2, 200, "%d steps");

  ImGui::Separator();
  if (error_) {
    ImGui::TextColored(ImVec4(0.8f, 0.1f, 0.1f, 1),
                       "%s cannot solve this scene:", solver::to_string(error_->method));
    ImGui::TextWrapped("%s", error_->error.c_str());
    ImGui::TextWrapped("(the picture is the last solve; choose another method)");
  } else if (shown_) {
    {
      const bool busy = !shown_->finished || shown_->request != requests_sent_;
      const int active = shown_->iterates.empty() ? 0 : shown_->iterates.back()->active_set_size();
      ImGui::Text("%s at load %.4f", busy ? "solving" : solver::to_string(shown_->status),
                  shown_->load_factor);
      ImGui::Text("%d iterations, %.2f ms", static_cast<int>(shown_->iterates.size()) - 1,
                  shown_->solve_seconds * 1e3);
      ImGui::Text("active contacts: %d of %d", active,
                  static_cast<int>(shown_->model->pairs.size()));
      if (!shown_->message.empty() && shown_->status == solver::Status::Failed)
        ImGui::TextWrapped("%s", shown_->message.c_str());
    }
  } else {
    ImGui::Text("setting up the solver ...");
  }
  if (!status_line_.empty()) ImGui::TextWrapped("%s", status_line_.c_str());
  ImGui::TextDisabled("H: keys   drag: pan   wheel: zoom");
  ImGui::End();

  if (help_) {
    ImGui::SetNextWindowPos(ImVec2(kPanelWidth + 40, 40));
    ImGui::Begin("Keys", &help_,
                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
    static const char* keys[][2] = {{"Space", "play / pause the iterations"},
                                    {"Right, Left", "one iteration forward / back"},
                                    {"R", "reset to iteration 0"},
                                    {"S", "screenshot (PNG of the picture)"},
                                    {"F5", "reload the scene file"},
                                    {"Home", "reset pan and zoom (or double-click)"},
                                    {"mouse drag", "pan the picture; wheel: zoom"},
                                    {"H, F1", "this help"},
                                    {"Q, Esc", "quit"}};
    if (ImGui::BeginTable("keys", 2)) {
      for (const auto& key : keys) {
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        ImGui::TextUnformatted(key[0]);
        ImGui::TableSetColumnIndex(1);
        ImGui::TextUnformatted(key[1]);
      }
      ImGui::EndTable();
    }
    ImGui::End();
  }
}

void GuiApp::run_script(std::vector<gui::ScriptAction>& script, std::size_t& next, double now,
                        bool& failed) {
  while (next < script.size()) {
    const gui::ScriptAction& action = script[next];
    if (action.at >= 0 && now < action.at) return;
    if (action.wait) {
      if (wait_started_ < 0) wait_started_ = now;
      if (!solved_on_screen_ || worker_.busy() || recording_ || !queue_.empty()) {
        if (now - wait_started_ > 120.0) {
          std::cerr << args_.script << ":" << action.line
                    << ": wait: the solve did not finish within 120 s\n";
          failed = true;
          quit_ = true;
        }
        return;
      }
      wait_started_ = -1.0;
    } else {
      push(action.request);
    }
    ++next;
    if (!action.wait) return;  // one request a frame, like a user
  }
}

void GuiApp::report_frame() {
  // Called after a swap: the shown state is on screen now.
  if (error_ && error_->request > reported_request_) {
    reported_request_ = error_->request;
    log_.write({{"event", "solved"},
                {"request", error_->request},
                {"load_factor", error_->load_factor},
                {"method", solver::to_string(error_->method)},
                {"converged", false},
                {"status", "failed"},
                {"message", error_->message},
                {"active", 0},
                {"active_contacts", std::vector<int>{}}});
  }
  if (!shown_) {
    solved_on_screen_ = error_ && error_->request == requests_sent_;
    return;
  }
  const auto now = Clock::now();
  if (shown_->request != first_frame_request_) {
    first_frame_request_ = shown_->request;
    if (const auto it = requested_at_.find(shown_->request);
        it != requested_at_.end() && args_.bench > 0 && bench_.phase == 2)
      bench_.first_latency_ms.push_back(
          std::chrono::duration<double, std::milli>(now - it->second).count());
  }
  solved_on_screen_ = (shown_->finished && shown_->request == requests_sent_ && follow_) ||
                      (error_ && error_->request == requests_sent_);
  if (!shown_->finished || shown_->request <= reported_request_ || shown_->iterates.empty()) return;
  reported_request_ = shown_->request;
  const solver::Snapshot& final_state = *shown_->iterates.back();
  double latency = 0.0;
  if (const auto it = requested_at_.find(shown_->request); it != requested_at_.end()) {
    latency = std::chrono::duration<double, std::milli>(now - it->second).count();
    requested_at_.erase(requested_at_.begin(), std::next(it));
  }
  if (args_.bench > 0 && bench_.phase == 2 && shown_->request == bench_.waiting) {
    bench_.solved_latency_ms.push_back(latency);
    bench_.solve_ms.push_back(shown_->solve_seconds * 1e3);
    bench_.iterations.push_back(static_cast<int>(shown_->iterates.size()) - 1);
  }
  const std::vector<int> active = active_contacts(final_state);
  log_.write({{"event", "solved"},
              {"request", shown_->request},
              {"load_factor", shown_->load_factor},
              {"method", solver::to_string(shown_->method)},
              {"preconditioner", solver::to_string(shown_->preconditioner)},
              {"iterations", static_cast<int>(shown_->iterates.size()) - 1},
              {"converged", shown_->status == solver::Status::Converged},
              {"status", solver::to_string(shown_->status)},
              {"message", shown_->message},
              {"active", static_cast<int>(active.size())},
              {"active_contacts", active},
              {"solve_ms", shown_->solve_seconds * 1e3},
              {"latency_ms", latency}});
}

void GuiApp::bench_step(double /*now*/) {
  Bench& b = bench_;
  const auto now = Clock::now();
  if (b.phase == -1) {
    if (solved_on_screen_ && !worker_.busy()) b.phase = 0;  // set up and first solve done
    return;
  }
  if (b.phase == 0) {
    // A drag at a pointer's pace: a new load factor every 1/60 s, 0 .. maximum; frames
    // run as fast as they can in between (no vsync in the benchmark).
    if (b.drag_frames == 0) {
      b.drag_start = now;
    } else {
      b.frame_ms.push_back(std::chrono::duration<double, std::milli>(now - b.last_frame).count());
    }
    b.last_frame = now;
    ++b.drag_frames;
    const double elapsed = std::chrono::duration<double>(now - b.drag_start).count();
    if (b.k < args_.bench) {
      if (elapsed >= b.k / 60.0) {
        push({RequestKind::SetLoad, slider_max_ * b.k / std::max(1, args_.bench - 1), {}});
        ++b.k;
      }
    } else {
      b.drag_seconds = elapsed;
      b.phase = 1;
    }
  } else if (b.phase == 1) {
    if (solved_on_screen_ && !worker_.busy()) {
      b.phase = 2;
      b.k = 0;
    }
  } else if (b.phase == 2) {
    // Isolated changes: each waits for its converged frame before the next.
    if (b.waiting != 0 && !(solved_on_screen_ && !worker_.busy())) return;
    if (b.k >= 30) {
      b.phase = 3;
      quit_ = true;
      return;
    }
    const double t = slider_max_ * (0.5 + 0.01 * ((b.k % 2) ? b.k : -b.k));
    push({RequestKind::SetLoad, t, {}});
    b.waiting = requests_sent_ + 1;
    solved_on_screen_ = false;
    ++b.k;
  }
}

int GuiApp::run(render::GlfwWindow& window, std::vector<gui::ScriptAction> script) {
  if (!log_.open(args_.state_file)) {
    std::cerr << args_.state_file << ": cannot write the state file\n";
    return kExitOutput;
  }
  render::FontAtlas font;
  render::GlRenderer renderer(window, font);
  renderer_ = &renderer;

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  if (fs::exists(render::kDejaVuSans)) io.Fonts->AddFontFromFileTTF(render::kDejaVuSans, 15.0f);
  ImGui::StyleColorsLight();
  // Our key callback first: ImGui's callbacks chain to the one installed before them.
  glfwSetWindowUserPointer(window.handle(), this);
  glfwSetKeyCallback(window.handle(), &GuiApp::key_event);
  ImGui_ImplGlfw_InitForOpenGL(window.handle(), true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  glfwSwapInterval(args_.bench > 0 ? 0 : 1);

  send_to_worker();  // the first solve
  std::size_t next_action = 0;
  bool script_failed = false;
  const bool scripted = !script.empty();
  int frames = 0;
  while (!quit_) {
    const double now = seconds_since(start_);
    const bool busy = worker_.busy() || playing_ || recording_ || scripted || args_.bench > 0 ||
                      ImGui::IsAnyMouseDown() || !queue_.empty();
    if (busy)
      glfwPollEvents();
    else
      glfwWaitEventsTimeout(0.25);
    if (glfwWindowShouldClose(window.handle()) || interrupted()) push({RequestKind::Quit, 0.0, {}});

    // Scene file changed on disk: reload, keeping the view.
    if (now >= next_file_check_) {
      next_file_check_ = now + 0.5;
      std::error_code error;
      const auto time = fs::last_write_time(args_.scene, error);
      if (!error && time != scene_time_) {
        scene_time_ = time;
        push({RequestKind::Reload, 0.0, {}});
      }
    }

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    int fb_width = 0, fb_height = 0;
    glfwGetFramebufferSize(window.handle(), &fb_width, &fb_height);
    const int view_x = static_cast<int>(kPanelWidth);
    const int view_width = std::max(16, fb_width - view_x);
    const int view_height = std::max(16, fb_height);
    mouse(static_cast<float>(view_x), static_cast<float>(view_width),
          static_cast<float>(view_height));
    if (scripted) run_script(script, next_action, now, script_failed);
    if (args_.bench > 0) bench_step(now);
    panels(static_cast<float>(fb_height));

    sync();  // the one place where requests change the state
    if (view_width != view_width_ || view_height != view_height_) {
      view_width_ = view_width;
      view_height_ = view_height;
      redraw_ = true;
    }
    step_recording();
    // Draft quality (no multisampling) while the slider is dragged: the picture follows
    // the pointer at a higher frame rate; full quality again as soon as it rests.
    // The first picture of a new load factor is a draft too (it appears a few ms sooner);
    // the next frame refines it. Screenshots are always taken at full quality.
    const bool fresh = shown_ && shown_->request != drafted_request_ && shown_->finished;
    if (fresh) drafted_request_ = shown_->request;
    const bool draft = (dragging_slider_ || (args_.bench > 0 && bench_.phase == 0) || fresh) &&
                       !screenshot_requested_ && !recording_;
    if (draft != draft_) {
      draft_ = draft;
      renderer.set_samples(draft ? 1 : 4);
      redraw_ = true;
    }
    // Bounded work per frame: a picture that costs more than a frame (a huge scene on a
    // software renderer) is redrawn at most every other such period, so the panels and
    // the slider keep answering between pictures.
    const bool picture_due =
        last_picture_ms_ < 16.0 || screenshot_requested_ || recording_ ||
        std::chrono::duration<double, std::milli>(Clock::now() - last_picture_end_).count() >=
            last_picture_ms_;
    if (redraw_ && picture_due) {
      const auto draw_start = Clock::now();
      draw_picture(view_width_, view_height_);
      if (last_picture_ms_ >= 16.0 || args_.bench > 0) glFinish();  // true cost, not submission
      last_picture_end_ = Clock::now();
      last_picture_ms_ =
          std::chrono::duration<double, std::milli>(last_picture_end_ - draw_start).count();
      if (args_.bench > 0 && bench_.phase == 0) {
        glFinish();  // the benchmark times the GL work too, not just its submission
        bench_.draw_ms.push_back(
            std::chrono::duration<double, std::milli>(Clock::now() - draw_start).count());
      }
      redraw_ = false;
    }
    if (screenshot_requested_) {
      screenshot(pending_screenshot_);
      screenshot_requested_ = false;
    }

    ImGui::Render();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb_width, fb_height);
    glClearColor(0.94f, 0.94f, 0.94f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    renderer.blit_to_default(view_x, 0, fb_height);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    const auto swap_start = Clock::now();
    glfwSwapBuffers(window.handle());
    if (args_.bench > 0 && bench_.phase == 0)
      bench_.swap_ms.push_back(
          std::chrono::duration<double, std::milli>(Clock::now() - swap_start).count());
    ++frames;
    report_frame();
    if (!ready_reported_ && frames >= 2 && shown_) {
      ready_reported_ = true;
      log_.write({{"event", "ready"},
                  {"window", {fb_width, fb_height}},
                  {"view", {view_x, 0, view_width_, view_height_}},
                  {"slider", {slider_[0], slider_[1], slider_[2], slider_[3]}},
                  {"max_load", slider_max_},
                  {"renderer", window.description()}});
    }
  }

  if (screenshot_pool_) screenshot_pool_->finish();
  for (std::thread& t : finishers_)
    t.join();
  log_.write({{"event", "quit"}, {"frames", frames}});
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();

  if (args_.bench > 0) {
    const Bench& b = bench_;
    std::printf("scene          %s (%zu struts, %zu contact pairs)\n", args_.scene.c_str(),
                target_.model->struts.size(), target_.model->pairs.size());
    std::printf("renderer       %s, window %dx%d\n", window.description().c_str(),
                view_width_ + static_cast<int>(kPanelWidth), view_height_);
    std::printf(
        "drag           %d load changes at 60 per second: %.1f frames/s (frame time median "
        "%.2f ms, max %.2f ms)\n",
        args_.bench, b.drag_seconds > 0 ? b.drag_frames / b.drag_seconds : 0.0, median(b.frame_ms),
        b.frame_ms.empty() ? 0.0 : *std::max_element(b.frame_ms.begin(), b.frame_ms.end()));
    std::printf(
        "per frame      picture median %.2f ms (draw lists %.2f ms, the rest GL until "
        "finished; %zu of the %d frames drew a new picture); ImGui + blit + swap median "
        "%.2f ms\n",
        median(b.draw_ms), median(b.lists_ms), b.draw_ms.size(), b.drag_frames, median(b.swap_ms));
    std::printf(
        "latency        load change -> frame with the converged solve: median %.2f ms, "
        "max %.2f ms (%zu changes)\n",
        median(b.solved_latency_ms),
        b.solved_latency_ms.empty()
            ? 0.0
            : *std::max_element(b.solved_latency_ms.begin(), b.solved_latency_ms.end()),
        b.solved_latency_ms.size());
    std::printf("               load change -> first frame at the new load: median %.2f ms\n",
                median(b.first_latency_ms));
    std::printf("solve          median %.2f ms, median %.0f iterations (warm-started FETI-C)\n",
                median(b.solve_ms),
                median(std::vector<double>(b.iterations.begin(), b.iterations.end())));
  }
  if (script_failed) return kExitNotConverged;
  return kExitOk;
}

int run_gui(const GuiArgs& args) {
  if (!parse_image_size(args.size)) {
    std::cerr << "--size: expected WxH\n";
    return kExitUsage;
  }
  std::vector<gui::ScriptAction> script;
  if (!args.script.empty()) {
    std::ifstream in(args.script);
    if (!in) {
      std::cerr << args.script << ": cannot read the script\n";
      return kExitUsage;
    }
    std::stringstream text;
    text << in.rdbuf();
    std::vector<gui::ScriptError> errors;
    script = gui::parse_script(text.str(), errors);
    for (const gui::ScriptError& error : errors)
      std::cerr << args.script << ":" << error.line << ": " << error.message << '\n';
    if (!errors.empty()) return kExitUsage;
  }
  const auto scene = load_scene_or_report(args.scene);
  if (!scene) return kExitInvalidScene;
  auto model = std::make_shared<const solver::Model>(solver::build_model(*scene));
  const std::string title =
      model->title.empty() ? fs::path(args.scene).filename().string() : model->title;
  const ImageSize size = *parse_image_size(args.size);
  std::unique_ptr<render::GlfwWindow> window;
  try {
    window = std::make_unique<render::GlfwWindow>(size.width, size.height, "fetic - " + title);
  } catch (const render::NoDisplayError& error) {
    std::cerr << "fetic gui: no display: " << error.what()
              << ".\nThe window needs an X server: run it in a desktop session, or under a "
                 "virtual one (xvfb-run -a fetic gui "
              << args.scene << ").\nWithout a display, render the same pictures to PNG files: "
              << "fetic render " << args.scene << " --out DIR\n";
    return kExitNoDisplay;
  } catch (const render::RenderError& error) {
    std::cerr << "fetic gui: " << error.what() << '\n';
    return kExitNoDisplay;
  }
  GuiApp app(args, std::move(model), title);
  return app.run(*window, std::move(script));
}

}  // namespace

void register_gui(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<GuiArgs>();
  CLI::App* command = app.add_subcommand(
      "gui", "Interactive window: load slider, live warm-started FETI-C, iteration history");
  command->add_option("scene", args->scene, "Scene file (TOML, see README)")->required();
  command->add_option("--method", args->method, "Method to start with")
      ->check(CLI::IsMember({"sd", "cg", "active-set", "feti", "feti-c"}))
      ->capture_default_str();
  command->add_option("--preconditioner", args->preconditioner, "FETI preconditioner")
      ->check(CLI::IsMember({"dirichlet", "lumped", "none"}))
      ->capture_default_str();
  command->add_option("--load", args->load, "Load factor to start at")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command
      ->add_option("--max-load", args->max_load,
                   "Top of the load slider (0: 2, twice the scene's loads)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--magnification", args->magnification, "Lock the magnification (0: auto)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--size", args->size, "Window size in pixels")
      ->check(image_size_check())
      ->capture_default_str();
  command->add_option("--state-file", args->state_file,
                      "Write what the app does as JSON lines to this file (- for stdout)");
  command->add_option("--script", args->script, "Run timed actions from this file (see README)");
  command->add_option("--screenshot-dir", args->screenshot_dir, "Where S saves screenshots")
      ->capture_default_str();
  command->add_option("--record-dir", args->record_dir, "Where recordings go")
      ->capture_default_str();
  command->add_flag("--no-overlay", args->no_overlay, "Start without the information panel");
  command
      ->add_option("--bench", args->bench,
                   "Benchmark: drag the slider over N load changes, then time 30 isolated "
                   "changes; print latency and frame rate, quit")
      ->check(CLI::Range(2, 100000));
  command->callback([args, &exit_code] { exit_code = run_gui(*args); });
}

}  // namespace fetic::app
