#include "app/json_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include <nlohmann/json.hpp>

#include "solver/threads.hpp"

namespace fetic::app {

void JsonText::raw(std::string_view text) {
  buffer_.append(text);
  maybe_flush();
}

void JsonText::number(double value) {
  if (!std::isfinite(value)) {
    raw("null");  // what dump() writes for them
    return;
  }
  // nlohmann's own shortest round-trip formatting (the one dump() calls), so that the
  // bytes are those of dump(); 64 characters is its serializer's buffer.
  char text[64];
  const char* end = nlohmann::detail::to_chars(text, text + sizeof text, value);
  buffer_.append(text, static_cast<std::size_t>(end - text));
  maybe_flush();
}

void JsonText::number(long long value) {
  char text[24];
  const auto result = std::to_chars(text, text + sizeof text, value);
  buffer_.append(text, static_cast<std::size_t>(result.ptr - text));
  maybe_flush();
}

void JsonText::string(std::string_view text) {
  raw(nlohmann::ordered_json(std::string(text)).dump());
}

void JsonText::newline(int depth) {
  buffer_.push_back('\n');
  buffer_.append(static_cast<std::size_t>(depth), ' ');
}

void JsonText::member(std::string_view key, int depth, bool first) {
  if (!first) buffer_.push_back(',');
  newline(depth);
  string(key);
  raw(": ");
}

void JsonText::parallel_items(std::size_t count, int depth, ItemWriter item, void* context) {
  raw("[");
  runs_.resize(kRunsAtOnce);
  for (std::size_t first = 0; first < count; first += kRun * kRunsAtOnce) {
    const std::size_t last = std::min(count, first + kRun * kRunsAtOnce);
    const std::size_t used = (last - first + kRun - 1) / kRun;
    // About a microsecond per item (threads.hpp's unit).
    const int threads = solver::threads_for(static_cast<long long>(last - first));
#pragma omp parallel for num_threads(threads) schedule(dynamic)
    for (std::size_t r = 0; r < used; ++r) {
      JsonText text(std::move(runs_[r]));
      const std::size_t end = std::min(last, first + (r + 1) * kRun);
      for (std::size_t k = first + r * kRun; k < end; ++k) {
        if (k > 0) text.raw(",");
        text.newline(depth + 1);
        item(context, text, k, depth + 1);
      }
      runs_[r] = text.take();
    }
    for (std::size_t r = 0; r < used; ++r)
      raw(runs_[r]);
  }
  newline(depth);
  raw("]");
}

void JsonText::flush() {
  if (!out_ || buffer_.empty()) return;
  out_->write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  buffer_.clear();
}

}  // namespace fetic::app
