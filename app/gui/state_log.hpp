#pragma once
// What `fetic gui` reports about itself (--state-file FILE, "-" for stdout): one JSON
// object a line, flushed at once, for tests and scripts: "ready" (window and slider
// geometry), "solved" (a solve that finished and is on screen: load factor, iterations,
// active contacts), "screenshot", "recorded", "reloaded", "error", "quit".

#include <fstream>
#include <iostream>
#include <mutex>
#include <string>

#include <nlohmann/json.hpp>

namespace fetic::app::gui {

class StateLog {
 public:
  // Empty path: reports nothing. Returns false when the file cannot be opened.
  bool open(const std::string& path) {
    if (path.empty()) return true;
    if (path == "-") {
      stdout_ = true;
      return true;
    }
    file_.open(path, std::ios::out | std::ios::trunc);
    return static_cast<bool>(file_);
  }
  // Thread-safe (screenshots are written from encoder threads).
  void write(const nlohmann::json& event) {
    std::lock_guard lock(mutex_);
    const std::string line = event.dump();
    if (stdout_) {
      std::cout << line << std::endl;
    } else if (file_.is_open()) {
      file_ << line << std::endl;
    }
  }

 private:
  std::mutex mutex_;
  std::ofstream file_;
  bool stdout_ = false;
};

}  // namespace fetic::app::gui
