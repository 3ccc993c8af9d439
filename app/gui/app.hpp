#pragma once
// The window of `fetic gui`: its state and what changes it. Mouse, keyboard, --script and
// --bench only queue requests (push); once per frame sync() applies them all, so the
// inputs cannot disagree. The solver runs on its own thread (SolverWorker) and publishes
// immutable states, so the window never waits for a solve.
//
// The members are defined by purpose, one file each:
//   sync_point.cpp     applying requests, taking the newest solve
//   main_loop.cpp      the frame loop: input, panels, sync, picture, swap
//   picture.cpp        the scene and information panel drawn for the shown iterate
//   comparison.cpp     two methods side by side: two pictures, one residual plot
//   panels.cpp         the ImGui controls and the help window
//   input.cpp          keys, mouse pan and zoom, the script runner
//   recording.cpp      screenshots and recordings
//   scene_file.cpp     reloading the scene file
//   state_reports.cpp  the "solved" events of the state file after each swap
//   bench.cpp          the --bench measurement
//   bench_view.cpp     the --bench-view measurement (panning and zooming)
//   paraview_export.cpp  the shown iterate as ParaView files

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "app/gui/bench.hpp"
#include "app/gui/options.hpp"
#include "app/gui/pick_index.hpp"
#include "app/gui/recording.hpp"
#include "app/gui/requests.hpp"
#include "app/gui/script.hpp"
#include "app/gui/solver_worker.hpp"
#include "app/gui/state_log.hpp"
#include "app/solve_monitor.hpp"
#include "app/view_file.hpp"
#include "app/vtu_export.hpp"
#include "render/draw_list.hpp"
#include "render/frame_sequence.hpp"
#include "render/overlay.hpp"
#include "render/png_writer.hpp"
#include "render/scene_framing.hpp"
#include "render/scene_mesh.hpp"
#include "render/view.hpp"
#include "solver/model.hpp"
#include "solver/stopwatch.hpp"

struct GLFWwindow;

namespace fetic::render {
class GlRenderer;
class GlfwWindow;
}  // namespace fetic::render

namespace fetic::app::gui {

using Clock = std::chrono::steady_clock;

constexpr float kPanelWidth =
    330.0f;  // ImGui panel on the left (at scale 1); the picture fills the rest
// The smallest text of the picture (plot ticks, 0.68 of the base text size) at scale 1.
constexpr float kSmallestText = 11.0f;

using solver::seconds_since;

class App {
 public:
  App(const Options& args, std::shared_ptr<const solver::Model> model, std::string title);

  int run(render::GlfwWindow& window, std::vector<ScriptAction> script);

  // Methods that would not fit in memory on this scene, each with the reason: picking one
  // (the method or the compared method) is refused with that reason instead of solving.
  void refuse_methods(std::map<solver::MethodKind, std::string> reasons) {
    memory_refusals_ = std::move(reasons);
  }

 private:
  // The panel's width: kPanelWidth times the scale of text and controls (--ui-scale).
  float panel_width() const { return kPanelWidth * ui_scale_; }

  // main_loop.cpp: the frame loop's steps
  struct ScriptRun {  // the window script and the next action due
    explicit ScriptRun(std::vector<ScriptAction> actions)
        : script(std::move(actions)), scripted(!script.empty()) {}
    std::vector<ScriptAction> script;
    std::size_t next_action = 0;
    bool scripted = false;
  };
  struct FrameLayout {  // this frame's framebuffer and where the picture goes in it
    int fb_width = 0, fb_height = 0, view_x = 0;
  };
  void start_imgui(render::GlfwWindow& window);
  void frame(render::GlfwWindow& window, ScriptRun& run);
  void choose_quality();  // draft while the picture moves, full quality at rest
  void draw_picture_when_due();
  void present(render::GlfwWindow& window);
  void report_ready(const render::GlfwWindow& window, int frames);
  int finish(const render::GlfwWindow& window, int frames);

