// The state of the window changes here only: App::apply turns one request into state
// (and into a solver request when the solve's input changed); App::sync, once per frame,
// applies all queued requests and takes the newest state the solver published. The
// requests that change only how the picture is drawn are applied in views.cpp, beside
// the saved views that hold the same settings.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "app/exit_codes.hpp"
#include "app/gui/app.hpp"
#include "render/contact_chart.hpp"
#include "solver/method.hpp"

namespace fetic::app::gui {
namespace {

namespace fs = std::filesystem;

// How long the sync point waits for a quick solve to finish within the frame.
constexpr std::chrono::microseconds kQuickSolve{5000};

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace

App::App(const Options& args, std::shared_ptr<const solver::Model> model, std::string title)
    : args_(args),
      title_(std::move(title)),
      worker_([] { glfwPostEmptyEvent(); }),
      compare_worker_([] { glfwPostEmptyEvent(); }) {
  target_.model = std::move(model);
  target_.model_generation = 1;
  target_.method = *solver::parse_method(args.method);
  target_.options.preconditioner = *solver::parse_preconditioner(args.preconditioner);
  target_.max_load = args.max_load;  // 0: the worker chooses from the scene
  slider_max_ = args.max_load > 0.0 ? args.max_load : 2.0;
  target_.load_factor = args.max_load > 0.0 ? std::min(args.load, args.max_load) : args.load;
  if (!args.compare.empty()) compare_ = solver::parse_method(args.compare);
  magnification_ = args.magnification;
  show_overlay_ = !args.no_overlay;
  chart_ = render::chart_shown(*target_.model, -1);
  if (!args.view.empty())
    load_view(
        {RequestKind::LoadView, 0.0, args.view});  // checked by cmd_gui before the window opened
  std::error_code ignored;
  scene_time_ = fs::last_write_time(args.scene, ignored);
}

void App::send_to_worker() {
  target_.request = ++requests_sent_;
  requested_at_[target_.request] = Clock::now();
  worker_.request(target_);
  if (compare_) {
    SolverTarget second = target_;
    second.method = *compare_;
    compare_worker_.request(second);
  }
}

int App::last_index() const {
  return shown_ ? std::max(0, static_cast<int>(shown_->iterates.size()) - 1) : 0;
}

int App::shown_index() const {
  if (!shown_ || shown_->iterates.empty()) return 0;
  const int last = last_index();
  return follow_ ? last : std::clamp(cursor_, 0, last);
}

bool App::advance_live() {
  if (!live_ || !shown_ || shown_->finished || shown_->request != requests_sent_ ||
      shown_index() < last_index())
    return false;
  worker_.allow(last_index() + 1);
  if (compare_) compare_worker_.allow(last_index() + 1);  // both take the next iteration
  follow_ = true;
  return true;
}

std::string App::shown_status() const {
  if (!shown_) return {};
  const int index = shown_index(), last = last_index();
  std::string status = shown_->cancelled   ? "cancelled"
                       : !shown_->finished ? (live_ && worker_.paused() ? "paused" : "running")
                                           : solver::to_string(shown_->status);
  if (shown_->finished || index < last) status += " at iteration " + std::to_string(last);
  if (index < last) status += "; showing " + std::to_string(index);
  return status;
}

// One request into state; each kind of request has its function below.
void App::apply(const Request& r) {
  switch (r.kind) {
    case RequestKind::SetLoad:
    case RequestKind::SetMethod:
    case RequestKind::SetPreconditioner:
    case RequestKind::SetCompare:
      return apply_solver_request(r);
    case RequestKind::TogglePlay:
    case RequestKind::Play:
    case RequestKind::Pause:
    case RequestKind::Step:
    case RequestKind::StepBack:
    case RequestKind::Reset:
    case RequestKind::SetLive:
    case RequestKind::Cancel:
    case RequestKind::Scrub:
      return apply_history_request(r);
    case RequestKind::SetMagnification:
    case RequestKind::Toggle:
    case RequestKind::SetColor:
    case RequestKind::ResetView:
    case RequestKind::LoadView:
      return apply_display_request(r);
    default:
      return apply_output_request(r);
  }
}

// A method that would not fit in memory (refuse_methods) is not switched to: a script's
// line ends the run with status 7, as `fetic solve` refuses it; a click says why.
bool App::refused_for_memory(const Request& r, solver::MethodKind kind) {
  const auto refusal = memory_refusals_.find(kind);
  if (refusal == memory_refusals_.end()) return false;
  const std::string message = "not switched to " + r.text + ": " + refusal->second;
  if (r.script_line > 0)
    fail(r, message, kExitOutOfMemory);
  else
    say(message, true);
  return true;
}

// What is solved: the load, the method, its preconditioner, the second method.
void App::apply_solver_request(const Request& r) {
  switch (r.kind) {
    case RequestKind::SetLoad: {
      if (r.script_line > 0 && r.value > slider_max_) {
        fail(r,
             "load " + number_text(r.value) + " is beyond the slider's maximum " +
                 number_text(slider_max_) + " (--max-load sets it)",
             kExitUsage);
        break;
      }
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
        if (refused_for_memory(r, *kind)) break;
        target_.method = *kind;
        follow_ = true;
        send_to_worker();
      } else {
        say("unknown method " + r.text, true);
      }
      break;
    case RequestKind::SetPreconditioner:
      if (const auto p = solver::parse_preconditioner(r.text)) {
        target_.options.preconditioner = *p;
        follow_ = true;
        send_to_worker();
      } else {
        say("unknown preconditioner " + r.text, true);
      }
      break;
    case RequestKind::SetCompare: {
      const std::optional<solver::MethodKind> kind =
          r.text == "none" ? std::nullopt : solver::parse_method(r.text);
      if (r.text != "none" && !kind) {
        say("unknown method " + r.text, true);
        break;
      }
      if (kind && refused_for_memory(r, *kind)) break;
      compare_ = kind;
      compare_shown_.reset();
      // Both methods solve the shown load from the start (a method set up afresh starts
      // cold), so that their iterations compare.
      ++target_.model_generation;
      follow_ = true;
      send_to_worker();
      redraw_ = true;
      break;
    }
    default:
      break;
  }
}

// The iterations of the shown solve: playback, stepping (live or stored), scrubbing.
void App::apply_history_request(const Request& r) {
  const int last = shown_ ? std::max(0, static_cast<int>(shown_->iterates.size()) - 1) : 0;
  const bool finished = shown_ && shown_->finished;
  switch (r.kind) {
    case RequestKind::TogglePlay:
      apply(Request{playing_ ? RequestKind::Pause : RequestKind::Play, 0.0, {}});
      break;
    case RequestKind::Play:
      if (shown_index() >= last && (finished || !live_))
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
      playing_ = false;
      if (advance_live()) break;  // the solver makes the next iteration
      cursor_ = std::min(shown_index() + 1, last);
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
    case RequestKind::SetLive:
      live_ = r.value != 0.0;
      target_.live = live_;
      // On: the running solve stops after the iteration it is in; off: it runs to the end.
      worker_.allow(live_ ? 0 : -1);
      compare_worker_.allow(live_ ? 0 : -1);
      redraw_ = true;
      break;
    case RequestKind::Cancel:
      worker_.cancel();
      if (compare_) compare_worker_.cancel();
      playing_ = false;
      break;
    case RequestKind::Scrub:
      // Beyond the last iteration: the last (a script's "scrub 1000" shows the end).
      if (r.script_line > 0 && !shown_) {
        fail(r, "scrub: no solve is on screen yet (a 'wait' first waits for one)", kExitUsage);
        break;
      }
      cursor_ = std::clamp(static_cast<int>(r.value), 0, last);
      playing_ = false;
      follow_ = cursor_ == last && finished;
      redraw_ = true;
      break;
    default:
      break;
  }
}

// Outputs and the rest: screenshots, recordings, exports, views saved, reload, quit.
void App::apply_output_request(const Request& r) {
  switch (r.kind) {
    case RequestKind::Screenshot:
      screenshot_requested_ = true;
      pending_screenshot_ = r.text;
      break;
    case RequestKind::RecordIterations:
    case RequestKind::RecordSweep:
      start_recording(r);
      break;
    case RequestKind::Reload:
      reload();
      break;
    case RequestKind::ExportParaView:
      export_paraview(r);
      break;
    case RequestKind::ScreenshotWindow:
      window_shot_requested_ = true;
      pending_window_shot_ = r.text;
      break;
    case RequestKind::SaveView:
    case RequestKind::Locate:  // both need the picture drawn first
      after_picture_.push_back(r);
      redraw_ = true;
      break;
    case RequestKind::Quit:
      quit_ = true;
      break;
    default:
      break;
  }
}

void App::sync() {
  const std::uint64_t sent_before = requests_sent_;
  for (std::size_t i = 0; i < queue_.size(); ++i)  // apply() may queue more
    apply(queue_[i]);
  queue_.clear();
  // A solve that is quick (the last one took less than the budget) lands in this very
  // frame: wait for it a little rather than show it one frame later. Slow solves are not
  // waited for; their iterates appear as they come.
  std::shared_ptr<const SolveState> latest;
  if (requests_sent_ != sent_before && shown_ && shown_->finished &&
      shown_->solve_seconds < kQuickSolve.count() * 1e-6)
    latest = worker_.wait_for(requests_sent_, kQuickSolve);
  else
    latest = worker_.latest();
  if (latest && latest->iterates.empty() && latest->finished) {
    // The method cannot solve this scene (or its survey was cancelled): say so, keep the
    // last picture.
    error_ = std::move(latest);
  } else if (latest != shown_) {
    shown_ = std::move(latest);
    if (shown_ && shown_->max_load > 0.0) slider_max_ = shown_->max_load;
    if (shown_ && error_ && shown_->request > error_->request) error_.reset();
    redraw_ = true;
  }
  if (compare_) {
    std::shared_ptr<const SolveState> second = compare_worker_.latest();
    if (second != compare_shown_) {
      compare_shown_ = std::move(second);
      redraw_ = true;
    }
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
        // Wait for the solver; stepping live, let it make the next iteration.
        if (live_ && shown_->request == requests_sent_) worker_.allow(last + 1);
        next_tick_ = now + 1.0 / play_rate_;
        break;
      }
    }
  }
}

}  // namespace fetic::app::gui
