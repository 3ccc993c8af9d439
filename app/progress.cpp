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

SharedProgress::SharedProgress(ProgressMode mode, int writers)
    : line_(mode), texts_(static_cast<size_t>(writers)) {}

void SharedProgress::update(int writer, const std::string& text) {
  const std::lock_guard lock(mutex_);
  texts_.at(static_cast<size_t>(writer)) = text;
  if (!line_.enabled() || line_.elapsed_seconds() <= 1.0 || !line_.due()) return;
  std::string shown;
  for (const std::string& part : texts_)
    if (!part.empty()) shown += (shown.empty() ? "" : "; ") + part;
  if (!shown.empty()) line_.update(shown);
}

}  // namespace fetic::app