  // sync_point.cpp
  void push(Request request) { queue_.push_back(std::move(request)); }
  void send_to_worker();
  // --monitor: the worker writes a line per iteration of every solve (main_loop.cpp).
  void open_monitor();
  std::string close_monitor();  // "" when every line arrived
  void apply(const Request& request);
  void apply_solver_request(const Request& request);  // load, method, preconditioner, compare
  bool refused_for_memory(const Request& request, solver::MethodKind kind);
  void apply_history_request(const Request& request);  // play, step, scrub, live, cancel
  void apply_display_request(const Request& request);  // magnification, colours, toggles, views
  void apply_output_request(const Request& request);   // screenshots, recordings, exports, quit
  void sync();  // the sync point: applies the queued requests, takes the newest state
  int shown_index() const;
  int last_index() const;  // the newest iterate of the shown solve
  // Live stepping: lets the solver make one more iteration when the newest is on screen.
  bool advance_live();
  // The shown iterate against its solve: "converged; showing iteration 3 of 6", ...
  std::string shown_status() const;

  // picture.cpp
  render::View view(int width, int height) const;
  void draw_picture(int width, int height);
  // draw_picture's steps: the framing (fitted once per scene, survey and size, then zoomed
  // and panned), the struts' mesh and its values, the overlay panel.
  render::SceneFraming frame_picture(const render::View& v, int width, int height);
  // The struts' mesh and its per-frame values. Two are kept: one at the picture's level of
  // detail and, on a large scene, one a level coarser for the drafts drawn while the view
  // moves (a quarter of the cells), so that neither is built again when the view rests.
  struct MeshSlot {
    std::shared_ptr<const render::SceneMesh> mesh;
    std::shared_ptr<const solver::Model> model;
    render::MeshValues values;
    std::shared_ptr<const solver::Snapshot> values_iterate;  // what values are of
    std::array<double, 3> values_key{0, 0, 0};               // mesh id and colour scales
  };
  const MeshSlot& update_mesh(const render::View& v, const render::SceneFraming& framing,
                              int index);
  void update_slot(MeshSlot& slot, const render::View& v, const render::SceneFraming& framing,
                   const render::MeshDetail& detail, int index);
  const render::DrawList& contact_chart(const render::View& v, int index);
  render::DrawList picture_overlay(const render::OverlayInfo& info,
                                   const solver::Snapshot& snapshot,
                                   const std::vector<solver::HistoryEntry>& history,
                                   const render::View& v);
  render::RunExtent plot_extent();  // the survey's scales, the iteration axis widened

  // comparison.cpp
  bool comparing() const;     // a second method is on and has something to show
  int compare_index() const;  // its iterate shown beside the first's (the same iteration)
  void draw_comparison(int width, int height);

  // panels.cpp
  void panels(float height);  // the panel on the left, the help window when asked for
  void load_controls();
  void solver_controls();
  void history_controls();
  void display_toggles();
  void output_buttons();
  void status_text();
  void help_window();

  // input.cpp
  static void key_event(GLFWwindow* window, int key, int scancode, int action, int mods);
  void mouse(float view_x, float view_width, float view_height);
  void run_script(std::vector<ScriptAction>& script, std::size_t& next, double now);

  // recording.cpp
  void start_recording(const Request& request);
  void screenshot(const std::string& path);
  void step_recording();

  // A request that cannot do what it says: the status line in red and an "error" event;
  // from a script, the message on stderr (script:line) and the run ends with `status`.
  void fail(const Request& request, const std::string& message, int status);

  // The status line under the panel; errors are shown in red.
  void say(std::string line, bool error = false) {
    status_line_ = std::move(line);
    status_is_error_ = error;
  }

  // scene_file.cpp
  void reload();
  void watch_scene_file(double now);

  // state_reports.cpp
  void report_frame();

