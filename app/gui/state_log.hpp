#pragma once
// What `fetic gui` reports about itself (--state-file FILE, "-" for stdout): one JSON
// object a line, written at once, for tests and scripts: "ready" (window and slider
// geometry), "solved" (a solve that finished and is on screen: load factor, iterations,
// active contacts), "screenshot", "recorded", "reloaded", "error", "quit". Written through
// app::OutputStream: every line is checked, and a lost one makes the run end with status 5.

#include <mutex>
#include <string>

#include <nlohmann/json.hpp>

#include "app/output_file.hpp"

namespace fetic::app::gui {

class StateLog {
 public:
  // Empty path: reports nothing. Throws OutputError when the target cannot be opened.
  void open(const std::string& path) {
    if (!path.empty()) out_.open(path);
  }
  // Thread-safe (screenshots are written from encoder threads).
  void write(const nlohmann::json& event) {
    if (out_.is_open()) out_.write(event.dump() + "\n");
  }
  // Closes the file; returns what was lost ("" when every line arrived).
  std::string close() { return out_.close(); }

  // A screenshot, recorded frame or movie that could not be written: an "error" event,
  // and the run ends with status 5 (thread-safe).
  void output_lost(const std::string& message) {
    write({{"event", "error"}, {"message", message}});
    std::lock_guard lock(lost_mutex_);
    if (lost_outputs_++ == 0) first_lost_ = message;
  }
  // "" when every output arrived, else how many were lost and the first reason.
  std::string lost_outputs() const {
    std::lock_guard lock(lost_mutex_);
    if (lost_outputs_ == 0) return "";
    return std::to_string(lost_outputs_) +
           " output(s) could not be written, the first: " + first_lost_;
  }

 private:
  OutputStream out_;
  mutable std::mutex lost_mutex_;
  int lost_outputs_ = 0;
  std::string first_lost_;
};

}  // namespace fetic::app::gui
