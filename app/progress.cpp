#include "app/progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace fetic::app {

ProgressMode progress_mode(bool progress_flag, bool quiet_flag) {
  if (quiet_flag) return ProgressMode::Never;
  return progress_flag ? ProgressMode::Always : ProgressMode::Auto;
}

ProgressLine::ProgressLine(ProgressMode mode, double seconds_between_updates)
    : interval_(seconds_between_updates), start_(std::chrono::steady_clock::now()) {
  terminal_ = ::isatty(STDERR_FILENO) == 1;
  enabled_ = mode == ProgressMode::Always || (mode == ProgressMode::Auto && terminal_);
}

ProgressLine::~ProgressLine() {
  clear();
}

double ProgressLine::elapsed_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

bool ProgressLine::due() const {
  if (!enabled_) return false;
  if (!ever_) return true;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count() >=
         interval_;
}

void ProgressLine::update(const std::string& text, bool now) {
  if (!enabled_ || (!now && !due())) return;
  last_ = std::chrono::steady_clock::now();
  ever_ = true;
  char elapsed[48];
  std::snprintf(elapsed, sizeof elapsed, ", elapsed %.1f s", elapsed_seconds());
  if (terminal_) {
    std::fprintf(stderr, "\r%s%s\x1b[K", text.c_str(), elapsed);
    shown_ = true;
  } else {
    std::fprintf(stderr, "%s%s\n", text.c_str(), elapsed);
  }
  std::fflush(stderr);
}

void ProgressLine::clear() {
  if (!shown_) return;
  std::fprintf(stderr, "\r\x1b[K");
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace fetic::app