  // views.cpp
  SavedView current_view() const;
  void save_view(const std::string& path);  // "": the next fetic_view_NNNN.json
  void load_view(const Request& request);   // text: the view file
  void use_view(const SavedView& saved);
  void set_color(render::ColorBy color);
  void place_pending_center();  // a loaded view's centre, into pan_ (framing_ is fitted)
  void view_buttons();          // in the panel: save and load views
  std::string in_screenshot_dir(const std::string& path) const;
  // Numbered outputs in --screenshot-dir (recording.cpp): the first name from `from` on
  // ("fetic_view_%04d.json") that is not taken, and its number. A counter moves past a
  // number only when its output was written, so the first success is _0000.
  std::pair<std::string, int> numbered_name(const char* pattern, int from) const;
  // Creates the folder of an output (--screenshot-dir on first use); false, the output
  // reported lost, when it cannot.
  bool output_folder_ready(const std::string& path);
  // A reserved number given back after its output failed (unless a later one was taken).
  static void give_back(std::atomic<int>& counter, int number);

  // picking.cpp
  void index_picture(const solver::Snapshot& snapshot, const render::SceneFraming& framing);
  void refresh_pick_index();  // index_picture for the last picture, when it is stale
  void hover(render::Point at);
  nlohmann::json pick_values(const Pickable& item) const;
  std::string pick_text(const Pickable& item) const;
  void picking(float view_x, float view_width, float view_height);  // tooltip, pins
  void toggle_pin(const Pickable& item);
  void pinned_window(float view_x, float view_width, float view_height);
  void locate(const std::string& what);
  // window_shot.cpp
  void capture_window(int width, int height);
  // paraview_export.cpp
  void export_paraview(const Request& request);  // text: the directory ("": --vtu-dir)

  // bench.cpp
  void bench_step(double now);
  void print_bench(const render::GlfwWindow& window) const;
  // bench_view.cpp
  bool benchmarking() const { return args_.bench > 0 || args_.bench_view > 0; }
  void view_bench_step();
  void print_view_bench(const render::GlfwWindow& window) const;

  const Options& args_;
  std::string title_;
  std::map<solver::MethodKind, std::string> memory_refusals_;  // refuse_methods
  // --monitor, written by the worker's thread: declared before the worker, so that it
  // outlives the worker's thread.
  std::unique_ptr<SolveMonitor> monitor_;
  SolverWorker worker_;
  SolverWorker compare_worker_;  // the second method of the comparison
  std::optional<solver::MethodKind> compare_;
  std::shared_ptr<const SolveState> compare_shown_;
  SolverTarget target_;
  RequestQueue queue_;
  StateLog log_;
  std::uint64_t requests_sent_ = 0;
  std::map<std::uint64_t, Clock::time_point> requested_at_;

  // What is on screen.
  std::shared_ptr<const SolveState> shown_;
  std::shared_ptr<const SolveState> error_;  // the newest request could not be solved
  bool follow_ = true;                       // show the newest iterate
  bool playing_ = false;
  bool live_ = false;  // Step and Play advance the solver itself (SolverTarget::live)
  int cursor_ = 0;
  double play_rate_ = 4.0;  // iterations per second
  double next_tick_ = 0.0;
  bool redraw_ = true;
  std::uint64_t reported_request_ = 0;     // last "solved" event
  std::uint64_t first_frame_request_ = 0;  // last request seen in a frame
  bool solved_on_screen_ = false;          // newest request finished and swapped

  // The picture: the framing for the current scene, survey and size (PictureKey), and the
  // struts' mesh (kept on the GPU by the renderer) with this frame's values.
  struct PictureKey {  // shared pointers: what they point to cannot be replaced unseen
    std::shared_ptr<const solver::Model> model;
    std::shared_ptr<const render::RunExtent> extent;
    int width = 0, height = 0;
    double magnification = 0.0;
    bool overlay = true;
    bool operator==(const PictureKey&) const = default;
  };
  PictureKey framing_key_;
  render::SceneFraming framing_;
  // The struts' meshes (MeshSlot above).
  MeshSlot fine_mesh_, draft_mesh_;
  struct ChartKey {  // what the contact chart is drawn from (null iterate: no chart)
    std::shared_ptr<const solver::Snapshot> iterate;
    std::shared_ptr<const solver::Model> model;
    int width = 0, height = 0;
    float text_size = 0.0f;
    bool operator==(const ChartKey&) const = default;
  };
  ChartKey chart_key_;
  render::DrawList chart_list_;

