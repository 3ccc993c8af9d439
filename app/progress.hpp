#pragma once
// A progress line on stderr for long solves and renders: redrawn in place on a terminal
// (carriage return, erase to the end of the line), at most a few times a second; off
// when stderr is not a terminal unless forced (--progress: then one line per update, for
// logs); never with --quiet.

#include <chrono>
#include <mutex>
#include <string>
#include <vector>

namespace fetic::app {

enum class ProgressMode { Auto, Always, Never };

// --progress forces, --quiet silences (it wins), neither: Auto.
ProgressMode progress_mode(bool progress_flag, bool quiet_flag);

class ProgressLine {
 public:
  explicit ProgressLine(ProgressMode mode, double seconds_between_updates = 0.25);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  bool enabled() const { return enabled_; }
  // True when an update now would be shown (lets callers skip composing the text).
  bool due() const;
  // Shows "text, elapsed T s" when due (or always when `now` is set).
  void update(const std::string& text, bool now = false);
  // Erases the line on a terminal, before other output goes to the screen.
  void clear();
  double elapsed_seconds() const;

 private:
  bool enabled_ = false;
  bool terminal_ = false;
  bool shown_ = false;  // a line is on the terminal
  double interval_ = 0.25;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_{};
  bool ever_ = false;
};

// One progress line for several writers that run at the same time (the result file and
// the ParaView frame, each on a thread of its own): each reports its own text, the line
// shows them all ("writing r.json: 12 of 50 parts; writing v/struts_0000.vtu: 3 of 14
// arrays, elapsed 2.1 s") once the writing has taken over a second. Thread-safe.
class SharedProgress {
 public:
  explicit SharedProgress(ProgressMode mode, int writers);
  void update(int writer, const std::string& text);
  // The writer is done: its text leaves the line.
  void done(int writer) { update(writer, ""); }

 private:
  std::mutex mutex_;
  ProgressLine line_;
  std::vector<std::string> texts_;
};

}  // namespace fetic::app
