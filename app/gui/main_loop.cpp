// The frame loop of the window: events, input, panels, the sync point, the picture
// (drawn only when something changed, and at most as often as it can be afforded), the
// ImGui pass and the swap.

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <thread>
#include <vector>

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "app/data_paths.hpp"
#include "app/exit_codes.hpp"
#include "app/gui/app.hpp"
#include "app/interrupt.hpp"
#include "render/font.hpp"
#include "render/gl_renderer.hpp"
#include "render/glfw_window.hpp"

namespace fetic::app::gui {
namespace {

namespace fs = std::filesystem;

}  // namespace

void App::open_monitor() {
  if (args_.monitor.empty()) return;
  monitor_ = std::make_unique<SolveMonitor>(*target_.model, args_.monitor_full, true);
  monitor_->open(args_.monitor);
  worker_.observe_with([monitor = monitor_.get()](const solver::Model& model,
                                                  const solver::Method& method, double load_factor,
                                                  bool started) {
    if (started) monitor->begin_load(load_factor, model);
    monitor->observe(method);
  });
}

std::string App::close_monitor() {
  if (!monitor_) return "";
  worker_.observe_with(nullptr);  // waits for a line being written
  return monitor_->close();
}

int App::run(render::GlfwWindow& window, std::vector<ScriptAction> script) {
  try {
    log_.open(args_.state_file);
    open_monitor();
  } catch (const OutputError& error) {
    return report_output_error(error);
  }
  // Text and controls scale with --ui-scale or the monitor's content scale; the picture's
  // text is at least kSmallestText (App::view), its glyphs rasterized at up to 22 pixels
  // times the scale.
  ui_scale_ = args_.ui_scale > 0.0 ? static_cast<float>(args_.ui_scale) : window.content_scale();
  render::FontAtlas font(22.0f * std::max(1.0f, ui_scale_), font_file("DejaVuSans.ttf"),
                         font_file("DejaVuSans-Bold.ttf"));
  render::GlRenderer renderer(window, font);
  renderer_ = &renderer;
  start_imgui(window);

  send_to_worker();  // the first solve
  ScriptRun run{std::move(script)};
  int frames = 0;
  while (!quit_) {
    frame(window, run);
    ++frames;
    report_frame();
    report_ready(window, frames);
  }
  return finish(window, frames);
}

void App::start_imgui(render::GlfwWindow& window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  const std::string regular = font_file("DejaVuSans.ttf");
  if (fs::exists(regular)) io.Fonts->AddFontFromFileTTF(regular.c_str(), 15.0f * ui_scale_);
  ImGui::StyleColorsLight();
  ImGui::GetStyle().ScaleAllSizes(ui_scale_);
  // Our key callback first: ImGui's callbacks chain to the one installed before them.
  glfwSetWindowUserPointer(window.handle(), this);
  glfwSetKeyCallback(window.handle(), &App::key_event);
  ImGui_ImplGlfw_InitForOpenGL(window.handle(), true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  glfwSwapInterval(benchmarking() ? 0 : 1);
}

// One frame: events, input and panels, the sync point, the picture when it is due, then
// the ImGui pass and the swap.
void App::frame(render::GlfwWindow& window, ScriptRun& run) {
  const double now = seconds_since(start_);
  const bool busy = (worker_.busy() && !worker_.paused()) || playing_ || recording_ ||
                    run.scripted || benchmarking() || ImGui::IsAnyMouseDown() || !queue_.empty() ||
                    draft_;
  if (busy)
    glfwPollEvents();
  else
    glfwWaitEventsTimeout(0.25);
  if (glfwWindowShouldClose(window.handle()) || interrupted()) push({RequestKind::Quit, 0.0, {}});

  watch_scene_file(now);

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  glfwGetFramebufferSize(window.handle(), &layout_.fb_width, &layout_.fb_height);
  layout_.view_x = static_cast<int>(panel_width());
  const int view_width = std::max(16, layout_.fb_width - layout_.view_x);
  const int view_height = std::max(16, layout_.fb_height);
  mouse(static_cast<float>(layout_.view_x), static_cast<float>(view_width),
        static_cast<float>(view_height));
  picking(static_cast<float>(layout_.view_x), static_cast<float>(view_width),
          static_cast<float>(view_height));
  if (run.scripted) run_script(run.script, run.next_action, now);
  if (args_.bench > 0) bench_step(now);
  if (args_.bench_view > 0) view_bench_step();
  panels(static_cast<float>(layout_.fb_height));

  sync();  // the one place where requests change the state
  if (view_width != view_width_ || view_height != view_height_) {
    view_width_ = view_width;
    view_height_ = view_height;
    redraw_ = true;
  }
  step_recording();
  choose_quality();
  draw_picture_when_due();
  for (const Request& r : after_picture_)  // the picture they read is drawn now
    r.kind == RequestKind::SaveView ? save_view(r.text) : locate(r.text);
  after_picture_.clear();
  if (screenshot_requested_) {
    screenshot(pending_screenshot_);
    screenshot_requested_ = false;
  }
  present(window);
}

// Draft quality (no multisampling) while the slider is dragged: the picture follows the
// pointer at a higher frame rate; full quality again as soon as it rests. The first
// picture of a new load factor is a draft too (it appears a few ms sooner); the next frame
// refines it. Screenshots are always taken at full quality.
void App::choose_quality() {
  const bool fresh = shown_ && shown_->request != drafted_request_ && shown_->finished;
  if (fresh) drafted_request_ = shown_->request;
  // So is the picture while it is panned or zoomed, until it has rested for kViewRest.
  const bool moving = Clock::now() - view_moved_ < kViewRest;
  const bool draft =
      (dragging_slider_ || (args_.bench > 0 && bench_.phase == 0) || fresh || moving) &&
      !screenshot_requested_ && !recording_;
  if (draft != draft_) {
    draft_ = draft;
    renderer_->set_samples(draft ? 1 : 4);
    redraw_ = true;
  }
}

// Bounded work per frame: a picture that costs more than a frame (a huge scene on a
// software renderer) is redrawn at most every other such period, so the panels and the
// slider keep answering between pictures.
void App::draw_picture_when_due() {
  const bool picture_due =
      last_picture_ms_ < 16.0 || screenshot_requested_ || window_shot_requested_ || recording_ ||
      !after_picture_.empty() ||
      std::chrono::duration<double, std::milli>(Clock::now() - last_picture_end_).count() >=
          last_picture_ms_;
  if (!redraw_ || !picture_due) return;
  const auto draw_start = Clock::now();
  draw_picture(view_width_, view_height_);
  if (last_picture_ms_ >= 16.0 || benchmarking()) glFinish();  // true cost, not submission
  last_picture_end_ = Clock::now();
  last_picture_ms_ =
      std::chrono::duration<double, std::milli>(last_picture_end_ - draw_start).count();
  if (args_.bench > 0 && bench_.phase == 0) {
    glFinish();  // the benchmark times the GL work too, not just its submission
    bench_.draw_ms.push_back(
        std::chrono::duration<double, std::milli>(Clock::now() - draw_start).count());
  }
  redraw_ = false;
  if (args_.bench > 0 && bench_.phase == 3 && bench_.pan_solving) ++bench_.pan_pictures;
  if (view_bench_.phase == 0 || view_bench_.phase == 1) {
    ++view_bench_.pictures[view_bench_.phase];
    view_bench_.picture_ms.push_back(last_picture_ms_);
  }
}

// The ImGui pass over the picture, the capture of the whole window when asked, the swap.
void App::present(render::GlfwWindow& window) {
  ImGui::Render();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, layout_.fb_width, layout_.fb_height);
  glClearColor(0.94f, 0.94f, 0.94f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  renderer_->blit_to_default(layout_.view_x, 0, layout_.fb_height);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  capture_window(layout_.fb_width, layout_.fb_height);
  const auto swap_start = Clock::now();
  glfwSwapBuffers(window.handle());
  if (args_.bench > 0 && bench_.phase == 0)
    bench_.swap_ms.push_back(
        std::chrono::duration<double, std::milli>(Clock::now() - swap_start).count());
}

// The "ready" event, once: the second frame that shows a state.
void App::report_ready(const render::GlfwWindow& window, int frames) {
  if (ready_reported_ || frames < 2 || !shown_) return;
  ready_reported_ = true;
  log_.write({{"event", "ready"},
              {"window", {layout_.fb_width, layout_.fb_height}},
              {"view", {layout_.view_x, 0, view_width_, view_height_}},
              {"slider", {slider_[0], slider_[1], slider_[2], slider_[3]}},
              {"max_load", slider_max_},
              {"ui_scale", ui_scale_},
              {"text_size", render::text_size(view(view_width_, view_height_))},
              {"renderer", window.description()}});
}

// After the last frame: the background work joined, the outputs closed, the exit status.
int App::finish(const render::GlfwWindow& window, int frames) {
  if (screenshot_pool_) screenshot_pool_->finish();
  for (std::thread& t : finishers_)
    t.join();
  log_.write({{"event", "quit"}, {"frames", frames}});
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();

  if (args_.bench > 0) print_bench(window);
  if (args_.bench_view > 0) print_view_bench(window);
  const std::string lost_monitor = close_monitor();
  const std::string lost_outputs = log_.lost_outputs();
  if (!lost_outputs.empty()) std::cerr << "fetic gui: " << lost_outputs << '\n';
  if (const std::string lost = log_.close(); !lost.empty()) {
    std::cerr << lost << "; the state file is incomplete\n";
    return kExitOutput;
  }
  if (!lost_outputs.empty()) return kExitOutput;
  if (!lost_monitor.empty()) {
    std::cerr << "fetic gui: the monitor stream is incomplete: " << lost_monitor << '\n';
    return kExitOutput;
  }
  if (interrupted()) {
    std::cerr << "fetic gui: interrupted by " << interrupt_name() << "; the window closed\n";
    return kExitInterrupted;
  }
  if (script_status_ != 0) return script_status_;
  return kExitOk;
}

}  // namespace fetic::app::gui