  // View settings.
  double magnification_ = 0.0;  // 0: automatic
  double shown_magnification_ = 0.0;
  // The colouring: moment_, else stress_, else subdomains_ or struts. Stress and moment
  // exclude each other; subdomains_ is kept under them (what turning them off returns to).
  bool subdomains_ = true, stress_ = false, moment_ = false;
  bool forces_ = true, gaps_ = true, show_overlay_ = true;
  bool labels_ = false;
  bool corners_ = false;  // FETI-DP's primal corners (render/corner_marks.hpp)
  bool chart_ = false;    // the per-contact chart beside the picture (render/contact_chart.hpp)
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
  // The last pan or zoom: pictures are drafts (no multisampling) until the view has rested
  // this long, then drawn again at full quality.
  static constexpr std::chrono::milliseconds kViewRest{250};
  Clock::time_point view_moved_{};
  render::Point base_center_{0.0f, 0.0f};
  int view_width_ = 0, view_height_ = 0;
  std::shared_ptr<const render::RunExtent> axis_survey_;  // the survey longest_history_ is for
  int longest_history_ = 0;  // iterations of the longest solve drawn with it

  // Scene file.
  std::filesystem::file_time_type scene_time_{};
  double next_file_check_ = 0.0;
  std::string status_line_;
  bool status_is_error_ = false;  // the status line reports a failure (shown in red)

  // Screenshots and recordings.
  std::unique_ptr<render::PngEncoderPool> screenshot_pool_;
  std::atomic<int> screenshot_count_{0};  // written by the encoder threads on failure
  std::string pending_screenshot_;
  bool screenshot_requested_ = false;
  std::unique_ptr<Recording> recording_;
  std::vector<std::thread> finishers_;
  int recordings_ = 0;
  int sweep_steps_ = 20;

  render::GlRenderer* renderer_ = nullptr;
  FrameLayout layout_;
  float ui_scale_ = 1.0f;  // --ui-scale, else the monitor's content scale
  bool quit_ = false;
  double wait_started_ = -1.0;  // when the script's current "wait" began
  int script_status_ = 0;       // a script's action failed: the run's exit status
  float slider_[4] = {0, 0, 0, 0};
  bool ready_reported_ = false;
  Clock::time_point start_ = Clock::now();

  BenchMeasurement bench_;
  ViewBench view_bench_;
  int mesh_builds_ = 0;  // the struts' mesh built (scene, pieces, colouring or detail)

  // Saved views (views.cpp).
  render::SceneFraming placed_;              // the framing of the last picture
  render::RunExtent drawn_extent_;           // and the scales it was drawn with
  std::optional<render::RunExtent> scales_;  // a loaded view's scales
  bool center_pending_ = false;              // place pending_center_ at the next picture
  solver::Vec2 pending_center_{0, 0};
  int views_saved_ = 0;
  // Save view and Locate read the picture: they wait for the next one to be drawn.
  std::vector<Request> after_picture_;

  // Picking (picking.cpp).
  PickIndex picks_;
  std::shared_ptr<const SolveState> pick_state_;  // the last picture's state and iterate
  int pick_iterate_ = 0;
  bool pick_stale_ = false;  // picks_ is not yet of the last picture
  std::optional<Pickable> hovered_;
  render::Point last_pointer_{-1.0f, -1.0f};  // where the pointer was the frame before
  // An index build slower than this is not repeated under a resting pointer.
  static constexpr double kSlowIndexMs = 50.0;
  std::vector<Pickable> pinned_;
  double pick_query_ms_ = 0.0;
  bool window_shot_requested_ = false;
  std::string pending_window_shot_;
  std::atomic<int> window_shots_{0};
  std::string view_path_;  // the view file the panel loads: --view, or the last saved
  // ParaView export: one series per directory and model.
  std::unique_ptr<VtuSeries> vtu_;
  std::shared_ptr<const solver::Model> vtu_model_;
};

}  // namespace fetic::app::gui
