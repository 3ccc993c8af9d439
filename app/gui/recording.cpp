// Screenshots (S, --screenshot-dir) and recordings (--record-dir): pictures are read
// back on the UI thread, encoded and written on worker threads; a finished recording
// becomes a movie when ffmpeg is on the path.

#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <tuple>

#include <nlohmann/json.hpp>

#include "app/exit_codes.hpp"
#include "app/gui/app.hpp"
#include "app/render_output.hpp"
#include "render/gl_renderer.hpp"

namespace fetic::app::gui {

namespace fs = std::filesystem;

// Record buttons, record-iterations and record-sweep N: a numbered directory under
// --record-dir; step_recording then renders one frame per UI frame.
void App::start_recording(const Request& r) {
  if (recording_) {
    fail(r, "a recording is already running", kExitUsage);
    return;
  }
  auto rec = std::make_unique<Recording>();
  rec->sweep = r.kind == RequestKind::RecordSweep;
  char name[64];
  std::snprintf(name, sizeof name, "%s_%03d", rec->sweep ? "sweep" : "iterations", ++recordings_);
  rec->directory = fs::path(args_.record_dir) / name;
  std::error_code error;
  fs::create_directories(rec->directory, error);
  if (error) {
    const std::string message = rec->directory.string() +
                                ": cannot create the recording directory (" + error.message() + ")";
    say(message, true);
    log_.output_lost(message);
    return;
  }
  rec->pool = std::make_unique<render::PngEncoderPool>(default_encoder_threads(), 8);
  if (rec->sweep) {
    const int n = r.value >= 2 ? static_cast<int>(r.value) : sweep_steps_;
    for (int i = 0; i < n; ++i)
      rec->loads.push_back(slider_max_ * i / (n - 1));
  } else {
    if (!shown_ || shown_->iterates.empty()) {
      fail(r, "nothing to record yet: no solve is on screen", kExitUsage);
      return;
    }
    rec->iterations = shown_;
  }
  say("recording into " + rec->directory.string());
  recording_ = std::move(rec);
}

void App::screenshot(const std::string& requested) {
  // A name without a directory goes into --screenshot-dir, like the numbered ones.
  std::string path = requested;
  int number = -1;
  if (path.empty()) {
    std::tie(path, number) = numbered_name("fetic_screenshot_%04d.png", screenshot_count_);
    screenshot_count_ = number + 1;
  } else if (fs::path(path).is_relative()) {
    path = (fs::path(args_.screenshot_dir) / path).string();
  }
  if (!output_folder_ready(path)) {
    if (number >= 0) give_back(screenshot_count_, number);
    return;
  }
  if (!screenshot_pool_) screenshot_pool_ = std::make_unique<render::PngEncoderPool>(1, 4);
  const double load = shown_ ? shown_->load_factor : 0.0;
  const int iteration = shown_index();
  const int newest = last_index();  // how far the shown solve has got
  say("screenshot " + path);
  screenshot_pool_->submit(renderer_->read_back(),
                           [this, path, load, iteration, newest, number](render::PngBytes png) {
                             try {
                               write_png_atomically(path, png);
                               log_.write({{"event", "screenshot"},
                                           {"path", path},
                                           {"load_factor", load},
                                           {"iteration", iteration},
                                           {"newest_iteration", newest}});
                             } catch (const std::exception& error) {
                               if (number >= 0) give_back(screenshot_count_, number);
                               log_.output_lost(error.what());
                             }
                           });
}

std::pair<std::string, int> App::numbered_name(const char* pattern, int from) const {
  for (int number = from;; ++number) {
    char name[64];
    std::snprintf(name, sizeof name, pattern, number);
    const std::string path = (fs::path(args_.screenshot_dir) / name).string();
    std::error_code ignored;
    if (!fs::exists(path, ignored)) return {path, number};
  }
}

bool App::output_folder_ready(const std::string& path) {
  const fs::path folder = fs::path(path).parent_path();
  std::error_code error;
  if (folder.empty() || fs::is_directory(folder, error)) return true;
  fs::create_directories(folder, error);
  if (!error) return true;
  const std::string message =
      path + ": cannot create the folder " + folder.string() + " (" + error.message() + ")";
  say(message, true);
  log_.output_lost(message);
  return false;
}

void App::give_back(std::atomic<int>& counter, int number) {
  int expected = number + 1;
  counter.compare_exchange_strong(expected, number);
}

void App::step_recording() {
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
    if (!shown_->iterates.empty()) rec.steps.push_back(render::summarize(*shown_->iterates.back()));
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
  say("recorded " + std::to_string(finished->next) + " frames in " + finished->directory.string());
  finishers_.emplace_back([this, finished] {
    nlohmann::json event{{"event", "recorded"},
                         {"directory", finished->directory.string()},
                         {"frames", finished->next}};
    try {
      finished->pool->finish();
      if (program_on_path("ffmpeg")) {
        const std::string movie = (finished->directory / "movie.mp4").string();
        if (assemble_movie(finished->directory.string(), finished->next, 8, movie, std::cerr) ==
            kExitOk)
          event["movie"] = movie;
        else
          event["error"] = movie + ": the movie could not be made (see the messages above)";
      }
    } catch (const std::exception& error) {
      event["error"] = finished->directory.string() + ": " + error.what();
    }
    log_.write(event);
    if (event.contains("error")) log_.output_lost(event["error"].get<std::string>());
  });
}

}  // namespace fetic::app::gui
